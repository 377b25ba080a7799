"""The pristine project: which labs exist, their student files, the files a scratch copy is made of.

Trust: reads the checkout only (never the submission)."""
import hashlib
import itertools
import os
import re

from .common import PRISTINE_ENTRIES, SKIPPED_DIRS

# ---------------------------------------------------------------- the project

def repo_root():
    """The checkout (or the autograder's source folder) this grader belongs to."""
    return os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def lab_order(repo):
    """The labs in teaching order (the wb_lab(...) lines of CMakeLists.txt)."""
    try:
        with open(os.path.join(repo, "CMakeLists.txt"), encoding="utf-8") as f:
            return re.findall(r"^\s*wb_lab\(\s*([A-Za-z0-9_-]+)", f.read(), re.M)
    except OSError:
        return []


def known_labs(repo):
    """Subfolders of labs/ that have graded tests in tests/<lab>/, in teaching order."""
    labs_dir = os.path.join(repo, "labs")
    found = []
    for name in sorted(os.listdir(labs_dir)) if os.path.isdir(labs_dir) else []:
        tests = os.path.join(repo, "tests", name)
        if os.path.isdir(os.path.join(labs_dir, name)) and os.path.isdir(tests) and any(
                f.endswith(".cpp") for f in os.listdir(tests)):
            found.append(name)
    order = lab_order(repo)
    return sorted(found, key=lambda l: (order.index(l) if l in order else len(order), l))


def student_files(repo, lab):
    """The file names a student edits in one lab: labs/<lab>/*.cpp."""
    d = os.path.join(repo, "labs", lab)
    return sorted(f for f in os.listdir(d) if f.endswith(".cpp") and os.path.isfile(os.path.join(d, f)))


def pristine_files(repo):
    """{relative path: bytes} of everything the scratch copy is made of."""
    files = {}
    for entry in PRISTINE_ENTRIES:
        top = os.path.join(repo, entry)
        if os.path.isfile(top):
            with open(top, "rb") as f:
                files[entry] = f.read()
            continue
        if not os.path.isdir(top):
            continue
        for dirpath, dirnames, filenames in os.walk(top):
            rel_dir = os.path.relpath(dirpath, repo)
            dirnames[:] = sorted(d for d in dirnames if not d.startswith(".") and d != "__pycache__"
                                 and os.path.join(rel_dir, d) not in SKIPPED_DIRS)
            for name in sorted(filenames):
                if name.startswith(".") or name.endswith((".pyc", "~", ".orig", ".rej", ".swp")):
                    continue
                path = os.path.join(dirpath, name)
                if os.path.isfile(path):
                    with open(path, "rb") as f:
                        files[os.path.join(rel_dir, name)] = f.read()
    return files


def sync_tree(src, files):
    """Makes the folder src hold exactly `files` ({relative path: bytes}), rewriting only what
    changed (so that a build recompiles only that) and removing what is not in it."""
    for rel, data in files.items():
        path = os.path.join(src, rel)
        try:
            with open(path, "rb") as f:
                if f.read() == data:
                    continue
        except OSError:
            os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "wb") as f:
            f.write(data)
    for dirpath, _, filenames in os.walk(src, topdown=False):
        for name in filenames:
            if os.path.relpath(os.path.join(dirpath, name), src) not in files:
                os.remove(os.path.join(dirpath, name))
        if dirpath != src and not os.listdir(dirpath):
            os.rmdir(dirpath)


def digest(files):
    h = hashlib.sha256()
    for rel in sorted(files):
        h.update(rel.encode() + b"\0" + hashlib.sha256(files[rel]).digest())
    return h.hexdigest()

def lab_deps(repo, lab):
    """The labs `lab` depends on (wb_lab(<lab> DEPS ...) in CMakeLists.txt), recursively."""
    try:
        with open(os.path.join(repo, "CMakeLists.txt"), encoding="utf-8") as f:
            text = f.read()
    except OSError:
        return []
    direct = {}
    for m in re.finditer(r"^\s*wb_lab\(\s*([A-Za-z0-9_-]+)([^)]*)\)", text, re.M):
        words = m.group(2).split()
        deps = words[words.index("DEPS") + 1:] if "DEPS" in words else []
        # DEPS ends at the next keyword (TESTS_USE_GLUE, TEST_UNITS n, ...)
        direct[m.group(1)] = list(itertools.takewhile(lambda w: not w.isupper(), deps))
    out, todo = [], list(direct.get(lab, []))
    while todo:
        d = todo.pop(0)
        if d not in out and d != lab:
            out.append(d)
            todo += direct.get(d, [])
    return out


