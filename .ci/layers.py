#!/usr/bin/env python3
"""Imports point down the layers: no import cycle between source files.

Rust (src/): every file is a module (`src/a/b.rs` and `src/a/b/mod.rs` are
`a::b`); a file imports module `m` when its code names a path into `m`
(`crate::m::…`, `super::…`, `self::…` resolved from the file's module, or
`use` of them), its own tests excluded (a `#[cfg(test)] mod tests` block at
the end of a file, and files named `tests.rs`, may look anywhere). Python
(embedded/): `import x` / `from x import` of a sibling file.

A cycle between files fails the check, except the ones listed in KNOWN
below, each a debt with its reason; a listed cycle that no longer exists
fails too, so the list only shrinks.
"""
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

# Cycles still to remove (sorted member files), with the reason they exist.
KNOWN = set()


def rust_modules():
    mods = {}
    for f in sorted((ROOT / "src").rglob("*.rs")):
        rel = f.relative_to(ROOT / "src")
        parts = list(rel.with_suffix("").parts)
        if parts[-1] in ("mod", "lib"):
            parts = parts[:-1]
        if parts and parts[-1] == "tests":
            continue
        mods[tuple(parts)] = f
    return mods


def strip_tests(text):
    """The file without its trailing `#[cfg(test)] mod tests { … }` block."""
    m = re.search(r"^#\[cfg\(test\)\]\s*\n(?:#\[[^\n]*\]\s*\n)*mod tests\s*\{", text, re.M)
    return text[: m.start()] if m else text


def resolve(mods, here, path):
    """The longest known module that a `::`-path from module `here` names."""
    segs = path.split("::")
    if segs[0] == "crate":
        base, segs = [], segs[1:]
    elif segs[0] in ("super", "self"):
        base = list(here)
        while segs and segs[0] in ("super", "self"):
            if segs[0] == "super":
                base = base[:-1]
            segs = segs[1:]
    else:
        return None
    for k in range(len(segs), -1, -1):
        cand = tuple(base + segs[:k])
        if cand in mods:
            return cand
    return None


def rust_graph():
    mods = rust_modules()
    graph = {}
    for mod, f in mods.items():
        text = strip_tests(f.read_text())
        text = re.sub(r"//[^\n]*", "", text)  # comments and doc comments
        deps = set()
        # `use a::{b, c::d}` groups: expand one level of braces.
        for m in re.finditer(r"\b((?:crate|super|self)(?:::\w+)*)::\{([^}]*)\}", text):
            for item in m.group(2).split(","):
                item = item.strip().split(" as ")[0]
                if item:
                    t = resolve(mods, mod, m.group(1) + "::" + item.split("::{")[0])
                    if t:
                        deps.add(t)
        for m in re.finditer(r"\b((?:crate|super|self)(?:::\w+)+)", text):
            t = resolve(mods, mod, m.group(1))
            if t:
                deps.add(t)
        # A module's own children and itself are not imports.
        graph[str(f.relative_to(ROOT))] = {
            str(mods[d].relative_to(ROOT)) for d in deps
            if d != mod and d[: len(mod)] != mod
        }
    return graph


def python_graph():
    files = {p.stem: p for p in (ROOT / "embedded").glob("*.py")}
    graph = {}
    for name, p in files.items():
        text = p.read_text()
        deps = set(re.findall(r"^\s*import (\w+)", text, re.M)) | set(
            re.findall(r"^\s*from (\w+) import", text, re.M))
        graph[str(p.relative_to(ROOT))] = {
            str(files[d].relative_to(ROOT)) for d in deps if d in files and d != name}
    return graph


def cycles(graph):
    """Strongly connected components of more than one file (Tarjan)."""
    index, low, stack, on, out, counter = {}, {}, [], set(), [], [0]
    sys.setrecursionlimit(10000)

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in graph.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(tuple(sorted(comp)))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def layer_graph(graph):
    """The same imports between top-level modules of src/ (`scalar`,
    `control`, `sim`, …; `lib.rs`, `error.rs` and `joint.rs` are their own),
    where a parent's re-export of its child does not hide a cycle."""
    def layer(f):
        parts = Path(f).relative_to("src").with_suffix("").parts
        return "src/" + parts[0].removesuffix(".rs") if parts else f
    out = {}
    for f, deps in graph.items():
        if not f.startswith("src/"):
            continue
        a = layer(f)
        out.setdefault(a, set()).update(layer(d) for d in deps if layer(d) != a)
    return out


def main():
    graph = rust_graph()
    graph.update(python_graph())
    found = set(cycles(graph)) | set(cycles(layer_graph(graph)))
    bad = False
    layers = layer_graph(graph)
    for c in sorted(found - KNOWN):
        bad = True
        print("import cycle:", " <-> ".join(c))
        for f in c:
            g = graph if f in graph else layers
            print("   ", f, "imports", sorted(set(g[f]) & set(c)))
    for c in sorted(KNOWN - found):
        bad = True
        print("listed as a known cycle but gone (remove it from KNOWN in .ci/layers.py):", c)
    for c in sorted(found & KNOWN):
        print("known cycle (to remove):", " <-> ".join(c))
    print("layers: %d files, %d cycles (%d known)" % (len(graph), len(found), len(found & KNOWN)))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
