#!/usr/bin/env python3
"""Bound, observed worst case and an output fingerprint of the budgeted steps.

For each joint and wrist entry of `count.py`'s table (or the entries named),
builds the release image the entry lives in, prints its static bound
(`wcet.py`), the largest instruction count the emulator executed over the
entry's argument vectors, the median, and a SHA-1 prefix of every output
word of every vector. Two builds whose fingerprints are equal produced the
same output bits on every vector: the check that a change meant to shorten
the code left its results alone.

Usage (from embedded/):
    perfcheck.py              the default joint and wrist steps on both cores
    perfcheck.py --all        every budgeted joint and wrist row
    perfcheck.py ENTRY ...    e.g. perfcheck.py joint_f32 wrist_i16f16
CARGO_TARGET_DIR selects the build directory (default embedded/target).
"""

import hashlib
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import count  # noqa: E402


def main():
    args = sys.argv[1:]
    if any(a in ("-h", "--help") for a in args):
        print(__doc__)
        return
    target_dir = os.environ.get("CARGO_TARGET_DIR", os.path.join(HERE, "target"))
    budgeted = [s for s in count.all_steps() if s.max_insns and s.entry.startswith(("joint", "wrist"))]
    if args == ["--all"]:
        want = [s.entry for s in budgeted]
    else:
        want = args or ["joint_f32", "joint_i16f16", "wrist_f32", "wrist_i16f16"]
    steps = {}
    for s in budgeted:
        steps.setdefault(s.entry, s)
    missing = [e for e in want if e not in steps]
    if missing:
        sys.exit(f"not a budgeted joint or wrist entry: {', '.join(missing)}")
    built = {}
    for e in want:
        s = steps[e]
        core = count.CORES[s.core]
        if (s.core, s.image) not in built:
            built[(s.core, s.image)] = count.build(core, "release", target_dir, s.image)
        elf = built[(s.core, s.image)]
        line = subprocess.run([sys.executable, os.path.join(HERE, "wcet.py"), elf, e, "--cycles-core", s.core],
                              capture_output=True, text=True, check=True).stdout.split("\n")[0]
        bound = line.split(":", 1)[1].split(";")[0].strip()
        r = count.measure(count.Firmware(core, elf), e, s.vectors, s.prepare, mask=s.prep_mask)
        digest = hashlib.sha1(repr(r.outputs).encode()).hexdigest()[:12]
        print(f"{e:26s} {s.core:4s} {bound:34s} observed {r.insns:6d} median {r.median:6d} "
              f"outputs {digest} bad {len(r.bad)}", flush=True)


if __name__ == "__main__":
    main()
