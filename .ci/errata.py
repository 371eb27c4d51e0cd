#!/usr/bin/env python3
"""Check docs/ERRATA.md (format described at the top of that file):

* entries are `### E<ch>.<k> — title` under `## Chapter <ch>`, numbered
  1, 2, 3 ... per chapter with no gaps;
* every entry has at least one `*Rerun:* `cargo test ...`` line;
* each such command names its target (`--lib` or `--test NAME`), enables
  the features that target needs (the `#![cfg(feature = ...)]` of a test
  file; `#[cfg(feature = ...)] pub mod m;` of src/lib.rs for lib tests under
  `m::`), and every one of its filters selects at least one test.

The tests are built once (`cargo test --all-features --no-run`); each
command's tests are then listed (`-- --list`), which runs no test.
"""
import re
import shlex
import subprocess
import sys
from pathlib import Path

root = Path(__file__).resolve().parent.parent
text = (root / "docs/ERRATA.md").read_text()
errors = []

# --- numbering -------------------------------------------------------------
entries = []  # (id, body)
chapter = None
seen = {}
for m in re.finditer(r"^(## Chapter (\d+)|### (E(\d+)\.(\d+)) — .*)$", text, re.M):
    if m.group(2):
        chapter = int(m.group(2))
        continue
    ch, k = int(m.group(4)), int(m.group(5))
    if ch != chapter:
        errors.append(f"{m.group(3)} is under chapter {chapter}")
    if k != seen.get(ch, 0) + 1:
        errors.append(f"{m.group(3)}: expected E{ch}.{seen.get(ch, 0) + 1} (no gaps)")
    seen[ch] = k
    entries.append((m.group(3), m.end()))
bodies = []
for i, (eid, start) in enumerate(entries):
    end = entries[i + 1][1] if i + 1 < len(entries) else len(text)
    body = text[start:end]
    nxt = re.search(r"^#{2,3} ", body, re.M)
    bodies.append((eid, body[: nxt.start()] if nxt else body))
if not entries:
    errors.append("no entries found")

# --- feature requirements ----------------------------------------------------
lib_gates = {}
lib = (root / "src/lib.rs").read_text()
for m in re.finditer(r'#\[cfg\(feature\s*=\s*"(\w+)"\)\]\s*pub mod (\w+);', lib):
    lib_gates[m.group(2)] = m.group(1)


def test_file_feature(name):
    f = root / "tests" / f"{name}.rs"
    if not f.exists():
        return None
    m = re.search(r'#!\[cfg\(feature\s*=\s*"(\w+)"\)\]', f.read_text())
    return m.group(1) if m else None


# --- commands ------------------------------------------------------------------
commands = []  # (id, argv)
for eid, body in bodies:
    found = re.findall(r"^\*Rerun:\* `([^`]+)`\s*$", body, re.M)
    if not found:
        errors.append(f"{eid}: no `*Rerun:* `cargo test ...`` line")
    for c in found:
        commands.append((eid, c))

print("building the tests once (cargo test --all-features --no-run)", flush=True)
subprocess.run(["cargo", "test", "--all-features", "--no-run", "-q"], cwd=root, check=True)

for eid, cmd in commands:
    argv = shlex.split(cmd)
    if argv[:2] != ["cargo", "test"]:
        errors.append(f"{eid}: `{cmd}` is not a `cargo test` command")
        continue
    args = argv[2:]
    if "--" in args:
        i = args.index("--")
        before, after = args[:i], args[i + 1 :]
    else:
        before, after = args, []
    features, target, filters, flags = set(), None, [], []
    all_features = False
    j = 0
    while j < len(before):
        a = before[j]
        if a == "--features":
            features |= set(re.split(r"[ ,]+", before[j + 1]))
            j += 2
            continue
        if a == "--all-features":
            all_features = True
        elif a == "--lib":
            target = ["--lib"]
        elif a == "--test":
            target = ["--test", before[j + 1]]
            j += 2
            continue
        elif a.startswith("-"):
            flags.append(a)
        else:
            filters.append(a)
        j += 1
    for a in after:
        if a in ("--exact",):
            flags.append(a)
        elif not a.startswith("-"):
            filters.append(a)
    if target is None:
        errors.append(f"{eid}: `{cmd}` names no target (--lib or --test NAME)")
        continue
    if not filters:
        errors.append(f"{eid}: `{cmd}` has no test filter")
        continue
    if target[0] == "--test":
        need = test_file_feature(target[1])
        if need and not (all_features or need in features):
            errors.append(f"{eid}: `{cmd}` needs --features {need} (tests/{target[1]}.rs)")
    listed = subprocess.run(
        ["cargo", "test", "-q", "--all-features", *target, "--", "--list", *flags],
        cwd=root, capture_output=True, text=True,
    )
    if listed.returncode != 0:
        errors.append(f"{eid}: listing `{cmd}` failed:\n{listed.stderr[-2000:]}")
        continue
    names = [l[: -len(": test")] for l in listed.stdout.splitlines() if l.endswith(": test")]
    exact = "--exact" in flags
    for f in filters:
        hits = [n for n in names if (n == f if exact else f in n)]
        if target == ["--lib"]:
            # A lib test under a feature-gated module needs that feature.
            for n in hits:
                need = lib_gates.get(n.split("::")[0])
                if need and not (all_features or need in features):
                    errors.append(f"{eid}: `{cmd}`: {n} needs --features {need}")
                    break
        if not hits:
            errors.append(f"{eid}: filter `{f}` of `{cmd}` selects no test")
        else:
            print(f"  {eid}: {f} -> {len(hits)} test(s)")

if errors:
    print("\ndocs/ERRATA.md check failed:")
    for e in errors:
        print("  " + e)
    sys.exit(1)
print(f"docs/ERRATA.md: {len(entries)} entries, {len(commands)} rerun commands, all select tests")
