#!/usr/bin/env -S sh -c 'exec "${0%/*}/../../tools/lib/start-python" "$0" "$@"'
"""Bad-input regression cases: every case must end in one clear line.

Runs each case of tests/badinput/cases.json against the lab executables in
--bin and checks the run contract for bad input (docs/run-contract.md):
exit status 2 (or the case's `status`; `kill_after` S: a slow valid run,
stopped after S seconds, that must have warned; `differs_from`: the
arguments of a second run whose initial momentum must differ), exactly one line of valid UTF-8 on
stderr of at most MAX_LINE bytes naming what the case `expect`s, nothing on
stdout, no output file left behind (`absent`), within TIME_LIMIT_S seconds
and MEMORY_LIMIT_BYTES of address space. Large scenes (deep nesting, a 17 MiB
file) are generated into a temporary folder, not checked in.

  tests/badinput/run_badinput.py --bin build/bin [--side solution] [-k NAME]
"""
import argparse
import json
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
MAX_LINE = 1100  # messages are cut to 1000 bytes (kMaxMessageBytes) plus the "<exe>: error: " prefix
TIME_LIMIT_S = 20.0  # each case is refused in well under a second; this is a hang detector
MEMORY_LIMIT_BYTES = 2 << 30  # a refused scene must not allocate gigabytes first


def generate(kind, tmp):
    """Writes the scene of a generated case; returns its path."""
    path = os.path.join(tmp, kind + ".json")
    if kind == "deep-array":  # 60,000 nested arrays (120 KB) as a force list
        text = '{"forces": ' + "[" * 60000 + "]" * 60000 + "}"
    elif kind == "deep-object":
        text = '{"a": ' * 100000 + "1" + "}" * 100000
    elif kind == "deep-top":
        text = "[" * 200000 + "]" * 200000
    elif kind == "huge-string-value":  # 15 MB value of the wrong type
        text = '{"dt": 0.1, "t_end": 1, "name": ["' + "a" * 15_000_000 + '"]}'
    elif kind == "too-large":  # 17 MiB: valid JSON, refused by its size
        text = '{"dt": 0.1' + " " * (17 << 20) + "}"
    elif kind == "many-emitters":  # 100 emitters of 5M particles in a few KB
        e = '{"count": 5000000, "min": [0, 0], "max": [1, 1], "m": 1}'
        text = '{"dt": 0.1, "t_end": 1, "emitters": [' + ", ".join([e] * 100) + "]}"
    elif kind == "boids-6000":  # boids, not newton: no O(n^2) potential to wait for
        text = json.dumps({"dt": 0.01, "t_end": 1, "forces": [{"type": "damping", "b": 1},
                                                               {"type": "boids"}],
                           "emitters": [{"count": 6000, "min": [0, 0], "max": [100, 100],
                                         "m": 1}]})
    elif kind == "emitter-200":
        text = ('{"dt": 0.01, "emitters": [{"count": 200, "min": [0, 0], "max": [1, 1], '
                '"m": 1}]}')
    elif kind == "long-key":
        text = '{"' + "k" * 100000 + '": 1}'
    elif kind == "newline-in-file-name":
        path = os.path.join(tmp, "bad\nname.json")
        text = '{"dt": 0.1, "dt": 0.2}'
    else:
        raise SystemExit(f"run_badinput.py: unknown generator '{kind}'")
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)
    return path


def summary_state(stdout):
    """The summary line's momentum (which the emitters' seeds decide)."""
    lines = stdout.decode("utf-8", "replace").strip().splitlines()
    return json.loads(lines[-1]).get("momentum0") if lines else None


def limit_memory():
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT_BYTES, MEMORY_LIMIT_BYTES))


def run_case(case, args):
    """Returns a list of problems (empty: the case passed)."""
    suffix = "" if args.side == "student" else "-" + args.side
    exe = os.path.join(args.bin, case["lab"] + suffix)
    if not os.path.exists(exe):
        return None  # lab not built
    tmp = tempfile.mkdtemp(prefix="wb-badinput-")
    try:
        scene = generate(case["generate"], tmp) if "generate" in case else ""
        subst = {"{scene}": scene, "{scenes}": os.path.join(HERE, "scenes"), "{tmp}": tmp,
                 "{repo}": REPO}
        argv = [exe]
        for a in case["args"]:
            for k, v in subst.items():
                a = a.replace(k, v)
            argv.append(a)
        start = time.monotonic()
        # A valid but slow run ("kill_after": S) must warn before it starts: it
        # is stopped after S seconds and its stderr checked.
        kill_after = case.get("kill_after")
        limit = TIME_LIMIT_S * args.time_scale
        try:
            p = subprocess.run(argv, capture_output=True, timeout=kill_after or limit,
                               preexec_fn=None if args.no_memory_limit else limit_memory)
        except subprocess.TimeoutExpired as e:
            if not kill_after:
                return [f"took more than {limit} s"]
            p = subprocess.CompletedProcess(argv, "killed", e.stdout or b"", e.stderr or b"")
        else:
            if kill_after:
                return [f"finished within {kill_after} s, expected a run long enough to warn"]
        wall = time.monotonic() - start
        problems = []
        status = case.get("status", "killed" if kill_after else 2)
        if p.returncode != status:
            problems.append(f"exit status {p.returncode}, expected {status}")
        try:
            err = p.stderr.decode("utf-8")
        except UnicodeDecodeError as e:
            problems.append(f"stderr is not valid UTF-8 ({e})")
            err = p.stderr.decode("utf-8", "replace")
        lines = err.split("\n")
        if status == 2:
            if len(lines) != 2 or lines[1] != "":
                problems.append(f"stderr has {len(lines) - 1} lines, expected exactly one")
            if len(p.stderr) > MAX_LINE:
                problems.append(f"stderr is {len(p.stderr)} bytes, expected at most {MAX_LINE}")
            if p.stdout:
                problems.append("stdout is not empty")
            if "\r" in err:
                problems.append("stderr holds a carriage return")
        for want in case.get("expect", []):
            if want not in err:
                problems.append(f"stderr lacks {want!r}")
        out = p.stdout.decode("utf-8", "replace")
        for want in case.get("stdout", []):
            if want not in out:
                problems.append(f"stdout lacks {want!r}")
        if "differs_from" in case:  # another run whose summary must differ (seeds)
            other = [exe] + [a.replace("{scenes}", subst["{scenes}"]) for a in case["differs_from"]]
            q = subprocess.run(other, capture_output=True, timeout=limit)
            if q.returncode != 0 or summary_state(q.stdout) == summary_state(p.stdout):
                problems.append("gives the same summary as " + " ".join(case["differs_from"]))
        for name in case.get("absent", []):
            left = [f for f in os.listdir(tmp) if f.startswith(name)]
            if left:
                problems.append(f"left output files behind: {left}")
        if args.verbose or problems:
            print(f"    ({wall:.2f} s) stderr: {err.strip()[:300]!r}")
        return problems
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default=os.path.join(REPO, "build", "bin"),
                    help="folder of the lab executables (default: build/bin)")
    ap.add_argument("--side", default="solution", choices=["solution", "student"],
                    help="which executables (default: solution; bad input is refused before "
                         "any student function runs, so both sides must pass)")
    ap.add_argument("-k", dest="only", help="run only the cases whose name contains this")
    ap.add_argument("--no-memory-limit", action="store_true",
                    help="do not limit the address space (needed under AddressSanitizer)")
    ap.add_argument("--time-scale", type=float, default=1.0,
                    help="multiply the time limit (sanitizer builds run 10-50 times slower)")
    ap.add_argument("-v", "--verbose", action="store_true", help="print every message")
    args = ap.parse_args()
    with open(os.path.join(HERE, "cases.json"), encoding="utf-8") as f:
        cases = json.load(f)["cases"]
    failed = ran = 0
    for case in cases:
        if args.only and args.only not in case["name"]:
            continue
        problems = run_case(case, args)
        if problems is None:
            print(f"skip {case['name']} ({case['lab']} not built)")
            continue
        ran += 1
        print(("ok   " if not problems else "FAIL ") + f"{case['class']}/{case['name']}")
        for pr in problems:
            print("    " + pr)
        failed += bool(problems)
    print(f"badinput: {ran - failed} of {ran} cases passed")
    if ran == 0:  # a pack without the forces, euler or midpoint labs
        print("badinput: no case ran: none of their lab executables is in " + args.bin)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
