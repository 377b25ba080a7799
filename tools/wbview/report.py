"""The viewer pages of tools/report: one per run that writes a trace (docs/view.md)."""
import os

from .cli import make_view


def flag(argv, name):
    """The value of `name` in an argv list, or None."""
    if name in argv:
        i = argv.index(name)
        if i + 1 < len(argv):
            return argv[i + 1]
    return None


def view_of_run(argv, summary, root):
    """The page of one run of tools/report: <trace>-view.html beside the run's trace (its
    --out), from its --stats, --scene and summary (the dict the run printed). Paths in
    argv are taken from `root` (the report runs there) and shown from it. Returns the
    page's path, or None when the run wrote no trace. Raises InputError."""
    trace = flag(argv, "--out")
    if not trace or not trace.endswith(".csv"):
        return None

    def full(p):
        return p if p is None or os.path.isabs(p) else os.path.join(root, p)
    out = full(trace)[:-len(".csv")] + "-view.html"
    make_view(full(trace), out, stats=full(flag(argv, "--stats")), summary=summary,
              scene=full(flag(argv, "--scene")), shown_from=root)
    return out
