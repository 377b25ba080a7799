"""Figures of single runs: trajectories, energy and momentum, phase portraits."""
import math
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
    if rows and "qw" in rows[0]:
        raise InputError(f"{path}: a rigid-body trace (3D, with orientations), expected a "
                         "particle trace t,id,x,y,vx,vy: draw it with tools/plot rigid-frames, "
                         "rigid-polhode or rigid-animate")
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


def read_scene(path, flag="--exact"):
    """A scene JSON file (for --exact, --scene)."""
    import json
    try:
        with open(path, encoding="utf-8") as f:
            doc = json.load(f)
    except OSError as e:
        raise InputError(f"{flag}: {path}: cannot read ({e.strerror})") from None
    except json.JSONDecodeError as e:
        raise InputError(f"{flag}: {path}: not JSON ({e.msg}, line {e.lineno})") from None
    if not isinstance(doc, dict):
        raise InputError(f"{flag}: {path}: expected a JSON object (a scene)")
    return doc


def exact_paths(scene, ids, t_end, samples=1500):
    """{id: (xs, ys)} of the scene's closed-form motion from 0 to t_end, or ({}, None)."""
    from .exact import motion
    kind, at = motion(read_scene(scene))
    if at is None:
        return {}, None
    n = len(read_scene(scene).get("particles", []))
    # A closed curve is drawn once: over many turns its dashes would fill a band.
    span = min(t_end, getattr(at, "period", t_end) * 1.002)
    out = {}
    for pid in ids:
        if 0 <= pid < n:
            pts = [at(pid, span * k / samples) for k in range(samples + 1)]
            end = at(pid, t_end)
            out[pid] = ([p for p, _ in pts], [q for _, q in pts], end)
    return out, kind


def _draw_exact(ax, paths, kind):
    for k, (xs, ys, end) in enumerate(paths.values()):
        ax.plot(xs, ys, color="black", lw=1.0, ls=(0, (5, 3)), alpha=0.8, zorder=5,
                label=f"exact ({kind})" if k == 0 else None)
        ax.plot([end[0]], [end[1]], ls="", marker="x", color="black", ms=8, mew=1.8,
                zorder=8, label="exact, at the end" if k == 0 else None)


def _view_of(ax, paths, pad=0.25):
    """Limits the view to the exact paths (plus a margin); runs that leave it left the exact
    motion far behind."""
    xs = [x for p in paths.values() for x in p[0]]
    ys = [y for p in paths.values() for y in p[1]]
    if not xs:
        return
    w = max(max(xs) - min(xs), max(ys) - min(ys), 1e-9)
    ax.set_xlim(min(xs) - pad * w, max(xs) + pad * w)
    ax.set_ylim(min(ys) - pad * w, max(ys) + pad * w)


def plot_paths(paths, labels, out, scene=None, ids=None, title=None):
    """Several runs' trajectories (e.g. one per integrator) on the same axes, over the
    scene's closed-form motion when it has one."""
    if labels is None:
        labels = [os.path.splitext(os.path.basename(p))[0] for p in paths]
    if len(labels) != len(paths):
        raise InputError(f"--labels: {len(labels)} labels for {len(paths)} files, expected "
                         "one label per file")
    runs = [read_trace(p) for p in paths]
    if ids is None:
        ids = choose_ids(runs[0].keys(), 10)
    fig, ax = new_figure(figsize=(6.6, 5.8))
    t_end = max(max((t for t in d["t"] if finite(t)), default=0.0)
                for r in runs for d in r.values())
    ex, kind = exact_paths(scene, ids, t_end) if scene else ({}, None)
    styles = ["-", (0, (4, 2)), (0, (1, 1.5)), "-."]
    far = []
    for k, (data, label) in enumerate(zip(runs, labels)):
        color, marker = integrator_style(label, labels)
        for j, pid in enumerate(ids):
            if pid not in data:
                raise InputError(f"--ids: particle {pid} is not in {paths[k]}")
            xs, ys = _finite_xy(data[pid])
            ax.plot(xs, ys, color=color, ls=styles[k % len(styles)], lw=1.3,
                    label=label if j == 0 else None)
            if xs:
                ax.plot([xs[-1]], [ys[-1]], "o", color=color, ms=5, zorder=6)
        if ex:
            # How far the run ends from the exact motion (largest over the particles).
            from .exact import motion
            _, at = motion(read_scene(scene))
            off = [math.hypot(data[p]["x"][-1] - at(p, data[p]["t"][-1])[0],
                              data[p]["y"][-1] - at(p, data[p]["t"][-1])[1]) for p in ids
                   if p in ex]
            far.append((label, max(off) if off and all(finite(o) for o in off) else None))
    if ex:
        _draw_exact(ax, ex, kind)
        _view_of(ax, ex)
        from . import runinfo
        for n, (label, d) in enumerate(far):
            ax.plot([], [], ls="", label=f"{label}: ends {d:.3g} m from exact" if d is not None
                    else f"{label}: " + ("diverged (its summary)" if runinfo.said_diverged(n)
                                         else "not finite at the end"))
    starts = [(runs[0][p]["x"][0], runs[0][p]["y"][0]) for p in ids]
    ax.scatter([a for a, _ in starts], [b for _, b in starts], s=40, facecolors="white",
               edgecolors="black", zorder=7, label="start")
    ax.set_aspect("equal", adjustable="box" if ex else "datalim")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(title or "Trajectories by run")
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.11), ncol=2, fontsize=7.5,
              frameon=False)
    fig.tight_layout()
    save_figure(fig, out)


def plot_trace(path, out, ids=None, title=None, exact=None):
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
    # A run that diverged, or ran a million times its size away (its trace stops at the
    # last finite state), is clipped to RUNAWAY times the starting size.
    clipped = _clip_runaway(ax, data, ids, RUNAWAY if diverged else RAN_AWAY)
    if exact:
        t_end = max(max((t for t in d["t"] if finite(t)), default=0.0) for d in data.values())
        ex, kind = exact_paths(exact, ids, t_end)
        if ex:
            _draw_exact(ax, ex, kind)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    t_end = max((max((t for t in d["t"] if finite(t)), default=0.0) for d in data.values()),
                default=0.0)
    ax.set_title(title or f"Trajectories, t = 0 to {t_end:g} s{note}")
    handles = [Line2D([], [], ls="", marker="o", mfc="white", mec="black", label="start"),
               Line2D([], [], ls="", marker="o", color="black", label="end")]
    if not many or exact:
        handles = ax.get_legend_handles_labels()[0] + handles
    if diverged:
        from . import runinfo
        handles.append(Line2D([], [], ls="", label=(
            f"the run diverged (its summary): {diverged} not finite at the end"
            if runinfo.said_diverged(0) else f"{diverged} not finite at the end")))
    if clipped:
        far = max(math.hypot(x, y) for i in ids for x, y in zip(*_finite_xy(data[i])))
        handles.append(Line2D([], [], ls="", label=f"view clipped to {RUNAWAY}x the\n"
                                                   f"starting size: the run ran away\n"
                                                   f"(to {far:.2g} m from the origin)"))
    ax.legend(handles=handles, loc="best", framealpha=0.85)
    fig.tight_layout()
    save_figure(fig, out)


CLIP_ENERGY = 1e3  # an energy figure whose values pass this many times the start is clipped
RUNAWAY = 20  # the view of a run that diverged is clipped to this many times its starting size


RAN_AWAY = 1e6  # a finite path farther than this many times its starting size ran away


def _clip_runaway(ax, data, ids, threshold=RUNAWAY):
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
    if reach <= threshold * size * 1.0001:
        return False
    half = RUNAWAY * size
    ax.set_xlim(cx - half, cx + half)
    ax.set_ylim(cy - half, cy + half)
    return True


def read_stats(path):
    rows = read_csv(path, STATS_COLUMNS, "stats CSV (" + ",".join(STATS_COLUMNS) + ")")
    return {c: column(path, rows, c) for c in STATS_COLUMNS}


ROUNDING_E0 = 1e-9  # |E0| below this times the run's largest |K| + |U| is rounding noise


def energy_scale(s):
    """(scale, kind) for the energy error of a run: (|E0|, "relative") when E0 means
    something, else (1, "absolute") (|E - E0| in J) when E0 is 0 or rounding noise around 0
    (a cancellation, or potentials that are 0 at the start: below ROUNDING_E0 times the
    |K| + |U| of the first two rows)."""
    e0 = s["energy"][0]
    # The size of K and U at the first two rows (not later: a run that blew up would make
    # any E0 look like noise).
    typical = max([abs(k) + abs(u) for k, u in zip(s["kinetic"][:2], s["potential"][:2])
                   if finite(k) and finite(u)], default=0.0)
    if not finite(e0) or e0 == 0.0 or abs(e0) < ROUNDING_E0 * typical:
        return 1.0, "absolute"
    return abs(e0), "relative"


def drift_series(s):
    """(t, |E - E0| / scale, kind) over the finite rows; kind "relative" or "absolute"."""
    scale, kind = energy_scale(s)
    e0 = s["energy"][0]
    if not finite(e0):
        return None
    t = [ti for ti, e in zip(s["t"], s["energy"]) if finite(e)]
    d = [abs(e - e0) / scale for e in s["energy"] if finite(e)]
    return t, d, kind


def _diverged_at(s, step=None):
    """(t, step, said) where the run stopped: the row of `step` when the run's summary gave
    it (--diverged or --summary: the run contract's rule, docs/run-contract.md; said=True,
    the figure may call it "diverged"), else the first row whose energy is not finite
    (said=False: the figure says "not finite", a fact of the data, not a verdict); None
    when neither."""
    if step is not None:
        for t, st in zip(s["t"], s["step"]):
            if st == step:
                return t, st, True
        raise InputError(f"--diverged: step {step} is not a row of the stats (the run's "
                         f"last row is step {s['step'][-1]:.0f})")
    for t, st, e in zip(s["t"], s["step"], s["energy"]):
        if not finite(e):
            return t, st, False
    return None


def _stop_words(div):
    """How a figure names the row where a run stopped (see _diverged_at)."""
    return "diverged at" if div[2] else "not finite from"


def _start_scale(s):
    """The energy scale of the start: the median |K| + |U| over the first tenth of the rows
    (E0 alone may be 0, or rounding noise, when the potentials are 0 at the start; the
    largest over the run says nothing when the run blew up)."""
    ku = [abs(k) + abs(u) for k, u in zip(s["kinetic"], s["potential"]) if finite(k) and finite(u)]
    head = sorted(ku[:max(2, len(ku) // 10)])
    return head[len(head) // 2] if head else 0.0


def _blew_up(s, step=None):
    """True when the run diverged or its energy grew past CLIP_ENERGY times its start."""
    if _diverged_at(s, step) is not None:
        return True
    first = max(abs(s["energy"][0]) if finite(s["energy"][0]) else 0.0, _start_scale(s))
    peak = max([abs(v) for v in s["energy"] if finite(v)], default=0.0)
    return first > 0 and peak > CLIP_ENERGY * first


def measured_growth(s):
    """Per-step factor of |E| from the first row to the last finite one (geometric mean)."""
    pts = [(st, abs(e)) for st, e in zip(s["step"], s["energy"]) if finite(e)]
    if len(pts) < 2 or pts[0][1] == 0 or pts[-1][0] <= pts[0][0]:
        return None
    return (pts[-1][1] / pts[0][1]) ** (1.0 / (pts[-1][0] - pts[0][0]))


def _predicted(e0, f, n):
    """e0 * f^n, or nan when that overflows."""
    if e0 <= 0 or f <= 0:
        return math.nan
    lg = math.log(e0) + n * math.log(f)
    return math.exp(lg) if lg < 700 else math.nan


def _lg(values):
    """log10 of the positive finite values (others dropped, as nan). A run that overflowed
    reaches 1e308, where a matplotlib log axis itself overflows, so blown-up energies are
    drawn as log10 on a linear axis labelled in powers of ten."""
    return [math.log10(v) if finite(v) and v > 0 else math.nan for v in values]


def _pow10_axis(ax):
    from matplotlib.ticker import FuncFormatter, MaxNLocator
    ax.yaxis.set_major_locator(MaxNLocator(nbins=7, integer=True))
    ax.yaxis.set_major_formatter(FuncFormatter(lambda y, _: f"1e{y:.0f}"))


def _finite_pairs(t, y):
    pts = [(a, b) for a, b in zip(t, y) if finite(a) and finite(b)]
    return [a for a, _ in pts], [b for _, b in pts]


def _mark_divergence(ax, div, color="0.25", label=True):
    t, step, said = div
    ax.axvline(t, color=color, ls=":", lw=1.2)
    if label:
        ax.text(t, 0.5, f" {'diverged at' if said else 'not finite from'} step {step:.0f}\n"
                        f" (t = {t:.3g} s)",
                transform=blended_transform_factory(ax.transData, ax.transAxes),
                ha="right", va="center", fontsize=8, color=color, rotation=90)


def energy_changers(doc):
    """What in a scene changes its energy on purpose (damping, driving forces, inelastic or
    frictional contacts), as words; [] for a conservative scene. Read from the scene, not
    from the run: the stats figure then draws E - E0 as what those do, not as an error."""
    why = []
    forces = [f for f in (doc or {}).get("forces", []) or [] if isinstance(f, dict)]

    def num(d, k, default=0.0):
        try:
            return float(d.get(k, default))
        except (TypeError, ValueError):
            return default
    kinds = {f.get("type") for f in forces}
    if any(f.get("type") == "damping" and num(f, "b") > 0 for f in forces):
        why.append("damping")
    if any(f.get("type") == "spring" and num(f, "damping") > 0 for f in forces):
        why.append("the springs' dampers")
    for kind, words in (("boids", "the boids' steering"), ("vortex", "the vortex's drag"),
                        ("curl-noise", "the flow's drag (curl-noise)")):
        if kind in kinds:
            why.append(words)
    contact = (doc or {}).get("contact") if isinstance((doc or {}).get("contact"), dict) else {}
    planes = [p for p in (doc or {}).get("planes", []) or [] if isinstance(p, dict)]
    if "planes" in (doc or {}) or contact:
        e = [num(contact, "restitution", 1.0)] + [num(p, "restitution", num(
            contact, "restitution", 1.0)) for p in planes]
        mu = [num(contact, "friction")] + [num(p, "friction", num(contact, "friction"))
                                           for p in planes]
        if min(e) < 1:
            why.append("inelastic contacts (e < 1)")
        if max(mu) > 0:
            why.append("friction")
    return why


def plot_stats(path, out, title=None, growth=None, diverged=None, changes=None):
    """Energy, its change and momentum against time. `changes`: what in the scene changes
    the energy on purpose (energy_changers): then the middle panel is E - E0 in J, said to
    be their work, not an error."""
    from . import runinfo
    s = read_stats(path)
    if diverged is None and runinfo.diverged_steps():
        diverged = runinfo.diverged_steps()[0]
    drift = drift_series(s)
    blew = _blew_up(s, diverged)
    show_drift = drift is not None and not blew
    panels = 3 if show_drift else 2
    heights = [3, 1.6, 2] if show_drift else [3, 2]
    fig, axes = new_figure(panels, 1, figsize=(6.4, 2.0 + 1.9 * panels), sharex=True,
                           gridspec_kw={"height_ratios": heights})
    ax = axes[0]
    div = _diverged_at(s, diverged)
    curves = []
    for key, label, style in (("energy", "total E", "-"), ("kinetic", "kinetic K", "--"),
                              ("potential", "potential U", ":")):
        t, y = _finite_pairs(s["t"], s[key])
        if blew:
            t, y = _finite_pairs(t, _lg([abs(b) for b in y]))
            label = "|" + label.split()[-1] + "|"
        curves.append((t, y, label, style))
    ys = [v for _, y, _, _ in curves for v in y]
    span = (max(ys) - min(ys)) if ys else 0.0
    from . import flat
    e_scale = max([abs(v) for _, y, _, _ in curves for v in y] + [0.0])
    for k, (t, y, label, style) in enumerate(curves):
        same = [c for c in curves[:k] if _coincides((c[0], c[1]), (t, y), span)]
        kw = {}
        if same:
            every = max(1, len(t) // 12)
            kw = dict(marker="o", mfc="white", ms=4, markevery=(k * every // 3 % every, every))
            label += _overlap_label(same[0][2], same[0][1], y, log10=blew)
        if not blew and flat.is_constant(y, e_scale):
            label += flat.label(y, "J", e_scale)
        ax.plot(t, y, style, label=label, **kw)
    if not blew:
        flat.plain_ticks(ax)
        if all(flat.is_constant(y, e_scale) for _, y, _, _ in curves if y):
            flat.flat_view(ax, [y for _, y, _, _ in curves], scale=e_scale)
    if blew:
        _pow10_axis(ax)
        ax.set_ylabel("|energy| (J), log scale")
        g = measured_growth(s)
        if growth and finite(growth):
            st0, e0 = s["step"][0], abs(s["energy"][0])
            tp = [t for t, st in zip(s["t"], s["step"]) if finite(t)]
            pred = [_predicted(e0, growth, st - st0) for st in s["step"]]
            tp, pred = _finite_pairs(s["t"], _lg(pred))
            ax.plot(tp, pred, color="0.35", lw=2.5, alpha=0.35,
                    label=f"predicted ×{growth:.4g} per step")
        if g:
            ax.plot([], [], ls="", label=f"measured |E|: ×{g:.4g} per step")
        if div:
            _mark_divergence(ax, div)
    else:
        ax.set_ylabel("energy (J)")
    ax.legend(loc="best", framealpha=0.85)
    ax.set_title(title or ("Energy and momentum" + (f" ({_stop_words(div)} t = {div[0]:g} s)"
                                                    if div is not None else "")))
    if show_drift and changes:
        # Damping, driving or lossy contacts change E on purpose: E - E0 is their work.
        ax2 = axes[1]
        e0 = s["energy"][0]
        t2, d2 = _finite_pairs(s["t"], [e - e0 for e in s["energy"]])
        ax2.plot(t2, d2, color="#444444", lw=1.1,
                 label=f"final {d2[-1]:+.3g} J" if d2 else None)
        ax2.axhline(0, color="0.6", lw=0.8)
        if d2:
            ax2.legend(loc="best", framealpha=0.85)
        ax2.set_ylabel("E - E0 (J)")
        ax2.set_title("energy changed on purpose by " + ", ".join(changes)
                      + ": not an error", fontsize=8.5)
    elif show_drift:
        ax2 = axes[1]
        t, d, kind = drift
        tp, dp = zip(*[(a, b) for a, b in zip(t, d) if b > 0]) if any(b > 0 for b in d) \
            else ([], [])
        if dp:
            unit = "" if kind == "relative" else " J"
            ax2.plot(tp, dp, color="#444444", lw=1.1,
                     label=f"max {max(d):.2e}{unit}, final {d[-1]:.2e}{unit}")
            if not (min(dp) > 1e-3 and max(dp) < 10 * min(dp)):
                ax2.set_yscale("log")  # decades of drift; a large one within a decade reads
                # better on a linear axis (a log axis labels its minor ticks there)
            ax2.legend(loc="lower right", framealpha=0.85)
        else:
            ax2.text(0.5, 0.5, "E = E0 to the last digit", transform=ax2.transAxes,
                     ha="center", va="center")
        ax2.set_ylabel("|E - E0| / |E0|" if kind == "relative" else "|E - E0| (J)")
        if kind == "absolute":
            ax2.set_title("E0 is 0 (or rounding noise): absolute error, not relative",
                          fontsize=8.5)
    axm = axes[-1]
    if blew:
        # Momentum of a run that blew up spans hundreds of decades too: its size |p|.
        t, p = _finite_pairs(s["t"], [math.hypot(a, b) for a, b in zip(s["px"], s["py"])])
        t, p = _finite_pairs(t, _lg(p))
        axm.plot(t, p, label="|p|")
        _pow10_axis(axm)
        axm.set_ylabel("|momentum| (kg m/s), log")
    else:
        ps = [_finite_pairs(s["t"], s[key]) for key in ("px", "py")]
        p_scale = max([abs(v) for _, y in ps for v in y] + [0.0])
        for (t, y), label, style in zip(ps, ("px", "py"), ("-", "--")):
            if flat.is_constant(y, p_scale):
                label += flat.label(y, "kg m/s", p_scale)
            axm.plot(t, y, style, label=label)
        flat.plain_ticks(axm)
        if all(flat.is_constant(y, p_scale) for _, y in ps if y):
            flat.flat_view(axm, [y for _, y in ps], scale=p_scale)
        axm.set_ylabel("momentum (kg m/s)")
    axm.set_xlabel("time t (s)")
    axm.legend(loc="best", framealpha=0.85)
    if blew and div:
        _mark_divergence(axm, div, label=False)
    fig.tight_layout()
    save_figure(fig, out)


COINCIDE = 2e-3  # curves closer than this fraction of the y range are drawn as coinciding


SAME_VALUES = 1e-3  # "coincides" in a legend: every value within this fraction of the other's


def _coincides(a, b, span):
    """True when two series (same length, same times) differ by less than COINCIDE * span:
    drawn on top of each other at the figure's scale."""
    if len(a[0]) != len(b[0]) or not a[0] or span <= 0:
        return False
    if any(abs(x - y) > 1e-12 * max(1.0, abs(x)) for x, y in zip(a[0], b[0])):
        return False
    return max(abs(x - y) for x, y in zip(a[1], b[1])) <= COINCIDE * span


def _same_values(a, b, log10=False):
    """True when two series' values agree within SAME_VALUES of each other everywhere (on a
    log10 axis, within log10(1 + SAME_VALUES)): then, and only then, a legend says
    "coincides with". Curves that only lie on top of each other at the figure's scale (a
    10 % difference under a range of 10^100) are said to be "on top of" each other."""
    if len(a) != len(b):
        return False
    if log10:
        return all(abs(x - y) <= math.log10(1 + SAME_VALUES) for x, y in zip(a, b))
    return all(abs(x - y) <= SAME_VALUES * max(abs(x), abs(y)) for x, y in zip(a, b))


def _overlap_label(other, a, b, log10=False):
    return (f" (coincides with {other})" if _same_values(a, b, log10)
            else f" (on top of {other} at this scale)")


def plot_energy(paths, labels, out, relative=False, title=None, growth=None, diverged=None):
    """Total energy (or its error) of several runs. A run that blew up switches the figure to
    |E| on a log scale up to each run's last finite step, the divergence marked, with the
    predicted per-step growth (growth: {label: factor}) beside the measured one."""
    if labels is None:
        labels = [os.path.splitext(os.path.basename(p))[0] for p in paths]
    if len(labels) != len(paths):
        raise InputError(f"--labels: {len(labels)} labels for {len(paths)} files, expected "
                         "one label per file")
    growth = growth or {}
    unknown = [k for k in growth if k not in labels]
    if unknown:
        raise InputError(f"--growth: '{unknown[0]}' is not one of the labels "
                         f"{','.join(labels)}")
    from . import runinfo
    diverged = dict(runinfo.diverged_steps(labels), **(diverged or {}))
    unknown = [k for k in diverged if k not in labels]
    if unknown:
        raise InputError(f"--diverged: '{unknown[0]}' is not one of the labels "
                         f"{','.join(labels)}")
    stats = [read_stats(p) for p in paths]
    blew = any(_blew_up(s, diverged.get(lb)) for s, lb in zip(stats, labels))
    fig, ax = new_figure(figsize=(6.4, 4.4))
    series, kinds, notes = [], set(), []
    for s, label in zip(stats, labels):
        if relative:
            dr = drift_series(s)
            if dr is None:
                series.append(([], []))
                continue
            t, d, kind = dr
            kinds.add(kind)
            pts = _finite_pairs(*zip(*[(a, b) for a, b in zip(t, d) if b > 0])) \
                if any(b > 0 for b in d) else ([], [])
            series.append(_finite_pairs(pts[0], _lg(pts[1])) if blew else pts)
        elif blew:
            t, y = _finite_pairs(s["t"], s["energy"])
            series.append(_finite_pairs(t, _lg([abs(b) for b in y])))
        else:
            series.append(_finite_pairs(s["t"], s["energy"]))
    ys = [v for _, y in series for v in y]
    if relative and not blew:
        pos = [math.log10(v) for v in ys if v > 0]
        span = (max(pos) - min(pos)) if pos else 0.0
        comp = [(t, [math.log10(v) for v in y]) for t, y in series]
    else:
        span = (max(ys) - min(ys)) if ys else 0.0
        comp = series
    drawn = []
    for k, ((t, y), s, label) in enumerate(zip(series, stats, labels)):
        color, marker = integrator_style(label, labels)
        div = _diverged_at(s, diverged.get(label))
        suffix = f" ({_stop_words(div)} step {div[1]:.0f})" if div is not None else ""
        same = [j for j in drawn if _coincides(comp[j], comp[k], span)]
        kw = {}
        if same:
            # Drawn on top of an earlier curve: dashed with sparse markers, and said so.
            every = max(1, len(t) // 12)
            kw = dict(ls=(0, (4, 3)), marker=marker, markevery=(k * every // 3 % every, every),
                      ms=5, mfc="white")
            suffix += _overlap_label(labels[same[0]], series[same[0]][1], y,
                                     log10=blew)
            notes.append(f"{label} = {labels[same[0]]}")
        ax.plot(t, y, color=color, label=label + suffix, **kw)
        drawn.append(k)
        if div is not None and t:
            ax.plot([t[-1]], [y[-1]], marker="x", color=color, ms=8, mew=2)
            ax.axvline(div[0], color=color, ls=":", lw=1.0)
        if blew and not relative and label in growth and s["energy"] and finite(s["energy"][0]):
            f = growth[label]
            st0, e0 = s["step"][0], abs(s["energy"][0])
            last = max([st for st, e in zip(s["step"], s["energy"]) if finite(e)])
            pts = [(tt, _predicted(e0, f, st - st0)) for tt, st in zip(s["t"], s["step"])
                   if st <= last]
            pts = [(a, math.log10(b)) for a, b in pts if finite(b) and b > 0]
            g = measured_growth(s)
            ax.plot([a for a, _ in pts], [b for _, b in pts], color=color, lw=4, alpha=0.25,
                    label=f"{label}: predicted ×{f:.4g}/step, measured "
                          + (f"×{g:.4g}" if g else "n/a"))
    if blew:
        _pow10_axis(ax)
    elif relative:
        ax.set_yscale("log")
    if relative:
        ax.set_ylabel("|E - E0| / |E0|" if kinds == {"relative"} else
                      "|E - E0| (J): E0 is 0 to rounding" if kinds == {"absolute"} else
                      "|E - E0| / |E0|, or (J) where E0 is 0")
    elif blew:
        ax.set_ylabel("|total energy| (J), log scale")
    else:
        ax.set_ylabel("total energy E (J)")
    ax.set_xlabel("time t (s)")
    ax.set_title(title or ("Energy error" if relative else "Total energy") + " by run")
    ax.legend(loc="best", framealpha=0.85, fontsize=7.5)
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
    drawn = []
    for k, (path, label) in enumerate(zip(paths, labels)):
        data = read_trace(path)
        if pid not in data:
            raise InputError(f"--id: particle {pid} is not in {path} (ids "
                             f"{min(data)}..{max(data)})")
        xs, vs = _finite_xy(data[pid], axis, v)
        color, marker = integrator_style(label, labels)
        diverged = len(xs) < len(data[pid][axis])
        span = max((max(c) - min(c) for c in (xs, vs) if c), default=0.0)
        same = [(lb, px, pv) for lb, (px, pv) in drawn if len(px) == len(xs) and xs and
                max(max(abs(a - b) for a, b in zip(px, xs)),
                    max(abs(a - b) for a, b in zip(pv, vs))) <= COINCIDE * span]
        kw = dict(ls=styles[k % len(styles)], lw=1.2 if k else 1.0)
        if same:
            every = max(1, len(xs) // 15)
            # Markers of each coinciding curve at other places, so none hides another's.
            kw = dict(ls=(0, (4, 3)), lw=1.2, marker=marker,
                      markevery=(k * every // 3 % every, every), ms=5, mfc="white")
        from . import runinfo
        ax.plot(xs, vs, color=color, **kw,
                label=label + ((" (diverged: its summary)" if runinfo.said_diverged(k)
                                else " (not finite at the end)") if diverged else "")
                + (_overlap_label(same[0][0], same[0][1] + same[0][2], xs + vs)
                   if same else ""))
        drawn.append((label, (xs, vs)))
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
