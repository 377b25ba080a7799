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
PACK_PLOTS = [("tools/plot rigid-frames out/run.csv --scene {scene} -o out/run.png",
               "the bodies at sampled times, in 3D"),
              ("tools/plot rigid-momenta out/run-stats.csv -o out/run-energy.png",
               "energy, momentum, angular momentum against time")]

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


def equal_axes(ax, points):
    pts = [p for p in points if all(finite(c) for c in p)]
    if not pts:
        return
    lo = [min(p[i] for p in pts) for i in range(3)]
    hi = [max(p[i] for p in pts) for i in range(3)]
    half = max(max(h - l for l, h in zip(lo, hi)) / 2, 1e-3)
    mid = [(l + h) / 2 for l, h in zip(lo, hi)]
    ax.set_xlim(mid[0] - half, mid[0] + half)
    ax.set_ylim(mid[1] - half, mid[1] + half)
    ax.set_zlim(mid[2] - half, mid[2] + half)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")


AXIS_COLORS = ["#d62728", "#2ca02c", "#1f77b4"]  # body x, y, z


def draw_planes(ax, scene, pts):
    """The scene's planes as translucent squares around the drawn points."""
    good = [p for p in pts if all(finite(c) for c in p)]
    if not scene or not good:
        return
    mid = [sum(p[i] for p in good) / len(good) for i in range(3)]
    half = max(max(p[i] for p in good) - min(p[i] for p in good) for i in range(3)) / 2 + 0.5
    for plane in scene.get("planes", []) or []:
        try:
            n = [float(c) for c in plane["normal"]]
            o = [float(c) for c in plane.get("point", [0, 0, 0])]
        except (KeyError, TypeError, ValueError):
            continue
        nn = math.sqrt(sum(c * c for c in n))
        if not nn > 0:
            continue
        n = [c / nn for c in n]
        a = [0.0, 0.0, 1.0] if abs(n[2]) < 0.9 else [1.0, 0.0, 0.0]
        u = [n[1] * a[2] - n[2] * a[1], n[2] * a[0] - n[0] * a[2], n[0] * a[1] - n[1] * a[0]]
        un = math.sqrt(sum(c * c for c in u))
        u = [c / un for c in u]
        w = [n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2], n[0] * u[1] - n[1] * u[0]]
        d = sum((m - oo) * nc for m, oo, nc in zip(mid, o, n))
        c = [m - d * nc for m, nc in zip(mid, n)]  # the centre, projected on the plane
        X, Y, Z = ([[c[i] + half * (s * u[i] + t * w[i]) for s in (-1, 1)] for t in (-1, 1)]
                   for i in range(3))
        ax.plot_surface(_arr(X), _arr(Y), _arr(Z), color="#8c6d31", alpha=0.15, linewidth=0)


def _arr(rows):
    import numpy
    return numpy.array(rows)


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

    A run that diverged early gets a second column: the first moments of the run
    on log scales (|E|, |p|, |L|) up to the step where it stopped being finite,
    while the left column keeps the scale of the runs that stayed finite.
    """
    runs = [read_stats(p) for p in paths]
    labels = labels or [os.path.basename(p) for p in paths]
    if len(labels) != len(paths):
        raise InputError(f"--labels: got {len(labels)} labels for {len(paths)} files")
    colors = [integrator_style(label, labels)[0] if label in INTEGRATORS else f"C{n}"
              for n, label in enumerate(labels)]
    ends = [last_finite(s["energy"]) for s in runs]
    t_end = max((s["t"][-1] for s in runs if s["t"] and finite(s["t"][-1])), default=0.0)
    blowups = {n: runs[n]["t"][ends[n] + 1] for n in range(len(runs))
               if ends[n] < len(runs[n]["t"]) - 1}
    blow_steps = {n: int(runs[n]["step"][ends[n] + 1]) for n in blowups}
    # Runs whose summary says they diverged with a finite last row (|E| past 1000 times
    # its initial scale, docs/run-contract.md): the blow-up is that row.
    for label, step in (diverged or {}).items():
        if label not in labels:
            raise InputError(f"--diverged: '{label}' is not one of the labels {','.join(labels)}")
        n = labels.index(label)
        if n not in blowups:
            rows = [k for k, st in enumerate(runs[n]["step"]) if st == step]
            if not rows:
                raise InputError(f"--diverged: {label}: step {step} is not a row of its stats")
            blowups[n], blow_steps[n] = runs[n]["t"][rows[0]], step
    finite_runs = [n for n in range(len(runs)) if n not in blowups]
    zoom = bool(blowups) and bool(finite_runs) and t_end > 0 and \
        max(blowups.values()) < EARLY_BLOWUP * t_end
    fig, grid = new_figure(3, 2 if zoom else 1, figsize=(12.5 if zoom else 7.5, 8.0),
                           sharex="col", squeeze=False)
    axes = [row[0] for row in grid]
    styles = ["-", "--", ":"]
    groups = (("energy",), ("px", "py", "pz"), ("Lx", "Ly", "Lz"))
    notes = []
    for n, (s, label) in enumerate(zip(runs, labels)):
        end = ends[n]
        t = s["t"][:end + 1]
        axes[0].plot(t, s["energy"][:end + 1], color=colors[n], label=label)
        for ax, cols in zip(axes[1:], groups[1:]):
            for i, c in enumerate(cols):
                ax.plot(t, s[c][:end + 1], color=colors[n], ls=styles[i],
                        label=f"{label}: {c}" if len(runs) > 1 else c)
        if n in blowups:
            for ax in axes:
                ax.axvline(blowups[n], color=colors[n], lw=0.8, ls="-.")
            notes.append(f"{label} diverged at t = {blowups[n]:g} s, step "
                         f"{blow_steps[n]} (dash-dot line)")
    if len(runs) > 1:
        e0 = runs[0]["energy"]
        for s, label in zip(runs[1:], labels[1:]):
            e = s["energy"]
            if len(e) == len(e0) and all(finite(a) and finite(b) and
                                         abs(a - b) <= 1e-12 * max(abs(a), abs(b), 1e-300)
                                         for a, b in zip(e, e0)):
                notes.append(f"the energies of {labels[0]} and {label} coincide")
    for ax, cols in zip(axes, groups):
        shown = finite_runs if zoom else range(len(runs))
        vals = [v for n in shown for c in cols for v in runs[n][c][:ends[n] + 1]]
        first = [abs(runs[n][c][0]) for n in shown for c in cols if finite(runs[n][c][0])]
        scale = max(first + [1e-12])
        if zoom and vals:
            # The left column keeps the finite runs' scale; the blow-up is on the right.
            lo, hi = min(vals), max(vals)
            pad = 0.05 * (hi - lo) if hi > lo else max(abs(hi), 1.0) * 0.05
            ax.set_ylim(lo - pad, hi + pad)
        elif vals and max(abs(v) for v in vals) > 1e3 * scale:
            # A blow-up spans decades: log scales, so that the other runs stay readable.
            _log_or_symlog(ax, vals, scale)
            ax.text(0.01, 0.02, "log scale: a run blew up", transform=ax.transAxes,
                    fontsize=8, color="#555")
    if zoom:
        axes[0].set_title("The whole run, on the scale of the runs that stayed finite",
                          fontsize=10)
    axes[0].set_ylabel("energy E (J)")
    axes[1].set_ylabel("momentum p (kg m/s)")
    axes[2].set_ylabel("angular momentum L\nabout the origin (kg m²/s)")
    axes[2].set_xlabel("time t (s)")
    for ax in axes:
        ax.legend(loc="best", ncol=2 if len(runs) > 1 else 3, fontsize=8)
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
    """The angular velocity in the body frame: components against time, and its curve."""
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
    diverged = len(t) < len(d["t"])
    apply = new_figure(figsize=(11.0, 4.2))
    fig = apply[0]
    fig.clf()
    ax = fig.add_subplot(1, 2, 1)
    for j in range(3):
        ax.plot(t, [p[j] for p in w], color=AXIS_COLORS[j], label=f"ω along body {'xyz'[j]}")
    if diverged and t:
        ax.axvline(t[-1], color="k", ls="-.", lw=0.8, label=f"last finite state, t = {t[-1]:g} s")
    ax.set_xlabel("time t (s)")
    ax.set_ylabel("body-frame angular velocity (rad/s)")
    ax.legend(loc="best")
    ax.set_title("ω in the body frame, R^T ω")
    ax3 = fig.add_subplot(1, 2, 2, projection="3d")
    ax3.plot([p[0] for p in w], [p[1] for p in w], [p[2] for p in w], color="#444", lw=0.8)
    if w:
        ax3.scatter(*[[w[0][j]] for j in range(3)], color="#2ca02c", s=20, label="start")
        ax3.scatter(*[[w[-1][j]] for j in range(3)], color="#d62728", s=20, label="end")
        ax3.legend(loc="upper left")
    ax3.set_xlabel("ω_x (rad/s)")
    ax3.set_ylabel("ω_y (rad/s)")
    ax3.set_zlabel("ω_z (rad/s)", labelpad=4)
    # Shrink the box inside its axes, and keep the axes off the figure's right edge, so
    # that the z label is not cut.
    ax3.set_box_aspect(None, zoom=0.78)
    fig.subplots_adjust(left=0.07, right=0.9, wspace=0.3)
    ax3.set_title("polhode: the tip of ω in the body frame")
    fig.suptitle(title or f"body {body}" + (" (diverged)" if diverged else ""))
    save_figure(fig, out)


def _scene_bodies(scene, ids):
    bodies = scene.get("bodies", []) if scene else []
    return {b: (bodies[b] if b < len(bodies) else {}) for b in ids}


def plot_frames(path, out, scene=None, count=8, title=None):
    """Each body's outline and axes at `count` sampled times, in 3D, with its path."""
    data = read_trace(path)
    bodies = _scene_bodies(scene, data)
    fig, _ = new_figure(figsize=(7.5, 7.0))
    fig.clf()
    ax = fig.add_subplot(1, 1, 1, projection="3d")
    import matplotlib
    cmap = matplotlib.colormaps["viridis"]
    pts = []
    note = ""
    strip = column = False
    # Bodies whose centres all stay within their own size (spinning in place) would stack
    # their outlines into one tangle: the samples are then drawn side by side along x, a
    # film strip, `gap` apart (the bodies' spread in x plus 1.6 of the largest size).
    # When some bodies move and others stay, each body that stays is drawn as a strip of its
    # own along z (1.6 of its size apart), so that it neither tangles nor meets the others.
    sizes, travels, xs0, still = [], [], [], {}
    for b, d in data.items():
        end = min(last_finite(d[c]) for c in ("x", "y", "z", "qw"))
        if end < 0:
            continue
        sizes.append(body_size(bodies.get(b, {})) if shape_edges(bodies.get(b, {})) else 0.5)
        travels.append(max(math.dist((d["x"][k], d["y"][k], d["z"][k]),
                                     (d["x"][0], d["y"][0], d["z"][0])) for k in range(end + 1)))
        xs0.append(d["x"][0])
        still[b] = travels[-1] < sizes[-1]
    in_place = bool(sizes) and all(still.values())
    gap = (max(xs0) - min(xs0) + 1.6 * max(sizes)) if in_place else 0.0
    for b, d in sorted(data.items()):
        end = min(last_finite(d[c]) for c in ("x", "y", "z", "qw"))
        if end < 0:
            continue
        if end < len(d["t"]) - 1:
            note = f" (diverged: drawn up to t = {d['t'][end]:g} s)"
        xs, ys, zs = d["x"][:end + 1], d["y"][:end + 1], d["z"][:end + 1]
        segs = shape_edges(bodies.get(b, {}))
        size = body_size(bodies.get(b, {})) if segs else 0.5
        n = max(1, min(count, end + 1))
        step = gap if n > 1 else 0.0
        up = 1.6 * size if n > 1 and not in_place and still.get(b) else 0.0
        strip = strip or step > 0
        column = column or up > 0
        if not step and not up:
            ax.plot(xs, ys, zs, color="#888", lw=0.7)
            pts += list(zip(xs, ys, zs))
        for i in range(n):
            k = round(i * end / max(n - 1, 1))
            color = cmap(i / max(n - 1, 1))
            lines, axes = world_segments(d, k, segs, 0.6 * size)
            shift = (i * step, 0.0, i * up)
            lines = [tuple(tuple(c + o for c, o in zip(p, shift)) for p in ln) for ln in lines]
            axes = [tuple(tuple(c + o for c, o in zip(p, shift)) for p in ln) for ln in axes]
            for p, q in lines:
                ax.plot(*zip(p, q), color=color, lw=0.9)
                pts += [p, q]
            for j, (p, q) in enumerate(axes):
                ax.plot(*zip(p, q), color=AXIS_COLORS[j], lw=1.2)
    if strip:
        note += ("\nthe bodies stay in place: each sampled time is drawn side by side along "
                 f"x, {gap:.3g} m apart, earliest on the left")
    if column:
        note += ("\na body that stays in place is drawn one sampled time above the other "
                 "(earliest at the bottom)")
    draw_planes(ax, scene, pts)
    equal_axes(ax, pts)
    ts = [d["t"] for d in data.values()]
    t_end = max(t[-1] for t in ts)
    sm = matplotlib.cm.ScalarMappable(cmap=cmap, norm=matplotlib.colors.Normalize(0, t_end))
    fig.colorbar(sm, ax=ax, shrink=0.6, pad=0.12, label="time of the outline (s)")
    ax.set_title(title or f"bodies at {count} sampled times; body axes x, y, z in red, green, "
                 f"blue{note}")
    save_figure(fig, out)


def animate(path, out, scene=None, frames=60, fps=20, title=None):
    """A GIF of the run: every body's outline and axes, one frame per sampled row."""
    from matplotlib.animation import PillowWriter
    data = read_trace(path)
    bodies = _scene_bodies(scene, data)
    fig, _ = new_figure(figsize=(5.5, 5.0))
    fig.clf()
    ax = fig.add_subplot(1, 1, 1, projection="3d")
    geo = {b: shape_edges(bodies.get(b, {})) for b in data}
    ends = {b: min(last_finite(d[c]) for c in ("x", "y", "z", "qw")) for b, d in data.items()}
    pts = []
    for b, d in data.items():
        pts += list(zip(d["x"][:ends[b] + 1], d["y"][:ends[b] + 1], d["z"][:ends[b] + 1]))
        size = body_size(bodies.get(b, {}))
        pts += [(d["x"][0] + s * size, d["y"][0], d["z"][0]) for s in (-0.5, 0.5)]
    n_rows = max(len(d["t"]) for d in data.values())
    n = max(1, min(frames, n_rows))
    rows = [round(i * (n_rows - 1) / max(n - 1, 1)) for i in range(n)]
    tmp = os.path.join(os.path.dirname(os.path.abspath(out)),
                       f".{os.path.basename(out)}.tmp-{os.getpid()}.gif")
    writer = PillowWriter(fps=fps)
    try:
        with writer.saving(fig, tmp, dpi=80):
            for k in rows:
                ax.cla()
                t_now = None
                for b, d in sorted(data.items()):
                    kk = min(k, ends[b])
                    if kk < 0:
                        continue
                    t_now = d["t"][kk]
                    size = body_size(bodies.get(b, {})) if geo[b] else 0.5
                    lines, axes = world_segments(d, kk, geo[b], 0.6 * size)
                    for p, q in lines:
                        ax.plot(*zip(p, q), color="#333", lw=1.0)
                    for j, (p, q) in enumerate(axes):
                        ax.plot(*zip(p, q), color=AXIS_COLORS[j], lw=1.5)
                    ax.plot(d["x"][:kk + 1], d["y"][:kk + 1], d["z"][:kk + 1], color="#999",
                            lw=0.6)
                draw_planes(ax, scene, pts)
                equal_axes(ax, pts)
                diverged = any(ends[b] < min(k, len(d["t"]) - 1) for b, d in data.items())
                ax.set_title((title or "") + (f"  t = {t_now:.3f} s" if t_now is not None
                                              else "") + ("  (diverged)" if diverged else ""))
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
        ctx.figure(out, f"Energy, momentum and angular momentum about the origin against time "
                        f"(--every {every}; a run that diverged: every step, and a right-hand "
                        f"column shows its first moments on log scales when it blew up early). "
                        f"In this run: {said}.", args)
    out = ctx.path(f"{stem}-polhode.png")
    args = ["rigid-polhode", trace, "-o", out]
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
    args = ["rigid-frames", trace, "--scene", ctx.scene_path, "-o", out]
    if ctx.plot(args):
        ctx.figure(out, f"The bodies at 8 sampled times ({default}), coloured by time, with "
                        "their axes and the path of their centre (bodies that stay in place are "
                        "drawn one sampled time beside or above the other, as the title "
                        "says).", args)
    out = ctx.path(f"{stem}.gif")
    args = ["rigid-animate", trace, "--scene", ctx.scene_path, "--frames", "48", "-o", out]
    if ctx.plot(args):
        ctx.figure(out, f"Animation of the run ({default}, 48 frames).", args)
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


def _creep_figure(ctx, integ):
    stem = ctx.stem
    traces = []
    for solver in ("passes", "accumulated"):
        doc = json.loads(json.dumps(ctx.doc))
        doc.setdefault("contact", {})["solver"] = solver
        scene = ctx.path(f"{stem}-{solver}.json")
        with open(scene, "w", encoding="utf-8") as f:
            json.dump(doc, f, indent=1)
        trace = ctx.path(f"{stem}-{solver}-trace.csv")
        s = ctx.run(["--scene", scene, "--integrator", integ, "--out", trace, "--every", "10"],
                    f"{stem} (solver {solver})", label=solver)
        if s is None:
            return
        traces.append(trace)
    out = ctx.path(f"{stem}-creep.png")
    args = ["rigid-creep"] + traces + ["--labels", "passes (one-shot),accumulated",
                                       "--after", str(CREEP[stem]), "-o", out]
    if ctx.plot(args):
        ctx.figure(out, "The largest speed of the box against time (log scale), the same "
                        "scene solved by the one-shot passes and by the accumulated, "
                        "warm-started impulses (R6); the dotted line is 1 s after landing.",
                   args)
