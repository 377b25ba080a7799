"""The thin entries (tools/<name>) over their modules (tools/wbtools/<name>.py, grader/,
wbplot/, wbview/). Guards against an entry whose module does not define what it calls, and
against a module-level name defined twice: the second definition silently replaces the
first (the move to modules once added an entry run() to tools/wbtools/pattern.py, which
already had a run() helper: its stubs and periods stages then failed with a TypeError)."""
import ast
import collections
import glob
import importlib
import inspect
import os

TOOLS = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def python_entries():
    """[(entry, module, function)] of every extension-less Python tool in tools/ and
    tools/gradescope/: the imported function its `if __name__ == "__main__":` block calls."""
    out = []
    for path in sorted(glob.glob(os.path.join(TOOLS, "*")) +
                       glob.glob(os.path.join(TOOLS, "gradescope", "*"))):
        if not os.path.isfile(path) or "." in os.path.basename(path):
            continue
        with open(path, encoding="utf-8") as f:
            text = f.read()
        if "python" not in text.split("\n", 1)[0]:
            continue
        tree = ast.parse(text, path)
        imported = {a.asname or a.name: node.module for node in tree.body
                    if isinstance(node, ast.ImportFrom) for a in node.names}
        main = next((node for node in tree.body if isinstance(node, ast.If)
                     and "__main__" in ast.unparse(node.test)), None)
        called = [c.func.id for c in ast.walk(main) if isinstance(c, ast.Call)
                  and isinstance(c.func, ast.Name) and c.func.id in imported] if main else []
        out.append((os.path.relpath(path, TOOLS), imported.get(called[0]) if called else None,
                    called[0] if called else None))
    return out


def test_every_entry_calls_a_function_its_module_defines_without_arguments():
    """Defect: an entry that imports a name its module no longer defines, or one that needs
    arguments (the command stops with a traceback before parsing its flags)."""
    entries = python_entries()
    assert len(entries) >= 8
    for entry, module, name in entries:
        assert module, f"tools/{entry}: its __main__ block calls no function it imports"
        fn = getattr(importlib.import_module(module), name)
        required = [p for p in inspect.signature(fn).parameters.values()
                    if p.default is p.empty and p.kind in (p.POSITIONAL_ONLY,
                                                           p.POSITIONAL_OR_KEYWORD)]
        assert callable(fn) and not required, f"tools/{entry}: {module}.{name} needs {required}"


def test_no_module_defines_a_name_twice():
    """Defect: a function or class defined twice at the top of a module: the later one
    replaces the earlier for every caller, with no error until a caller breaks."""
    twice = []
    for path in sorted(glob.glob(os.path.join(TOOLS, "**", "*.py"), recursive=True)):
        with open(path, encoding="utf-8") as f:
            tree = ast.parse(f.read(), path)
        names = collections.Counter(node.name for node in tree.body if isinstance(
            node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)))
        twice += [f"{os.path.relpath(path, TOOLS)}: {n}" for n, c in names.items() if c > 1]
    assert twice == []


def test_every_tools_test_names_the_defect_it_guards():
    """Defect: a unit test of the tools with no docstring: a maintainer who sees it fail cannot
    tell which class of defect came back, nor whether the test still guards anything (issue 35:
    each test names the defect class it guards)."""
    bare = []
    for path in sorted(glob.glob(os.path.join(TOOLS, "**", "tests", "test_*.py"),
                                 recursive=True)):
        with open(path, encoding="utf-8") as f:
            tree = ast.parse(f.read(), path)
        bare += [f"{os.path.relpath(path, TOOLS)}:{node.lineno} {node.name}"
                 for node in ast.walk(tree)
                 if isinstance(node, ast.FunctionDef) and node.name.startswith("test")
                 and not ast.get_docstring(node)]
    assert not bare, "tests without a docstring naming their defect:\n" + "\n".join(bare)
