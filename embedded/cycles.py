"""Cycle tables of the Cortex-M4F and Cortex-M0+ instruction sets.

Shared by `count.py` (which counts every executed instruction's cycles in
the emulator) and `wcet.py` (which weights the longest path with them). Each
table follows the core's Technical Reference Manual; `selftest()` checks it
against hand-checked cases (`count.py --selftest`).
"""


# ------------------------------------------------------------------- timing
def _regs(op_str):
    """Number of registers in a `{...}` list (d-registers count 2 words)."""
    if "{" not in op_str:
        return 1
    inner = op_str[op_str.index("{") + 1 : op_str.index("}")]
    n = 0
    for part in inner.split(","):
        part = part.strip()
        w = 2 if part.startswith("d") else 1
        if "-" in part:
            a, b = part.split("-")
            n += (int(b.strip()[1:]) - int(a.strip()[1:]) + 1) * w
        else:
            n += w
    return n


def _base(mn):
    """Mnemonic without width suffix and condition code (`bne.w` -> `b`)."""
    mn = mn.split(".")[0]
    return mn


CONDS = ("eq", "ne", "cs", "hs", "cc", "lo", "mi", "pl", "vs", "vc", "hi", "ls", "ge", "lt", "gt", "le", "al")


def _strip_cond(mn):
    for c in CONDS:
        if mn.endswith(c) and len(mn) > len(c):
            stem = mn[: -len(c)]
            # keep real mnemonics ending in a condition-like suffix
            if stem in ("b", "bx", "bl", "blx", "it", "ite", "itt", "mov", "movs", "add", "adds", "sub", "subs",
                        "ldr", "str", "cmp", "mvn", "mvns", "orr", "orrs", "and", "ands", "eor", "eors", "lsl",
                        "lsls", "lsr", "lsrs", "asr", "asrs", "rsb", "rsbs", "vmov", "vneg", "vabs", "vadd",
                        "vsub", "vmul", "vdiv", "vcvt", "pop", "push", "ldrb", "strb", "ldrh", "strh", "umull",
                        "mul", "muls", "mla", "vmrs", "bic", "bics", "sbc", "sbcs", "adc", "adcs", "clz"):
                return stem
    return mn


def m4_cycles(mn, op_str, taken):
    """Cortex-M4(F) cycles of one executed instruction (zero wait states)."""
    m = _strip_cond(_base(mn))
    P = 3  # pipeline refill, TRM: 1-3
    if m in ("tbb", "tbh"):
        return 2 + P
    if m in ("b", "bl", "blx", "bx", "cbz", "cbnz"):
        if not taken:
            return 1
        return 1 + P
    if m == "pop":
        n = _regs(op_str)
        return 1 + n + (P if "pc" in op_str else 0)
    if m in ("push", "ldm", "ldmia", "ldmdb", "stm", "stmia", "stmdb", "vpush", "vpop", "vldmia", "vstmia", "vldmdb", "vstmdb"):
        return 1 + _regs(op_str)
    if m in ("ldrd", "strd"):
        return 3
    if m.startswith("ldr") or m.startswith("str") or m in ("vldr", "vstr"):
        if m.startswith("ldr") and op_str.startswith("pc"):
            return 2 + P
        return 2
    if m in ("sdiv", "udiv"):
        return 12
    if m in ("vdiv", "vsqrt"):
        return 14
    if m in ("vmla", "vmls", "vnmla", "vnmls", "vfma", "vfms", "vfnma", "vfnms"):
        return 3
    if m == "vmov" and op_str.count(",") == 2:
        return 2  # two core registers <-> one double / two singles
    if m in ("mov", "add") and op_str.startswith("pc"):
        return 1 + P
    return 1


def m0p_cycles(mn, op_str, taken):
    """Cortex-M0+ cycles of one executed instruction (zero wait states,
    single-cycle multiplier)."""
    m = _strip_cond(_base(mn))
    if m == "b":
        return 2 if taken else 1
    if m == "bl":
        return 3
    if m in ("bx", "blx"):
        return 2
    if m == "pop":
        n = _regs(op_str)
        return 3 + n if "pc" in op_str else 1 + n
    if m in ("push", "ldm", "ldmia", "stm", "stmia"):
        return 1 + _regs(op_str)
    if m.startswith("ldr") or m.startswith("str"):
        return 2
    if m in ("mov", "add") and op_str.startswith("pc"):
        return 2
    if m in ("dmb", "dsb", "isb"):
        return 3
    return 1


# Hand-checked costs from the manuals' tables (mnemonic, operands, taken,
# cycles), run by `--selftest` against the two functions above.
M4_CASES = [
    ("adds", "r1, #4", False, 1), ("mul", "r1, r6, fp", False, 1), ("umull", "ip, r6, r3, r0", False, 1),
    ("udiv", "r1, r2, lr", False, 12), ("ldr", "r1, [r0, #0x18]", False, 2), ("ldrd", "r2, r1, [sp]", False, 3),
    ("push", "{r4, r5, r6, r7, lr}", False, 6), ("pop", "{r7, pc}", True, 6), ("pop", "{r8, sb, fp}", False, 4),
    ("bne", "#0x100", False, 1), ("bne.w", "#0x100", True, 4), ("bl", "#0x100", True, 4), ("bx", "lr", True, 4),
    ("cbz", "r1, #0x10", False, 1), ("tbb", "[pc, r6]", True, 5), ("it", "lo", False, 1), ("moveq", "r0, r1", False, 1),
    ("vadd.f32", "s4, s4, s6", False, 1), ("vdiv.f32", "s0, s2, s0", False, 14), ("vsqrt.f32", "s0, s0", False, 14),
    ("vmla.f32", "s0, s1, s2", False, 3), ("vldr", "s2, [pc, #0x184]", False, 2), ("vmov", "d0, r0, r1", False, 2),
    ("vmov", "s0, r2", False, 1), ("vpush", "{d8, d9}", False, 5), ("vcvt.f32.s32", "s0, s0", False, 1),
]
M0P_CASES = [
    ("adds", "r4, r2, #1", False, 1), ("muls", "r4, r2, r4", False, 1), ("ldr", "r4, [pc, #8]", False, 2),
    ("str", "r4, [sp, #0x10]", False, 2), ("push", "{r4, r6, r7, lr}", False, 5), ("pop", "{r4, r5, r6, r7, pc}", True, 8),
    ("pop", "{r4, r5}", False, 3), ("b", "#0x10", True, 2), ("bne", "#0x10", False, 1), ("bne", "#0x10", True, 2),
    ("bl", "#0x100", True, 3), ("bx", "lr", True, 2), ("mov", "pc, r0", True, 2), ("stm", "r6!, {r2, r3}", False, 3),
]


def selftest():
    bad = []
    for fn, cases in ((m4_cycles, M4_CASES), (m0p_cycles, M0P_CASES)):
        for mn, op, taken, want in cases:
            got = fn(mn, op, taken)
            if got != want:
                bad.append(f"{fn.__name__}({mn} {op}, taken={taken}) = {got}, manual: {want}")
    print(f"cycle table self-test: {len(M4_CASES) + len(M0P_CASES) - len(bad)} passed, {len(bad)} failed")
    for b in bad:
        print("  " + b)
    return not bad
