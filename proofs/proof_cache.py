#!/usr/bin/env python3
"""Run the exhaustive proofs whose compiled code changed; cite the rest.

An exhaustive proof (`exhaustive_*`, see proofs/mod.rs) checks a property at
every input of a type. Its verdict depends only on the machine code the test
runs, so a proof recorded for some code still holds for the same code. This
script builds the release test binary once, together with the LLVM IR that
the code generator turns into that binary (`--emit=llvm-ir,link`: with thin
LTO this is the IR after the link-time optimisation, one file per module),
and fingerprints each proof by the IR reachable from its test entry:

* roots: the functions the test harness's descriptor of the test points at
  (the test function or the closure it was inlined into);
* closure: every function, constant and static those reference, across all
  modules of the program (std's and the dependencies' included), with the
  metadata and attribute groups they use;
* canonical form: symbols defined in the program are renamed by the order in
  which the walk meets them, local values and metadata by their order in
  each definition, so names, hashes in mangled names and unrelated code do
  not enter the fingerprint; names of functions declared but defined
  nowhere in the IR (none in practice: the program is whole) stay as they
  are; the build's own paths are replaced by placeholders.

The fingerprint also covers `rustc -vV`. A proof whose fingerprint equals
the one in proofs/exhaustive-record.tsv is cited (its recorded PROOF lines,
commit and time are printed); every other proof is run from the same binary
whose IR was hashed. `--record` writes the record of the proofs that ran
and passed; `--all` runs every proof whatever the record says.

Usage (repository root):
    python3 proofs/proof_cache.py            run the changed proofs, cite the rest
    python3 proofs/proof_cache.py --all      run every proof
    python3 proofs/proof_cache.py --record   ... and record those that ran
    python3 proofs/proof_cache.py --filter S only proofs whose name contains S
    python3 proofs/proof_cache.py --hashes   print the fingerprints, run nothing
Exit status 1 when a proof that ran failed.
"""

import argparse
import datetime
import hashlib
import json
import os
import re
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
RECORD = ROOT / "proofs" / "exhaustive-record.tsv"
HEADER = "test\tfingerprint\tresult\tseconds\tcommit\tdate\trustc\tproof_lines\n"

IDENT = r'(?:"(?:[^"\\]|\\.)*"|[-a-zA-Z$._0-9]+)'
GLOBAL_REF = re.compile(r"@(" + IDENT + r")")
LOCAL_REF = re.compile(r"%(" + IDENT + r")")
LABEL_DEF = re.compile(r"^(" + IDENT + r"):", re.M)
META_REF = re.compile(r"!(\d+)\b")
ATTR_REF = re.compile(r"#(\d+)\b")
SRCLOC = re.compile(r", !srcloc !\d+")
MANGLE_HASH = re.compile(r"17h[0-9a-f]{16}E")
DEF_NAME = re.compile(r"@(" + IDENT + r")\(")


class Module:
    """The definitions of one `.ll` file."""

    def __init__(self, path):
        self.path = path
        self.defs = {}  # name -> (linkage_is_local, text)
        self.decls = set()
        self.meta = {}  # id -> text
        self.attrs = {}  # id -> text
        self.types = {}  # name -> text
        self._parse(path.read_text(errors="replace"))

    def _parse(self, text):
        lines = text.split("\n")
        i, n = 0, len(lines)
        while i < n:
            line = lines[i]
            if line.startswith("define "):
                m = DEF_NAME.search(line)
                body = [line]
                i += 1
                while i < n and lines[i] != "}":
                    body.append(lines[i])
                    i += 1
                body.append("}")
                local = " internal " in line or " private " in line
                self.defs[m.group(1)] = (local, "\n".join(body))
            elif line.startswith("declare "):
                m = DEF_NAME.search(line)
                if m:
                    self.decls.add(m.group(1))
            elif line.startswith("@"):
                m = re.match(r"@(" + IDENT + r") = ", line)
                if m:
                    local = " internal " in line[: 80 + len(m.group(0))] or " private " in line[: 80 + len(m.group(0))]
                    self.defs[m.group(1)] = (local, line)
            elif line.startswith("!"):
                m = re.match(r"!(\d+) = (.*)$", line)
                if m:
                    self.meta[m.group(1)] = m.group(2)
            elif line.startswith("attributes #"):
                m = re.match(r"attributes #(\d+) = (.*)$", line)
                if m:
                    self.attrs[m.group(1)] = m.group(2)
            elif line.startswith("%"):
                m = re.match(r"%(" + IDENT + r") = type (.*)$", line)
                if m:
                    self.types[m.group(1)] = m.group(2)
            i += 1


def demangle_path(name):
    """The path components of a legacy-mangled Rust symbol, or None."""
    name = name.strip('"')
    if not name.startswith("_ZN"):
        return None
    s, i, parts = name, 3, []
    while i < len(s) and s[i] != "E":
        j = i
        while j < len(s) and s[j].isdigit():
            j += 1
        if j == i:
            return None
        k = int(s[i:j])
        parts.append(s[j : j + k])
        i = j + k
    return parts


def normalise_paths(text, subs):
    for old, new in subs:
        text = text.replace(old, new)
    return text


class Program:
    def __init__(self, modules, subs):
        self.modules = modules
        self.subs = subs
        self.external = {}  # exported name -> module index
        for k, m in enumerate(modules):
            for name, (local, _) in m.defs.items():
                if not local and name not in self.external:
                    self.external[name] = k

    def resolve(self, mod, name):
        """(module, name) of the definition `name` refers to from `mod`."""
        if name in self.modules[mod].defs and (
            self.modules[mod].defs[name][0] or name not in self.external
        ):
            return (mod, name)
        if name in self.external:
            return (self.external[name], name)
        return None

    def fingerprint(self, roots, extra="", dump=None):
        """SHA-256 of the canonical closure of `roots` ((module, name) pairs)."""
        order = {}
        queue = []

        def visit(key):
            if key not in order:
                order[key] = len(order)
                queue.append(key)
            return order[key]

        for r in roots:
            visit(r)
        h = hashlib.sha256()
        h.update(extra.encode())
        types_seen = set()
        done = 0
        while done < len(queue):
            mod, name = queue[done]
            done += 1
            m = self.modules[mod]
            text = m.defs[name][1]

            def global_sub(match):
                ref = match.group(1)
                if ref.startswith("llvm."):
                    return "@" + ref
                target = self.resolve(mod, ref)
                if target is None:
                    return "@X:" + MANGLE_HASH.sub("E", ref)
                return "@D%d" % visit(target)

            # Inline assembly's `!srcloc` is the position of its source in
            # the compilation's source map (diagnostics only: it moves with
            # any edit anywhere in the crate and is not code).
            text = SRCLOC.sub("", text)
            text = GLOBAL_REF.sub(global_sub, text)
            text = MANGLE_HASH.sub("E", text)
            # Metadata and attribute groups used here, renamed by first use,
            # their contents appended (nested metadata followed).
            meta_ids, meta_text = {}, []
            pending = list(META_REF.findall(text))
            while pending:
                mid = pending.pop(0)
                if mid in meta_ids:
                    continue
                meta_ids[mid] = len(meta_ids)
                body = m.meta.get(mid, "?")
                body = GLOBAL_REF.sub(global_sub, body)
                pending.extend(META_REF.findall(body))
                meta_text.append(body)
            msub = lambda mm: "!m%d" % meta_ids.get(mm.group(1), -1)  # noqa: E731
            text = META_REF.sub(msub, text)
            meta_text = [META_REF.sub(msub, t) for t in meta_text]
            attr_text = []
            attr_ids = {}
            for aid in ATTR_REF.findall(text):
                if aid not in attr_ids:
                    attr_ids[aid] = len(attr_ids)
                    attr_text.append(m.attrs.get(aid, "?"))
            text = ATTR_REF.sub(lambda mm: "#a%d" % attr_ids.get(mm.group(1), -1), text)
            # Named types keep their names; their definitions are hashed once.
            locals_ = {}
            out_types = []

            def local_sub(match):
                ref = match.group(1)
                if ref in m.types:
                    if ref not in types_seen:
                        types_seen.add(ref)
                        out_types.append(ref + "=" + m.types[ref])
                    return "%" + ref
                if ref not in locals_:
                    locals_[ref] = len(locals_)
                return "%%v%d" % locals_[ref]

            text = LOCAL_REF.sub(local_sub, text)
            text = LABEL_DEF.sub(lambda mm: "%%v%d:" % locals_.setdefault(mm.group(1), len(locals_)), text)
            text = normalise_paths(text, self.subs)
            for part in [text] + meta_text + attr_text + out_types:
                if dump is not None:
                    dump.write(part + "\n")
                h.update(part.encode())
                h.update(b"\n")
            h.update(b"\x00")
        return h.hexdigest()[:16], len(queue)


def run(cmd, **kw):
    return subprocess.run(cmd, check=True, text=True, capture_output=True, cwd=ROOT, **kw).stdout


def build():
    """Build the release test binary with its IR; return (exe, ll files)."""
    cmd = ["cargo", "rustc", "--lib", "--profile", "bench", "--message-format=json",
           "--", "--emit=llvm-ir,link"]
    proc = subprocess.run(cmd, cwd=ROOT, text=True, stdout=subprocess.PIPE)
    if proc.returncode != 0:
        sys.exit("build failed: " + " ".join(cmd))
    exe = None
    for line in proc.stdout.splitlines():
        try:
            msg = json.loads(line)
        except ValueError:
            continue
        if msg.get("reason") == "compiler-artifact" and msg.get("executable") and \
                msg["target"]["name"] == "mrr_control":
            exe = msg["executable"]
    if exe is None:
        sys.exit("no test executable in cargo's output")
    lls = sorted(Path(exe).parent.glob(Path(exe).name + ".*.ll"))
    if not lls:
        sys.exit("no LLVM IR beside " + exe)
    return exe, lls


def test_roots(program, tests):
    """Map each test path to the functions its harness descriptor points at."""
    roots = {t: [] for t in tests}
    for k, m in enumerate(program.modules):
        names = {}
        for name, (_, text) in m.defs.items():
            if text.startswith("@") and " constant [" in text and " x i8] c\"" in text:
                mm = re.search(r'c"([^"]*)"', text)
                if mm and mm.group(1) in roots:
                    names[name] = mm.group(1)
        if not names:
            continue
        for name, (_, text) in m.defs.items():
            if not text.startswith("@"):
                continue
            refs = GLOBAL_REF.findall(text)
            hit = [names[r] for r in refs if r in names]
            if len(hit) != 1:
                continue
            for r in refs:
                target = program.resolve(k, r)
                if target and program.modules[target[0]].defs[target[1]][1].startswith("define"):
                    roots[hit[0]].append(target)
    return roots


def read_record():
    rec = {}
    if RECORD.exists():
        for line in RECORD.read_text().splitlines()[1:]:
            f = line.split("\t")
            if len(f) >= 8:
                rec[f[0]] = f
    return rec


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--all", action="store_true")
    ap.add_argument("--record", action="store_true")
    ap.add_argument("--hashes", action="store_true")
    ap.add_argument("--filter", default="")
    ap.add_argument("--dump", help="write the canonical text of the first selected proof to this file")
    args = ap.parse_args()

    t0 = time.time()
    exe, lls = build()
    rustc = run(["rustc", "-vV"])
    rustc_release = re.search(r"release: (\S+)", rustc).group(1)
    listing = run([exe, "--list", "--ignored"])
    tests = [line.split(": ")[0] for line in listing.splitlines()
             if line.endswith(": test") and "::exhaustive_" in line and args.filter in line]
    cargo_home = os.environ.get("CARGO_HOME", str(Path.home() / ".cargo"))
    subs = [(str(ROOT), "$ROOT"), (cargo_home, "$CARGO_HOME")]
    program = Program([Module(p) for p in lls], subs)
    roots = test_roots(program, tests)
    print("built and parsed %d IR modules in %.0f s" % (len(lls), time.time() - t0))

    record = read_record()
    commit = run(["git", "rev-parse", "--short=10", "HEAD"]).strip()
    dirty = bool(run(["git", "status", "--porcelain", "--untracked-files=no"]).strip())
    status, ran = 0, {}
    for test in tests:
        if not roots[test]:
            print("NO ROOT for %s: it will be run" % test)
            fp, size = "none", 0
        else:
            dump = open(args.dump, "w") if args.dump else None
            fp, size = program.fingerprint(sorted(roots[test]), rustc, dump)
            if dump:
                dump.close()
                args.dump = None
        if args.hashes:
            print("%s %s (%d definitions)" % (fp, test, size))
            continue
        old = record.get(test)
        if old and old[1] == fp and old[2] == "ok" and not args.all and fp != "none":
            print("CITED %s: compiled code %s unchanged since it was proven on %s (%s, %s s, rustc %s)"
                  % (test, fp, old[4], old[5], old[3], old[6]))
            for pl in old[7].split(" || "):
                if pl:
                    print("  " + pl + " [recorded]")
            continue
        why = "no record" if not old else ("forced" if args.all else "compiled code changed")
        print("RUN %s (%s; fingerprint %s)" % (test, why, fp), flush=True)
        t = time.time()
        proc = subprocess.run([exe, "--ignored", "--exact", test, "--nocapture", "--test-threads", "1"],
                              cwd=ROOT, text=True, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
        secs = time.time() - t
        sys.stdout.write(proc.stdout)
        ok = proc.returncode == 0 and "1 passed" in proc.stdout
        if not ok:
            status = 1
            print("FAILED %s" % test)
        proofs = [line[line.index("PROOF"):] for line in proc.stdout.splitlines() if "PROOF " in line]
        ran[test] = [test, fp, "ok" if ok else "FAILED", "%.1f" % secs,
                     commit + ("+" if dirty else ""),
                     datetime.date.today().isoformat(), rustc_release, " || ".join(proofs)]
        if args.record and ok:  # after each proof, so an interrupted run keeps what it proved
            record[test] = ran[test]
            if not args.filter:  # forget proofs whose test no longer exists
                record = {t: f for t, f in record.items() if t in tests}
            RECORD.write_text(HEADER + "".join("\t".join(record[t]) + "\n" for t in sorted(record)))
    if args.record:
        print("recorded %d proofs in %s" % (sum(f[2] == "ok" for f in ran.values()), RECORD.relative_to(ROOT)))
    if not args.hashes:
        print("exhaustive proofs: %d run, %d cited, %.0f s" % (len(ran), len(tests) - len(ran), time.time() - t0))
    return status


if __name__ == "__main__":
    sys.exit(main())
