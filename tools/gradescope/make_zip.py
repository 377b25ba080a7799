#!/usr/bin/env -S sh -c 'exec "${0%/*}/../lib/start-python" "$0" "$@"'
"""Builds the Gradescope autograder zip of one lab (what `tools/pack --gradescope LAB` runs).

The zip holds setup.sh and run_autograder at its root, and the pristine
project the grader needs: CMakeLists.txt, CMakePresets.json, cmake/,
framework/, labs/ (whole: a lab may link another lab's skeleton), scenes/,
tests/common/ and tests/<LAB>/ (the grader grades the labs whose tests it
has: its probes too), tools/grade and tools/grader/, the diagnosis tools/diagnosis/ with
the lab's catalogue tests/mutants/<LAB>/signatures.json, tools/setup and the sandbox launcher's source. Never
solutions/, tests/mutants/, other labs' tests or a build folder. Files are
those of the commit HEAD (git archive), never the work tree: an instructor's
uncommitted try of an exercise or a test must not ship (issue 44).
"""
import argparse
import os
import sys
import tempfile
import zipfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tools"))
from wbtools import committed  # noqa: E402
ENTRIES = ["CMakeLists.txt", "CMakePresets.json", "cmake", "framework", "labs", "scenes",
           "tests/common", "tools/grade", "tools/grader", "tools/setup", "tools/diagnosis",
           "tools/gradescope/sandbox.c"]
AT_ROOT = ["tools/gradescope/setup.sh", "tools/gradescope/run_autograder"]
DATE = (2020, 1, 1, 0, 0, 0)  # fixed: the same tree gives the same zip


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
    """Writes the zip of `lab` (or of each lab of a list: the hostile suite grades the cases of
    every lab in one zip, set up once; Gradescope gets one lab per assignment) from the commit
    HEAD of the checkout `root`; returns the number of files. ValueError (one line): an unknown
    lab, or no commit to make it from."""
    with tempfile.TemporaryDirectory(prefix="wb-zip-") as tmp:
        try:
            head = committed.export_head(root, os.path.join(tmp, "head"))
        except committed.NotCommitted as e:
            raise ValueError(f"the zip is made from the committed tree (HEAD), and {e}")
        return _build(lab, out, head)


def _build(lab, out, root):
    labs = labs_with_tests(root)
    graded = [lab] if isinstance(lab, str) else list(lab)
    for one in graded:
        if one not in labs:
            raise ValueError(f"unknown lab '{one}' (labs with tests: {', '.join(labs)})")
    every = sorted(os.path.relpath(os.path.join(d, n), root).replace(os.sep, "/")
                   for d, _, names in os.walk(root) for n in names)  # HEAD's files, exported
    files = [p for p in every if wanted(p, graded) and os.path.isfile(os.path.join(root, p))
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
    edited = committed.uncommitted(ROOT)
    print(f"tools/pack: wrote {out} ({n} files of HEAD {committed.head(ROOT)[:10]}; setup.sh and "
          "run_autograder at the root)" + (f"; not in it, uncommitted: {', '.join(edited[:6])}"
                                           + (f" and {len(edited) - 6} more" if len(edited) > 6
                                              else "") if edited else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
