#!/usr/bin/env -S sh -c 'exec "${0%/*}/../lib/start-python" "$0" "$@"'
"""Builds the Gradescope autograder zip of one lab (what `tools/pack --gradescope LAB` runs).

The zip holds setup.sh and run_autograder at its root, and the pristine
project the grader needs: CMakeLists.txt, CMakePresets.json, cmake/,
framework/, labs/ (whole: a lab may link another lab's skeleton), scenes/,
tests/common/ and tests/<LAB>/ (the grader grades the labs whose tests it
has: its probes too), tools/grade and tools/grader/, the diagnosis tools/wbgrade_hints.py with
the lab's catalogue tests/mutants/<LAB>/signatures.json, tools/setup and the sandbox launcher's source. Never
solutions/, tests/mutants/, other labs' tests or a build folder. Files are
the checkout's tracked files (git ls-files) as they are in the work tree.
"""
import argparse
import os
import subprocess
import sys
import zipfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
ENTRIES = ["CMakeLists.txt", "CMakePresets.json", "cmake", "framework", "labs", "scenes",
           "tests/common", "tools/grade", "tools/grader", "tools/setup", "tools/wbgrade_hints.py",
           "tools/gradescope/sandbox.c"]
AT_ROOT = ["tools/gradescope/setup.sh", "tools/gradescope/run_autograder"]
DATE = (2020, 1, 1, 0, 0, 0)  # fixed: the same tree gives the same zip


def tracked(root):
    """Tracked files of the checkout (relative paths), or every file if not a git checkout."""
    try:
        out = subprocess.run(["git", "-C", root, "ls-files", "-z"], check=True,
                             stdout=subprocess.PIPE, stderr=subprocess.DEVNULL).stdout
        return sorted(p for p in out.decode().split("\0") if p)
    except (OSError, subprocess.CalledProcessError):
        files = []
        for d, dirs, names in os.walk(root):
            dirs[:] = [x for x in dirs if not x.startswith((".", "build"))]
            files += [os.path.relpath(os.path.join(d, n), root) for n in names]
        return sorted(files)


def labs_with_tests(root):
    tests = os.path.join(root, "tests")
    return sorted(d for d in os.listdir(os.path.join(root, "labs"))
                  if os.path.isdir(os.path.join(tests, d)) and d not in ("common", "mutants"))


def wanted(rel, labs):
    # The labs' tests and probes, and their catalogues (the diagnosis' numbers), never the
    # mutants nor the tools' own unit tests (tools/grader/tests/).
    if rel.startswith("tools/") and "/tests/" in rel:
        return False
    labs = [labs] if isinstance(labs, str) else labs
    for e in ENTRIES + [x for lab in labs for x in (f"tests/{lab}",
                                                    f"tests/mutants/{lab}/signatures.json")]:
        if rel == e or rel.startswith(e + "/"):
            return True
    return False


def add(z, path, arcname):
    info = zipfile.ZipInfo(arcname, DATE)
    mode = os.stat(path).st_mode
    info.external_attr = ((0o755 if mode & 0o111 else 0o644) | 0o100000) << 16
    info.compress_type = zipfile.ZIP_DEFLATED
    with open(path, "rb") as f:
        z.writestr(info, f.read())


def build(lab, out, root=ROOT):
    """The zip of `lab` (or of each lab of a list: the hostile suite grades the cases of every
    lab in one zip, set up once; Gradescope gets one lab per assignment)."""
    labs = labs_with_tests(root)
    graded = [lab] if isinstance(lab, str) else list(lab)
    for one in graded:
        if one not in labs:
            raise ValueError(f"unknown lab '{one}' (labs with tests: {', '.join(labs)})")
    files = [p for p in tracked(root) if wanted(p, graded) and os.path.isfile(os.path.join(root, p))
             and not os.path.islink(os.path.join(root, p))]
    tmp = out + ".tmp"
    with zipfile.ZipFile(tmp, "w") as z:
        for rel in AT_ROOT:
            add(z, os.path.join(root, rel), os.path.basename(rel))
        for rel in files:
            add(z, os.path.join(root, rel), rel)
    os.replace(tmp, out)
    return len(files) + len(AT_ROOT)


def main(argv):
    ap = argparse.ArgumentParser(prog="tools/pack --gradescope", description=__doc__.split("\n")[0])
    ap.add_argument("lab", help="the lab graded by this autograder")
    ap.add_argument("--out", help="the zip to write (default: <lab>-autograder.zip)")
    args = ap.parse_args(argv)
    out = os.path.abspath(args.out or f"{args.lab}-autograder.zip")
    if not os.path.isdir(os.path.dirname(out)):
        print(f"tools/pack: error: --out: folder '{os.path.dirname(out)}' does not exist",
              file=sys.stderr)
        return 2
    try:
        n = build(args.lab, out)
    except ValueError as e:
        print(f"tools/pack: error: --gradescope: {e}", file=sys.stderr)
        return 2
    print(f"tools/pack: wrote {out} ({n} files; setup.sh and run_autograder at the root)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
