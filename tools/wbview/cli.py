"""tools/view: one self-contained HTML page that plays a run (docs/view.md)."""
import argparse
import os
import sys
import time

from wbplot.common import write_text_atomic
from wbview import say_written

from . import model, page
from .data import InputError, read_scene, read_stats, read_summary, read_trace

EPILOG = """\
Beside RUN.csv the viewer looks for RUN-stats.csv and RUN-summary.json (the names
tools/report gives them) when --stats and --summary are not given. A run's summary is
the last line it prints: keep it with `> out/run-summary.json`.
Open the page in any current browser (no server, no network: everything is inside it).
Exit status: 0 written, 2 bad input (one line names the file and what was expected).
See docs/view.md."""


def parser():
    p = argparse.ArgumentParser(
        prog="tools/view", formatter_class=argparse.RawDescriptionHelpFormatter,
        description="Writes one self-contained HTML page that plays a run of any lab: the "
                    "particles or bodies moving (play, pause, step, scrub, speed, trails), "
                    "the energy and momentum curves with a cursor on the playhead, where a "
                    "diverged run diverged, the exact motion where the scene has one, a "
                    "second run and its difference from the first, and the frame budget.",
        epilog=EPILOG)
    p.add_argument("run", metavar="RUN.csv", help="the run's trace (its --out file)")
    p.add_argument("run2", metavar="RUN2.csv", nargs="?",
                   help="a second run of the same scene (another integrator, the solution's "
                        "run), drawn over the first with the difference between them")
    p.add_argument("--stats", metavar="STATS.csv", help="the run's --stats file (energy, "
                   "momentum); default RUN-stats.csv when it exists")
    p.add_argument("--summary", metavar="FILE", help="the run's summary line: its stdout saved "
                   "to a file (the last line is read); default RUN-summary.json when it exists")
    p.add_argument("--stats2", metavar="STATS.csv", help="the second run's stats (default "
                   "RUN2-stats.csv when it exists)")
    p.add_argument("--summary2", metavar="FILE", help="the second run's summary (default "
                   "RUN2-summary.json when it exists)")
    p.add_argument("--scene", metavar="SCENE.json", help="the scene the run was made from: "
                   "radii, springs, planes, obstacles, bodies' shapes, hinges, the exact motion")
    p.add_argument("--labels", metavar="A,B", help="names of the runs (default: the file names)")
    p.add_argument("-o", "--out", metavar="VIEW.html",
                   help="the page to write (default RUN-view.html beside RUN.csv)")
    p.add_argument("--no-setup", action="store_true",
                   help="install nothing first (tools/lib/start-python)")
    p.add_argument("--live", action="store_true",
                   help="a lab's live page instead: your code compiled to WebAssembly, running "
                        "in the browser (tools/view --live --lab LAB; --live --help lists its "
                        "flags; docs/live.md)")
    return p


def beside(path, suffix):
    """RUN.csv -> RUN<suffix> when that file exists, else None."""
    stem = path[:-4] if path.endswith(".csv") else path
    cand = stem + suffix
    return cand if os.path.isfile(cand) else None


def load_run(path, stats_path, summary_path):
    """The trace, stats and summary of a run; summary_path may be the summary itself (a
    dict: tools/report has it in hand)."""
    trace = read_trace(path)
    stats_path = stats_path or beside(path, "-stats.csv")
    if isinstance(summary_path, dict):
        summary, summary_path = summary_path, "the run's"
    else:
        summary_path = summary_path or beside(path, "-summary.json")
        summary = read_summary(summary_path) if summary_path else None
    stats = read_stats(stats_path, trace.kind) if stats_path else None
    return trace, stats, summary, stats_path, summary_path


def make_view(run, out, stats=None, summary=None, scene=None, run2=None, stats2=None,
              summary2=None, labels=None, shown_from=None):
    """Writes the page; returns (the page's metadata, a one-line account of what it holds).
    Paths are shown as given, or from the folder `shown_from`. Raises InputError on bad
    input (nothing written)."""
    if labels is None:
        labels = [os.path.basename(run)[:-4] if run.endswith(".csv") else os.path.basename(run)]
        if run2:
            labels.append(os.path.basename(run2)[:-4] if run2.endswith(".csv")
                          else os.path.basename(run2))
    trace, st, sm, stats_path, summary_path = load_run(run, stats, summary)
    doc = read_scene(scene) if scene else None
    second = None
    if run2:
        t2, s2, m2, _, _ = load_run(run2, stats2, summary2)
        second = (t2, s2, m2)
    meta = model.build(trace, st, sm, doc, scene, second,
                       labels=(labels + ["run 2"])[:2] if len(labels) < 2 else labels[:2])
    # Where the page's files are from the page itself (its test reads the CSV back).
    here = os.path.dirname(os.path.abspath(out))
    for r, path in zip(meta["runs"], [run, run2]):
        r["from_page"] = os.path.relpath(os.path.abspath(path), here)
        if shown_from:
            r["path"] = os.path.relpath(os.path.abspath(path), shown_from)
    if scene:
        meta["scene_from_page"] = os.path.relpath(os.path.abspath(scene), here)
        if shown_from:
            meta["scene_path"] = os.path.relpath(os.path.abspath(scene), shown_from)
    what = (f"{trace.n} {'bodies' if trace.kind == 'rigid' else 'particles'}, "
            f"{trace.frames} written steps")
    if meta["runs"][0]["kept_every"] > 1:
        what += f" (every {meta['runs'][0]['kept_every']}th kept)"
    used = [f"stats {stats_path}" if stats_path else "no stats",
            f"summary {summary_path}" if summary_path else "no summary",
            f"scene {scene}" if scene else "no scene"]
    if meta["exact"]:
        used.append(f"exact motion: {meta['exact']['kind']}")
    if os.path.isdir(out):
        raise InputError(f"-o: {out}: is a folder, expected an .html file to write")
    write_text_atomic(out, page.render(meta))
    return meta, f"{what}; {', '.join(used)}"


def main(argv=None):
    if "--live" in (sys.argv[1:] if argv is None else argv):  # a live page: docs/live.md
        from wbview.live.cli import main as live_main
        return live_main(argv)
    p = parser()
    try:
        args = p.parse_args(argv)
    except SystemExit as e:
        return 2 if e.code else 0
    labels = None
    if args.labels is not None:
        labels = [s.strip() for s in args.labels.split(",")]
        want = 2 if args.run2 else 1
        if len(labels) != want or not all(labels):
            print(f"tools/view: error: --labels: got '{args.labels}', expected {want} "
                  "non-empty name(s) separated by a comma", file=sys.stderr)
            return 2
    for flag in ("stats2", "summary2"):
        if getattr(args, flag) and not args.run2:
            print(f"tools/view: error: --{flag}: given without a second run (RUN2.csv)",
                  file=sys.stderr)
            return 2
    out = args.out or ((args.run[:-4] if args.run.endswith(".csv") else args.run) + "-view.html")
    if not out.endswith((".html", ".htm")):
        print(f"tools/view: error: -o: got '{out}', expected a file name ending in .html",
              file=sys.stderr)
        return 2
    t0 = time.monotonic()
    try:
        _, what = make_view(args.run, out, args.stats, args.summary, args.scene, args.run2,
                            args.stats2, args.summary2, labels)
    except InputError as e:
        print(f"tools/view: error: {e}", file=sys.stderr)
        return 2
    say_written("tools/view", out, t0, what)
    return 0
