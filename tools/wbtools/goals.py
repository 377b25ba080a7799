"""Checks the measured goals of the constraint scenes against runs of the solution.

Runs <build-dir>/bin/<lab>-solution on each scene that has goals (tools/wbplot/goals.py:
box-rest, slope-stick, slope-slide, door, wheel, revolute-pendulum in the rigid lab;
column and pile in the collisions lab), reads the traces and prints every goal with its
measured value and bound. Exit status: 0 every goal holds, 1 one does not (or a run
failed), 2 bad input (a missing executable or scene, a bad flag)."""
import argparse
import os
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tools"))

from wbplot import goals  # noqa: E402


def main():
    ap = argparse.ArgumentParser(prog="tools/goals", description=__doc__.split("\n\n")[0])
    ap.add_argument("--build-dir", default="build", help="executables in DIR/bin (default build)")
    ap.add_argument("--lab", action="append", choices=sorted(goals.GOALS),
                    help="only this lab (repeatable; default both)")
    ap.add_argument("--scene", action="append", metavar="STEM",
                    help="only this scene (repeatable), e.g. box-rest")
    try:
        args = ap.parse_args()
    except SystemExit as e:
        return 2 if e.code else 0
    labs = args.lab or sorted(goals.GOALS)
    bad = total = 0
    with tempfile.TemporaryDirectory(prefix="wb-goals-") as out:
        for lab in labs:
            exe = os.path.join(ROOT, args.build_dir, "bin", f"{lab}-solution")
            if not os.path.exists(exe):
                print(f"tools/goals: error: {exe}: not built (build the solutions first)",
                      file=sys.stderr)
                return 2
            for stem in goals.GOALS[lab]:
                if args.scene and stem not in args.scene:
                    continue
                scene = os.path.join(ROOT, "scenes", lab, stem + ".json")
                t0 = time.monotonic()
                try:
                    results = goals.measure(lab, stem, exe, scene, out)
                except (RuntimeError, OSError, ValueError, KeyError, StopIteration) as e:
                    print(f"FAIL {lab}/{stem}: the run or its trace failed: {e}")
                    bad += 1
                    continue
                for g in results:
                    total += 1
                    bad += not g["holds"]
                    print(f"{'ok  ' if g['holds'] else 'FAIL'} {lab}/{stem}: {g['goal']}: "
                          f"{g['value']:.3g} {g['op']} {g['bound']:g}")
                print(f"     ({lab}/{stem}: {time.monotonic() - t0:.1f} s)")
    print(f"goals: {total - bad} of {total} hold")
    return 1 if bad else 0


def run():
    """The entry tools/goals calls: main() with the command line, its exit status."""
    sys.exit(main())
