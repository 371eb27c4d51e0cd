#!/usr/bin/env python3
"""Counter-guided search for the joint step's expensive inputs.

Maximises the executed instructions of a joint-step entry over the reading
space (mode-state scenario, motor position and counter, counter jump, link
count or torsion, the target's tracking errors and acceleration, expected
torque) on the emulator of `count.py`: seeded random restarts, each followed by coordinate
hill-climbing (one reading at a time, a few mutations per reading, a
mutation kept when the count grows), for a bounded time. The best vectors
found are written to `found_vectors.json`, which every `count.py` run
replays; the observed worst case then approaches the static bound from
below. Run it offline (it is not part of CI):

    .venv-embedded/bin/python embedded/search.py --seconds 300 [--seed 1]

Each vector is `(prepare_joint words, entry words)`, as in `count.py`.
"""

import argparse
import json
import os
import random
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import count  # noqa: E402

L = 1 << 17
MN = 2000 * 100
JUMPS = [0, 1, -1, 1999, -2000, 2001, -2001, 200_000, -200_000, -907_999_999, 907_999_999,
         0x7FFFFFFF, -0x80000000, 0x7FFFFFFF - 1]
LINKS = [L, L + 1, 0xFFFFFFFF, 0x80000000, 0, L - 1]

# The readings and their ranges (SI: rad, rad/s, rad/s², N·m; the step
# stores I16F16 values in the crate's stored units, which for these fields
# are the same).
COORDS = ["scenario", "seed", "pos", "c0", "jump", "link", "wrap", "ad", "e", "ev", "te"]


def random_point(rng):
    return {
        "scenario": rng.randrange(count.JOINT_SCENARIOS),
        "seed": rng.getrandbits(32),
        "pos": rng.randrange(MN) if rng.random() < 0.7 else rng.randrange(-(10**9), 10**9),
        "c0": rng.getrandbits(32),
        "jump": rng.choice([rng.randrange(-60, 60), rng.choice(JUMPS), rng.randrange(-(2**31), 2**31)]),
        "link": ("torsion", rng.choice(count.JOINT_D) + rng.randrange(-2000, 2000)) if rng.random() < 0.7
        else ("raw", rng.choice(LINKS + [rng.getrandbits(32)])),
        # a consistent link count made invalid by adding wrap * L (the
        # estimator reduces it modulo L and flags it)
        "wrap": rng.choice([0, 0, 1, rng.randrange(1 << 15)]),
        "ad": rng.choice([0.0, rng.uniform(-2000, 2000), 3e4]),
        "e": rng.choice(count.JOINT_E) * rng.uniform(0.5, 1.0),
        "ev": rng.choice(count.JOINT_EV),
        "te": rng.choice(count.JOINT_TE) + rng.uniform(-0.3, 0.3),
    }


def mutate(p, k, rng):
    q = dict(p)
    v = p[k]
    r = rng.random()
    if k == "scenario":
        q[k] = rng.randrange(count.JOINT_SCENARIOS)
    elif k == "wrap":
        q[k] = rng.choice([0, 1, rng.randrange(1 << 15)])
    elif k in ("seed", "c0"):
        q[k] = rng.getrandbits(32)
    elif k == "pos":
        q[k] = rng.randrange(MN) if r < 0.6 else rng.randrange(-(10**9), 10**9)
    elif k == "jump":
        q[k] = (rng.choice(JUMPS) if r < 0.3 else int(v * rng.uniform(0.5, 1.5)) if r < 0.6
                else rng.randrange(-(2**31), 2**31) if r < 0.8 else v + rng.randrange(-100, 100))
        q[k] = max(-(2**31), min(2**31 - 1, q[k]))
    elif k == "link":
        if r < 0.5:
            d = p["link"][1] if p["link"][0] == "torsion" else 0
            q[k] = ("torsion", rng.choice([int(d * rng.uniform(0.8, 1.2)), rng.choice(count.JOINT_D),
                                           rng.randrange(-25_000_000, 25_000_000)]))
        else:
            q[k] = ("raw", rng.choice(LINKS + [rng.getrandbits(32), L + rng.getrandbits(20)]))
    else:
        span = {"ad": 3e4, "e": 30, "ev": 40, "te": 60}[k]
        menu = {"e": count.JOINT_E, "ev": count.JOINT_EV, "te": count.JOINT_TE, "ad": [0.0, 3e4, -3e4]}.get(k, [0.0])
        q[k] = (rng.choice(menu) if r < 0.3 else v * rng.uniform(0.7, 1.3) if r < 0.7
                else rng.uniform(-span, span))
    return q


def words(p, f):
    """(prepare words, entry words) of a point, `f` the value -> word map."""
    if p["link"][0] == "torsion":
        # a reading consistent with torsion D (counts of 2π/(LMN)), as in
        # count.joint_est_case: position -p, counter c0 - jump
        pp = p["pos"] % MN
        pe = (pp + p["jump"]) % MN
        lc = ((p["link"][1] - pe * L) // MN) % L
        lc += min(p.get("wrap", 0), (0xFFFFFFFF - lc) // L) * L
        pos, m = -pp, (p["c0"] - p["jump"]) & 0xFFFFFFFF
    else:
        lc, pos, m = p["link"][1], p["pos"], (p["c0"] + p["jump"]) & 0xFFFFFFFF
    pre = [pos & 0xFFFFFFFF, (pos >> 32) & 0xFFFFFFFF, p["c0"], p["scenario"], p["seed"]]
    # The target: tracking errors e, ė (motor side) from the position and
    # speed the step measures from the counts.
    args = count.joint_args(pos, p["c0"], lc, m, p["e"], p["ev"], p["ad"], p["te"], f)
    return pre, args


def search(fw, entry, f, mask, seconds, rng, keep=8, pinned=False):
    def evaluate(p):
        pre, args = words(p, f)
        return recount(fw, entry, mask, {"pre": pre, "args": args})

    t_end = time.time() + seconds
    found, evals = [], 0
    restarts = 0
    while time.time() < t_end:
        cur = random_point(rng)
        if restarts % 3 == 2 or pinned:
            # every third restart from an invalid link count with a counter
            # jump of an output revolution or more (a known expensive pair)
            cur["link"] = (("raw", rng.choice([L, 0xFFFFFFFF, L + rng.getrandbits(16)])) if rng.random() < 0.3
                           else ("torsion", rng.choice(count.JOINT_D)))
            cur["wrap"] = rng.choice([1, rng.randrange(1, 1 << 15)])
            cur["jump"] = rng.choice([-907_999_999, 907_999_999, rng.randrange(-(2**31), -(10**8))])
        restarts += 1
        c = evaluate(cur)
        evals += 1
        improved = True
        while improved and time.time() < t_end:
            improved = False
            coords = [k for k in COORDS if not (pinned and k in ("wrap", "jump"))]
            for k in rng.sample(coords, len(coords)):
                for _ in range(4):
                    q = mutate(cur, k, rng)
                    n = evaluate(q)
                    evals += 1
                    if n > c:
                        cur, c, improved = q, n, True
                    elif n == c and rng.random() < 0.2:
                        cur = q  # drift along a plateau
        found.append((c, cur))
    found.sort(key=lambda t: -t[0])
    out, seen = [], set()
    for c, p in found:
        pre, args = words(p, f)
        key = tuple(pre + args)
        if key in seen:
            continue
        seen.add(key)
        out.append({"pre": pre, "args": args, "count": c})
        if len(out) >= keep:
            break
    return out, evals, len(found)


def recount(fw, entry, mask, v):
    """The executed instructions of a vector (`pre`, `args` words) on this
    firmware (-1 if its preparation or step does not return)."""
    pre = list(v["pre"])
    pre[3] |= mask
    if fw.call("prepare_joint", pre, limit=5_000_000)[3] != "ok":
        return -1
    n, _, _, st = fw.call(entry, v["args"], count=True)
    return n if st == "ok" else -1


TARGETS = [  # (core, image, entry, word map, prepare mask)
    ("M4F", "main", "joint_f32", count.f32w, count.MASK[("f32", "stop")]),
    ("M0+", "main", "joint_i16f16", count.xw, count.MASK[("x", "stop")]),
    ("M4F", "variants", "joint_passive_f32", count.f32w, count.MASK[("f32", "passive")]),
    ("M0+", "variants", "joint_passive_i16f16", count.xw, count.MASK[("x", "passive")]),
]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--seconds", type=float, default=120, help="per entry")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--only", help="entries containing this")
    ap.add_argument("--no-build", action="store_true")
    ap.add_argument("--out", default=count.FOUND_PATH)
    ap.add_argument("--pinned", action="store_true",
                    help="every restart from an invalid link count with a large counter jump, kept fixed")
    args = ap.parse_args()
    target_dir = os.environ.get("CARGO_TARGET_DIR", os.path.join(count.HERE, "target"))
    data = {}
    if os.path.exists(args.out):
        with open(args.out) as fh:
            data = json.load(fh)
    for image in ("variants", "main"):
        for core_key, img, entry, f, mask in TARGETS:
            if img != image or (args.only and args.only not in entry):
                continue
            core = count.CORES[core_key]
            path = (count.elf_path(core, "release", target_dir, image) if args.no_build
                    else count.build(core, "release", target_dir, image))
            fw = count.Firmware(core, path)
            rng = random.Random(f"{args.seed} {core_key} {entry}")
            out, evals, restarts = search(fw, entry, f, mask, args.seconds, rng, pinned=args.pinned)
            key = f"{core_key} {entry}"
            # The kept vectors' counts are from the code they were found on:
            # count them again on this firmware, so that a vector found now
            # is ranked against what the kept ones cost today.
            old = [dict(v, count=recount(fw, entry, mask, v)) for v in data.get(key, [])]
            merged = sorted(old + out, key=lambda v: -v["count"])
            dedup, seen = [], set()
            for v in merged:
                k = tuple(v["pre"] + v["args"])
                if k not in seen:
                    seen.add(k)
                    dedup.append(v)
            data[key] = dedup[:8]
            print(f"{key}: {evals} evaluations, {restarts} restarts in {args.seconds:.0f} s; best "
                  f"{out[0]['count'] if out else '-'} (kept: {[v['count'] for v in data[key]]})", flush=True)
    with open(args.out, "w") as fh:
        json.dump(data, fh, indent=1)
        fh.write("\n")


if __name__ == "__main__":
    main()
