"""What the docs quote from the code, checked against the code (tools/pattern docrefs).

Every Markdown file of the repository is read (docs/, handouts/, the READMEs, the pack's
README template), and three kinds of quotation are checked, each where a script can tell
what is meant:

  flags      a command in a code span or a ```sh block that starts with a tool
             (tools/<name>) or a lab executable (build/bin/<lab>): each --flag it gives
             must be one that program defines (a Python tool's argparse add_argument, a
             bash tool's case labels, the labs' CLI11 add_option/add_flag in framework/)
  calls      a call quoted as name(a, b, ...) in a code span: for a task function of a
             lab (declared in labs/<lab>/*.h) the arguments must be the header's parameter
             names, in order; for a Python function of tools/ (or module.name(...)) the
             number of arguments must be one some definition of that name accepts, and a
             keyword argument must be one of its parameters
  paths      a repository path in a code span or a link (tools/..., docs/..., labs/...):
             it must exist (a pattern with <placeholder> or * must match something)

Names the code does not define (std::sqrt, math in prose) are not checked. A quotation with
"..." in it stands for more than it says and is not checked either."""
import ast
import glob
import os
import re

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
TOOLS = os.path.join(ROOT, "tools")

CODE_SPAN = re.compile(r"(`+)(.+?)\1", re.S)
FENCE = re.compile(r"^```([A-Za-z]*)\n(.*?)^```", re.S | re.M)
CALL = re.compile(r"(?<![\w.:>])((?:[A-Za-z_]\w*(?:\.|::))*)([A-Za-z_]\w*)\(([^()]*)\)")
FLAG = re.compile(r"^--[a-z][a-z0-9-]*$")
PATH_TOPS = ("tools", "docs", "labs", "tests", "scenes", "framework", "handouts", "cmake",
             "bench", "fuzz", "solutions")
PATH = re.compile(r"^(?:\.\./)*((?:" + "|".join(PATH_TOPS) + r")/[A-Za-z0-9_./<>*{}-]*)$")
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")


def markdown_files(root=ROOT):
    """Every Markdown file of the repository (not build trees, not .git), relative, sorted."""
    out = []
    for d, dirs, names in os.walk(root):
        dirs[:] = sorted(x for x in dirs if not x.startswith((".", "build")) and
                         x != "__pycache__")
        out += [os.path.relpath(os.path.join(d, n), root) for n in names if n.endswith(".md")]
    return sorted(out)


def quotations(text):
    """(line, kind, text) of every code span ("span") and every line of a fenced block
    ("block:<language>", e.g. "block:sh", "block:"); the fenced blocks' text is not searched
    for spans."""
    out, blocks = [], []
    for m in FENCE.finditer(text):
        first = text.count("\n", 0, m.start(2)) + 1
        for k, line in enumerate(m.group(2).split("\n")):
            out.append((first + k, "block:" + m.group(1), line))
        blocks.append((m.start(), m.end()))
    rest = text
    for a, b in reversed(blocks):
        rest = rest[:a] + "\n" * text.count("\n", a, b) + rest[b:]
    for m in CODE_SPAN.finditer(rest):
        out.append((rest.count("\n", 0, m.start()) + 1, "span", m.group(2).replace("\n", " ")))
    return sorted(out, key=lambda q: q[0])


# ---------------------------------------------------------------------------- flags

def python_flags(path):
    """The option strings of every add_argument(...) call in a Python file."""
    with open(path, encoding="utf-8") as f:
        tree = ast.parse(f.read(), path)
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Call) and getattr(node.func, "attr", "") == "add_argument":
            out |= {a.value for a in node.args
                    if isinstance(a, ast.Constant) and isinstance(a.value, str)
                    and a.value.startswith("-")}
    return out


def bash_flags(path):
    """The flags a bash tool's argument loop accepts: its case labels (--x) or --x|...)."""
    with open(path, encoding="utf-8") as f:
        text = f.read()
    return set(re.findall(r"(--[a-z][a-z0-9-]*)\s*(?=[|)])", text))


def tool_code(entry, root=ROOT):
    """([files], kind) that define a tool's flags: for a thin Python entry, the module it
    imports its main()/run() from (tools/wbtools/<name>.py: one module per tool), or the
    whole package when that is one tool (tools/grader/, tools/wbplot/ and its plug-ins); for
    a bash tool, itself. None when it is neither."""
    path = os.path.join(root, entry)
    with open(path, encoding="utf-8") as f:
        text = f.read()
    first = text.split("\n", 1)[0]
    if "python" in first:
        m = re.search(r"^from ([\w.]+) import (?:run|main|entry)\b", text, re.M)
        parts = m.group(1).split(".") if m else []
        mod = os.path.join(root, "tools", *parts) + ".py"
        if not m or not os.path.isfile(mod):
            return [path], "python"
        if parts[0] == "wbtools":
            return [mod], "python"
        return sorted(glob.glob(os.path.join(root, "tools", parts[0], "**", "*.py"),
                                recursive=True)), "python"
    if "bash" in first or first.startswith("#!/bin/sh"):
        return [path], "bash"
    return None


def lab_executable_flags(root=ROOT):
    """The flags every lab executable defines (CLI11, in framework/), with --help."""
    out = {"--help", "-h"}
    for path in glob.glob(os.path.join(root, "framework", "**", "*.cpp"), recursive=True) + \
            glob.glob(os.path.join(root, "framework", "**", "*.h"), recursive=True):
        with open(path, encoding="utf-8") as f:
            text = f.read()
        for m in re.finditer(r"add_(?:option|flag)\(\s*\"([^\"]+)\"", text):
            out |= {n for n in m.group(1).split(",") if n.startswith("-")}
    return out


class Flags:
    """The flags each program defines, read once."""

    def __init__(self, root=ROOT):
        self.root, self._tools, self._labs = root, {}, None

    def of(self, program):
        """The set of flags of `program` (tools/<name> or build/bin/<exe>), or None when it
        is not a program this check knows (ctest, cmake, a test binary)."""
        if program.startswith("build/bin/"):
            exe = program[len("build/bin/"):]
            if exe.endswith("-tests") or "{" in exe:
                return None  # Catch's own flags; a template's placeholder
            if self._labs is None:
                self._labs = lab_executable_flags(self.root)
            return self._labs
        if not program.startswith("tools/") or not os.path.isfile(os.path.join(self.root,
                                                                                 program)):
            return None
        if program not in self._tools:
            code = tool_code(program, self.root)
            if code is None:
                self._tools[program] = None
            else:
                paths, kind = code
                flags = set()
                for path in paths:
                    flags |= python_flags(path) if kind == "python" else bash_flags(path)
                self._tools[program] = flags | {"--help", "-h"}
        return self._tools[program]


def commands(text):
    """The commands of one quoted line: [(program, [flags])], split at && || | ; and after
    leading VAR=value assignments; comments dropped."""
    text = re.sub(r"(^|\s)#.*$", "", text)
    out = []
    for part in re.split(r"&&|\|\||[|;]", text):
        words = part.split()
        while words and re.match(r"^[A-Z_][A-Z0-9_]*=", words[0]):
            words = words[1:]
        if words and words[0] in ("sudo", "nice", "env", "time"):
            words = words[1:]
        if words:
            out.append((words[0].lstrip("./") if words[0].startswith("./") else words[0],
                        [w.split("=", 1)[0] for w in words[1:] if FLAG.match(w.split("=", 1)[0])]))
    return out


def flag_findings(doc, text, flags, counts):
    found = []
    for line, kind, q in quotations(text):
        if kind in ("block:sh", "block:") or q.startswith(("tools/", "build/bin/")):
            for program, given in commands(q):
                known = flags.of(program)
                if known is None:
                    continue
                for flag in given:
                    counts["flags"] += 1
                    if flag not in known:
                        found.append(f"{doc}:{line}: `{program} {flag}`: {program} has no "
                                     f"flag {flag} (its flags: {', '.join(sorted(known))})")
    return found


# ---------------------------------------------------------------------------- calls

def lab_functions(root=ROOT):
    """{name: [parameter names]} of every task function declared in labs/<lab>/*.h (the
    grader's own reading of the headers, tools/grader/stubs.py)."""
    from grader import stubs
    out = {}
    for h in sorted(glob.glob(os.path.join(root, "labs", "*", "*.h"))):
        for _, _, name, params in stubs.parse(h).functions:
            out.setdefault(name, []).append([p for _, p in params])
    return out


def cpp_names(root=ROOT):
    """Every name followed by "(" in the framework's and the labs' headers: a quoted call of
    one of these is C++ (Force::add), not a Python function of the same name."""
    out = set()
    for path in glob.glob(os.path.join(root, "framework", "**", "*.h"), recursive=True) + \
            glob.glob(os.path.join(root, "labs", "*", "*.h")):
        with open(path, encoding="utf-8") as f:
            out |= set(re.findall(r"\b([A-Za-z_]\w*)\s*\(", f.read()))
    return out


def python_functions(root=ROOT):
    """{name: [(module, parameters, required, open)]} of every function in tools/ (open: it
    takes *args or **kwargs)."""
    out = {}
    for path in sorted(glob.glob(os.path.join(root, "tools", "**", "*.py"), recursive=True)):
        if f"{os.sep}tests{os.sep}" in path:
            continue
        with open(path, encoding="utf-8") as f:
            tree = ast.parse(f.read(), path)
        module = os.path.basename(path)[:-3]
        for node in ast.walk(tree):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                a = node.args
                params = [x.arg for x in a.posonlyargs + a.args + a.kwonlyargs]
                if params[:1] in (["self"], ["cls"]):
                    params = params[1:]
                required = len(a.posonlyargs + a.args) - len(a.defaults) - (
                    1 if [x.arg for x in a.args[:1]] in (["self"], ["cls"]) else 0)
                out.setdefault(node.name, []).append(
                    (module, params, max(0, required) + sum(1 for d in a.kw_defaults if d is None),
                     bool(a.vararg or a.kwarg)))
    return out


def split_args(text):
    """The arguments of a quoted call, split at top-level commas (the grader's own splitter
    of C++ parameter lists)."""
    from grader import stubs
    return [a.strip() for a in stubs._split_top(text)]


def call_findings(doc, text, lab_funcs, py_funcs, cpp, counts):
    """Quoted calls that do not match the code. Python functions are looked for outside the
    handouts only (the handouts quote C++), and not under a name the C++ headers use."""
    found = []
    python = not doc.startswith("handouts" + os.sep)
    for line, kind, q in quotations(text):
        if kind not in ("span", "block:python") or "..." in q or "…" in q:
            continue
        for m in CALL.finditer(q):
            qual, name, args = m.group(1), m.group(2), split_args(m.group(3))
            shown = f"{qual}{name}({m.group(3)})"
            if name in lab_funcs and not qual:
                counts["calls"] += 1
                if not any(args == params for params in lab_funcs[name]):
                    want = " or ".join(f"{name}({', '.join(p)})" for p in lab_funcs[name])
                    found.append(f"{doc}:{line}: `{shown}`: the header declares {want}")
            elif python and name in py_funcs and name not in lab_funcs and name not in cpp and (
                    not qual or qual.rstrip(".") in {d[0] for d in py_funcs[name]}):
                counts["calls"] += 1
                defs = [d for d in py_funcs[name]
                        if not qual or d[0] == qual.rstrip(".").split(".")[-1]]
                kw = [a.split("=", 1)[0].strip() for a in args if re.match(r"^\w+\s*=", a)]
                if not any((d[2] <= len(args) <= len(d[1]) or d[3]) and
                           all(k in d[1] or d[3] for k in kw) for d in defs):
                    want = " or ".join(f"{d[0]}.{name}({', '.join(d[1])})" for d in defs)
                    found.append(f"{doc}:{line}: `{shown}`: the code defines {want}")
    return found


# ---------------------------------------------------------------------------- paths

GENERATED = ("handouts/figures/",)  # made by tools/pack in the pack, not in the repository


def exists(rel, root=ROOT):
    """Whether a quoted path is in the repository: <placeholder>, {placeholder}, a one-letter
    capital segment (labs/L/, X.png) and * match anything; a program may be named by its
    source (bench/bench_integrators for bench/bench_integrators.cpp)."""
    if rel.startswith(GENERATED):
        return True
    pattern = re.sub(r"<[^>]*>|\{[^}]*\}|(?<=/)[A-Z](?=[/.]|$)", "*", rel)
    if pattern != rel or "*" in rel:
        return bool(glob.glob(os.path.join(root, pattern)))
    return any(os.path.exists(os.path.join(root, rel + ext)) for ext in ("", ".cpp", ".py"))


def path_findings(doc, text, root, counts):
    found = []
    here = os.path.dirname(doc)
    for line, kind, q in quotations(text):
        if kind != "span":
            continue
        m = PATH.match(q.strip().rstrip(".,:;"))
        counts["paths"] += bool(m)
        if m and not exists(m.group(1), root):
            found.append(f"{doc}:{line}: `{q.strip()}` does not exist in the repository")
    for m in LINK.finditer(text):
        target = m.group(1).split("#")[0]
        if not target or re.match(r"^[a-z]+:", target) or target.startswith("../build/"):
            continue
        counts["paths"] += 1
        if not os.path.exists(os.path.normpath(os.path.join(root, here, target))):
            found.append(f"{doc}:{text.count(chr(10), 0, m.start()) + 1}: link {target} "
                         "does not resolve")
    return found


def check(root=ROOT, docs=None):
    """(every finding of the three checks over `docs` (default: every Markdown file),
    {"docs", "flags", "calls", "paths": how many were checked})."""
    flags, lab_funcs, py_funcs = Flags(root), lab_functions(root), python_functions(root)
    cpp = cpp_names(root)
    found, counts = [], {"docs": 0, "flags": 0, "calls": 0, "paths": 0}
    for doc in docs or markdown_files(root):
        with open(os.path.join(root, doc), encoding="utf-8") as f:
            text = f.read()
        counts["docs"] += 1
        if doc == os.path.join("tools", "pack.d", "README.md"):
            # The pack's README template: its paths are the pack's (tools/pack --verify
            # checks them in the staged pack), its commands are checked here.
            found += flag_findings(doc, text, flags, counts)
            continue
        found += flag_findings(doc, text, flags, counts)
        found += call_findings(doc, text, lab_funcs, py_funcs, cpp, counts)
        found += path_findings(doc, text, root, counts)
    return found, counts
