"""The creep figure (handouts/rigid.md#r6, handouts/collisions.md#c5): the largest speed of
any body against time, one curve per run (the one-shot passes against the accumulated,
warm-started solver), on a log scale. Reads rigid traces (vz, wx.. columns) and particle
traces (vx, vy)."""
import math

from .common import InputError, new_figure, read_csv, save_figure

FLOOR = 1e-20  # m/s: speeds below this (exact zeros included) are drawn on this line


def largest_speeds(path):
    """(times, largest linear speed) over the bodies of a trace, one value per written t."""
    rows = read_csv(path, ["t", "id", "vx", "vy"], "trace CSV (t,id,...,vx,vy,...)")
    by_t = {}
    for i, r in enumerate(rows):
        try:
            t = float(r["t"])
            v = [float(r[c]) for c in ("vx", "vy", "vz") if c in r]
        except ValueError:
            raise InputError(f"{path}: row {i + 2}: expected numbers") from None
        s = math.sqrt(sum(c * c for c in v))
        by_t[t] = max(by_t.get(t, 0.0), s if math.isfinite(s) else math.inf)
    ts = sorted(by_t)
    return ts, [by_t[t] for t in ts]


def plot_creep(traces, labels, out, after=None, title=None):
    if len(labels) != len(traces):
        raise InputError(f"--labels: got {len(labels)} labels for {len(traces)} traces")
    fig, ax = new_figure(figsize=(7.5, 4.2))
    notes = []
    for n, (path, label) in enumerate(zip(traces, labels)):
        ts, vs = largest_speeds(path)
        ax.semilogy(ts, [max(v, FLOOR) for v in vs], color=f"C{n}", lw=1.0, label=label)
        late = [v for t, v in zip(ts, vs) if after is None or t >= after]
        if late:
            zeros = sum(1 for v in late if v < FLOOR)
            note = f"{label}: largest speed" + (f" after t = {after:g} s" if after else "")
            note += f": {max(late):.2g} m/s"
            if zeros:
                note += f" ({zeros} rows below {FLOOR:g} m/s, drawn on that line)"
            notes.append(note)
    if after is not None:
        ax.axvline(after, color="#555", ls=":", lw=0.8)
    ax.set_xlabel("time t (s)")
    ax.set_ylabel("largest speed of any body (m/s), log scale")
    ax.legend(loc="best")
    ax.set_title((title or "Resting contact: one-shot passes against accumulated impulses")
                 + ("\n" + "\n".join(notes) if notes else ""), fontsize=9)
    save_figure(fig, out)


def add_command(sub, name, lab):
    s = sub.add_parser(name, help=f"{lab}: the largest speed of any body against time, one "
                       "curve per trace (log scale): how a resting contact creeps")
    s.add_argument("traces", nargs="+", metavar="TRACE.csv")
    s.add_argument("--labels", required=True, help="comma-separated, one per trace")
    s.add_argument("--after", type=float, help="mark this time and report the largest speed "
                   "after it")
    s.add_argument("-o", "--out", required=True, metavar="FIG.png")
    s.add_argument("--title")
