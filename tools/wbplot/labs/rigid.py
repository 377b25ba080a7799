"""Rigid lab figures: energy and momenta, the body-frame angular velocity, the body in 3D,
an animation, and the work-precision sweep (docs/report.md, handouts/rigid.md).

tools/plot subcommands (work on a student's own runs of build/bin/rigid):
  rigid-momenta STATS.csv [STATS.csv ...] [--labels a,b] -o FIG.png
  rigid-polhode TRACE.csv [--id K] -o FIG.png
  rigid-frames  TRACE.csv [--scene S.json] [--count N] -o FIG.png
  rigid-animate TRACE.csv [--scene S.json] [--frames N] [--fps F] -o FIG.gif
  rigid-sweep   SWEEP.csv -o FIG.png
  rigid-creep   TRACE.csv [TRACE.csv ...] --labels a,b [--after T] -o FIG.png
"""
import json
import math
import os

from .. import creep
from ..common import (InputError, column, finite, integrator_style, new_figure, parse_label_map,
                      parse_list, read_csv, save_figure)

# The generic particle figures read 2D traces: they do not apply to the rigid lab's.
REPLACES_GENERIC = True

# The pack README's plot commands for a run of this lab (tools/pack): out/run.csv, its stats.
PACK_PLOTS = [("tools/plot rigid-frames out/run.csv --scene {scene} --summary "
               "out/run-summary.json -o out/run.png", "the bodies at sampled times, in 3D"),
              ("tools/plot rigid-momenta out/run-stats.csv --summary out/run-summary.json "
               "-o out/run-energy.png", "energy, momentum, angular momentum against time")]

TRACE_COLUMNS = ["t", "id", "x", "y", "z", "qw", "qx", "qy", "qz", "vx", "vy", "vz", "wx",
                 "wy", "wz"]
STATS_COLUMNS = ["step", "t", "energy", "kinetic", "potential", "px", "py", "pz", "Lx", "Ly",
                 "Lz"]
SWEEP_COLUMNS = ["scene", "integrator", "dt", "steps", "wall_s", "error", "energy_error",
                 "status"]
MAX_WRITTEN_STEPS = 2000  # rows per body the report asks for (--every)
INTEGRATORS = ["implicit-gyroscopic", "explicit-gyroscopic"]


# ----------------------------------------------------------------------------
# Reading


def read_trace(path):
    """{id: {column: [floats]}} from a rigid trace CSV, rows in file order."""
    rows = read_csv(path, TRACE_COLUMNS, "rigid trace CSV (" + ",".join(TRACE_COLUMNS) + ")")
    ids = column(path, rows, "id")
    data = {}
    cols = {c: column(path, rows, c) for c in TRACE_COLUMNS if c != "id"}
    for i, b in enumerate(ids):
        if not finite(b) or b != int(b):
            raise InputError(f"{path}: row {i + 2}, column 'id': expected a whole number")
        d = data.setdefault(int(b), {c: [] for c in cols})
        for c in cols:
            d[c].append(cols[c][i])
    return data


def read_stats(path):
    rows = read_csv(path, STATS_COLUMNS, "rigid stats CSV (" + ",".join(STATS_COLUMNS) + ")")
    return {c: column(path, rows, c) for c in STATS_COLUMNS}


def read_scene(path):
    if path is None:
        return None
    try:
        with open(path, encoding="utf-8") as f:
            doc = json.load(f)
    except OSError as e:
        raise InputError(f"{path}: cannot read ({e.strerror})") from None
    except json.JSONDecodeError as e:
        raise InputError(f"{path}: not JSON ({e})") from None
    if not isinstance(doc, dict) or not isinstance(doc.get("bodies"), list):
        raise InputError(f"{path}: expected a rigid scene with a 'bodies' array")
    return doc


def rotation(qw, qx, qy, qz):
    """The rotation matrix (rows) of a quaternion, normalised here."""
    n = math.sqrt(qw * qw + qx * qx + qy * qy + qz * qz)
    if not (n > 0 and math.isfinite(n)):
        return None
    w, x, y, z = qw / n, qx / n, qy / n, qz / n
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]


def body_omega(d, k):
    """omega in the body frame, R^T omega, at row k (None if not finite)."""
    R = rotation(d["qw"][k], d["qx"][k], d["qy"][k], d["qz"][k])
    w = (d["wx"][k], d["wy"][k], d["wz"][k])
    if R is None or not all(finite(c) for c in w):
        return None
    return tuple(sum(R[i][j] * w[i] for i in range(3)) for j in range(3))


def last_finite(values):
    """Index of the last row before the first non-finite one (len - 1 if none)."""
    for i, v in enumerate(values):
        if not finite(v):
            return i - 1
    return len(values) - 1


def shape_edges(body):
    """Line segments (pairs of body-frame points) that draw a body of the scene."""
    shape = body.get("shape") if isinstance(body, dict) else None
    try:
        if shape == "box":
            a, b, c = (0.5 * float(s) for s in body["size"])
            corners = [(sx * a, sy * b, sz * c) for sz in (-1, 1) for sy in (-1, 1)
                       for sx in (-1, 1)]
            return [(corners[i], corners[j]) for i in range(8) for j in range(i + 1, 8)
                    if bin(i ^ j).count("1") == 1]
        if shape in ("sphere", "cylinder"):
            r = float(body["radius"])
            n = 24
            ring = [(math.cos(2 * math.pi * k / n), math.sin(2 * math.pi * k / n))
                    for k in range(n + 1)]
            segs = []
            if shape == "sphere":
                for p, q in zip(ring, ring[1:]):  # three great circles
                    segs.append(((r * p[0], r * p[1], 0), (r * q[0], r * q[1], 0)))
                    segs.append(((r * p[0], 0, r * p[1]), (r * q[0], 0, r * q[1])))
                    segs.append(((0, r * p[0], r * p[1]), (0, r * q[0], r * q[1])))
            else:
                h = 0.5 * float(body["length"])
                for z in (-h, h):
                    for p, q in zip(ring, ring[1:]):
                        segs.append(((r * p[0], r * p[1], z), (r * q[0], r * q[1], z)))
                for k in range(0, n, n // 4):
                    p = ring[k]
                    segs.append(((r * p[0], r * p[1], -h), (r * p[0], r * p[1], h)))
            return segs
    except (KeyError, TypeError, ValueError):
        pass
    return []


def body_size(body):
    try:
        if body.get("shape") == "box":
            return max(float(s) for s in body["size"])
        if body.get("shape") == "sphere":
            return 2 * float(body["radius"])
        return max(2 * float(body["radius"]), float(body["length"]))
    except (KeyError, TypeError, ValueError, AttributeError):
        return 1.0


def world_segments(d, k, segs, axis_len):
    """The body's segments and its three axes in the world at row k."""
    R = rotation(d["qw"][k], d["qx"][k], d["qy"][k], d["qz"][k])
    x = (d["x"][k], d["y"][k], d["z"][k])
    if R is None or not all(finite(c) for c in x):
        return [], []

    def to_world(p):
        return tuple(x[i] + sum(R[i][j] * p[j] for j in range(3)) for i in range(3))

    lines = [(to_world(p), to_world(q)) for p, q in segs]
    axes = []
    for j in range(3):
        e = [0.0, 0.0, 0.0]
        e[j] = axis_len
        axes.append((x, to_world(e)))
    return lines, axes


AXIS_COLORS = ["#d62728", "#2ca02c", "#1f77b4"]  # body x, y, z


# ----------------------------------------------------------------------------
# Figures


# A run that blew up before this fraction of the time axis gets a zoomed column:
# on the whole axis its blow-up would be a vertical line at the left edge.
EARLY_BLOWUP = 0.2


def _log_or_symlog(ax, vals, scale):
    """Log scale for positive values, symmetric log around +-scale otherwise."""
    if all(v > 0 for v in vals):
        ax.set_yscale("log")
    else:
        import matplotlib.ticker as mticker
        ax.set_yscale("symlog", linthresh=scale)
        ax.yaxis.set_major_locator(mticker.SymmetricalLogLocator(base=1e8, linthresh=scale))


def _norm3(s, cols, k):
    v = [s[c][k] for c in cols]
    return math.sqrt(sum(c * c for c in v)) if all(finite(c) for c in v) else float("nan")


def plot_momenta(paths, labels, out, title=None, diverged=None):
    """Energy, linear momentum and angular momentum (about the origin) against time.

    Whether a run diverged comes from its summary (--diverged LABEL=STEP, or --summary):
    such a run is drawn up to that step, a dash-dot line marks it, and when it blew up
    early a second column shows its first moments on log scales (|E|, |p|, |L|), while the
    left column keeps the scale of the runs that stayed finite. A run whose data stop
    being finite without a summary to say why is drawn the same way, and called "not
    finite" rather than "diverged". Every other panel is linear; a quantity constant to
    rounding is drawn flat, its value in the legend (flat.py).
    """
    from .. import flat, runinfo
    runs = [read_stats(p) for p in paths]
    labels = labels or [os.path.basename(p) for p in paths]
    if len(labels) != len(paths):
        raise InputError(f"--labels: got {len(labels)} labels for {len(paths)} files")
    diverged = dict(runinfo.diverged_steps(labels), **(diverged or {}))
    colors = [integrator_style(label, labels)[0] if label in INTEGRATORS else f"C{n}"
              for n, label in enumerate(labels)]
    ends = [last_finite(s["energy"]) for s in runs]
    t_end = max((s["t"][-1] for s in runs if s["t"] and finite(s["t"][-1])), default=0.0)
    # The row where a run stopped: the step its summary names, else its first non-finite row.
    blowups, blow_steps, said = {}, {}, set()
    for label, step in diverged.items():
        if label not in labels:
            raise InputError(f"--diverged: '{label}' is not one of the labels {','.join(labels)}")
        n = labels.index(label)
        rows = [k for k, st in enumerate(runs[n]["step"]) if st == step]
        if not rows:
            raise InputError(f"--diverged: {label}: step {step} is not a row of its stats")
        blowups[n], blow_steps[n] = runs[n]["t"][rows[0]], step
        ends[n] = min(ends[n], rows[0])
        said.add(n)
    for n in range(len(runs)):
        if n not in blowups and ends[n] < len(runs[n]["t"]) - 1:
            blowups[n] = runs[n]["t"][ends[n] + 1]
            blow_steps[n] = int(runs[n]["step"][ends[n] + 1])
    finite_runs = [n for n in range(len(runs)) if n not in blowups]
    zoom = bool(blowups) and bool(finite_runs) and t_end > 0 and \
        max(blowups.values()) < EARLY_BLOWUP * t_end
    fig, grid = new_figure(3, 2 if zoom else 1, figsize=(12.5 if zoom else 7.5, 8.0),
                           sharex="col", squeeze=False)
    axes = [row[0] for row in grid]
    styles = ["-", "--", ":"]
    groups = (("energy",), ("px", "py", "pz"), ("Lx", "Ly", "Lz"))
    units = ("J", "kg m/s", "kg m²/s")
    notes = []
    # The scale of each quantity, for "constant to rounding": the energy's from the start
    # (|E0| or |K0| + |U0|), the momenta's from their largest component over the runs.
    e_scale = max([abs(s[c][0]) for s in runs for c in ("energy", "kinetic", "potential")
                   if s[c] and finite(s[c][0])] + [0.0])
    for gi, (ax, cols) in enumerate(zip(axes, groups)):
        shown = finite_runs if zoom else range(len(runs))
        vals = [v for n in shown for c in cols for v in runs[n][c][:ends[n] + 1] if finite(v)]
        scale = e_scale if gi == 0 else max([abs(v) for v in vals] + [0.0])
        logged = False
        big = [n for n in blowups if n in shown]
        if not zoom and big:
            first = [abs(runs[n][c][0]) for n in shown for c in cols if finite(runs[n][c][0])]
            s0 = max(first + [1e-12])
            if vals and max(abs(v) for v in vals) > 1e3 * s0:
                # A blow-up spans decades: log scales, so that the other runs stay readable.
                _log_or_symlog(ax, vals, s0)
                logged = True
                who = ", ".join(f"{labels[n]} {'diverged' if n in said else 'is not finite'}"
                                for n in big)
                ax.set_title(f"log scale: {who}", loc="left", fontsize=8, color="#555")
        drawn = []
        for n, (s, label) in enumerate(zip(runs, labels)):
            end = ends[n]
            t = s["t"][:end + 1]
            for i, c in enumerate(cols):
                y = s[c][:end + 1]
                name = label if gi == 0 else (f"{label}: {c}" if len(runs) > 1 else c)
                if not logged and n in shown and flat.is_constant(y, scale):
                    name += flat.label(y, units[gi], scale)
                ax.plot(t, y, color=colors[n], ls=styles[i] if gi else "-", label=name)
                if n in shown:
                    drawn.append(y)
        if zoom and vals:
            # The left column keeps the finite runs' scale; the blow-up is on the right.
            lo, hi = min(vals), max(vals)
            pad = 0.05 * (hi - lo) if hi > lo else max(abs(hi), 1.0) * 0.05
            ax.set_ylim(lo - pad, hi + pad)
        if not logged:
            flat.plain_ticks(ax)
            if drawn and all(flat.is_constant(y, scale) for y in drawn):
                flat.flat_view(ax, drawn, scale=scale)
    for n in blowups:
        for ax in axes:
            ax.axvline(blowups[n], color=colors[n], lw=0.8, ls="-.")
        notes.append(f"{labels[n]} diverged at t = {blowups[n]:g} s, step {blow_steps[n]} "
                     "(its summary; dash-dot line)" if n in said else
                     f"{labels[n]} is not finite from t = {blowups[n]:g} s, step "
                     f"{blow_steps[n]} (dash-dot line)")
    if len(runs) > 1:
        e0 = runs[0]["energy"]
        for s, label in zip(runs[1:], labels[1:]):
            e = s["energy"]
            if len(e) == len(e0) and all(finite(a) and finite(b) and
                                         abs(a - b) <= 1e-12 * max(abs(a), abs(b), 1e-300)
                                         for a, b in zip(e, e0)):
                notes.append(f"the energies of {labels[0]} and {label} coincide")
    if zoom:
        axes[0].set_title("The whole run, on the scale of the runs that stayed finite",
                          fontsize=10)
    axes[0].set_ylabel("energy E (J)")
    axes[1].set_ylabel("momentum p (kg m/s)")
    axes[2].set_ylabel("angular momentum L\nabout the origin (kg m²/s)")
    axes[2].set_xlabel("time t (s)")
    for ax in axes:
        n_entries = len(ax.get_legend_handles_labels()[1])
        if n_entries > 4:  # beside the panel: inside, six entries would cover its curves
            ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7.5,
                      borderaxespad=0.0, frameon=False)
        else:
            ax.legend(loc="best", fontsize=8, framealpha=0.85)
    if zoom:
        right = [row[1] for row in grid]
        t_zoom = 1.25 * max(blowups.values())
        quantities = (("|E| (J)", lambda s, k: abs(s["energy"][k])),
                      ("|p| (kg m/s)", lambda s, k: _norm3(s, groups[1], k)),
                      ("|L| (kg m²/s)", lambda s, k: _norm3(s, groups[2], k)))
        for ax, (name, value) in zip(right, quantities):
            drawn = False
            for n, (s, label) in enumerate(zip(runs, labels)):
                ks = [k for k in range(ends[n] + 1) if s["t"][k] <= t_zoom]
                pts = [(s["t"][k], value(s, k)) for k in ks]
                pts = [(t, v) for t, v in pts if finite(v) and v > 0]
                if pts:
                    ax.plot([t for t, _ in pts], [v for _, v in pts], color=colors[n],
                            marker="." if n in blowups else None, ms=3, label=label)
                    drawn = True
                if n in blowups:
                    ax.axvline(blowups[n], color=colors[n], lw=0.8, ls="-.")
            if drawn:
                ax.set_yscale("log")
            else:
                ax.text(0.5, 0.5, f"{name.split(' ')[0]} = 0 in every run", ha="center",
                        va="center", transform=ax.transAxes, color="#555")
            ax.set_ylabel(name + ", log scale")
            ax.set_xlim(0, t_zoom)
        right[0].set_title(f"The first {t_zoom:.3g} s (one dot per written step)", fontsize=10)
        right[0].legend(loc="best", fontsize=8)
        right[2].set_xlabel("time t (s)")
    fig.suptitle(title or "Energy and momenta" + ("\n" + "; ".join(notes) if notes else ""))
    fig.tight_layout()
    save_figure(fig, out)


def plot_polhode(path, out, body=0, title=None):
    """The angular velocity in the body frame: components against time, and its curve.

    ω's three components share a unit, so the 3D curve is drawn at one scale on all three
    axes: a component that is constant to rounding (a hinged door's 1e-18 rad/s off its
    axis) is a flat line there, its value in the legend, instead of noise blown up to fill
    its axis (flat.py)."""
    from .. import flat, runinfo
    data = read_trace(path)
    if body not in data:
        raise InputError(f"{path}: no body with id {body} (ids: {sorted(data)})")
    d = data[body]
    t, w = [], []
    for k in range(len(d["t"])):
        wb = body_omega(d, k)
        if wb is None:
            break
        t.append(d["t"][k])
        w.append(wb)
    stopped = len(t) < len(d["t"])
    said = runinfo.said_diverged(0)
    apply = new_figure(figsize=(11.0, 4.2))
    fig = apply[0]
    fig.clf()
    ax = fig.add_subplot(1, 2, 1)
    comps = [[p[j] for p in w] for j in range(3)]
    scale = max([abs(v) for c in comps for v in c] + [0.0])
    flat_j = [flat.is_constant(c, scale) for c in comps]
    for j in range(3):
        ax.plot(t, comps[j], color=AXIS_COLORS[j], label=f"ω along body {'xyz'[j]}"
                + (flat.label(comps[j], "rad/s", scale) if flat_j[j] else ""))
    if stopped and t:
        ax.axvline(t[-1], color="k", ls="-.", lw=0.8, label=f"last finite state, t = {t[-1]:g} s")
    flat.plain_ticks(ax)
    if w and all(flat_j):
        flat.flat_view(ax, comps, scale=scale)
    ax.set_xlabel("time t (s)")
    ax.set_ylabel("body-frame angular velocity (rad/s)")
    ax.legend(loc="best", framealpha=0.85)
    ax.set_title("ω in the body frame, R^T ω")
    ax3 = fig.add_subplot(1, 2, 2, projection="3d")
    ax3.plot(comps[0], comps[1], comps[2], color="#444", lw=0.8)
    if w:
        ax3.scatter(*[[w[0][j]] for j in range(3)], color="#2ca02c", s=20, label="start")
        ax3.scatter(*[[w[-1][j]] for j in range(3)], color="#d62728", s=20, label="end")
        ax3.legend(loc="upper left")
        # One scale on the three axes: the widest real motion of a component (or a tenth
        # of |ω| when none moves), each axis centred on its component.
        spans = [max(c) - min(c) for c, f in zip(comps, flat_j) if not f]
        mids = [flat.value_of(c, scale) if f else (max(c) + min(c)) / 2
                for c, f in zip(comps, flat_j)]
        # Every component constant: a point, in a view of 10 % of |ω| around it (1 rad/s
        # about a body at rest), as flat.flat_view draws a constant.
        half = 0.55 * max(spans + [0.2 * scale]) if spans else max(
            0.1 * max(abs(m) for m in mids), 1.0)
        for j, setter in enumerate((ax3.set_xlim, ax3.set_ylim, ax3.set_zlim)):
            mid = mids[j]
            setter(mid - half, mid + half)
        from matplotlib.ticker import MaxNLocator
        for a in (ax3.xaxis, ax3.yaxis, ax3.zaxis):
            a.get_major_formatter().set_useOffset(False)
            a.set_major_locator(MaxNLocator(4))  # fewer labels: they ran into each other
    ax3.set_xlabel("ω_x (rad/s)")
    ax3.set_ylabel("ω_y (rad/s)")
    ax3.set_zlabel("ω_z (rad/s)", labelpad=4)
    # Shrink the box inside its axes, and keep the axes off the figure's right edge, so
    # that the z label is not cut.
    ax3.set_box_aspect(None, zoom=0.78)
    fig.subplots_adjust(left=0.07, right=0.9, wspace=0.3)
    still = [f"ω_{'xyz'[j]}" for j in range(3) if flat_j[j]]
    ax3.set_title("polhode: the tip of ω in the body frame"
                  + ("\nω is constant to rounding: the curve is a point" if w and all(flat_j)
                     else f"\n{', '.join(still)} constant to rounding (flat)" if still else ""))
    why = ""
    if stopped:
        why = (" (diverged, as its summary says: drawn up to its last finite state)" if said
               else f" (not finite after t = {t[-1]:g} s: drawn up to there)" if t
               else " (not finite from the start)")
    elif said:
        why = " (diverged, as its summary says)"
    fig.suptitle(title or f"body {body}" + why)
    save_figure(fig, out)


def _scene_bodies(scene, ids):
    bodies = scene.get("bodies", []) if scene else []
    return {b: (bodies[b] if b < len(bodies) else {}) for b in ids}


def _outline(d, k, segs, size):
    """The body's segments and axes in the world at row k: ([(p, q)], [(p, q)] x3)."""
    return world_segments(d, k, segs, 0.6 * size)


def _bodies_view(data, bodies, rows_of):
    """The drawn extent of the bodies: their outlines at the rows drawn and their paths."""
    pts = []
    for b, d in data.items():
        segs = shape_edges(bodies.get(b, {}))
        size = body_size(bodies.get(b, {})) if segs else 0.5
        for k in rows_of(b):
            lines, axes = _outline(d, k, segs, size)
            pts += [p for ln in lines + axes for p in ln]
            pts.append((d["x"][k], d["y"][k], d["z"][k]))
        end = max(rows_of(b), default=-1)
        pts += list(zip(d["x"][:end + 1], d["y"][:end + 1], d["z"][:end + 1]))
    return pts


def _ends(data):
    return {b: min(last_finite(d[c]) for c in ("x", "y", "z", "qw")) for b, d in data.items()}


def _stop_note(data, ends):
    """Why a drawing stops early: the run's summary, else what the data show."""
    from .. import runinfo
    stopped = [b for b, d in data.items() if ends[b] < len(d["t"]) - 1]
    if runinfo.said_diverged(0):
        t = min((data[b]["t"][max(ends[b], 0)] for b in stopped), default=None)
        return " (diverged, as its summary says" + (f": drawn up to t = {t:g} s)" if t is not None
                                                    else ")")
    if stopped:
        b = stopped[0]
        return f" (not finite after t = {data[b]['t'][max(ends[b], 0)]:g} s: drawn up to there)"
    return ""


def plot_frames(path, out, scene=None, count=8, title=None):
    """Each body's outline and axes at `count` sampled times, in 3D, with its path.

    When some body stays within its own size (spinning, swinging on a hinge, resting), its
    outlines at the sampled times would stack into one tangle: each sampled time then gets
    a panel of its own, the same view in all of them. Otherwise the outlines share one
    view, coloured by time. The view fits the bodies (scene3d.py); planes and hinge axes
    are drawn where the scene puts them."""
    from .. import scene3d
    data = read_trace(path)
    bodies = _scene_bodies(scene, data)
    ends = _ends(data)
    live = {b: d for b, d in data.items() if ends[b] >= 0}
    if not live:
        raise InputError(f"{path}: no finite state to draw")
    still = {}
    for b, d in live.items():
        size = body_size(bodies.get(b, {})) if shape_edges(bodies.get(b, {})) else 0.5
        travel = max(math.dist((d["x"][k], d["y"][k], d["z"][k]),
                               (d["x"][0], d["y"][0], d["z"][0])) for k in range(ends[b] + 1))
        still[b] = travel < size
    n = max(1, min(count, min(ends[b] + 1 for b in live)))

    def rows(b, upto=None):
        e = ends[b] if upto is None else upto
        return sorted({round(i * e / max(n - 1, 1)) for i in range(n)})
    samples = {b: rows(b) for b in live}
    box = scene3d.view_box(_bodies_view(live, bodies, lambda b: samples[b]))
    note = _stop_note(data, ends)
    import matplotlib
    if any(still.values()) and n > 1:
        cols = min(n, 4)
        nrows = math.ceil(n / cols)
        fig, _ = new_figure(figsize=(3.2 * cols, 3.2 * nrows + 0.7))
        fig.clf()
        for i in range(n):
            ax = fig.add_subplot(nrows, cols, i + 1, projection="3d")
            scene3d.draw_geometry(ax, scene, box)
            t_i = None
            for b, d in sorted(live.items()):
                k = samples[b][min(i, len(samples[b]) - 1)]
                t_i = d["t"][k]
                segs = shape_edges(bodies.get(b, {}))
                size = body_size(bodies.get(b, {})) if segs else 0.5
                lines, axes = _outline(d, k, segs, size)
                scene3d.draw_lines(ax, list(zip(zip(d["x"][:k], d["y"][:k], d["z"][:k]),
                                                zip(d["x"][1:k + 1], d["y"][1:k + 1],
                                                    d["z"][1:k + 1]))), ["#999"], lw=0.6)
                scene3d.draw_lines(ax, lines, ["#222"], lw=0.9)
                for j, ln in enumerate(axes):
                    scene3d.draw_lines(ax, [ln], [AXIS_COLORS[j]], lw=1.2)
            scene3d.setup(ax, box, scene)
            ax.tick_params(labelsize=7)
            for lab in (ax.xaxis.label, ax.yaxis.label, ax.zaxis.label):
                lab.set_fontsize(8)
            ax.set_title(f"t = {t_i:.3g} s", fontsize=9)
        fig.suptitle(title or (f"bodies at {n} sampled times, one panel each (a body stays "
                               "within its own size: drawn in place, the same view in every "
                               f"panel); body axes x, y, z in red, green, blue{note}"),
                     fontsize=10)
        fig.tight_layout()
        save_figure(fig, out)
        return
    fig, _ = new_figure(figsize=(7.5, 7.0))
    fig.clf()
    ax = fig.add_subplot(1, 1, 1, projection="3d")
    cmap = matplotlib.colormaps["viridis"]
    scene3d.draw_geometry(ax, scene, box)
    for b, d in sorted(live.items()):
        e = ends[b]
        segs = shape_edges(bodies.get(b, {}))
        size = body_size(bodies.get(b, {})) if segs else 0.5
        path_pts = list(zip(d["x"][:e + 1], d["y"][:e + 1], d["z"][:e + 1]))
        scene3d.draw_lines(ax, list(zip(path_pts, path_pts[1:])), ["#888"], lw=0.7)
        for i, k in enumerate(samples[b]):
            color = cmap(i / max(len(samples[b]) - 1, 1))
            lines, axes = _outline(d, k, segs, size)
            scene3d.draw_lines(ax, lines, [color], lw=0.9)
            for j, ln in enumerate(axes):
                scene3d.draw_lines(ax, [ln], [AXIS_COLORS[j]], lw=1.2)
    scene3d.setup(ax, box, scene)
    t_end = max(d["t"][ends[b]] for b, d in live.items())
    sm = matplotlib.cm.ScalarMappable(cmap=cmap, norm=matplotlib.colors.Normalize(0, t_end))
    fig.colorbar(sm, ax=ax, shrink=0.6, pad=0.12, label="time of the outline (s)")
    ax.set_title(title or f"bodies at {n} sampled times; body axes x, y, z in red, green, "
                 f"blue{note}")
    save_figure(fig, out)


def animate(path, out, scene=None, frames=60, fps=20, title=None):
    """A GIF of the run: every body's outline and axes, one frame per sampled row, the view
    fitted to the bodies over the whole run, planes and hinge axes where they are."""
    from matplotlib.animation import PillowWriter
    from .. import scene3d
    from ..common import finish_frame
    data = read_trace(path)
    bodies = _scene_bodies(scene, data)
    geo = {b: shape_edges(bodies.get(b, {})) for b in data}
    ends = _ends(data)
    n_rows = max(len(d["t"]) for d in data.values())
    n = max(1, min(frames, n_rows))
    rows = [round(i * (n_rows - 1) / max(n - 1, 1)) for i in range(n)]
    live = {b: d for b, d in data.items() if ends[b] >= 0}
    if not live:
        raise InputError(f"{path}: no finite state to draw")
    box = scene3d.view_box(_bodies_view(
        live, bodies, lambda b: sorted({min(k, ends[b]) for k in rows})))
    note = _stop_note(data, ends)
    fig, _ = new_figure(figsize=(6.4, 5.8))
    fig.clf()
    ax = fig.add_subplot(1, 1, 1, projection="3d")
    tmp = os.path.join(os.path.dirname(os.path.abspath(out)),
                       f".{os.path.basename(out)}.tmp-{os.getpid()}.gif")
    writer = PillowWriter(fps=fps)
    try:
        with writer.saving(fig, tmp, dpi=80):
            for k in rows:
                ax.cla()
                scene3d.draw_geometry(ax, scene, box)
                t_now = None
                for b, d in sorted(live.items()):
                    kk = min(k, ends[b])
                    t_now = d["t"][kk]
                    size = body_size(bodies.get(b, {})) if geo[b] else 0.5
                    lines, axes = _outline(d, kk, geo[b], size)
                    p = list(zip(d["x"][:kk + 1], d["y"][:kk + 1], d["z"][:kk + 1]))
                    scene3d.draw_lines(ax, list(zip(p, p[1:])), ["#999"], lw=0.6)
                    scene3d.draw_lines(ax, lines, ["#333"], lw=1.0)
                    for j, ln in enumerate(axes):
                        scene3d.draw_lines(ax, [ln], [AXIS_COLORS[j]], lw=1.5)
                scene3d.setup(ax, box, scene)
                stopped = any(ends[b] < min(k, len(d["t"]) - 1) for b, d in data.items())
                ax.set_title((title or "") + (f"  t = {t_now:.3f} s" if t_now is not None
                                              else "") + (note if stopped else ""))
                finish_frame(fig, out, inside=True)
                writer.grab_frame()
        os.replace(tmp, out)
    except OSError as e:
        raise InputError(f"{out}: cannot write ({e.strerror})") from None
    finally:
        import matplotlib.pyplot as plt
        plt.close(fig)
        if os.path.exists(tmp):
            os.remove(tmp)


def plot_sweep(path, out, title=None):
    """Work-precision: relative L and E errors against the wall time of the run's step loop
    (log-log), per integrator. A step's cost is what it weighs: an implicit-gyroscopic step
    (a Newton step with a 3x3 solve per body) costs more than an explicit one, so steps alone
    would flatter it."""
    rows = read_csv(path, SWEEP_COLUMNS, "rigid sweep CSV")
    by = {}
    for i, r in enumerate(rows):
        by.setdefault(r["integrator"], []).append(i)
    steps = column(path, rows, "wall_s")
    err = column(path, rows, "error")
    eerr = column(path, rows, "energy_error")
    fig, axes = new_figure(1, 2, figsize=(11.0, 4.2))
    notes = []
    names = list(by)
    for name, idx in by.items():
        color, marker = integrator_style(name, names)
        for ax, ys in zip(axes, (err, eerr)):
            xy = [(steps[i], ys[i]) for i in idx
                  if finite(ys[i]) and ys[i] > 0 and finite(steps[i]) and steps[i] > 0]
            ax.loglog([p[0] for p in xy], [p[1] for p in xy], color=color, marker=marker,
                      label=name)
        bad = [i for i in idx if rows[i]["status"] != "ok"]
        if bad:
            notes.append(f"{name}: {len(bad)} diverged run(s) not drawn")
        if any(not (finite(steps[i]) and steps[i] > 0) for i in idx):
            notes.append(f"{name}: run(s) too fast to time (wall time 0) not drawn")
        zero = [i for i in idx if finite(err[i]) and err[i] == 0]
        if zero:
            notes.append(f"{name}: {len(zero)} run(s) with zero error not drawn")
    # Curves that lie on top of each other: say so, with how close they are.
    if len(names) == 2:
        a, b = (by[n] for n in names)
        pairs = [(i, j) for i in a for j in b if rows[i]["dt"] == rows[j]["dt"]]
        diffs = [abs(ys[i] - ys[j]) / max(abs(ys[i]), abs(ys[j]))
                 for ys in (err, eerr) for i, j in pairs
                 if finite(ys[i]) and finite(ys[j]) and max(abs(ys[i]), abs(ys[j])) > 0]
        if pairs and diffs and max(diffs) < 0.25:
            notes.append(f"the two integrators' errors agree within {100 * max(diffs):.0f}% "
                         "at every dt: what separates them is what a step costs")
    axes[0].set_ylabel("|L(T) - L0| / |L0|")
    axes[1].set_ylabel("max |E - E0| / E0")
    for ax in axes:
        ax.set_xlabel("wall time of the step loop (s): what the steps cost")
        ax.legend(loc="best")
    scene = rows[0]["scene"]
    fig.suptitle(title or f"work-precision on the torque-free scene {scene}: exact L and E are "
                 "the initial ones" + ("\n" + "; ".join(notes) if notes else ""))
    save_figure(fig, out)


# ----------------------------------------------------------------------------
# tools/plot subcommands


def add_commands(sub):
    s = sub.add_parser("rigid-momenta", help="rigid lab: energy, momentum and angular "
                       "momentum against time (one or more --stats files)")
    s.add_argument("stats", nargs="+", metavar="STATS.csv")
    s.add_argument("--labels", help="comma-separated, one per file")
    s.add_argument("--diverged", metavar="LABEL=STEP,...",
                   help="runs whose summary says they diverged, and at which step")
    s.add_argument("-o", "--out", required=True, metavar="FIG.png")
    s.add_argument("--title")
    s = sub.add_parser("rigid-polhode", help="rigid lab: angular velocity in the body frame")
    s.add_argument("trace", metavar="TRACE.csv")
    s.add_argument("--id", type=int, default=0, help="body id (default 0)")
    s.add_argument("-o", "--out", required=True, metavar="FIG.png")
    s.add_argument("--title")
    s = sub.add_parser("rigid-frames", help="rigid lab: the bodies at sampled times in 3D")
    s.add_argument("trace", metavar="TRACE.csv")
    s.add_argument("--scene", metavar="S.json", help="the scene (for the bodies' shapes)")
    s.add_argument("--count", type=int, default=8, help="sampled times (default 8)")
    s.add_argument("-o", "--out", required=True, metavar="FIG.png")
    s.add_argument("--title")
    s = sub.add_parser("rigid-animate", help="rigid lab: a GIF animation of a run")
    s.add_argument("trace", metavar="TRACE.csv")
    s.add_argument("--scene", metavar="S.json", help="the scene (for the bodies' shapes)")
    s.add_argument("--frames", type=int, default=60, help="frames (default 60)")
    s.add_argument("--fps", type=int, default=20, help="frames per second (default 20)")
    s.add_argument("-o", "--out", required=True, metavar="FIG.gif")
    s.add_argument("--title")
    creep.add_command(sub, "rigid-creep", "rigid lab")
    s = sub.add_parser("rigid-sweep", help="rigid lab: work-precision from a --sweep CSV")
    s.add_argument("sweep", metavar="SWEEP.csv")
    s.add_argument("-o", "--out", required=True, metavar="FIG.png")
    s.add_argument("--title")


def run(args):
    cmd = args.command
    if cmd == "rigid-creep":
        creep.plot_creep(args.traces, parse_list(args.labels, "--labels"), args.out,
                         after=args.after, title=args.title)
    elif cmd == "rigid-momenta":
        labels = parse_list(args.labels, "--labels") if args.labels else None
        diverged = parse_label_map(args.diverged, "--diverged", int, "LABEL=STEP")
        plot_momenta(args.stats, labels, args.out, title=args.title, diverged=diverged)
    elif cmd == "rigid-polhode":
        plot_polhode(args.trace, args.out, body=args.id, title=args.title)
    elif cmd == "rigid-frames":
        if args.count < 1:
            raise InputError(f"--count: got {args.count}, expected a whole number >= 1")
        plot_frames(args.trace, args.out, read_scene(args.scene), args.count, title=args.title)
    elif cmd == "rigid-animate":
        if args.frames < 1 or args.fps < 1:
            raise InputError("--frames and --fps: expected whole numbers >= 1")
        if not args.out.endswith(".gif"):
            raise InputError(f"-o: got '{args.out}', expected a file name ending in .gif")
        animate(args.trace, args.out, read_scene(args.scene), args.frames, args.fps,
                title=args.title)
    elif cmd == "rigid-sweep":
        plot_sweep(args.sweep, args.out, title=args.title)
    else:
        return False
    return True


# ----------------------------------------------------------------------------
# The report


def _torque_free(doc):
    return not (doc.get("forces") or doc.get("planes") or doc.get("hinges"))


def _every(doc):
    try:
        steps = round(float(doc["t_end"]) / float(doc["dt"]))
    except (KeyError, TypeError, ValueError, ZeroDivisionError):
        return 1
    return max(1, math.ceil(steps / MAX_WRITTEN_STEPS))


def _change(s, key):
    """'gains' / 'loses' / 'keeps' for a summary's energy, from the run's own numbers."""
    a, b = s.get(key + "0"), s.get(key)
    if not (isinstance(a, (int, float)) and isinstance(b, (int, float))):
        return None
    if abs(b - a) <= 1e-12 * max(abs(a), 1e-300):
        return "keeps its energy"
    return f"{'gains' if b > a else 'loses'} energy ({a:.6g} J to {b:.6g} J)"


def scene_figures(ctx):
    doc, stem = ctx.doc, ctx.stem
    default = doc.get("integrator") or INTEGRATORS[0]
    integs = [default] + ([i for i in INTEGRATORS if i != default] if _torque_free(doc) else [])
    every = str(_every(doc))
    stats, summaries = [], {}
    trace = ctx.path(f"{stem}-trace.csv")
    for integ in integs:
        st = ctx.path(f"{stem}-{integ}-stats.csv")
        argv = ["--scene", ctx.scene_path, "--integrator", integ, "--stats", st]
        if integ == default:
            argv += ["--out", trace]
        s = ctx.run(argv + ["--every", every], f"{stem} ({integ})", label=integ,
                    save=f"{stem}-{integ}")  # the summary `summary` claims read
        if s is None:
            continue
        if s.get("status") == "diverged" and every != "1" and s.get("steps", 0) <= 10**6:
            # Every step up to the blow-up, for the figure's zoomed column.
            s = ctx.run(argv + ["--every", "1"], f"{stem} ({integ}, every step)", label=integ,
                        again=True, save=f"{stem}-{integ}")
            if s is None:
                continue
        summaries[integ] = s
        stats.append((integ, st))
    if default not in summaries:
        return
    said = "; ".join(f"{i} {_change(summaries[i], 'energy')}" for i in summaries
                     if _change(summaries[i], "energy"))
    diverged = [i for i in summaries if summaries[i].get("status") == "diverged"]
    if diverged:
        said += "; diverged: " + ", ".join(diverged) + " (dash-dot line)"
    out = ctx.path(f"{stem}-momenta.png")
    args = ["rigid-momenta"] + [p for _, p in stats] + [
        "--labels", ",".join(i for i, _ in stats), "-o", out]
    args += ctx.diverged_args([i for i, _ in stats])
    if ctx.plot(args):
        ctx.figure(out, "Energy, momentum and angular momentum about the origin against time "
                        f"(--every {every}" + (
                            "; a run that diverged: every step, and a right-hand column shows "
                            "its first moments on log scales when it blew up early"
                            if diverged else "") + "; a quantity constant to rounding is drawn "
                        f"flat, its value in the legend). In this run: {said}.", args)
    # What the figures of the default run say of it (diverged, a stub) is its summary's.
    summary = ctx.path(f"{stem}-{default}-summary.json")
    out = ctx.path(f"{stem}-polhode.png")
    args = ["rigid-polhode", trace, "-o", out, "--summary", summary]
    if ctx.plot(args):
        ctx.figure(out, f"Body 0's angular velocity in its own frame ({default}): constant "
                        "components mean a spin about a principal axis. " + (
                            "On this torque-free body, a large component that changes sign "
                            "while the others pass through their extremes is a flip (the "
                            "Dzhanibekov effect)." if _torque_free(doc) else
                            "Under forces, hinges or contact the components also change sign "
                            "for other reasons (a pendulum's swing): that is not a flip."),
                   args)
    out = ctx.path(f"{stem}-frames.png")
    args = ["rigid-frames", trace, "--scene", ctx.scene_path, "-o", out, "--summary", summary]
    if ctx.plot(args):
        ctx.figure(out, f"The bodies at 8 sampled times ({default}) with their axes and the "
                        "path of their centre, the view fitted to the bodies, the scene's "
                        "planes and hinge axes (dashed) where they are. When a body stays "
                        "within its own size, each sampled time has a panel of its own; "
                        "otherwise the outlines share one view, coloured by time.", args)
    out = ctx.path(f"{stem}.gif")
    args = ["rigid-animate", trace, "--scene", ctx.scene_path, "--frames", "48", "-o", out,
            "--summary", summary]
    if ctx.plot(args):
        ctx.figure(out, f"Animation of the run ({default}, 48 frames), the view fitted to the "
                        "bodies, planes and hinge axes where they are.", args)
    if stem in CREEP:
        _creep_figure(ctx, default)
    if _torque_free(doc) and stem == "dzhanibekov":
        csv = ctx.path(f"sweep-{stem}.csv")
        s = ctx.run(["--scene", ctx.scene_path, "--sweep", csv, "--t-end", "10", "--repeats",
                     "3"], f"{stem} sweep", label="sweep")
        if s is not None:
            out = ctx.path(f"sweep-{stem}.png")
            args = ["rigid-sweep", csv, "-o", out]
            if ctx.plot(args):
                ctx.figure(out, "Work-precision of the two integrators over 10 s of the "
                                "torque-free flip: relative error of the angular momentum at "
                                "the end, and the largest relative energy error, against the "
                                "wall time of the step loop (the least of 3 timed runs): an "
                                "implicit-gyroscopic step costs more than an explicit one, so "
                                "the same number of steps is not the same work.", args)


# Scenes whose resting contacts the report runs with both solvers (handouts/rigid.md#r6).
CREEP = {"box-rest": 1.1}  # scene: the time from which it should rest (s)


def _set_solver(doc, solver):
    doc.setdefault("contact", {})["solver"] = solver


def _creep_figure(ctx, integ):
    stem = ctx.stem
    traces = []
    for solver, scene in creep.solver_scenes(ctx.doc, ctx.out_dir, stem, _set_solver).items():
        trace = ctx.path(f"{stem}-{solver}-trace.csv")
        s = ctx.run(["--scene", scene, "--integrator", integ, "--out", trace, "--every", "10"],
                    f"{stem} (solver {solver})", label=solver)
        if s is None:
            return
        traces.append(trace)
    creep.write_rest(ctx.path(f"{stem}-rest.csv"), traces, list(creep.SOLVERS), CREEP[stem])
    out = ctx.path(f"{stem}-creep.png")
    args = ["rigid-creep"] + traces + ["--labels", "passes (one-shot),accumulated",
                                       "--after", str(CREEP[stem]), "-o", out]
    if ctx.plot(args):
        ctx.figure(out, "The box solved by the one-shot passes and by the accumulated, "
                        "warm-started impulses (R6): on top its largest speed (log scale), "
                        "below how far it has moved since 1 s after landing (the dotted "
                        f"line); the numbers are in {stem}-rest.csv.", args)


# tools/claims makes these files itself when build/report has none (docs/report.md, Claims).
CLAIM_FILES = {f"{stem}-rest.csv": (lambda exe, out, stem=stem, after=after: creep.make_rest_file(
    exe, out, "rigid", stem, _set_solver, stem + "-{solver}-trace.csv", after))
    for stem, after in CREEP.items()}
