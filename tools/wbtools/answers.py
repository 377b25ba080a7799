"""No answer in the student pack (issue 29, docs/pack.md "No answer in the pack").

Provided code that does what a task asks ships compiled only (COMPILED_ONLY: the pack holds a
replacement source that calls the student's own function, and prebuilt/ holds the real one
compiled) or calls the student's function itself (framework/drivers/rigid/rigid_world.cpp).
`overlaps` recognises a shipped source that computes what a task's solution computes: the
solution file's text, its identifiers blanked (names differ, the computation does not), cut
into runs of K tokens; the runs that also appear in the task's specification (the lab's
headers and skeletons, its tests and tests/common: the formulas the handouts and tests state
on purpose) are left out; a shipped source holding SHARE or more of the rest is an answer,
unless ALLOWED says why it is not. Measured on 2026-12-03 (k = 16): the fast path held 26 %
of backward_euler.cpp and 14 % of assemble_system.cpp, rigid_world.cpp's passes 9 % of
plane_contact.cpp; unrelated framework files at most 3 %.

Trust: reads the checkout (and a staged pack); nothing else."""
import glob
import os
import re

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
K = 16        # tokens per run
SHARE = 0.08  # of a solution file's own runs found in one shipped file: an answer

# Shipped compiled only when the pack holds the lab (path: lab). The pack ships the file of
# the same path under tools/pack.d/compiled-only/ in its place; prebuilt/ holds the real one.
COMPILED_ONLY = {"framework/drivers/implicit/fast_backward_euler.cpp": "implicit"}
FALLBACKS = os.path.join(ROOT, "tools", "pack.d", "compiled-only")

# Overlaps that are not answers, and why (shipped path, solution path relative to solutions/).
ALLOWED = {
    ("framework/src/semi_implicit.cpp", "euler/symplectic_euler.cpp"):
        "the provided semi-implicit Euler step every lab's scenes run with (E2's two lines, "
        "which handouts/euler.md states): left for the lead to decide (issue 29 report)",
    ("framework/src/semi_implicit.cpp", "euler/explicit_euler.cpp"):
        "the same provided step (one evaluation at the start, then two updates)",
    ("framework/src/rk4.cpp", "midpoint/trapezoid.cpp"):
        "the provided RK4 reference integrator: its stages share the shape of any two-stage "
        "step: left for the lead to decide (issue 29 report)",
    ("framework/src/rk4.cpp", "midpoint/midpoint.cpp"):
        "the provided RK4 reference integrator (its first two stages are a midpoint stage)",
}

_TOK = re.compile(r"[A-Za-z_]\w*|\d[\w.]*|::|->|<<|>>|<=|>=|==|!=|&&|\|\||[-+*/%=<>!&|^~?:;,.(){}\[\]]")
_KEEP = {"for", "if", "else", "return", "const", "double", "int", "auto", "std", "Eigen", "while"}


def tokens(text):
    """C++ tokens without comments, strings and directives, identifiers blanked to ID except
    members (after . -> ::) and a few keywords."""
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    text = re.sub(r"//[^\n]*", "", text)
    text = re.sub(r'"(\\.|[^"\\])*"', '"s"', text)
    text = "\n".join(l for l in text.split("\n") if not l.lstrip().startswith("#"))
    toks = _TOK.findall(text)
    return [t if not re.match(r"[A-Za-z_]", t) or t in _KEEP or (i and toks[i - 1] in (".", "->", "::"))
            else "ID" for i, t in enumerate(toks)]


def runs(text, k=K):
    t = tokens(text)
    return {tuple(t[i:i + k]) for i in range(len(t) - k + 1)}


def _read(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        return f.read()


def solution_runs(lab, root=ROOT):
    """{solution file relative to solutions/: its runs not in the lab's specification}."""
    spec = set()
    for f in (glob.glob(os.path.join(root, "labs", lab, "*")) +
              glob.glob(os.path.join(root, "tests", lab, "*.cpp")) +
              glob.glob(os.path.join(root, "tests", lab, "*.h")) +
              glob.glob(os.path.join(root, "tests", "common", "*.h"))):
        if os.path.isfile(f):
            spec |= runs(_read(f))
    out = {}
    for s in sorted(glob.glob(os.path.join(root, "solutions", lab, "*.cpp"))):
        out[f"{lab}/{os.path.basename(s)}"] = runs(_read(s)) - spec
    return out


def overlaps(shipped, labs, root=ROOT):
    """[(shipped path, solution, share, allowed reason or "")] for every shipped source
    (shipped: {path relative to the pack: text}) holding SHARE or more of a packed lab's
    solution file."""
    found = []
    sols = {}
    for lab in labs:
        if os.path.isdir(os.path.join(root, "solutions", lab)):
            sols.update(solution_runs(lab, root))
    for rel, text in sorted(shipped.items()):
        if not rel.endswith((".cpp", ".h")):
            continue
        mine = runs(text)
        for sol, sr in sols.items():
            if not sr:
                continue
            share = len(mine & sr) / len(sr)
            if share >= SHARE:
                found.append((rel, sol, share, ALLOWED.get((rel, sol), "")))
    return found


def repo_shipped(labs, root=ROOT):
    """The provided sources a pack of `labs` ships, read from the checkout: framework/ (the
    COMPILED_ONLY files as the pack ships them)."""
    out = {}
    for path in glob.glob(os.path.join(root, "framework", "**", "*"), recursive=True):
        if not os.path.isfile(path):
            continue
        rel = os.path.relpath(path, root).replace(os.sep, "/")
        parts = rel.split("/")
        if parts[1] == "drivers" and parts[2] not in labs:
            continue
        if rel in COMPILED_ONLY and COMPILED_ONLY[rel] in labs:
            path = os.path.join(FALLBACKS, rel)
        out[rel] = _read(path)
    return out
