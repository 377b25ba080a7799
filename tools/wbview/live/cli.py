"""tools/view --live: a lab's live page from the current files (docs/live.md)."""
import argparse
import glob
import os
import sys
import time

from wbplot.common import write_text_atomic
from wbview import say_written
from wbview.data import InputError

from . import build, page, recorded

ROOT = build.ROOT
RECORDED = os.path.join(ROOT, "live", "recorded")         # shipped in the student pack
REPORT = os.path.join(ROOT, "build", "report")            # an instructor's tools/report


def parser():
    p = argparse.ArgumentParser(
        prog="tools/view --live",
        description="Builds a lab's live page: your C++ (labs/<lab>/) compiled to WebAssembly "
                    "with the framework, stepping the lab's scenes in the browser while you "
                    "turn h, the integrator and the scene's numbers, drag particles and bodies, "
                    "and compare with another integrator or the solution. Needs Debian's "
                    "emscripten (tools/setup --live); rebuilds only what changed.",
        epilog="Open the page in any current browser (no server, no network). Exit status: 0 "
               "written, 1 the build failed (em++'s messages shown), 2 cannot (no em++, an "
               "unknown lab). See docs/live.md.")
    p.add_argument("--live", action="store_true", required=True, help="a live page")
    p.add_argument("--lab", required=True, help="the lab (a folder of labs/)")
    p.add_argument("--side", choices=("student", "solution"), default="student",
                   help="whose files the page runs: labs/ (default) or solutions/ "
                        "(instructors)")
    p.add_argument("--no-solution", action="store_true",
                   help="leave the solution out of a student page even where solutions/ is "
                        "present (a faster first build)")
    p.add_argument("--build-dir", default=os.path.join(ROOT, "build", "live"),
                   help="the emscripten build (default build/live)")
    p.add_argument("-o", "--out", metavar="PAGE.html",
                   help="the page (default build/live/<lab>.html, <lab>-solution.html)")
    p.add_argument("--verbose", action="store_true", help="show the build's output")
    p.add_argument("--no-setup", action="store_true",
                   help="install nothing first (tools/lib/start-python)")
    return p


def lab_kind(lab):
    with open(os.path.join(ROOT, "framework", "drivers", lab, "main.cpp"), encoding="utf-8") as f:
        return "rigid" if "run_rigid_lab" in f.read() else "particles"


def recorded_run(lab, stem):
    """The solution's run of a default scene as data: shipped (a pack), else from this
    checkout's report."""
    r = recorded.load(RECORDED, lab, stem)
    if r is None and os.path.isdir(os.path.join(REPORT, lab)):
        r = recorded.from_report(REPORT, lab, stem)
    return r


def make_page(lab, side, out, build_dir, with_solution=True, quiet=True):
    """Builds the modules and writes the page; returns a one-line account."""
    if not os.path.isfile(os.path.join(ROOT, "framework", "drivers", lab, "main.cpp")) or \
            not os.path.isdir(os.path.join(ROOT, "labs", lab)):
        known = sorted(os.path.basename(d) for d in glob.glob(os.path.join(ROOT, "labs", "*")))
        raise build.BuildError(f"--lab: got '{lab}', expected one of: {', '.join(known)}")
    have_solutions = os.path.isdir(os.path.join(ROOT, "solutions", lab))
    if side == "solution" and not have_solutions:
        raise build.BuildError(f"--side solution: solutions/{lab} is not in this checkout")
    sides = [side]
    if side == "student" and with_solution and have_solutions:
        sides.append("solution")
    files = build.build(lab, sides, build_dir, quiet=quiet)
    kind = lab_kind(lab)
    scenes = []
    for path in sorted(glob.glob(os.path.join(ROOT, "scenes", lab, "*.json"))):
        stem = os.path.basename(path)[:-5]
        ref = recorded_run(lab, stem) if side == "student" else None
        scenes.append(page.scene_block(path, kind, ref))
    if not scenes:
        raise build.BuildError(f"scenes/{lab}/ has no scene")
    modules = {}
    for s, f in files.items():
        with open(f, encoding="utf-8") as fh:
            modules[s] = fh.read()
    built = {"from": f"{'labs' if side == 'student' else 'solutions'}/{lab}/",
             "command": f"tools/view --live --lab {lab}" + (" --side solution" if side == "solution" else "")}
    write_text_atomic(out, page.render(lab, kind, scenes, modules, side, built))
    recs = sum(1 for s in scenes if s["reference"])
    return (f"{len(scenes)} scenes, {'your code' if side == 'student' else 'the solution'}"
            + (", the solution live beside it" if "solution" in files and side == "student" else "")
            + (f", the solution's recorded runs of {recs}" if recs else ""))


def main(argv=None):
    p = parser()
    try:
        args = p.parse_args(argv)
    except SystemExit as e:
        return 2 if e.code else 0
    os.makedirs(args.build_dir, exist_ok=True)
    out = args.out or os.path.join(args.build_dir, args.lab + ("" if args.side == "student"
                                                                else "-solution") + ".html")
    t0 = time.monotonic()
    try:
        what = make_page(args.lab, args.side, out, args.build_dir, not args.no_solution,
                         quiet=not args.verbose)
    except build.BuildError as e:
        print(f"tools/view --live: {e}", file=sys.stderr)
        return e.status
    except InputError as e:
        print(f"tools/view --live: error: {e}", file=sys.stderr)
        return 2
    say_written("tools/view --live", out, t0, what)
    return 0
