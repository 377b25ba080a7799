"""tools/pattern imports: no module of tools/ imports one that imports it back.

A circle of imports (a imports b, b imports a, or a longer ring) makes each module's meaning
depend on which is loaded first, and says that one idea is split over two places: what both
need belongs in a module of its own. Every import counts, a lazy one inside a function too
(it only hides the circle until that function runs), and importing a.b.c loads the packages
a and a.b first. Only the modules under tools/ are followed (sys.path holds tools/, so
tools/grader/build.py is the module grader.build); the entry scripts without .py (tools/grade)
are imported by nobody and are left out."""
import ast
import collections
import os

SKIPPED = {"__pycache__", ".pytest_cache"}


def modules(tools):
    """{module name: file} of every .py file under `tools`."""
    out = {}
    for d, dirs, files in os.walk(tools):
        dirs[:] = sorted(x for x in dirs if x not in SKIPPED and not x.startswith((".", "build")))
        rel = os.path.relpath(d, tools)
        pkg = [] if rel == "." else rel.split(os.sep)
        for f in sorted(files):
            if not f.endswith(".py"):
                continue
            parts = pkg + ([] if f == "__init__.py" else [f[:-3]])
            if parts:
                out[".".join(parts)] = os.path.join(d, f)
    return out


def _with_parents(name, known):
    parts = name.split(".")
    return [p for p in (".".join(parts[:k]) for k in range(1, len(parts) + 1)) if p in known]


def imports(name, path, known):
    """[(module imported, line)] of the module `name` in `path`: only modules in `known`."""
    with open(path, encoding="utf-8") as f:
        tree = ast.parse(f.read(), path)
    is_pkg = os.path.basename(path) == "__init__.py"
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for a in node.names:
                out += [(m, node.lineno) for m in _with_parents(a.name, known)]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = name.split(".") if is_pkg else name.split(".")[:-1]
                base = base[:len(base) - (node.level - 1)] if node.level > 1 else base
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            found = _with_parents(target, known)
            found += [f"{target}.{a.name}" for a in node.names if f"{target}.{a.name}" in known]
            out += [(m, node.lineno) for m in found]
    return [(m, line) for m, line in out if m != name]


def graph(tools):
    """({module: {module it imports: first line}}, {module: file})."""
    files = modules(tools)
    g = {}
    for name, path in files.items():
        edges = {}
        for m, line in imports(name, path, files):
            edges.setdefault(m, line)
        g[name] = edges
    return g, files


def circles(g):
    """One shortest circle through each group of modules that import each other (every
    strongly connected component of more than one module), as [module, ..., module]."""
    index, low, stack, on, comps = {}, {}, [], set(), []

    def strong(v):  # Tarjan's algorithm, iterative
        work = [(v, iter(sorted(g.get(v, ()))))]
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        while work:
            u, it = work[-1]
            for w in it:
                if w not in index:
                    index[w] = low[w] = len(index)
                    stack.append(w)
                    on.add(w)
                    work.append((w, iter(sorted(g.get(w, ())))))
                    break
                if w in on:
                    low[u] = min(low[u], index[w])
            else:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[u])
                if low[u] == index[u]:
                    comp = []
                    while True:
                        w = stack.pop()
                        on.discard(w)
                        comp.append(w)
                        if w == u:
                            break
                    comps.append(sorted(comp))

    for v in sorted(g):
        if v not in index:
            strong(v)
    out = []
    for comp in sorted(c for c in comps if len(c) > 1):
        inside, start = set(comp), comp[0]
        prev, todo = {start: None}, collections.deque([start])
        ring = None
        while todo and ring is None:
            u = todo.popleft()
            for w in sorted(g[u]):
                if w == start:
                    ring = [u]
                    break
                if w in inside and w not in prev:
                    prev[w] = u
                    todo.append(w)
        while ring[-1] != start:
            ring.append(prev[ring[-1]])
        out.append(list(reversed(ring)) + [start])
    return out


def check(root):
    """Findings (one line each) for the modules under root/tools."""
    tools = os.path.join(root, "tools")
    g, files = graph(tools)
    findings = []
    for ring in circles(g):
        steps = [f"{a} ({os.path.relpath(files[a], root)}:{g[a][b]}) imports {b}"
                 for a, b in zip(ring, ring[1:])]
        findings.append("; ".join(steps) + ": an import circle; move what they share into a "
                        "module of its own, which imports neither")
    return findings, len(files)
