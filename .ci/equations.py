#!/usr/bin/env python3
"""Check docs/EQUATIONS.md: every equation of the covered chapters has a row,
and every implemented row names a file whose comments cite the number, as
"(X.Y)" or inside a range such as "X.A–X.B" / "(X.A)–(X.B)"."""
import re
import sys
from pathlib import Path

# chapter -> number of equations covered by the index
CHAPTERS = {2: 40, 3: 10, 4: 33, 5: 29, 6: 35}

root = Path(__file__).resolve().parent.parent
rows = {}
for line in (root / "docs/EQUATIONS.md").read_text().splitlines():
    cells = [c.strip() for c in line.strip().strip("|").split("|")]
    if len(cells) == 5 and re.fullmatch(r"\d+\.\d+", cells[0]):
        rows[cells[0]] = cells

RANGE = re.compile(r"\(?(\d+)\.(\d+)\)?\s*[–-]\s*\(?(\d+)\.(\d+)\)?")


def cited(text, ch, k):
    comments = "\n".join(l for l in text.splitlines() if l.lstrip().startswith("//"))
    if f"({ch}.{k})" in comments:
        return True
    for m in RANGE.finditer(comments):
        a, b, c, d = map(int, m.groups())
        if a == c == ch and b <= k <= d:
            return True
    return False


bad = []
for ch, n in CHAPTERS.items():
    for k in range(1, n + 1):
        key = f"{ch}.{k}"
        row = rows.get(key)
        if row is None:
            bad.append(f"eq. ({key}): no row in docs/EQUATIONS.md")
            continue
        status, path = row[2], row[3]
        if status.startswith("implemented") or status == "checked":
            f = root / path
            if not f.is_file():
                bad.append(f"eq. ({key}): file {path} does not exist")
            elif not cited(f.read_text(), ch, k):
                bad.append(f"eq. ({key}): {path} does not cite it")
        elif status.startswith("declined"):
            if len(row[4]) < 10:
                bad.append(f"eq. ({key}): declined without a reason")
        else:
            bad.append(f"eq. ({key}): unknown status {status!r}")
total = sum(CHAPTERS.values())
if bad:
    print("\n".join(bad))
    print(f"equation index: {len(bad)} problems")
    sys.exit(1)
print(f"equation index: all {total} equations of chapters {sorted(CHAPTERS)} found")
