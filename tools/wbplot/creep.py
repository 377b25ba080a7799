"""The creep figure (handouts/rigid.md#r6, handouts/collisions.md#c5): how resting contacts
behave under the one-shot passes and under the accumulated, warm-started solver, one curve
per run: on top the largest speed of any body (log scale), below the largest distance any
body has moved since a time `after` (mm): the quantity a student looks at when asking
"does it come to rest?". A solver may keep a velocity that its position correction cancels
every step: then the speeds stay up while nothing moves, and only the lower panel says
that the bodies stand still. Reads rigid traces (vz, wx.. columns) and particle traces.

The same numbers go to `<scene>-rest.csv` (solver, speed_max, moved_max after `after`),
which the handouts' claims read (docs/report.md, Claims)."""
import json
import math
import os

from .common import InputError, new_figure, read_csv, save_figure, write_text_atomic

FLOOR = 1e-20  # m/s: speeds below this (exact zeros included) are drawn on this line
SOLVERS = ("passes", "accumulated")


def _rows(path):
    return read_csv(path, ["t", "id", "x", "y", "vx", "vy"], "trace CSV (t,id,x,y,...,vx,vy,...)")


def _float(path, i, r, c):
    try:
        return float(r[c])
    except ValueError:
        raise InputError(f"{path}: row {i + 2}, column '{c}': expected a number") from None


def read_motion(path):
    """(times, {t: largest speed}, {t: {id: position}}) of a trace, one entry per written t."""
    speeds, where = {}, {}
    for i, r in enumerate(_rows(path)):
        t = _float(path, i, r, "t")
        v = [_float(path, i, r, c) for c in ("vx", "vy", "vz") if c in r]
        s = math.sqrt(sum(c * c for c in v))
        speeds[t] = max(speeds.get(t, 0.0), s if math.isfinite(s) else math.inf)
        where.setdefault(t, {})[r["id"]] = tuple(_float(path, i, r, c)
                                                 for c in ("x", "y", "z") if c in r)
    return sorted(speeds), speeds, where


def largest_speeds(path):
    """(times, largest linear speed) over the bodies of a trace, one value per written t."""
    ts, speeds, _ = read_motion(path)
    return ts, [speeds[t] for t in ts]


def moved_since(ts, where, after):
    """(times from `after` on, largest distance any body has moved from where it was at the
    first written time >= after), in metres."""
    later = [t for t in ts if after is None or t >= after]
    if not later:
        return [], []
    ref = where[later[0]]
    out = []
    for t in later:
        d = [math.dist(p, ref[b]) for b, p in where[t].items() if b in ref]
        out.append(max(d) if d else 0.0)
    return later, out


def rest_numbers(path, after):
    """(largest speed, largest distance moved) from `after` on."""
    ts, speeds, where = read_motion(path)
    late = [speeds[t] for t in ts if after is None or t >= after]
    _, moved = moved_since(ts, where, after)
    return (max(late) if late else math.nan), (max(moved) if moved else math.nan)


def write_rest(csv_path, traces, labels, after):
    """<scene>-rest.csv: solver, speed_max (m/s) and moved_max (m) from `after` on."""
    rows = ["solver,after,speed_max,moved_max"]
    for path, label in zip(traces, labels):
        speed, moved = rest_numbers(path, after)
        rows.append(f"{label},{after:.9g},{speed:.9g},{moved:.9g}")
    write_text_atomic(csv_path, "\n".join(rows) + "\n")


def plot_creep(traces, labels, out, after=None, title=None):
    from . import flat
    if len(labels) != len(traces):
        raise InputError(f"--labels: got {len(labels)} labels for {len(traces)} traces")
    fig, (ax, axm) = new_figure(2, 1, figsize=(7.5, 6.4), sharex=True,
                                gridspec_kw={"height_ratios": [3, 2]})
    notes, moves = [], []
    for n, (path, label) in enumerate(zip(traces, labels)):
        ts, speeds, where = read_motion(path)
        vs = [speeds[t] for t in ts]
        ax.semilogy(ts, [max(v, FLOOR) for v in vs], color=f"C{n}", lw=1.0, label=label)
        late = [v for t, v in zip(ts, vs) if after is None or t >= after]
        tm, moved = moved_since(ts, where, after)
        mm = [1e3 * d for d in moved]
        moves.append(mm)
        # Wide and pale, then dashed: two runs that both stand still stay both visible.
        axm.plot(tm, mm, color=f"C{n}", label=label + (
            flat.label(mm, "mm") if flat.is_constant(mm, 1.0) else ""),
            **(dict(lw=3.0, alpha=0.5) if n == 0 else dict(lw=1.2, ls=(0, (4, 3)))))
        if late:
            zeros = sum(1 for v in late if v < FLOOR)
            note = f"{label}, after t = {after:g} s: " if after is not None else f"{label}: "
            note += f"speed up to {max(late):.2g} m/s, moved at most {max(mm):.2g} mm"
            if zeros:
                note += f" ({zeros} rows below {FLOOR:g} m/s, drawn on that line)"
            notes.append(note)
    if after is not None:
        for a in (ax, axm):
            a.axvline(after, color="#555", ls=":", lw=0.8)
    ax.set_ylabel("largest speed of any body\n(m/s), log scale")
    ax.legend(loc="best")
    if moves and all(flat.is_constant(m, 1.0) for m in moves if m):
        flat.flat_view(axm, moves)
    flat.plain_ticks(axm)
    axm.set_ylabel("largest distance moved\n" + (f"since t = {after:g} s (mm)" if after
                                                 is not None else "(mm)"))
    axm.set_xlabel("time t (s)")
    axm.legend(loc="best")
    ax.set_title((title or "Resting contact: one-shot passes against accumulated impulses")
                 + ("\n" + "\n".join(notes) if notes else ""), fontsize=9)
    fig.tight_layout()
    save_figure(fig, out)


def add_command(sub, name, lab):
    s = sub.add_parser(name, help=f"{lab}: the largest speed of any body against time, and "
                       "the largest distance any body moved since --after, one curve per "
                       "trace: whether resting contacts come to rest")
    s.add_argument("traces", nargs="+", metavar="TRACE.csv")
    s.add_argument("--labels", required=True, help="comma-separated, one per trace")
    s.add_argument("--after", type=float, help="mark this time, report the largest speed "
                   "after it, and measure the distance moved from where the bodies were then")
    s.add_argument("-o", "--out", required=True, metavar="FIG.png")
    s.add_argument("--title")


def solver_scenes(doc, out_dir, stem, change):
    """{solver: scene file} for the scene with each solver (change(doc, solver) edits it)."""
    out = {}
    for solver in SOLVERS:
        d = json.loads(json.dumps(doc))
        change(d, solver)
        path = os.path.join(out_dir, f"{stem}-{solver}.json")
        with open(path, "w", encoding="utf-8") as f:
            json.dump(d, f, indent=1)
        out[solver] = path
    return out


def make_rest_file(exe, out_dir, lab, stem, change, trace_name, after):
    """What tools/claims needs without the report: scenes/<lab>/<stem>.json run with both
    solvers (the report's own commands and names) and <stem>-rest.csv from their traces."""
    import subprocess
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    with open(os.path.join(root, "scenes", lab, stem + ".json"), encoding="utf-8") as f:
        doc = json.load(f)
    traces = []
    for solver, scene in solver_scenes(doc, out_dir, stem, change).items():
        trace = os.path.join(out_dir, trace_name.format(solver=solver))
        argv = [exe, "--scene", scene, "--out", trace, "--every", "10"]
        p = subprocess.run(argv, capture_output=True, text=True)
        if p.returncode != 0:
            raise RuntimeError(f"{' '.join(argv)}: exit status {p.returncode}: "
                               + (p.stderr.strip().splitlines() or [""])[-1])
        traces.append(trace)
    write_rest(os.path.join(out_dir, f"{stem}-rest.csv"), traces, list(SOLVERS), after)
