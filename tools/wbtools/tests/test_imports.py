"""tools/pattern imports (tools/wbtools/imports.py): no module of tools/ imports one that
imports it back. Guards against a circle that goes unseen: a lazy import inside a function, a
relative import, a ring of three, and against a finding where there is no circle."""
import os

from wbtools import imports

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))


def tree(tmp_path, files):
    for rel, text in files.items():
        p = tmp_path / "tools" / rel
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text(text)
    return str(tmp_path)


def test_a_lazy_import_back_is_a_circle(tmp_path):
    """Defect: a module that imports another inside a function, which imports it back at the
    top (the catalogue and tools/mutants once did), passes the check."""
    root = tree(tmp_path, {"pkg/__init__.py": "", "pkg/a.py": "from pkg import b\n",
                           "pkg/b.py": "def f():\n    from pkg.a import g\n"})
    findings, n = imports.check(root)
    assert n == 3 and len(findings) == 1
    assert "pkg.a (tools/pkg/a.py:1) imports pkg.b" in findings[0]
    assert "pkg.b (tools/pkg/b.py:2) imports pkg.a" in findings[0]


def test_relative_imports_and_a_ring_of_three(tmp_path):
    """Defect: `from . import x` and `from .x import y` not followed, or a circle through a
    third module missed."""
    root = tree(tmp_path, {"p/__init__.py": "", "p/a.py": "from . import b\n",
                           "p/b.py": "from .c import thing\n", "p/c.py": "import p.a\n"})
    findings, _ = imports.check(root)
    assert len(findings) == 1
    assert findings[0].startswith("p.a (tools/p/a.py:1) imports p.b; p.b (tools/p/b.py:1) "
                                  "imports p.c; p.c (tools/p/c.py:1) imports p.a")


def test_a_chain_and_a_package_init_are_no_circle(tmp_path):
    """Defect: a finding where modules only import one way (a package's modules importing
    each other through it, a top-level module, the standard library)."""
    root = tree(tmp_path, {"q/__init__.py": '"""doc"""\n', "q/a.py": "import os\nfrom . import b\n",
                           "q/b.py": "from q.c import x\n", "q/c.py": "import json\n",
                           "top.py": "import q.a\n"})
    assert imports.check(root)[0] == []


def test_the_tools_have_no_circle():
    """The check on the repository itself (tools/pattern imports in tools/check): the diagnosis
    and the figures' helpers once imported each other back."""
    findings, n = imports.check(ROOT)
    assert findings == [] and n > 50
