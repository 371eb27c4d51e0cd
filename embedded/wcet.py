#!/usr/bin/env python3
"""Static worst-case instruction and cycle bounds of firmware entries.

For one entry symbol of the firmware ELF that `count.py` executes, this
disassembles the entry and everything it calls (capstone, Thumb / Thumb-2,
M profile), builds each function's control-flow graph by recursive descent
from its first instruction, bounds every loop, replaces every call by the
callee's own bound, and takes the longest path (IPET-lite: the longest path
through the acyclic graph left after each natural loop is collapsed into one
node costing `bound x longest iteration + longest exit`).

What is counted, and the convention shared with `count.py`:
* every instruction on the path counts once, including the condition-failed
  slots of a Thumb-2 IT block (the whole block is taken as executed; the
  emulator's per-translation-block counter counts them the same way, and
  `count.py --qemu` checks that count against QEMU's per-instruction trace);
* cycles use the same per-instruction cost function as the counter (the
  not-taken cost of every instruction, plus the taken-branch surcharge on
  every edge that leaves a block by a jump, a call or a return), so the
  cycle bound is comparable with the counter's cycle estimate.

What the bound assumes (it is safe under these, and loose by every
infeasible path it includes):
* every conditional branch may go either way, independently of every other
  (data-dependent exclusions, e.g. "the Stribeck branch and the saturation
  branch cannot both be taken", are not used);
* loops iterate at most their bound per entry (from `LOOP_BOUNDS` below, a
  per-function annotation that `count.py` checks against the emulator on
  every vector it runs; a loop without a bound is an error);
* paths into `firmware_panic` (or any callee without a returning path) end
  there: they are excluded from the bound, and the counter fails on any
  input that reaches them;
* indirect calls and jumps must be resolved (a literal-pool or MOVW/MOVT
  address for `blx rN`, a bounds-checked TBB/TBH table); otherwise the
  analysis stops with an error naming the address.

Usage: wcet.py ELF ENTRY [--cycles-core M4F|M0+]   (prints the bound)
"""

import os
import struct
import subprocess
import sys
from dataclasses import dataclass, field

from capstone import CS_ARCH_ARM, CS_MODE_MCLASS, CS_MODE_THUMB, Cs
from capstone import arm as csarm
from elftools.elf.elffile import ELFFile

# Loop bounds by function (symbol name, or a substring of the mangled name):
# the largest number of times any loop of that function may jump back to its
# header per entry into the loop, and why. `count.py` records, for every
# vector it runs, the back-edge traversals per loop entry in the emulator and
# fails if one exceeds its bound here.
LOOP_BOUNDS = {
    ("WristStepConfig", "6update"): (5, "the wrist step (src/wrist/step.rs) when not inlined: the six gauge "
                                         "products of each sensing row and the gauge probe (six passes, five "
                                         "jumps back), the two axes, and the laws' four friction parameters "
                                         "(three); five bounds them all"),
    ("KinematicErrorModel", "6series"): (6, "the seven terms of eq. (3.7), `KinematicErrorModel::series` "
                                            "(src/harmonic_drive/kinematic_error.rs): seven passes, six jumps back"),
    # compiler_builtins' shift-and-subtract division (Armv6-M has no divide
    # instruction): at most one iteration per quotient bit.
    "__udivsi3": (32, "one iteration per quotient bit of a 32-bit division"),
    "__aeabi_uidiv": (32, "one iteration per quotient bit of a 32-bit division"),
    "__aeabi_uidivmod": (32, "one iteration per quotient bit of a 32-bit division"),
    "__divsi3": (32, "one iteration per quotient bit of a 32-bit division"),
    "__aeabi_idiv": (32, "one iteration per quotient bit of a 32-bit division"),
    "__aeabi_idivmod": (32, "one iteration per quotient bit of a 32-bit division"),
    "__udivmodsi4": (32, "one iteration per quotient bit of a 32-bit division"),
    # A 64-bit division reaches compiler_builtins' `specialized_div_rem` on
    # Armv6-M: shift-and-subtract, at most one iteration per quotient bit. The
    # I16F16 quotient (`div_bits`, src/scalar/fixed.rs) no longer does (it is
    # loop-free); the reference steps and the set-up code still link them.
    ("specialized_div_rem", "u32_div_rem"): (32, "one iteration per quotient bit of a 32-bit division (compiler_builtins u32_div_rem)"),
    ("specialized_div_rem", "u64_div_rem"): (64, "one iteration per quotient bit of a 64-bit division (compiler_builtins u64_div_rem)"),
}

PANIC_SYMBOLS = ("firmware_panic",)


class WcetError(Exception):
    """The analysis cannot bound the code (unresolved indirect branch,
    unbounded or irreducible loop, code outside the image)."""


@dataclass
class Insn:
    addr: int
    size: int
    mn: str
    op: str
    cc: int
    kind: str  # "seq", "jump", "cjump", "call", "icall", "ret", "cret", "table", "trap"
    target: int = None
    it: int = 0  # number of slots of an IT instruction
    in_it: bool = False


@dataclass
class Block:
    start: int
    insns: list = field(default_factory=list)
    succs: list = field(default_factory=list)  # (start, taken)
    ret: bool = False  # may leave the function by a return (or a tail call)
    ret_taken: bool = True
    tail: int = None  # tail-called function
    noreturn_end: bool = False  # ends in a call that never returns (panic)
    calls: list = field(default_factory=list)  # callee addresses


@dataclass
class Bound:
    insns: int
    cycles: int
    returns: bool = True
    loops: list = field(default_factory=list)  # (function, header, latches, bound)
    functions: set = field(default_factory=set)
    panic_sites: int = 0
    addrs: set = field(default_factory=set)  # every instruction analysed
    # The longest path of this function by instructions: (node, members,
    # instructions of the node), nodes in path order (a loop is one node).
    path: list = field(default_factory=list)


def _base(mn):
    return mn.split(".")[0]


class Program:
    """The firmware image with its symbols, decoded on demand."""

    def __init__(self, path, cycles):
        self.cycles = cycles
        with open(path, "rb") as fh:
            elf = ELFFile(fh)
            self.segs = [(p["p_paddr"], p.data()) for p in elf.iter_segments() if p["p_type"] == "PT_LOAD"]
            self.funcs = {}
            self.syms = {}
            self.data_marks = []  # (addr, is_data)
            for s in elf.get_section_by_name(".symtab").iter_symbols():
                if not s.name:
                    continue
                v = s["st_value"]
                if s.name in ("$d", "$t") or s.name.startswith(("$d.", "$t.")):
                    self.data_marks.append((v & ~1, s.name.startswith("$d")))
                    continue
                self.syms[s.name] = v
                if s["st_info"]["type"] == "STT_FUNC":
                    self.funcs[v & ~1] = (s.name, s["st_size"])
        self.data_marks.sort()
        self.cs = Cs(CS_ARCH_ARM, CS_MODE_THUMB | CS_MODE_MCLASS)
        self.cs.detail = True
        self.decoded = {}
        self.memo = {}
        self.panic = {self.syms[n] & ~1 for n in PANIC_SYMBOLS if n in self.syms}
        self.loop_log = []  # every bounded loop: (function, header, latches, bound)

    # ------------------------------------------------------------- image
    def read(self, addr, n):
        for base, data in self.segs:
            if base <= addr and addr + n <= base + len(data):
                return data[addr - base : addr - base + n]
        raise WcetError(f"read of {n} bytes at {addr:#x} outside the image")

    def word(self, addr):
        return struct.unpack("<I", self.read(addr, 4))[0]

    def name(self, addr):
        f = self.funcs.get(addr & ~1)
        return f[0] if f else f"{addr:#x}"

    def func_of(self, addr):
        best = None
        for start, (name, size) in self.funcs.items():
            if start <= addr < start + max(size, 1):
                if best is None or start > best[0]:
                    best = (start, name, size)
        return best

    # ------------------------------------------------------------ decode
    def decode(self, addr):
        d = self.decoded.get(addr)
        if d is not None:
            return d
        code = self.read(addr, 4) if self._has(addr, 4) else self.read(addr, 2)
        ins = next(self.cs.disasm(code, addr, 1), None)
        if ins is None:
            raise WcetError(f"undecodable instruction at {addr:#x}")
        mn, op = ins.mnemonic, ins.op_str
        b = _base(mn)
        cc = ins.cc
        cond = cc not in (csarm.ARM_CC_AL, csarm.ARM_CC_INVALID)
        kind, target, it = "seq", None, 0
        ops = ins.operands
        writes_pc = False
        if b.startswith("it") and set(b[1:]) <= {"t", "e"}:
            it = len(b) - 1
        elif b in ("b", "beq", "bne", "bcs", "bhs", "bcc", "blo", "bmi", "bpl", "bvs", "bvc", "bhi", "bls", "bge",
                   "blt", "bgt", "ble", "bal"):
            target = ops[-1].imm
            kind = "cjump" if cond else "jump"
        elif b in ("cbz", "cbnz"):
            target = ops[-1].imm
            kind = "cjump"
        elif b.startswith("bl") and b not in ("bls", "blt", "ble", "blx") and not b.startswith("blx") and ops and ops[-1].type == csarm.ARM_OP_IMM:
            target = ops[-1].imm
            kind = "call"
        elif b.startswith("blx"):
            kind = "icall"
        elif b.startswith("bx"):
            kind = "cret" if cond else "ret"
            if op.strip() != "lr":
                kind = "ijump"
        elif b.startswith(("pop", "ldm")) and "pc" in op:
            kind = "cret" if cond else "ret"
        elif b.startswith(("tbb", "tbh")):
            kind = "table"
        elif b in ("udf", "bkpt"):
            kind = "trap"
        else:
            # Any other write to the PC is an indirect jump.
            if ops and ops[0].type == csarm.ARM_OP_REG and ops[0].reg == csarm.ARM_REG_PC and b not in ("cmp", "cmn", "tst", "teq", "str", "strb", "strh", "push", "stm", "vstr"):
                if b in ("ldr",) and "sp" in op and "], #4" in op:
                    kind = "cret" if cond else "ret"
                else:
                    writes_pc = True
                    kind = "ijump"
        d = Insn(addr, ins.size, mn, op, cc, kind, target, it)
        d.writes_pc = writes_pc
        self.decoded[addr] = d
        return d

    def _has(self, addr, n):
        try:
            self.read(addr, n)
            return True
        except WcetError:
            return False

    def table_targets(self, ins, prev):
        """Targets of a TBB/TBH jump table: the entry count comes from the
        bounds check `cmp rX, #N` + `bhi`/`bhs` among the instructions
        before it (in `prev`, latest last)."""
        idx_reg = ins.op.split(",")[1].strip().rstrip("]")
        n = None
        for p in reversed(prev[-8:]):
            b = _base(p.mn)
            if b == "cmp" and p.op.split(",")[0].strip() == idx_reg and "#" in p.op:
                k = int(p.op.split("#")[1], 0)
                # the branch to the default case follows the compare
                after = [q for q in prev if q.addr > p.addr and q.kind == "cjump"]
                if after and _base(after[0].mn) in ("bhi",):
                    n = k + 1
                elif after and _base(after[0].mn) in ("bhs", "bcs"):
                    n = k
                break
        if n is None:
            raise WcetError(f"jump table at {ins.addr:#x} without a recognised bounds check")
        base = ins.addr + 4
        half = _base(ins.mn) == "tbh"
        out = []
        for i in range(n):
            off = struct.unpack("<H", self.read(base + 2 * i, 2))[0] if half else self.read(base + i, 1)[0]
            out.append(base + 2 * off)
        return out

    def word_table(self, ins, prev, lo, hi):
        """Targets of an Armv6-M word jump table, `adr rB, table; ldr rX,
        [rB, rI]; mov pc, rX`: the table is the data region that starts at
        `table` (up to the next `$t` mapping symbol of the ELF), and every
        entry must be a Thumb address inside the function; `None` for any
        other `mov pc`."""
        if _base(ins.mn) != "mov" or not ins.op.startswith("pc,"):
            return None
        reg = ins.op.split(",")[1].strip()
        base_reg = table = None
        for p in reversed(prev):
            b = _base(p.mn)
            parts = [q.strip().strip("[]") for q in p.op.split(",")]
            if base_reg is None and b == "ldr" and parts[0] == reg and len(parts) == 3:
                base_reg = parts[1]
            elif base_reg is not None and b == "adr" and parts[0] == base_reg:
                table = ((p.addr + 4) & ~3) + int(parts[1].lstrip("#"), 0)
                break
        if table is None:
            return None
        end = min([m for m, is_data in self.data_marks if m > table and not is_data] + [hi or table + 1024])
        out = []
        for a in range(table, end - 3, 4):
            t = self.word(a)
            if not (t & 1) or hi is None or not (lo <= (t & ~1) < hi):
                raise WcetError(f"jump table at {table:#x} (from {ins.addr:#x}): entry {t:#x} is not code of the function")
            out.append(t & ~1)
        if not out:
            return None
        return out

    def byte_table(self, ins, prev, lo, hi):
        """Targets of an Armv6-M byte jump table as LLVM emits it for a
        small switch, `add rB, pc; ldrb rX, [rB, #k]; lsls rX, rX, #1;
        add pc, rX` (rB holding the index before the first instruction):
        the table starts at the first `add`'s address + 4 + k and is the
        data region up to the next `$t` mapping symbol; entry `e` jumps to
        the last `add`'s address + 4 + 2e, which must be code of the
        function. `None` for any other `add pc`."""
        if _base(ins.mn) != "add" or [q.strip() for q in ins.op.split(",")][0] != "pc" or len(prev) < 3:
            return None
        reg = ins.op.split(",")[1].strip()
        addpc, ldrb, lsl = prev[-3:]
        lp = [q.strip().strip("[]") for q in lsl.op.split(",")]
        bp = [q.strip().strip("[]") for q in ldrb.op.split(",")]
        ap = [q.strip() for q in addpc.op.split(",")]
        if not (_base(lsl.mn) == "lsls" and lp == [reg, reg, "#1"]
                and _base(ldrb.mn) == "ldrb" and len(bp) == 3 and bp[0] == reg
                and _base(addpc.mn) == "add" and ap == [bp[1], "pc"]):
            return None
        table = addpc.addr + 4 + int(bp[2].lstrip("#"), 0)
        end = min([m for m, is_data in self.data_marks if m > table and not is_data] + [hi or table + 256])
        out = []
        for a in range(table, end):
            t = ins.addr + 4 + 2 * self.read(a, 1)[0]
            if hi is None or not (lo <= t < hi):
                raise WcetError(f"byte jump table at {table:#x} (from {ins.addr:#x}): target {t:#x} is not code of the function")
            out.append(t)
        return out or None

    def resolve_icall(self, ins, prev):
        """The target of `blx rN` when rN was loaded in the same block from
        a literal pool or built by MOVW/MOVT."""
        reg = ins.op.strip()
        lo = hi = None
        for p in reversed(prev):
            b = _base(p.mn)
            dst = p.op.split(",")[0].strip()
            if dst != reg:
                continue
            if b == "ldr" and "[pc" in p.op:
                imm = int(p.op.split("#")[1].rstrip("]"), 0) if "#" in p.op else 0
                return self.word(((p.addr + 4) & ~3) + imm) & ~1
            if b == "movt" and hi is None:
                hi = int(p.op.split("#")[1], 0)
                continue
            if b == "movw" and lo is None:
                lo = int(p.op.split("#")[1], 0)
                if hi is not None:
                    return ((hi << 16) | lo) & ~1
            break
        raise WcetError(f"unresolved indirect call `{ins.mn} {ins.op}` at {ins.addr:#x} in {self.name_of(ins.addr)}")

    def name_of(self, addr):
        f = self.func_of(addr)
        return f[1] if f else "?"

    # --------------------------------------------------------------- CFG
    def cfg(self, entry):
        """Basic blocks of the function at `entry` (recursive descent)."""
        f = self.func_of(entry)
        lo, hi = (f[0], f[0] + f[2]) if f and f[2] else (entry, None)
        insns = {}
        work = [(entry, 0)]
        # successor edges at instruction level: addr -> [(addr, taken)]
        edges = {}
        exits = {}  # addr -> ("ret", taken) | ("tail", target) | ("noreturn",)
        calls = {}
        seen_it = {}
        prev_chain = {}
        while work:
            a, it_left = work.pop()
            if a in insns:
                continue
            ins = self.decode(a)
            insns[a] = ins
            ins.in_it = it_left > 0
            nxt = a + ins.size
            next_it = ins.it if ins.it else max(0, it_left - 1)
            seen_it[a] = it_left
            k = ins.kind
            # Whether a return or branch in an IT block is conditional comes
            # from the block structure found here, not from the decoder: each
            # instruction is decoded on its own, so capstone's IT state may be
            # stale. A return (`bx lr`, `pop {.., pc}`) is conditional exactly
            # in an IT slot (it may also fall through); an unconditional `b`
            # in an IT slot is conditional too.
            if k in ("ret", "cret"):
                k = "cret" if ins.in_it else "ret"
            elif k == "jump" and ins.in_it:
                k = "cjump"
            out = []
            if k == "seq":
                out = [(nxt, False)]
            elif k == "jump":
                t = ins.target
                if t == a:
                    exits[a] = ("noreturn",)  # `b .`
                elif hi is not None and not (lo <= t < hi) or (t in self.funcs and t != lo):
                    exits[a] = ("tail", t)
                else:
                    out = [(t, True)]
            elif k == "cjump":
                t = ins.target
                if hi is not None and not (lo <= t < hi) or (t in self.funcs and t != lo):
                    raise WcetError(f"conditional tail call at {a:#x}")
                out = [(t, True), (nxt, False)]
            elif k == "call" and hi is not None and lo < ins.target < hi and ins.target not in self.funcs:
                # Armv6-M: `bl` as a long branch inside the function (LR
                # is saved already); a jump, not a call.
                ins.kind = "jump"
                out = [(ins.target, True)]
            elif k == "call":
                calls[a] = ins.target
                if ins.target in self.panic:
                    exits[a] = ("noreturn",)
                else:
                    out = [(nxt, False)]
            elif k == "icall":
                chain = self._linear_before(insns, a)
                t = self.resolve_icall(ins, chain)
                calls[a] = t
                out = [(nxt, False)]
            elif k == "ret":
                exits[a] = ("ret",)
            elif k == "cret":
                exits[a] = ("ret",)
                out = [(nxt, False)]
            elif k == "table":
                chain = self._linear_before(insns, a)
                out = [(t, True) for t in self.table_targets(ins, chain)]
            elif k == "trap":
                exits[a] = ("noreturn",)
            elif k == "ijump" and self.word_table(ins, self._linear_before(insns, a), lo, hi) is not None:
                out = [(t, True) for t in self.word_table(ins, self._linear_before(insns, a), lo, hi)]
            elif k == "ijump" and self.byte_table(ins, self._linear_before(insns, a), lo, hi) is not None:
                out = [(t, True) for t in self.byte_table(ins, self._linear_before(insns, a), lo, hi)]
            elif k == "ijump":
                raise WcetError(f"unresolved indirect jump `{ins.mn} {ins.op}` at {a:#x} in {self.name_of(a)}")
            edges[a] = out
            for t, _ in out:
                work.append((t, next_it if t == nxt else 0))
        # Blocks: leaders are the entry, jump targets, and the instruction
        # after any instruction with several successors or a taken edge.
        leaders = {entry}
        for a, out in edges.items():
            ins = insns[a]
            if len(out) != 1 or out[0][1] or a in exits or ins.kind in ("call", "icall"):
                for t, _ in out:
                    leaders.add(t)
            for t, taken in out:
                if taken:
                    leaders.add(t)
        blocks = {}
        for start in sorted(leaders):
            if start not in insns:
                continue
            b = Block(start)
            a = start
            while True:
                ins = insns[a]
                b.insns.append(ins)
                if a in calls:
                    b.calls.append(calls[a])
                out = edges[a]
                ex = exits.get(a)
                if ex is not None:
                    if ex[0] == "ret":
                        b.ret = True
                    elif ex[0] == "tail":
                        b.ret = True
                        b.tail = ex[1]
                    else:
                        b.noreturn_end = True
                if ex is not None or len(out) != 1 or out[0][1] or (out and out[0][0] in leaders):
                    b.succs = out
                    break
                a = out[0][0]
            blocks[start] = b
        return blocks

    def _linear_before(self, insns, a):
        """Decoded instructions immediately preceding `a` in address order
        (straight-line context for table and indirect-call resolution)."""
        out = []
        p = a
        for _ in range(12):
            cand = [q for q in (p - 2, p - 4) if q in insns and insns[q].addr + insns[q].size == p]
            if not cand:
                break
            p = cand[0]
            out.append(insns[p])
        return list(reversed(out))

    # ------------------------------------------------------------- bound
    def bound(self, entry, stack=()):
        entry &= ~1
        if entry in self.memo:
            return self.memo[entry]
        if entry in stack:
            raise WcetError(f"recursion through {self.name(entry)}")
        if entry in self.panic:
            b = Bound(0, 0, returns=False)
            self.memo[entry] = b
            return b
        blocks = self.cfg(entry)
        fname = self.name(entry)
        res = Bound(0, 0, functions={fname})
        for b in blocks.values():
            res.addrs |= {i.addr for i in b.insns}
        cost = {}
        for s, b in blocks.items():
            n = len(b.insns)
            cyc = sum(self.cycles(i.mn, i.op, False) for i in b.insns)
            noret = b.noreturn_end
            for i in b.insns:
                if i.kind in ("call", "icall"):
                    t = b.calls[[j for j in b.insns if j.kind in ("call", "icall")].index(i)]
                    cb = self.bound(t, stack + (entry,))
                    cyc += self.cycles(i.mn, i.op, True) - self.cycles(i.mn, i.op, False)
                    n += cb.insns
                    cyc += cb.cycles
                    res.functions |= cb.functions
                    res.addrs |= cb.addrs
                    res.loops += cb.loops
                    res.panic_sites += cb.panic_sites
                    if not cb.returns:
                        noret = True
                        res.panic_sites += 1
            if b.tail is not None:
                cb = self.bound(b.tail, stack + (entry,))
                n += cb.insns
                cyc += cb.cycles
                res.functions |= cb.functions
                res.addrs |= cb.addrs
                res.loops += cb.loops
                if not cb.returns:
                    noret = True
            cost[s] = (n, cyc, noret)
        res.blocks = blocks
        best = longest_path(self, blocks, entry, cost, fname, res)
        res.insns, res.cycles, res.returns = best
        self.memo[entry] = res
        return res


def _taken_extra(prog, ins):
    return prog.cycles(ins.mn, ins.op, True) - prog.cycles(ins.mn, ins.op, False)


def dominators(blocks, entry):
    order, seen = [], set()

    def dfs(n):
        stack = [(n, iter([t for t, _ in blocks[n].succs]))]
        seen.add(n)
        while stack:
            v, it = stack[-1]
            for t in it:
                if t not in seen:
                    seen.add(t)
                    stack.append((t, iter([u for u, _ in blocks[t].succs])))
                    break
            else:
                order.append(v)
                stack.pop()

    dfs(entry)
    rpo = list(reversed(order))
    idx = {n: i for i, n in enumerate(rpo)}
    preds = {n: [] for n in rpo}
    for n in rpo:
        for t, _ in blocks[n].succs:
            preds[t].append(n)
    idom = {entry: entry}

    def intersect(a, b):
        while a != b:
            while idx[a] > idx[b]:
                a = idom[a]
            while idx[b] > idx[a]:
                b = idom[b]
        return a

    changed = True
    while changed:
        changed = False
        for n in rpo[1:]:
            ps = [p for p in preds[n] if p in idom]
            new = ps[0]
            for p in ps[1:]:
                new = intersect(p, new)
            if idom.get(n) != new:
                idom[n] = new
                changed = True
    return rpo, idx, preds, idom


def dominates(idom, a, b):
    while True:
        if a == b:
            return True
        if idom[b] == b:
            return False
        b = idom[b]


def longest_path(prog, blocks, entry, cost, fname, res):
    """Longest path (instructions and, separately, cycles) from `entry` to a
    return, with natural loops collapsed. Returns (insns, cycles, returns)."""
    rpo, idx, preds, idom = dominators(blocks, entry)
    back = []  # (latch, header)
    for n in rpo:
        for t, _ in blocks[n].succs:
            if idx[t] <= idx[n]:
                if not dominates(idom, t, n):
                    raise WcetError(f"irreducible loop at {t:#x} in {fname}")
                back.append((n, t))
    loops = {}
    for latch, h in back:
        body = loops.setdefault(h, {"body": {h}, "latches": set()})
        body["latches"].add(latch)
        work = [latch]
        while work:
            v = work.pop()
            if v not in body["body"]:
                body["body"].add(v)
                work += preds[v]
    # Innermost first: smaller bodies first.
    order = sorted(loops, key=lambda h: len(loops[h]["body"]))
    # node weights (insns, cycles); nodes merged into a loop node map to the header
    weight = {n: (cost[n][0], cost[n][1]) for n in rpo}
    noret = {n: cost[n][2] for n in rpo}
    rep = {n: n for n in rpo}  # representative (outermost collapsed header)
    bounds_used = []

    def find(n):
        while rep[n] != n:
            n = rep[n]
        return n

    def succ_edges(n, members):
        """Edges (target rep, extra cycles) out of block n."""
        b = blocks[n]
        last = b.insns[-1]
        out = []
        for t, taken in b.succs:
            out.append((find(t), _taken_extra(prog, last) if taken else 0, t))
        return out

    members = {n: {n} for n in rpo}
    for h in order:
        L = loops[h]
        hb = find(h)
        body = {find(n) for n in L["body"]}
        allm = set().union(*(members[n] for n in body))
        nb, how = _loop_bound(fname), "annotation"
        if nb is None:
            nb, how = counted_loop(blocks, L, preds, fname), "structure"
        if nb is None and os.environ.get("WCET_EXPLORE"):
            nb, how = int(os.environ["WCET_EXPLORE"]), "exploration only"

        if nb is None:
            raise WcetError(f"loop at {h:#x} in {fname} has no bound (add one to wcet.LOOP_BOUNDS)")
        latches = {find(x) for x in L["latches"]}
        # Longest path from the header to each node inside the body (DAG once
        # back edges to h are removed).
        topo = [n for n in rpo if find(n) == n and n in body]
        topo.sort(key=lambda n: idx[n])
        dist = {hb: weight[hb]}
        exit_best = (0, 0)
        iter_best = (0, 0)
        for n in topo:
            if n not in dist:
                continue
            di, dc = dist[n]
            for m in members[n]:
                for rt, extra, t in succ_edges(m, members):
                    if t == h or rt == hb:
                        if m in L["latches"] or rt == hb:
                            iter_best = (max(iter_best[0], di), max(iter_best[1], dc + extra))
                        continue
                    if rt == n:
                        continue
                    if rt in body:
                        w = weight[rt]
                        cand = (di + w[0], dc + extra + w[1])
                        old = dist.get(rt, (-1, -1))
                        dist[rt] = (max(old[0], cand[0]), max(old[1], cand[1]))
                    else:
                        exit_best = (max(exit_best[0], di), max(exit_best[1], dc))
            if any(blocks[m].ret for m in members[n]):
                exit_best = (max(exit_best[0], di), max(exit_best[1], dc + max(_taken_extra(prog, blocks[m].insns[-1]) for m in members[n] if blocks[m].ret)))
        w = (nb * iter_best[0] + exit_best[0], nb * iter_best[1] + exit_best[1])
        bounds_used.append((fname, h, sorted(blocks[x].insns[-1].addr for x in L["latches"]), nb, how))
        for n in body:
            rep[n] = hb
        members[hb] = allm
        weight[hb] = w
        noret[hb] = all(noret[n] for n in body)
    res.loops += bounds_used
    prog.loop_log += bounds_used
    # Longest path over the collapsed DAG.
    nodes = [n for n in rpo if find(n) == n]
    best = {entry: weight[find(entry)]}
    top = (-1, -1)
    pred, top_node = {}, None
    for n in nodes:
        if n not in best:
            continue
        di, dc = best[n]
        rets = [m for m in members[n] if blocks[m].ret]
        if rets and not noret[n]:
            ex = max(_taken_extra(prog, blocks[m].insns[-1]) for m in rets)
            if di > top[0]:
                top_node = n
            top = (max(top[0], di), max(top[1], dc + ex))
        for m in members[n]:
            for rt, extra, t in succ_edges(m, members):
                if rt == n:
                    continue
                if idx[rt] <= idx[n]:
                    raise WcetError(f"unexpected back edge {m:#x}->{t:#x} in {fname}")
                w = weight[rt]
                cand = (di + w[0], dc + extra + w[1])
                old = best.get(rt, (-1, -1))
                if cand[0] > old[0]:
                    pred[rt] = n
                best[rt] = (max(old[0], cand[0]), max(old[1], cand[1]))
    if top[0] < 0:
        return 0, 0, False
    n, path = top_node, []
    while n is not None:
        path.append((n, sorted(members[n]), weight[n][0]))
        n = pred.get(n)
    res.path = list(reversed(path))
    return top[0], top[1], True


def _loop_bound(fname):
    """The annotated bound of the loops of function `fname`, if any: a key
    of `LOOP_BOUNDS` is the symbol name or a tuple of substrings that all
    occur in it."""
    for k, (n, _) in LOOP_BOUNDS.items():
        if k == fname or (isinstance(k, tuple) and all(p in fname for p in k)):
            return n
    return None


def _dst(ins):
    """Registers an instruction writes (conservative: list forms included)."""
    b = _base(ins.mn)
    if b.startswith(("cmp", "cmn", "tst", "teq", "str", "push", "vstr", "vcmp", "it", "b", "cb", "tb", "stm")):
        if b.startswith("stm") and "!" in ins.op:
            return {ins.op.split(",")[0].rstrip("!").strip()}
        return set()
    if b.startswith(("pop", "ldm")):
        regs = ins.op[ins.op.index("{") + 1 : ins.op.index("}")]
        out = {r.strip() for r in regs.split(",")}
        if "!" in ins.op:
            out.add(ins.op.split(",")[0].rstrip("!").strip())
        return out
    first = ins.op.split(",")[0].strip()
    if b in ("umull", "smull", "umlal", "smlal", "ldrd", "vmov"):
        return {first, ins.op.split(",")[1].strip()}
    return {first}


def _imm(tok):
    tok = tok.strip()
    return int(tok[1:], 0) if tok.startswith("#") else None


def counted_loop(blocks, L, preds, fname):
    """Back-edge bound of a counted loop recognised from its code: one latch
    block ending `adds/subs rX, #c` ... `cmp rX, #K` ... `b<cond> header`,
    rX written nowhere else in the loop (and not clobbered by a call), and
    set to a constant `movs rX, #init` on every entry. The bound is found by
    stepping the counter with the latch's own arithmetic (32-bit wrap) and
    condition; `None` when the pattern does not match."""
    if len(L["latches"]) != 1:
        return None
    latch = blocks[next(iter(L["latches"]))]
    br = latch.insns[-1]
    h = [t for t, taken in latch.succs if taken and t in L["body"]]
    if br.kind != "cjump" or len(h) != 1:
        return None
    h = h[0]
    cond = _base(br.mn)[1:]
    cmp = inc = None
    for i in reversed(latch.insns[:-1]):
        b = _base(i.mn)
        parts = [p.strip() for p in i.op.split(",")]
        if cmp is None and b == "cmp" and len(parts) == 2 and _imm(parts[1]) is not None:
            cmp = (parts[0], _imm(parts[1]))
            continue
        if cmp is not None and b in ("adds", "subs", "add", "sub") and parts[0] == cmp[0]:
            c = _imm(parts[-1])
            if c is None or (len(parts) == 3 and parts[1] != parts[0]):
                return None
            inc = c if b.startswith("add") else -c
            break
        if cmp is not None and cmp[0] in _dst(i):
            return None
    if cmp is None or inc is None:
        return None
    reg, limit = cmp
    writes = 0
    for n in L["body"]:
        for i in blocks[n].insns:
            if reg in _dst(i):
                writes += 1
            if i.kind in ("call", "icall") and reg in ("r0", "r1", "r2", "r3", "r12", "ip", "lr"):
                return None
    if writes != 1:
        return None
    inits = set()
    for p in preds[h]:
        if p in L["body"]:
            continue
        v = None
        for i in reversed(blocks[p].insns):
            if reg in _dst(i):
                b = _base(i.mn)
                parts = [q.strip() for q in i.op.split(",")]
                if b in ("movs", "mov", "movw") and len(parts) == 2 and _imm(parts[1]) is not None:
                    v = _imm(parts[1])
                break
        if v is None:
            return None
        inits.add(v)
    if not inits:
        return None
    signed = cond in ("lt", "ge", "gt", "le")
    def test(v):
        a, k = v & 0xFFFFFFFF, limit & 0xFFFFFFFF
        if signed:
            a = a - (1 << 32) if a >> 31 else a
            k = k - (1 << 32) if k >> 31 else k
        return {"ne": a != k, "eq": a == k, "lo": a < k, "cc": a < k, "hs": a >= k, "cs": a >= k,
                "hi": a > k, "ls": a <= k, "lt": a < k, "ge": a >= k, "gt": a > k, "le": a <= k}.get(cond)
    worst = 0
    for v in inits:
        n = 0
        while True:
            v = (v + inc) & 0xFFFFFFFF
            t = test(v)
            if t is None or n > 10_000:
                return None
            if not t:
                break
            n += 1
        worst = max(worst, n)
    return worst


def path_profile(prog, entry, out=None, mult=1):
    """The instructions of the bound's longest path (by instructions), by
    address: {address: count}. A collapsed loop's whole weight is put on its
    header's address; callees are expanded along their own longest path."""
    import collections
    out = collections.Counter() if out is None else out
    b = prog.bound(entry)
    for node, members, w in b.path:
        if len(members) > 1 or any(t == node for m in members for t, _ in b.blocks[m].succs):
            out[node] += mult * w
            continue
        blk = b.blocks[node]
        for i in blk.insns:
            out[i.addr] += mult
        for t in blk.calls:
            path_profile(prog, t, out, mult)
        if blk.tail is not None:
            path_profile(prog, blk.tail, out, mult)
    return out


def analyze(elf, entry, cycles):
    prog = Program(elf, cycles)
    if entry not in prog.syms:
        raise WcetError(f"no symbol {entry}")
    return prog.bound(prog.syms[entry]), prog


def main():
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import cycles

    elf, entry = sys.argv[1], sys.argv[2]
    b, prog = analyze(elf, entry, cycles.m0p_cycles if "thumbv6m" in elf else cycles.m4_cycles)
    print(f"{entry}: bound {b.insns} instructions, {b.cycles} cycles; {len(b.functions)} functions, "
          f"{len(b.loops)} loops, {b.panic_sites} panic sites excluded")
    for f in sorted(b.functions):
        print("  ", f)
    for lp in b.loops:
        print("   loop", lp[0], hex(lp[1]), [hex(x) for x in lp[2]], "bound", lp[3], lp[4])
    if "--path" in sys.argv:
        # The longest path's instructions by source (needs line tables: the
        # `release-lines` profile builds the same code with them).
        prof = path_profile(prog, prog.syms[entry])
        assert sum(prof.values()) == b.insns, (sum(prof.values()), b.insns)
        addrs = sorted(prof)
        print(f"longest path: {b.insns} instructions")
        out = subprocess.run(["llvm-addr2line", "-a", "-i", "-f", "-C", "-e", elf] + [hex(a) for a in addrs],
                             capture_output=True, text=True).stdout.split("\n")
        groups, cur = {}, None
        for line in out:
            if line.startswith("0x") and all(c in "0123456789abcdefx" for c in line):
                cur = groups.setdefault(int(line, 16), [])
            elif cur is not None and line:
                cur.append(line)

        def short(f):
            # drop generic arguments (balanced <...>) and the hash suffix
            out, depth = [], 0
            for ch in f:
                depth += ch == "<"
                if depth == 0:
                    out.append(ch)
                depth -= ch == ">" and depth > 0
            parts = [p for p in "".join(out).split("::") if p and not (p.startswith("h") and len(p) == 17)]
            return "::".join(parts[-2:])

        for a in addrs:
            r = groups.get(a, [])
            frames = [(r[k], r[k + 1].split("/")[-1]) for k in range(0, len(r) - 1, 2)]
            inner = " <- ".join(f"{short(f)}@{l}" for f, l in frames[: 12 if "--frames" in sys.argv else 4])
            print(f"  {a:#x} x{prof[a]}  {prog.decode(a).mn} {prog.decode(a).op}   {inner}")


if __name__ == "__main__":
    main()
