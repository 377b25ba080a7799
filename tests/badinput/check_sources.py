#!/usr/bin/env -S sh -c 'exec "${0%/*}/../../tools/lib/start-python" "$0" "$@"'
"""One writer, one message line: no framework file writes to stdout, stderr or a file
except through the functions that check what they write (issue 31).

  stderr    wb::say (framework/src/contract.cpp): "<exe>: <kind>: <text>", the text made
            one line of valid UTF-8 by one_line (a file name or key from outside cannot
            split it); diagnostics are warnings or nothing. The one other line: the
            budget's stop (framework/src/budget.cpp, written by budget_clock.cpp from
            the watchdog thread, where iostreams may not run), its prefix made by
            one_line and its text fixed ASCII and digits
  stdout    the summary line (wb::print_summary) and --help (framework/src/cli.cpp)
  files     AtomicFile and CsvFile (framework/src/output.cpp): paths checked before the
            run, a temporary renamed into place, a failed write exit status 2

A new file under framework/ that prints or opens a file some other way fails this check,
naming the file, the line and the function that should be used instead.

  tests/badinput/check_sources.py [--root DIR]
"""
import argparse
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))

# (pattern, where it may appear, what to use instead)
RULES = [
    (re.compile(r"std::cerr|\bstderr\b|\bperror\s*\(|\bwrite\s*\(\s*2\s*,"),
     {"framework/src/contract.cpp", "framework/src/budget_clock.cpp"},
     "wb::say(exe, \"warning\", text) (wb/contract.h)"),
    (re.compile(r"std::cout|\bstdout\b|\bputs\s*\(|(?<![sn])printf\s*\("),
     {"framework/src/contract.cpp", "framework/src/cli.cpp"},
     "wb::print_summary (wb/contract.h)"),
    (re.compile(r"\bfopen\s*\(|std::ofstream|std::fstream\b|\bcreat\s*\("),
     {"framework/src/output.cpp"}, "wb::CsvFile or wb::AtomicFile (wb/output.h)"),
]


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--root", default=REPO, help="the checkout (default: this one)")
    args = ap.parse_args()
    found = 0
    base = os.path.join(args.root, "framework")
    for d, _, files in os.walk(base):
        for name in sorted(files):
            if not name.endswith((".cpp", ".h")):
                continue
            path = os.path.join(d, name)
            rel = os.path.relpath(path, args.root)
            with open(path, encoding="utf-8") as f:
                for n, line in enumerate(f, 1):
                    code = line.split("//", 1)[0]
                    for pattern, allowed, instead in RULES:
                        if rel not in allowed and pattern.search(code):
                            print(f"{rel}:{n}: {line.strip()[:80]!r}: use {instead}")
                            found += 1
    print(f"check_sources: {found} finding(s) in framework/")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
