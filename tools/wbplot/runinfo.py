"""What a figure says about a run comes from the run's own summary line (docs/run-contract.md):
`tools/plot ... --summary FILE[,FILE...]` hands it over, one file per run drawn, in the order
of the data files. The file holds the run's stdout (its last non-empty line is the summary),
e.g. `build/bin/lab --scene S --out out/run.csv --stats out/run-stats.csv | tee
out/run-summary.json`, or the `<name>-summary.json` the report keeps beside its CSV files.

From it a figure takes
- whether the run diverged, and at which step (status "diverged", steps): only then may it
  say "diverged" (without a summary it says what the data show: "not finite from ...");
- whether the run is a stub's (the summary's "stub": true, with its "warnings"): every figure
  of such a run carries a red mark saying so (stamp(), called by common.save_figure and by
  the animations), so that a plot of untouched stubs never passes for a result.
"""
import json

from .errors import InputError

# The summaries of the runs the current tools/plot command draws ([] without --summary):
# set by cli.run() before the figure is drawn, read by stamp() and by the figures.
CURRENT = []
# Subcommands that draw no run (a scene's force laws alone, a stability region, a sweep's
# table...) take no --summary.
NO_RUN = {"stability", "sweep", "cheapest", "amplification", "implicit-cost", "flow-probe",
          "rigid-sweep", "flow"}


def read_summary(path):
    """The JSON summary (the last non-empty line) of a run's saved stdout."""
    try:
        with open(path, encoding="utf-8") as f:
            lines = [ln for ln in f.read().splitlines() if ln.strip()]
    except OSError as e:
        raise InputError(f"--summary: {path}: cannot read ({e.strerror})") from None
    except UnicodeDecodeError:
        raise InputError(f"--summary: {path}: not a text file (expected a run's JSON "
                         "summary line)") from None
    try:
        s = json.loads(lines[-1]) if lines else None
    except json.JSONDecodeError:
        s = None
    if not isinstance(s, dict) or "status" not in s:
        raise InputError(f"--summary: {path}: its last line is not a run's JSON summary "
                         "(expected the run's stdout, e.g. `build/bin/LAB ... | tee "
                         "out/run-summary.json`)")
    return s


def add_flag(parser):
    parser.add_argument("--summary", metavar="FILE[,FILE...]",
                        help="the run's summary (its stdout saved, e.g. `... | tee "
                             "out/run-summary.json`; one file per data file, comma-separated): "
                             "the figure says 'diverged' and 'stub' from it")


def load(args):
    """Sets CURRENT from args.summary (a comma-separated list of files)."""
    global CURRENT
    text = getattr(args, "summary", None)
    CURRENT = [read_summary(p.strip()) for p in text.split(",")] if text else []


def stub_warnings(summaries=None):
    """The warnings of the stub runs drawn ([] when none is a stub)."""
    out = []
    for s in CURRENT if summaries is None else summaries:
        if s.get("stub"):
            for w in s.get("warnings") or ["the run's summary says it ran stubs"]:
                if str(w) not in out:
                    out.append(str(w))
    return out


def diverged_steps(labels=None):
    """{label or index: step} of the drawn runs whose summary says they diverged."""
    out = {}
    for n, s in enumerate(CURRENT):
        if s.get("status") == "diverged" and isinstance(s.get("steps"), int):
            key = labels[n] if labels and n < len(labels) else n
            out[key] = s["steps"]
    return out


def said_diverged(n=0):
    """True when the summary of the n-th run drawn says it diverged."""
    return n < len(CURRENT) and CURRENT[n].get("status") == "diverged"


STUB_GID = "wb-stub-mark"


def stamp(fig, inside=False):
    """A red box above a figure of a stub run, with its summary's warnings (idempotent). A
    PNG is saved with a tight bounding box, which grows to hold the box above the axes; an
    animation's frames are the figure as it is, so there (inside=True) the box sits inside
    its bottom edge."""
    import textwrap
    ws = stub_warnings()
    if not ws or any(t.get_gid() == STUB_GID for t in fig.texts):
        return
    width = max(40, int(fig.get_size_inches()[0] * 15))  # characters of 7.5 pt per line
    lines = textwrap.wrap("STUB RUN (the run's summary): " + " / ".join(ws), width)
    if len(lines) > 5:
        lines = lines[:5]
        lines[-1] = lines[-1][:width - 3] + "..."
    # Inside a frame: along its bottom edge, over the x label rather than the title.
    fig.text(0.5, 0.005 if inside else 1.01, "\n".join(lines), ha="center", va="bottom", fontsize=7.5, color="#b00000", gid=STUB_GID,
             bbox=dict(boxstyle="round,pad=0.3", fc="#fff0f0", ec="#b00000", lw=0.8))
