#!/usr/bin/env python3
"""Where a step's instructions go: runs one entry of count.py's table on its
worst-case argument vector (or on every vector, `--all`) in the emulator,
counts executed instructions per address and attributes them to source
through the DWARF line tables of the `release-lines` profile (the `release`
source with line tables, which can change some of LLVM's choices: its
counts are close to the counted image's, not always equal;
`llvm-addr2line -i` resolves the inlined frames).

Prints, for the chosen entry: instructions by innermost function, by
function at any inline depth (inclusive), and the hottest source lines.

Usage: profile.py ENTRY [--all] [--top N]     e.g. profile.py joint_i16f16
"""

import argparse
import collections
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import count  # noqa: E402
from unicorn import UC_HOOK_CODE  # noqa: E402


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("entry")
    p.add_argument("--all", action="store_true", help="sum over every argument vector, not only the worst")
    p.add_argument("--top", type=int, default=25)
    p.add_argument("--no-build", action="store_true")
    args = p.parse_args()
    step = next(s for s in count.all_steps() if args.entry in (s.entry, s.reference))
    core = count.CORES[step.core]
    target_dir = os.environ.get("CARGO_TARGET_DIR", os.path.join(count.HERE, "target"))
    elf = (count.elf_path(core, "release-lines", target_dir, step.image) if args.no_build
           else count.build(core, "release-lines", target_dir, step.image))
    fw = count.Firmware(core, elf)
    res = count.measure(fw, args.entry, step.vectors, step.prepare, mask=step.prep_mask)
    print(f"{args.entry}: worst {res.insns} instructions (median {res.median}) over {len(step.vectors)} vectors")
    if args.all:
        vectors = step.vectors
    else:
        vectors = [v for v in step.vectors if (v[1] if isinstance(v, tuple) else v) == res.worst_args][:1]
    hits = collections.Counter()

    def hook(uc, addr, size, _):
        if fw.counting:
            hits[addr] += 1

    h = fw.uc.hook_add(UC_HOOK_CODE, hook)
    fw.uc.ctl_flush_tb()
    try:
        for v in vectors:
            pre, a = v if isinstance(v, tuple) else (None, v)
            if pre is not None and step.prepare:
                if step.prep_mask:
                    pre = pre[:3] + [pre[3] | step.prep_mask] + pre[4:]
                fw.call(step.prepare, pre, limit=5_000_000)
            fw.call(args.entry, a, count=True)
    finally:
        fw.uc.hook_del(h)
    addrs = sorted(hits)
    out = subprocess.run(["llvm-addr2line", "-a", "-i", "-f", "-C", "-e", elf] + [hex(a) for a in addrs],
                         capture_output=True, text=True, check=True).stdout.splitlines()
    # With -a each address's group starts with the address itself, then
    # (function, file:line) pairs, innermost first.
    groups = []
    for line in out:
        if line.startswith("0x"):
            groups.append([])
        else:
            groups[-1].append(line)
    if len(groups) != len(addrs):
        sys.exit(f"addr2line gave {len(groups)} groups for {len(addrs)} addresses")
    inner, incl, lines = collections.Counter(), collections.Counter(), collections.Counter()
    sites = collections.Counter()
    total = sum(hits.values())
    for a, g in zip(addrs, groups):
        frames = [(g[i], g[i + 1]) for i in range(0, len(g) - 1, 2)]
        n = hits[a]
        inner[short(frames[0][0])] += n
        lines[loc(frames[0][1]) + "  " + short(frames[0][0])] += n
        for f in {short(f) for f, _ in frames}:
            incl[f] += n
        # The call site: the innermost frame in the library outside the
        # scalar layer (the code that asked for the product or kernel).
        site = next((fr for fr in frames if "src/" in fr[1] and "/scalar/" not in fr[1]
                     and "rustc" not in fr[1] and ".cargo" not in fr[1]), frames[-1])
        sites[loc(site[1]) + "  " + short(site[0])] += n
    print(f"{total} instructions executed (unicorn code hook, condition-failed IT slots not included)\n")
    for title, c in (("innermost function", inner), ("inclusive (any inline depth)", incl), ("source line", lines),
                     ("call site outside the scalar layer", sites)):
        print(f"-- by {title}")
        for k, n in c.most_common(args.top):
            print(f"{n:7d}  {k}")
        print()


def short(f):
    f = f.replace("mrr_control::", "").replace("<fixed::FixedI32<typenum::bit::B0, typenum::uint::UInt<typenum::uint::UInt<typenum::uint::UInt<typenum::uint::UInt<typenum::uint::UInt<typenum::uint::UTerm, typenum::bit::B1>, typenum::bit::B0>, typenum::bit::B0>, typenum::bit::B0>, typenum::bit::B0>>", "<I16F16")
    return f[:140]


def loc(s):
    s = s.split(" (discriminator")[0]
    for pre in ("/work/main/", os.path.expanduser("~/.cargo/registry/src/")):
        s = s.replace(pre, "")
    i = s.find("/src/")
    return s if i < 0 or s.startswith("src/") else s[i + 1:] if "rustc" in s else s


if __name__ == "__main__":
    main()
