"""Figures of single runs: trajectories, energy and momentum, phase portraits."""
import os

import matplotlib

from matplotlib.lines import Line2D
from matplotlib.transforms import blended_transform_factory

from .common import (InputError, column, finite, integrator_style, new_figure, read_csv,
                     save_figure)

TRACE_COLUMNS = ["t", "id", "x", "y", "vx", "vy"]
STATS_COLUMNS = ["step", "t", "energy", "kinetic", "potential", "px", "py", "force_evals"]
MAX_DRAWN = 300  # particles drawn in a trajectory figure when --ids is not given


def read_trace(path):
    """{id: {"t": [...], "x": [...], ...}} from a trace CSV, rows in file order."""
    rows = read_csv(path, TRACE_COLUMNS, "trace CSV (t,id,x,y,vx,vy)")
    by_id = {}
    for i, r in enumerate(rows):
        s = r["id"].strip()
        try:
            pid = int(s)
        except ValueError:
            raise InputError(f"{path}: row {i + 2}, column 'id': got '{s}', expected a "
                             "whole number") from None
        d = by_id.setdefault(pid, {c: [] for c in ("t", "x", "y", "vx", "vy")})
        for c in ("t", "x", "y", "vx", "vy"):
            s = r[c].strip()
            try:
                d[c].append(float(s))
            except ValueError:
                raise InputError(f"{path}: row {i + 2}, column '{c}': got '{s}', expected "
                                 "a number") from None
    return by_id


def choose_ids(all_ids, limit=MAX_DRAWN):
    """At most `limit` ids, evenly spread over the sorted ids (deterministic)."""
    ids = sorted(all_ids)
    if len(ids) <= limit:
        return ids
    return [ids[(k * len(ids)) // limit] for k in range(limit)]


def _finite_xy(d, a="x", b="y"):
    pts = [(p, q) for p, q in zip(d[a], d[b]) if finite(p) and finite(q)]
    return [p for p, _ in pts], [q for _, q in pts]


def plot_trace(path, out, ids=None, title=None):
    data = read_trace(path)
    if ids is None:
        ids = choose_ids(data.keys())
        note = "" if len(ids) == len(data) else f" ({len(ids)} of {len(data)} particles drawn)"
    else:
        unknown = [i for i in ids if i not in data]
        if unknown:
            raise InputError(f"--ids: particle {unknown[0]} is not in {path} (ids "
                             f"{min(data)}..{max(data)})")
        note = ""
    many = len(ids) > 10
    fig, ax = new_figure(figsize=(6.4, 5.6))
    cmap = matplotlib.colormaps["viridis"]
    starts, ends = [], []
    diverged = 0
    for k, pid in enumerate(ids):
        d = data[pid]
        xs, ys = _finite_xy(d)
        if len(xs) < len(d["x"]):
            diverged += 1
        if not xs:
            continue
        if many:
            color = cmap(k / max(1, len(ids) - 1))
            ax.plot(xs, ys, lw=0.6, alpha=0.7, color=color)
        else:
            ax.plot(xs, ys, lw=1.4, label=f"particle {pid}")
        starts.append((xs[0], ys[0]))
        ends.append((xs[-1], ys[-1]))
    size = 10 if many else 40
    if starts:
        ax.scatter([p for p, _ in starts], [q for _, q in starts], s=size, facecolors="white",
                   edgecolors="black", linewidths=0.8, zorder=3)
        ax.scatter([p for p, _ in ends], [q for _, q in ends], s=size, color="black", zorder=4)
    clipped = _clip_runaway(ax, data, ids) if diverged else False
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    t_end = max((max((t for t in d["t"] if finite(t)), default=0.0) for d in data.values()),
                default=0.0)
    ax.set_title(title or f"Trajectories, t = 0 to {t_end:g} s{note}")
    handles = [Line2D([], [], ls="", marker="o", mfc="white", mec="black", label="start"),
               Line2D([], [], ls="", marker="o", color="black", label="end")]
    if not many:
        handles = ax.get_legend_handles_labels()[0] + handles
    if diverged:
        handles.append(Line2D([], [], ls="", label=f"{diverged} diverged (non-finite)"))
    if clipped:
        handles.append(Line2D([], [], ls="", label=f"view clipped to {RUNAWAY}x the\n"
                                                   "starting size: the run ran away"))
    ax.legend(handles=handles, loc="best", framealpha=0.85)
    fig.tight_layout()
    save_figure(fig, out)


CLIP_ENERGY = 1e3  # an energy figure whose values pass this many times the start is clipped
RUNAWAY = 20  # the view of a run that diverged is clipped to this many times its starting size


def _clip_runaway(ax, data, ids):
    """For a run that diverged: limits the view to RUNAWAY times the size of the starting
    positions when the paths go farther; True if it did."""
    starts = [(data[i]["x"][0], data[i]["y"][0]) for i in ids
              if finite(data[i]["x"][0]) and finite(data[i]["y"][0])]
    pts = [(x, y) for i in ids for x, y in zip(*_finite_xy(data[i]))]
    if not starts or not pts:
        return False
    cx = (min(p for p, _ in starts) + max(p for p, _ in starts)) / 2
    cy = (min(q for _, q in starts) + max(q for _, q in starts)) / 2
    size = max([abs(p - cx) for p, _ in starts] + [abs(q - cy) for _, q in starts]
               + [0.5 * max(abs(p) for p, _ in starts), 0.5 * max(abs(q) for _, q in starts)])
    size = size if size > 0 else 1.0
    reach = max(max(abs(p - cx), abs(q - cy)) for p, q in pts)
    if reach <= RUNAWAY * size * 1.0001:
        return False
    half = RUNAWAY * size
    ax.set_xlim(cx - half, cx + half)
    ax.set_ylim(cy - half, cy + half)
    return True


def read_stats(path):
    rows = read_csv(path, STATS_COLUMNS, "stats CSV (" + ",".join(STATS_COLUMNS) + ")")
    return {c: column(path, rows, c) for c in STATS_COLUMNS}


def drift_series(s):
    """(t, |E - E0| / |E0|) or None when E0 is 0 or not finite (no relative drift)."""
    e0 = s["energy"][0]
    scale = max(abs(e0), 0.0)
    # E0 counts as 0 when it is a cancellation of much larger initial kinetic and
    # potential energies; judged at the start, since a run that blew up has huge
    # energies later that say nothing about E0.
    typical = max([abs(v) for v in (s["kinetic"][0], s["potential"][0]) if finite(v)], default=0.0)
    if not finite(e0) or scale == 0.0 or scale < 1e-12 * typical:
        return None
    t = [ti for ti, e in zip(s["t"], s["energy"]) if finite(e)]
    d = [abs(e - e0) / scale for e in s["energy"] if finite(e)]
    return t, d


def _diverged_at(s):
    for t, e in zip(s["t"], s["energy"]):
        if not finite(e):
            return t
    return None


def _finite_pairs(t, y):
    pts = [(a, b) for a, b in zip(t, y) if finite(a) and finite(b)]
    return [a for a, _ in pts], [b for _, b in pts]


def plot_stats(path, out, title=None):
    s = read_stats(path)
    drift = drift_series(s)
    panels = 3 if drift else 2
    heights = [3, 1.6, 2] if drift else [3, 2]
    fig, axes = new_figure(panels, 1, figsize=(6.4, 2.0 + 1.9 * panels), sharex=True,
                           gridspec_kw={"height_ratios": heights})
    ax = axes[0]
    for key, label, style in (("energy", "total E", "-"), ("kinetic", "kinetic K", "--"),
                              ("potential", "potential U", ":")):
        t, y = _finite_pairs(s["t"], s[key])
        ax.plot(t, y, style, label=label)
    ax.set_ylabel("energy (J)")
    ax.legend(loc="best", framealpha=0.85)
    div = _diverged_at(s)
    ax.set_title(title or ("Energy and momentum" + (f" (diverged at t = {div:g} s)" if div is not None else "")))
    if drift:
        ax2 = axes[1]
        t, d = drift
        tp, dp = zip(*[(a, b) for a, b in zip(t, d) if b > 0]) if any(b > 0 for b in d) else ([], [])
        if dp:
            ax2.semilogy(tp, dp, color="#444444", lw=1.1,
                         label=f"max {max(d):.2e}, final {d[-1]:.2e}")
            ax2.legend(loc="lower right", framealpha=0.85)
        else:
            ax2.text(0.5, 0.5, "E = E0 to the last digit", transform=ax2.transAxes,
                     ha="center", va="center")
        ax2.set_ylabel("|E - E0| / |E0|")
    else:
        ax.text(0.99, 0.02, "E0 = 0: no relative energy drift", transform=ax.transAxes,
                ha="right", va="bottom", fontsize=8.5)
    axm = axes[-1]
    for key, label, style in (("px", "px", "-"), ("py", "py", "--")):
        t, y = _finite_pairs(s["t"], s[key])
        axm.plot(t, y, style, label=label)
    axm.set_ylabel("momentum (kg m/s)")
    axm.set_xlabel("time t (s)")
    axm.legend(loc="best", framealpha=0.85)
    fig.tight_layout()
    save_figure(fig, out)


def plot_energy(paths, labels, out, relative=False, title=None):
    if labels is None:
        labels = [os.path.splitext(os.path.basename(p))[0] for p in paths]
    if len(labels) != len(paths):
        raise InputError(f"--labels: {len(labels)} labels for {len(paths)} files, expected "
                         "one label per file")
    fig, ax = new_figure(figsize=(6.4, 4.4))
    drawn = 0
    scale_all, peak, sane_all, marks = [], 0.0, [], []
    clip = None
    for path, label in zip(paths, labels):
        s = read_stats(path)
        first = [abs(v) for k in ("energy", "kinetic", "potential") for v in s[k][:1] if finite(v)]
        if first and max(first) > 0:
            scale_all.append(max(first))
        peak = max([peak] + [abs(v) for v in s["energy"] if finite(v)])
        sane_all += [v for v in s["energy"] if finite(v)]
        color, marker = integrator_style(label, labels)
        div = _diverged_at(s)
        suffix = f" (diverged at t = {div:g} s)" if div is not None else ""
        if relative:
            dr = drift_series(s)
            if dr is None:
                ax.plot([], [], color=color, label=f"{label}: E0 = 0, no relative drift")
                continue
            t, d = dr
            t, d = zip(*[(a, b) for a, b in zip(t, d) if b > 0]) if any(b > 0 for b in d) else ([], [])
            ax.plot(t, d, color=color, label=label + suffix)
        else:
            t, y = _finite_pairs(s["t"], s["energy"])
            ax.plot(t, y, color=color, label=label + suffix)
        if div is not None and t:
            marks.append((t[-1], (d if relative else y)[-1], color))
        drawn += 1
    if relative:
        ax.set_yscale("log")
        ax.set_ylabel("relative energy error |E - E0| / |E0|")
    elif scale_all and peak > CLIP_ENERGY * max(scale_all):
        # A run that blew up: a full axis would flatten every other curve, so the view
        # keeps the values within CLIP_ENERGY times the starting energies.
        lim = CLIP_ENERGY * max(scale_all)
        sane = [v for v in sane_all if abs(v) <= lim] or [-lim, lim]
        lo, hi = min(sane), max(sane)
        pad = 0.08 * (hi - lo) if hi > lo else max(abs(hi), 1.0) * 0.1
        clip = (lo - pad, hi + pad)
        ax.set_ylim(*clip)
        ax.set_ylabel("total energy E (J)")
        ax.plot([], [], ls="", label="(view clipped: runs that blew up leave the chart)")
    else:
        ax.set_ylabel("total energy E (J)")
    # The last finite value of a run that diverged: an x (on the edge when out of view).
    edge = blended_transform_factory(ax.transData, ax.transAxes)
    for t_last, v_last, color in marks:
        if clip and not clip[0] <= v_last <= clip[1]:
            ax.plot([t_last], [0.98 if v_last > clip[1] else 0.02], marker="x", color=color,
                    ms=8, mew=2, transform=edge, clip_on=False)
        else:
            ax.plot([t_last], [v_last], marker="x", color=color, ms=8, mew=2)
    ax.set_xlabel("time t (s)")
    ax.set_title(title or ("Relative energy error" if relative else "Total energy") + " by run")
    ax.legend(loc="best", framealpha=0.85)
    fig.tight_layout()
    save_figure(fig, out)


def plot_phase(paths, labels, out, pid=0, axis="x", title=None):
    if labels is None:
        labels = [os.path.splitext(os.path.basename(p))[0] for p in paths]
    if len(labels) != len(paths):
        raise InputError(f"--labels: {len(labels)} labels for {len(paths)} files, expected "
                         "one label per file")
    if axis not in ("x", "y"):
        raise InputError(f"--axis: got '{axis}', expected x or y")
    v = "v" + axis
    fig, ax = new_figure(figsize=(6.0, 5.4))
    styles = ["-", "-", "--", "-.", ":"]
    for k, (path, label) in enumerate(zip(paths, labels)):
        data = read_trace(path)
        if pid not in data:
            raise InputError(f"--id: particle {pid} is not in {path} (ids "
                             f"{min(data)}..{max(data)})")
        xs, vs = _finite_xy(data[pid], axis, v)
        color, _ = integrator_style(label, labels)
        diverged = len(xs) < len(data[pid][axis])
        ax.plot(xs, vs, styles[k % len(styles)], color=color, lw=1.2 if k else 1.0,
                label=label + (" (diverged)" if diverged else ""))
        if xs:
            ax.plot([xs[-1]], [vs[-1]], "o", color=color, ms=5)
    # One start marker: the traces share their initial state.
    d0 = read_trace(paths[0])[pid] if paths else None
    if d0 and finite(d0[axis][0]) and finite(d0[v][0]):
        ax.plot([d0[axis][0]], [d0[v][0]], "o", mfc="white", mec="black", ms=7, zorder=5,
                label="start")
    ax.plot([], [], "o", color="gray", ms=5, label="end of each run")
    ax.set_xlabel(f"position {axis} (m)")
    ax.set_ylabel(f"velocity {v} (m/s)")
    ax.set_title(title or f"Phase portrait of particle {pid} ({axis} against {v})")
    ax.legend(loc="best", framealpha=0.85)
    fig.tight_layout()
    save_figure(fig, out)
