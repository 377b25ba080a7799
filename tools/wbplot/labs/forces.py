"""The forces lab's own figures for curl-noise scenes (tools/report), and tools/plot subcommands.

    tools/plot flow-probe SCENE -o PROBE.json [--trace RUN.csv] [--grid N]
        a scene of N x N particles at rest on a grid, under the scene's curl-noise force alone,
        run for one step: their velocity after it is dt b u(x) / m, so it samples the flow u
        that the executable's F9 code computes (no second implementation of the flow)
    tools/plot flow PROBE_TRACE --probe PROBE.json [--trace RUN.csv] -o OUT.png [--csv OUT.csv]
        streamlines of that flow, the obstacles, the paths of some particles of a run, and
        the divergence of u measured on the grid by central differences (printed on the figure)
    tools/plot smoke RUN.csv --scene SCENE -o OUT.gif
        an animated GIF of a run's particles as smoke, with the scene's obstacles

A student runs them on their own build (build/bin/forces --scene PROBE.json --out P.csv
--every 1): handouts/forces.md, F9.
"""
import json
import math
import os

from ..common import InputError, new_figure, save_animation, save_figure, write_text_atomic
from ..runs import choose_ids, read_trace

PROBE_GRID = 161      # probe particles per side
PROBE_DT = 1e-3       # s, the probe's one step
MAX_PATHS = 60        # particle paths drawn over the streamlines
MAX_FRAMES = 80       # frames of the animation


# ----------------------------------------------------------------------------
# The scene's curl-noise force


def _read_json(path, what):
    if not os.path.exists(path):
        raise InputError(f"{what}: {path}: no such file")
    try:
        with open(path, encoding="utf-8") as f:
            doc = json.load(f)
    except (OSError, json.JSONDecodeError) as e:
        raise InputError(f"{what}: {path}: cannot read as JSON ({e})") from None
    if not isinstance(doc, dict):
        raise InputError(f"{what}: {path}: expected a JSON object")
    return doc


def curl_force(doc, path):
    """The scene's one curl-noise force entry."""
    fs = [f for f in doc.get("forces", []) or [] if isinstance(f, dict)
          and f.get("type") == "curl-noise"]
    if len(fs) != 1:
        raise InputError(f"{path}: has {len(fs)} curl-noise forces, expected exactly one")
    f = fs[0]
    try:
        b = float(f["b"])
    except (KeyError, TypeError, ValueError):
        raise InputError(f"{path}: curl-noise force: key 'b': expected a number") from None
    if not b > 0:
        raise InputError(f"{path}: curl-noise force: b = {b:g}: the flow can only be probed "
                         "through a drag b > 0")
    return f


def discs(force):
    out = []
    for o in force.get("obstacles", []) or []:
        try:
            out.append((float(o["center"][0]), float(o["center"][1]), float(o["radius"])))
        except (KeyError, IndexError, TypeError, ValueError):
            raise InputError("curl-noise force: obstacles: expected {\"center\": [x, y], "
                             "\"radius\": r} entries") from None
    return out


def _bounds_of_scene(doc, force):
    xs, ys = [], []
    for e in doc.get("emitters", []) or []:
        try:
            xs += [float(e["min"][0]), float(e["max"][0])]
            ys += [float(e["min"][1]), float(e["max"][1])]
        except (KeyError, IndexError, TypeError, ValueError):
            pass
    for p in doc.get("particles", []) or []:
        try:
            xs.append(float(p["x"][0]))
            ys.append(float(p["x"][1]))
        except (KeyError, IndexError, TypeError, ValueError):
            pass
    for cx, cy, r in discs(force):
        xs += [cx - r, cx + r]
        ys += [cy - r, cy + r]
    if not xs:
        return -1.0, 1.0, -1.0, 1.0
    return min(xs), max(xs), min(ys), max(ys)


def _bounds_of_trace(data):
    xs = [x for d in data.values() for x in d["x"] if math.isfinite(x)]
    ys = [y for d in data.values() for y in d["y"] if math.isfinite(y)]
    if not xs:
        raise InputError("the run's trace has no finite position")
    return min(xs), max(xs), min(ys), max(ys)


def write_probe(scene, out, trace=None, grid=PROBE_GRID):
    """Writes the probe scene (see the module's help); returns its dict."""
    doc = _read_json(scene, "scene")
    force = curl_force(doc, scene)
    x0, x1, y0, y1 = _bounds_of_trace(read_trace(trace)) if trace else _bounds_of_scene(doc, force)
    span = max(x1 - x0, y1 - y0, 1e-6)
    cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
    half = 0.55 * span  # a square view with a margin
    if grid < 5 or grid > 301:
        raise InputError(f"--grid: got {grid}, expected 5 to 301")
    step = 2 * half / (grid - 1)
    parts = [{"x": [cx - half + i * step, cy - half + j * step], "m": 1}
             for j in range(grid) for i in range(grid)]
    probe = {"name": f"{doc.get('name', 'scene')}-probe",
             "description": f"Probe of the curl-noise flow of {os.path.basename(scene)}: "
                            f"{grid} x {grid} particles of 1 kg at rest, one step of "
                            f"{PROBE_DT:g} s (tools/plot flow-probe).",
             "dt": PROBE_DT, "t_end": PROBE_DT, "particles": parts, "forces": [force]}
    folder = os.path.dirname(os.path.abspath(out))
    if not os.path.isdir(folder):
        raise InputError(f"-o: {out}: folder {folder} does not exist")
    write_text_atomic(out, json.dumps(probe) + "\n")
    return probe


# ----------------------------------------------------------------------------
# The flow on the grid, and its divergence


def flow_grid(probe_trace, probe):
    """(xs, ys, U, V): the flow u = v(dt) m / (b dt) at the probe's grid points."""
    data = read_trace(probe_trace)
    parts = probe["particles"]
    n = round(math.sqrt(len(parts)))
    if n * n != len(parts) or len(data) != len(parts):
        raise InputError(f"{probe_trace}: has {len(data)} particles, the probe scene "
                         f"{len(parts)} on a square grid: expected the probe's own run")
    b, dt = float(probe["forces"][0]["b"]), float(probe["dt"])
    xs = [parts[i]["x"][0] for i in range(n)]
    ys = [parts[j * n]["x"][1] for j in range(n)]
    U = [[0.0] * n for _ in range(n)]
    V = [[0.0] * n for _ in range(n)]
    for j in range(n):
        for i in range(n):
            d = data[j * n + i]
            if len(d["t"]) < 2 or not math.isclose(d["t"][-1], dt, rel_tol=1e-9):
                raise InputError(f"{probe_trace}: particle {j * n + i} has no row at t = "
                                 f"{dt:g} s: run the probe with --every 1")
            U[j][i] = d["vx"][-1] * float(parts[j * n + i]["m"]) / (b * dt)
            V[j][i] = d["vy"][-1] * float(parts[j * n + i]["m"]) / (b * dt)
    return xs, ys, U, V


def _outside(x, y, ds, margin=0.0):
    return all(math.hypot(x - cx, y - cy) > r + margin for cx, cy, r in ds)


def divergence(xs, ys, U, V, ds, k):
    """(rms and max |div u|, rms and max |curl u|) by central differences with step k grid
    spacings, over the grid points whose stencil (of the widest step, 2 spacings) lies
    outside every obstacle."""
    n = len(xs)
    dx, dy = xs[1] - xs[0], ys[1] - ys[0]
    divs, curls = [], []
    for j in range(2, n - 2):
        for i in range(2, n - 2):
            pts = [(xs[i + a], ys[j + c]) for a, c in ((0, 0), (2, 0), (-2, 0), (0, 2), (0, -2))]
            if not all(_outside(x, y, ds) for x, y in pts):
                continue
            div = ((U[j][i + k] - U[j][i - k]) / (2 * k * dx)
                   + (V[j + k][i] - V[j - k][i]) / (2 * k * dy))
            curl = ((V[j][i + k] - V[j][i - k]) / (2 * k * dx)
                    - (U[j + k][i] - U[j - k][i]) / (2 * k * dy))
            divs.append(abs(div))
            curls.append(abs(curl))
    if not divs:
        raise InputError("no grid point lies outside the obstacles: nothing to measure")

    def rms(a):
        return math.sqrt(sum(v * v for v in a) / len(a))
    return rms(divs), max(divs), rms(curls), max(curls), len(divs)


def plot_flow(probe_trace, probe_path, out, trace=None, csv_out=None, title=None):
    probe = _read_json(probe_path, "--probe")
    force = curl_force(probe, probe_path)
    ds = discs(force)
    xs, ys, U, V = flow_grid(probe_trace, probe)
    d1 = divergence(xs, ys, U, V, ds, 1)
    d2 = divergence(xs, ys, U, V, ds, 2)
    dx = xs[1] - xs[0]
    fig, ax = new_figure(figsize=(6.6, 6.2))
    import numpy as np
    Um, Vm = np.array(U), np.array(V)
    speed = np.hypot(Um, Vm)
    for j in range(len(ys)):
        for i in range(len(xs)):
            if not _outside(xs[i], ys[j], ds):
                Um[j, i] = Vm[j, i] = np.nan
    strm = ax.streamplot(np.array(xs), np.array(ys), Um, Vm, density=1.6, linewidth=0.7,
                         color=np.where(np.isnan(Um), 0.0, speed), cmap="Greys", arrowsize=0.7)
    fig.colorbar(strm.lines, ax=ax, shrink=0.8, pad=0.1, orientation="horizontal",
                 label="flow speed |u| (m/s), the streamlines' shade")
    from matplotlib.patches import Circle
    for cx, cy, r in ds:
        ax.add_patch(Circle((cx, cy), r, facecolor="0.75", edgecolor="0.2", lw=1.0, zorder=3))
    if trace:
        data = read_trace(trace)
        for i in choose_ids(list(data), MAX_PATHS):
            ax.plot(data[i]["x"], data[i]["y"], lw=0.8, color="C1", alpha=0.8, zorder=4)
            ax.plot(data[i]["x"][:1], data[i]["y"][:1], "o", ms=2.5, mfc="none", color="C1",
                    zorder=4)
        ax.plot([], [], color="C1", label=f"paths of {min(MAX_PATHS, len(data))} of the run's "
                                          f"{len(data)} particles (o: start)")
        ax.legend(loc="lower left", fontsize=8, framealpha=0.85)
    ax.text(0.02, 0.98,
            f"div u on the {len(xs)}x{len(xs)} grid, {d1[4]} points\n"
            f"off the obstacles, Δ = {dx:.3g} m:\n"
            f" step Δ:  rms {d1[0]:.2e}, max {d1[1]:.2e} 1/s\n"
            f" step 2Δ: rms {d2[0]:.2e}, max {d2[1]:.2e} 1/s\n"
            f"rms |curl u| = {d1[2]:.3g} 1/s (a wrong curl's\n"
            f"divergence would be this large)",
            transform=ax.transAxes, va="top", fontsize=7.5, family="monospace",
            bbox=dict(facecolor="white", alpha=0.85, edgecolor="0.6"), zorder=6)
    ax.set_xlim(xs[0], xs[-1])
    ax.set_ylim(ys[0], ys[-1])
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(title or f"{os.path.basename(probe_path)}: streamlines of u = curl psi")
    save_figure(fig, out)
    if csv_out:
        # rms_div_ratio: rms |div u| over its value at step Δ (truncation: about 4 at 2Δ);
        # div_over_curl: rms |div u| / rms |curl u| (a wrong curl: about 1).
        rows = ["step_m,rms_div,max_div,rms_curl,max_curl,points,rms_div_ratio,div_over_curl"]
        for k, d in ((1, d1), (2, d2)):
            rows.append(f"{k * dx:.9g},{d[0]:.9g},{d[1]:.9g},{d[2]:.9g},{d[3]:.9g},{d[4]},"
                        f"{d[0] / d1[0] if d1[0] > 0 else float('nan'):.9g},"
                        f"{d[0] / d[2] if d[2] > 0 else float('nan'):.9g}")
        write_text_atomic(csv_out, "\n".join(rows) + "\n")
    return d1, d2


# ----------------------------------------------------------------------------
# The animation


def plot_smoke(trace, scene, out, fps=20, title=None):
    try:
        import PIL  # noqa: F401  (PillowWriter needs it)
    except ImportError:
        raise InputError("smoke: the Python package PIL (pillow) is missing; install "
                         "python3-pil") from None
    doc = _read_json(scene, "--scene")
    ds = discs(curl_force(doc, scene))
    data = read_trace(trace)
    if not data:
        raise InputError(f"{trace}: no rows (expected a trace CSV t,id,x,y,vx,vy)")
    ids = sorted(data)
    rows = min(len(data[i]["t"]) for i in ids)
    step = max(1, math.ceil((rows - 1) / MAX_FRAMES))
    frames = list(range(0, rows, step))
    if frames[-1] != rows - 1:
        frames.append(rows - 1)
    x0, x1, y0, y1 = _bounds_of_trace(data)
    pad = 0.05 * max(x1 - x0, y1 - y0, 1e-6)
    # The frame takes the flow's shape (6.4 in on its long side, at 90 dpi 576 px), so that
    # the particles fill it instead of a narrow strip in a square.
    aspect = (y1 - y0 + 2 * pad) / max(x1 - x0 + 2 * pad, 1e-12)
    size = (6.4, max(2.4, 6.4 * aspect)) if aspect < 1 else (max(2.6, 6.4 / aspect + 0.9), 6.4)
    fig, ax = new_figure(figsize=size)
    from matplotlib.patches import Circle
    for cx, cy, r in ds:
        ax.add_patch(Circle((cx, cy), r, facecolor="0.55", edgecolor="0.2", lw=1.0, zorder=3))
    ax.set_xlim(x0 - pad, x1 + pad)
    ax.set_ylim(y0 - pad, y1 + pad)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    dots = ax.scatter([data[i]["x"][0] for i in ids], [data[i]["y"][0] for i in ids], s=4,
                      color="0.15", alpha=0.4, lw=0, zorder=2)
    label = ax.set_title(f"{title or os.path.basename(trace)}: t = 0.00 s")  # for the layout
    fig.tight_layout()
    from ..common import finish_frame
    from ..figfacts import tag

    def draw(k):
        pts = [(data[i]["x"][k], data[i]["y"][k]) for i in ids]
        dots.set_offsets([(x if math.isfinite(x) else 1e30, y if math.isfinite(y) else 1e30)
                          for x, y in pts])
        tag(dots, "body", [p for p in pts if all(math.isfinite(c) for c in p)])
        label.set_text(f"{title or os.path.basename(trace)}: t = {data[ids[0]]['t'][k]:.2f} s")
        finish_frame(fig, out, inside=True)
        return dots, label

    save_animation(fig, draw, frames, out, fps, dpi=90)


# ----------------------------------------------------------------------------
# tools/plot subcommands


def add_commands(sub):
    s = sub.add_parser("flow-probe", help="forces: write the probe scene that samples a "
                       "curl-noise scene's flow on a grid (run it for one step)")
    s.add_argument("scene")
    s.add_argument("-o", "--out", required=True, help="the probe scene (.json)")
    s.add_argument("--trace", help="a run of the scene: the grid covers where it went")
    s.add_argument("--grid", type=int, default=PROBE_GRID, help=f"points per side "
                   f"(default {PROBE_GRID})")
    s = sub.add_parser("flow", help="forces: streamlines of a curl-noise flow, particle paths "
                       "and the divergence measured on the probe's grid")
    s.add_argument("probe_trace", help="the trace of the probe scene's run (--every 1)")
    s.add_argument("--probe", required=True, help="the probe scene (tools/plot flow-probe)")
    s.add_argument("--trace", help="a run of the scene: some of its particles' paths")
    s.add_argument("-o", "--out", required=True)
    s.add_argument("--csv", help="also write the divergence figures to this CSV")
    s.add_argument("--title")
    s = sub.add_parser("smoke", help="forces: an animated GIF of a curl-noise run's particles")
    s.add_argument("trace")
    s.add_argument("--scene", required=True, help="the scene the trace was run from")
    s.add_argument("-o", "--out", required=True, help="output .gif")
    s.add_argument("--fps", type=int, default=20)
    s.add_argument("--title")


def run(args):
    if args.command == "flow-probe":
        write_probe(args.scene, args.out, trace=args.trace, grid=args.grid)
    elif args.command == "flow":
        plot_flow(args.probe_trace, args.probe, args.out, trace=args.trace, csv_out=args.csv,
                  title=args.title)
    elif args.command == "smoke":
        if not args.out.endswith(".gif"):
            raise InputError(f"-o: got {args.out}, expected a .gif file")
        if not 1 <= args.fps <= 60:
            raise InputError(f"--fps: got {args.fps}, expected 1 to 60")
        plot_smoke(args.trace, args.scene, args.out, fps=args.fps, title=args.title)
    else:
        return False
    return True


# ----------------------------------------------------------------------------
# The report: only scenes with a curl-noise force get these figures (the generic
# trajectory and energy figures are drawn for every forces scene).


def scene_figures(ctx):
    doc = ctx.doc
    if not any(isinstance(f, dict) and f.get("type") == "curl-noise"
               for f in doc.get("forces", []) or []):
        return
    trace = ctx.path(f"{ctx.stem}.csv")  # the generic run of the scene as shipped
    if not os.path.exists(trace):
        ctx.fail(f"{ctx.stem}: no trace of the scene's run: the flow figure needs it")
        return
    probe = ctx.path(f"{ctx.stem}-probe.json")
    a = ["flow-probe", ctx.scene_path, "-o", probe, "--trace", trace]
    if not ctx.plot(a):
        return
    probe_trace = ctx.path(f"{ctx.stem}-probe.csv")
    s = ctx.run(["--scene", probe, "--out", probe_trace, "--every", "1"],
                f"{ctx.stem}: probe of the flow", "flow probe (one step)",
                save=f"{ctx.stem}-probe")
    if s is None:
        return
    fig = ctx.path(f"{ctx.stem}-flow.png")
    csv = ctx.path(f"{ctx.stem}-divergence.csv")
    a = ["flow", probe_trace, "--probe", probe, "--trace", trace, "-o", fig, "--csv", csv,
         "--title", f"{ctx.stem}: streamlines of u = curl psi and particle paths"]
    if ctx.plot(a):
        ctx.figure(fig, "Streamlines of the flow u = curl psi that the F9 code computes "
                   "(sampled by a one-step run of particles at rest on a grid: the velocity "
                   "after one step is dt b u / m), the obstacles (grey), and the paths of some "
                   "of the run's particles. The box gives the divergence of u measured on the "
                   "grid by central differences at two steps: it is the differences' "
                   "truncation error, a small fraction of the vorticity, and shrinks about "
                   "fourfold when the step is halved; a wrong curl would leave a divergence as "
                   "large as the vorticity.", a)
    gif = ctx.path(f"{ctx.stem}.gif")
    a = ["smoke", trace, "--scene", ctx.scene_path, "-o", gif, "--title", ctx.stem,
         "--summary", ctx.path(f"{ctx.stem}-summary.json")]
    if ctx.plot(a):
        ctx.figure(gif, f"Animation of {ctx.stem}: every particle as a grey dot (every "
                   f"recorded frame, at most {MAX_FRAMES + 1}).", a)
