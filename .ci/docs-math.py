#!/usr/bin/env python3
"""Check the generated rustdoc HTML for equations rustdoc mangled.

Equations in the doc comments are written as fenced ```text blocks (Unicode,
one term per line), which every renderer shows as written. This scans every
page under target/doc/<crate>/ (or the directory given) and fails on:

* raw display math `$$` in prose (it is not rendered without a KaTeX header);
* raw TeX commands (\\frac, \\sum, \\mathrm, ...) in prose;
* "equation bullets": a list item that is a formula fragment, which is what
  Markdown makes of a continuation line of a multi-line equation starting
  with `-` or `+` (the minus sign disappears into a bullet).

Prose is the page with <pre>, <code>, <script> and <style> elements removed.
Usage: .ci/docs-math.py [DOC_DIR]   (default: $CARGO_TARGET_DIR or target, /doc/mrr_control)
"""
import html
import os
import re
import sys

TEX = re.compile(
    r"\\(frac|sum|prod|mathrm|mathbf|operatorname|hat|dot|ddot|tilde|bar|tau|rho|epsilon|"
    r"theta|varphi|phi|lambda|mu|Delta|delta|sqrt|qquad|quad|Big|big|left|right|begin|end|"
    r"cdot|le|ge|int|infty|text|tanh|atan|sgn|sin|cos|exp)(?![A-Za-z])"
)
# Characters that make a fragment look like a formula.
MATH_CHARS = set("=+−-*/^_()|·√∑∫≤≥<>̂̇̈")
OPERATORS = set("=+−*/^_·√∑∫≤≥")
WORD = re.compile(r"[A-Za-z]{4,}")


def strip(page: str) -> str:
    for tag in ("script", "style", "pre", "code"):
        page = re.sub(rf"<{tag}\b.*?</{tag}>", " ", page, flags=re.S)
    return page


def text_of(fragment: str) -> str:
    return html.unescape(re.sub(r"<[^>]+>", " ", fragment))


def is_formula(item: str) -> bool:
    """A list item that reads as a piece of an equation, not a sentence."""
    t = item.strip()
    if not t:
        return False
    if TEX.search(t):
        return True
    if re.fullmatch(r"[\w:]+", t):
        return False  # an item path, e.g. in all.html
    words = WORD.findall(t)
    symbols = sum(c in MATH_CHARS for c in t)
    operators = sum(c in OPERATORS for c in t)
    return len(words) <= 1 and symbols >= 2 and operators >= 1


def check_page(path: str) -> list:
    raw = open(path, encoding="utf-8").read()
    # Only the documentation body: rustdoc wraps it in <section id="main-content">.
    m = re.search(r'<section id="main-content".*?</section>\s*</div>\s*</main>', raw, re.S)
    body = m.group(0) if m else raw
    prose = strip(body)
    problems = []
    text = text_of(prose)
    if "$$" in text:
        problems.append("raw $$ display math")
    for t in sorted(set(TEX.findall(text))):
        problems.append(f"raw TeX command \\{t}")
    # A bullet that names its symbols in inline code (`rotor_inertia = I_m
    # N`, kg·m²) is written as a list on purpose; an equation that Markdown
    # split into bullets is plain text, so only items without code count.
    no_pre = body
    for tag in ("script", "style", "pre"):
        no_pre = re.sub(rf"<{tag}\b.*?</{tag}>", " ", no_pre, flags=re.S)
    for item in re.findall(r"<li\b[^>]*>(.*?)</li>", no_pre, re.S):
        if "<code" in item:
            continue
        t = " ".join(text_of(item).split())
        if is_formula(t):
            problems.append(f"equation bullet: <li>{t[:70]}</li>")
    return problems


def self_test():
    assert is_formula("K_r\\,\\mathrm{sat}(r,\\epsilon_r)")
    assert is_formula("− ρ_F Y sat(r Y, ε)")
    assert not is_formula("integral: the state advances by one sample, clamped")
    assert not is_formula("f32, f64 (float)")
    assert not is_formula("sim::transmission::SHD_17_100_K3")
    assert TEX.search("\\sum_{j=1}")
    assert "raw $$ display math" in check_page_text("<p>$$ x = 1 $$</p>")
    assert check_page_text("<pre>$$ \\frac{a}{b} $$</pre><ul><li>a sentence with words</li></ul>") == []
    assert check_page_text("<ul><li>\\sum_j ρ_j Y_j</li></ul>")
    assert check_page_text("<ul><li>− ρ_F Y sat(r Y, ε)</li></ul>")
    assert check_page_text("<ul><li><code>inertia = I N</code> (kg·m², the coefficient of <code>q</code>)</li></ul>") == []


def check_page_text(page: str) -> list:
    import tempfile

    with tempfile.NamedTemporaryFile("w", suffix=".html", delete=False, encoding="utf-8") as f:
        f.write(page)
    try:
        return check_page(f.name)
    finally:
        os.unlink(f.name)


def main():
    self_test()
    if len(sys.argv) > 1:
        root = sys.argv[1]
    else:
        target = os.environ.get("CARGO_TARGET_DIR", "target")
        root = os.path.join(target, "doc", "mrr_control")
    if not os.path.isdir(root):
        sys.exit(f"{root}: no generated docs (run cargo doc first)")
    pages, failures = 0, 0
    for d, _, files in os.walk(root):
        for name in sorted(files):
            if not name.endswith(".html"):
                continue
            path = os.path.join(d, name)
            pages += 1
            for p in check_page(path):
                failures += 1
                print(f"{os.path.relpath(path, root)}: {p}")
    print(f"docs-math: {pages} pages checked, {failures} problems")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
