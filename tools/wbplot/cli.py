"""The command line of tools/plot: one subcommand per kind of figure."""
import argparse
import math
import sys

from .common import InputError, parse_label_map, parse_list, write_text_atomic


class _Parser(argparse.ArgumentParser):
    """argparse that reports bad flags as one line and exit status 2."""

    def error(self, message):
        raise InputError(f"{message} (see {self.prog} --help)")


def _positive_float(text):
    x = float(text)
    if not (math.isfinite(x) and x > 0):
        raise ValueError(text)
    return x


def build_parser():
    p = _Parser(prog="tools/plot",
                description="Figures from the CSV files a lab executable writes (--out, "
                            "--stats, --sweep). Each subcommand writes PNG files.",
                epilog="Bad input (missing file or column, empty file, bad flag) exits with "
                       "status 2. See docs/report.md.")
    sub = p.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)

    s = sub.add_parser("trace", help="trajectories in the x-y plane from a trace CSV",
                       description="Trajectories in the x-y plane from a trace CSV "
                                   "(t,id,x,y,vx,vy): one line per particle, starts as open "
                                   "circles, ends as dots. At most 300 particles are drawn "
                                   "(evenly spread over the ids) unless --ids is given.")
    s.add_argument("trace", metavar="TRACE.csv")
    s.add_argument("-o", "--out", required=True, metavar="FIG.png")
    s.add_argument("--ids", help="comma-separated particle ids to draw (default: all, at most 300)")
    s.add_argument("--exact", metavar="SCENE.json",
                   help="also draw the scene's closed-form motion, dashed (free fall under "
                        "uniform gravity, \"exact\": \"oscillator\" or \"kepler\")")
    s.add_argument("--title")

    s = sub.add_parser("paths", help="several runs' trajectories overlaid, over the exact motion",
                       description="Trajectories of several runs (trace CSVs, e.g. one per "
                                   "integrator) on the same axes; with --exact, over the "
                                   "scene's closed-form motion (dashed), the view fitted to it "
                                   "and each run's final distance from it in the legend.")
    s.add_argument("traces", nargs="+", metavar="TRACE.csv")
    s.add_argument("--labels", help="comma-separated, one per file (default: file names)")
    s.add_argument("--exact", metavar="SCENE.json", help="the scene, for its closed form")
    s.add_argument("--ids", help="comma-separated particle ids (default: at most 10)")
    s.add_argument("-o", "--out", required=True, metavar="FIG.png")
    s.add_argument("--title")

    s = sub.add_parser("stats", help="energy and momentum against time from a stats CSV",
                       description="Energy (total, kinetic, potential), the energy error "
                                   "|E-E0|/|E0| (|E-E0| in J when E0 is 0 to rounding), and "
                                   "momentum (px, py) against time from a stats CSV. A run "
                                   "that blew up is drawn as |E|, |K|, |U|, |p| on a log scale "
                                   "up to its last finite step, the divergence marked, with "
                                   "--growth F beside the measured growth per step.")
    s.add_argument("stats", metavar="STATS.csv")
    s.add_argument("-o", "--out", required=True, metavar="FIG.png")
    s.add_argument("--growth", type=_positive_float, metavar="F",
                   help="predicted energy factor per step, drawn when the run blew up")
    s.add_argument("--diverged", type=int, metavar="STEP",
                   help="the step at which the run's summary says it diverged (its last "
                        "row; docs/run-contract.md, \"Diverged\"); without it (or "
                        "--summary), the first row whose energy is not finite is drawn as "
                        "'not finite'")
    s.add_argument("--scene", metavar="SCENE.json",
                   help="the run's scene: when it damps, drives or has lossy contacts, the "
                        "middle panel is E - E0, the energy they change on purpose, not an "
                        "error")
    s.add_argument("--title")

    s = sub.add_parser("energy", help="total energy of several runs on the same axes",
                       description="Total energy against time for several runs (stats CSVs), "
                                   "e.g. each integrator on the same scene. When a run blew up, "
                                   "|E| on a log scale up to each run's last finite step, the "
                                   "divergence marked, with the --growth predictions beside "
                                   "the measured growth. Curves that coincide are drawn dashed "
                                   "with markers and labelled so.")
    s.add_argument("stats", nargs="+", metavar="STATS.csv")
    s.add_argument("--labels", help="comma-separated, one per file (default: file names)")
    s.add_argument("-o", "--out", required=True, metavar="FIG.png")
    s.add_argument("--relative", action="store_true",
                   help="plot |E - E0| / |E0| on a log scale instead of E (|E - E0| in J "
                        "when E0 is 0 to rounding)")
    s.add_argument("--growth", metavar="LABEL=F,...",
                   help="predicted energy factor per step of some runs, drawn beside the "
                        "measured growth when a run blew up")
    s.add_argument("--diverged", metavar="LABEL=STEP,...",
                   help="the runs whose summary says they diverged, and at which step (an x "
                        "marks it); without it, a run diverged where its energy is first not "
                        "finite")
    s.add_argument("--title")

    s = sub.add_parser("phase", help="phase portrait of one particle, several traces overlaid",
                       description="Phase portrait (x against vx, or y against vy) of one "
                                   "particle from one or more trace CSVs.")
    s.add_argument("traces", nargs="+", metavar="TRACE.csv")
    s.add_argument("--labels", help="comma-separated, one per file (default: file names)")
    s.add_argument("--id", type=int, default=0, help="particle id (default 0)")
    s.add_argument("--axis", choices=["x", "y"], default="x", help="x (default) or y")
    s.add_argument("-o", "--out", required=True, metavar="FIG.png")
    s.add_argument("--title")

    s = sub.add_parser("forcelaw", help="the scene's force laws, with where a run's particles sit",
                       description="From a scene JSON: the vortex's swirl speed against "
                                   "radius, each spring's force against its stretch, the "
                                   "attractor's pull against distance (one panel each the "
                                   "scene has); with --trace, the particles at the last "
                                   "written step of that run on top.")
    s.add_argument("scene", metavar="SCENE.json")
    s.add_argument("--trace", metavar="TRACE.csv", help="a run of the scene (its last rows)")
    s.add_argument("-o", "--out", required=True, metavar="FIG.png")
    s.add_argument("--title")

    s = sub.add_parser("sweep", help="work-precision, convergence and energy-error figures",
                       description="From a sweep CSV (scene,integrator,dt,steps,force_evals,"
                                   "wall_s,error,energy_error,reference,status) writes "
                                   "PREFIX-work-precision.png, PREFIX-convergence.png and "
                                   "PREFIX-energy-error.png. The measured order is the "
                                   "least-squares slope of log error against log dt over the "
                                   "asymptotic range (docs/report.md).")
    s.add_argument("sweep", metavar="SWEEP.csv")
    s.add_argument("-o", "--out", required=True, metavar="PREFIX",
                   help="output prefix, e.g. build/report/euler/oscillator-sweep")
    s.add_argument("--scene", help="the scene to plot when the CSV holds several")
    s.add_argument("--scale", type=_positive_float, default=1.0,
                   help="length scale of the scene in m (default 1): errors below 1e-13 x "
                        "scale (rounding) or at least 0.1 x scale (not asymptotic) are left "
                        "out of the measured order")

    s = sub.add_parser("stability", help="regions of absolute stability in the z = h lambda plane",
                       description="Each method's region |R(z)| <= 1 (filled, boundary drawn), "
                                   "semi-implicit Euler's oscillator stability segment "
                                   "|h w| < 2 on the imaginary axis, and the scene's h w "
                                   "marked as z = +-i h w (or h w (-zeta +- i sqrt(1 - "
                                   "zeta^2)) with --damping).")
    s.add_argument("-o", "--out", required=True, metavar="FIG.png")
    s.add_argument("--methods", default="explicit-euler,symplectic-euler,midpoint,trapezoid,rk4",
                   help="comma-separated (default: all five)")
    s.add_argument("--mark", help="comma-separated h*omega values to mark")
    s.add_argument("--damping", type=float, metavar="ZETA",
                   help="damping ratio zeta >= 0 of the marked oscillator")
    s.add_argument("--title")

    s = sub.add_parser("cheapest", help="Markdown table: cheapest run reaching each target error",
                       description="For each scene and target error, the integrator and dt "
                                   "that reach final position error <= target at the least "
                                   "wall time, and separately with the fewest force "
                                   "evaluations ('none' if no run does). Prints the table.")
    s.add_argument("sweep", metavar="SWEEP.csv")
    s.add_argument("--targets", default="1e-2,1e-4,1e-6",
                   help="comma-separated target errors in m (default 1e-2,1e-4,1e-6)")
    s.add_argument("--md", metavar="FILE", help="also write the table to FILE")

    # Subcommands of the lab plug-ins (tools/wbplot/labs/<lab>.py: add_commands(sub)
    # registers them, run(args) returns True for a command it handled).
    for mod in _lab_plugins():
        if hasattr(mod, "add_commands"):
            mod.add_commands(sub)
    # What a figure says about a run (diverged, a stub) comes from the run's own summary.
    from . import runinfo
    for name, parser in sub.choices.items():
        if name not in runinfo.NO_RUN:
            runinfo.add_flag(parser)
    return p


def _lab_plugins():
    """The modules tools/wbplot/labs/<lab>.py, in name order."""
    import importlib
    import os
    here = os.path.join(os.path.dirname(os.path.abspath(__file__)), "labs")
    mods = []
    for name in sorted(os.listdir(here)) if os.path.isdir(here) else []:
        if name.endswith(".py") and not name.startswith("_"):
            mods.append(importlib.import_module(f"{__package__}.labs.{name[:-3]}"))
    return mods


def run(args):
    from . import runinfo, runs, stability, sweep
    runinfo.load(args)
    for mod in _lab_plugins():
        if hasattr(mod, "run") and mod.run(args):
            return
    if args.command == "trace":
        ids = parse_list(args.ids, "--ids", int) if args.ids else None
        runs.plot_trace(args.trace, args.out, ids=ids, title=args.title, exact=args.exact)
    elif args.command == "paths":
        ids = parse_list(args.ids, "--ids", int) if args.ids else None
        labels = parse_list(args.labels, "--labels") if args.labels else None
        runs.plot_paths(args.traces, labels, args.out, scene=args.exact, ids=ids,
                        title=args.title)
    elif args.command == "stats":
        changes = runs.energy_changers(runs.read_scene(args.scene, "--scene")) \
            if args.scene else None
        runs.plot_stats(args.stats, args.out, title=args.title, growth=args.growth,
                        diverged=args.diverged, changes=changes)
    elif args.command == "energy":
        labels = parse_list(args.labels, "--labels") if args.labels else None
        growth = parse_label_map(args.growth, "--growth", _positive_float, "LABEL=F with F > 0")
        diverged = parse_label_map(args.diverged, "--diverged", int, "LABEL=STEP")
        runs.plot_energy(args.stats, labels, args.out, relative=args.relative, title=args.title,
                         growth=growth, diverged=diverged)
    elif args.command == "phase":
        labels = parse_list(args.labels, "--labels") if args.labels else None
        runs.plot_phase(args.traces, labels, args.out, pid=args.id, axis=args.axis,
                        title=args.title)
    elif args.command == "forcelaw":
        from . import forcelaw
        forcelaw.plot_forcelaw(args.scene, args.out, trace=args.trace, title=args.title)
    elif args.command == "sweep":
        for f in sweep.plot_sweep(args.sweep, args.out, scene=args.scene, scale=args.scale):
            print(f)
    elif args.command == "stability":
        methods = parse_list(args.methods, "--methods")
        marks = parse_list(args.mark, "--mark", float) if args.mark else []
        stability.plot_stability(args.out, methods, marks, args.damping, title=args.title)
    elif args.command == "cheapest":
        targets = parse_list(args.targets, "--targets", float)
        for t in targets:
            if not (math.isfinite(t) and t > 0):
                raise InputError(f"--targets: got {t:g}, expected errors > 0")
        table = sweep.cheapest_markdown(sweep.read_sweep(args.sweep), targets)
        if args.md:
            write_text_atomic(args.md, table)
        sys.stdout.write(table)


def main(argv=None):
    parser = build_parser()
    args = None
    try:
        args = parser.parse_args(argv)
        if args.command is None:
            raise InputError("missing COMMAND (see tools/plot --help for the list)")
        run(args)
    except InputError as e:
        print(f"tools/plot: error: {e}", file=sys.stderr)
        return 2
    except (ValueError, ArithmeticError, KeyError, IndexError, TypeError) as e:
        # Data the figure cannot be drawn from: one line, never a traceback.
        print(f"tools/plot: error: {getattr(args, 'command', '')}: cannot draw this data "
              f"({type(e).__name__}: {e})", file=sys.stderr)
        return 2
    return 0
