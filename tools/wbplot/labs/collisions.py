"""The collisions lab's figures (tools/report) and tools/plot subcommands.

    tools/plot discs TRACE --scene SCENE -o OUT.png      discs to scale, planes, paths
    tools/plot animate TRACE --scene SCENE -o OUT.gif    an animated GIF of a run
    tools/plot rebound TRACE... --restitutions E,... -o OUT.png
                                                         first rebound height against e^2

A student runs them on their own trace (build/bin/collisions --out ...).
"""
import json
import math
import os

from .. import creep
from ..common import InputError, new_figure, parse_list, save_figure
from ..recipes import fmt_dt
from ..runs import choose_ids, read_trace

REPLACES_GENERIC = True  # discs to scale replace the generic dot trajectories

# The pack README's plot commands for a run of this lab (tools/pack): out/run.csv, its stats.
PACK_PLOTS = [("tools/plot discs out/run.csv --scene {scene} --summary out/run-summary.json "
               "-o out/run.png", "the discs to scale, with the planes"),
              ("tools/plot stats out/run-stats.csv --scene {scene} --summary "
               "out/run-summary.json -o out/run-energy.png", "energy and momentum against time")]

MAX_PATHS = 60        # particle paths drawn under the discs
MAX_FRAMES = 80       # frames of an animation
MAX_TRACE_ROWS = 2_000_000


# ----------------------------------------------------------------------------
# Reading a scene's geometry


def read_scene(path):
    """(planes, radii) of a scene file: planes as (point, unit normal, thickness or None)."""
    if not os.path.exists(path):
        raise InputError(f"--scene: {path}: no such file (expected the run's scene JSON)")
    try:
        with open(path, encoding="utf-8") as f:
            doc = json.load(f)
    except (OSError, json.JSONDecodeError) as e:
        raise InputError(f"--scene: {path}: cannot read as JSON ({e})") from None
    planes = []
    for k, p in enumerate(doc.get("planes", []) if isinstance(doc, dict) else []):
        try:
            px, py = (float(c) for c in p["point"])
            nx, ny = (float(c) for c in p["normal"])
        except (KeyError, TypeError, ValueError):
            raise InputError(f"--scene: {path}: planes[{k}]: expected point and normal "
                             "[x, y]") from None
        norm = math.hypot(nx, ny)
        if not norm > 0:
            raise InputError(f"--scene: {path}: planes[{k}].normal: expected a non-zero vector")
        planes.append(((px, py), (nx / norm, ny / norm), p.get("thickness")))
    radii = []
    for p in doc.get("particles", []):
        radii.append(float(p.get("radius", 0.0)))
    for e in doc.get("emitters", []):
        radii += [float(e.get("radius", 0.0))] * int(e.get("count", 0))
    return doc, planes, radii


def frames_of(data):
    """Times in the trace, sorted, and for each particle id its rows by time."""
    times = sorted({t for d in data.values() for t in d["t"]})
    return times


def state_at(data, ids, k):
    """Positions of `ids` at their k-th recorded row (all ids share the rows)."""
    return [data[i]["x"][k] for i in ids], [data[i]["y"][k] for i in ids]


# ----------------------------------------------------------------------------
# Drawing


def _limits(data, planes, radii):
    """The view: the discs' extent over the run (paths and radii), with a margin; a plane
    within the discs' own span of it (a floor they rest on or float above, a wall they
    reach) is brought into view, one farther away is not allowed to shrink them to specks."""
    xs = [x for d in data.values() for x in d["x"] if math.isfinite(x)]
    ys = [y for d in data.values() for y in d["y"] if math.isfinite(y)]
    if not xs:
        xs, ys = [0.0], [0.0]
    r = max(radii) if radii else 0.0
    lo_x, hi_x = min(xs) - r, max(xs) + r
    lo_y, hi_y = min(ys) - r, max(ys) + r
    span = max(hi_x - lo_x, hi_y - lo_y, 1e-9)
    near = span  # a floor the discs float above (a stub's run) stays in view too
    cx, cy = (lo_x + hi_x) / 2, (lo_y + hi_y) / 2
    for (px, py), (nx, ny), _ in planes:
        # The point of the plane nearest the discs' centre.
        d = (cx - px) * nx + (cy - py) * ny
        qx, qy = cx - d * nx, cy - d * ny
        gap = max(lo_x - qx, qx - hi_x, lo_y - qy, qy - hi_y, 0.0)
        if gap <= near:
            lo_x, hi_x = min(lo_x, qx), max(hi_x, qx)
            lo_y, hi_y = min(lo_y, qy), max(hi_y, qy)
    span = max(hi_x - lo_x, hi_y - lo_y, 1e-9)
    pad = 0.05 * span
    return lo_x - pad, hi_x + pad, lo_y - pad, hi_y + pad


def _draw_planes(ax, planes, lims):
    """Each plane as a line across the view, its solid side shaded (a band for a thin wall)."""
    from ..figfacts import tag
    lo_x, hi_x, lo_y, hi_y = lims
    big = 4 * max(hi_x - lo_x, hi_y - lo_y)
    for k, ((px, py), (nx, ny), thick) in enumerate(planes):
        tx, ty = -ny, nx
        # Centred on the point of the plane nearest the view's centre, so that the line
        # crosses the whole view wherever the scene put the plane's point.
        cx, cy = (lo_x + hi_x) / 2, (lo_y + hi_y) / 2
        d = (cx - px) * nx + (cy - py) * ny
        ox, oy = cx - d * nx, cy - d * ny
        a = (ox - big * tx, oy - big * ty)
        b = (ox + big * tx, oy + big * ty)
        depth = float(thick) if thick is not None else big
        poly = [a, b, (b[0] - depth * nx, b[1] - depth * ny), (a[0] - depth * nx, a[1] - depth * ny)]
        ax.fill(*zip(*poly), color="0.75", alpha=0.6, lw=0, zorder=1)
        (line,) = ax.plot([a[0], b[0]], [a[1], b[1]], color="0.2", lw=1.2, zorder=2)
        tag(line, "plane", [a, b], index=k, point=(px, py), normal=(nx, ny))
    ax.set_xlim(lo_x, hi_x)
    ax.set_ylim(lo_y, hi_y)


def _discs(ax, xs, ys, radii, color, alpha, zorder, cmap=None, values=None):
    from matplotlib.collections import EllipseCollection
    from ..figfacts import tag
    d = [2 * r for r in radii]
    kw = dict(facecolors=color) if values is None else dict(array=values, cmap=cmap)
    coll = EllipseCollection(d, d, [0.0] * len(d), units="xy", offsets=list(zip(xs, ys)),
                             offset_transform=ax.transData, edgecolors="k",
                             linewidths=0.3 if len(d) < 500 else 0.0, alpha=alpha,
                             zorder=zorder, **kw)
    ax.add_collection(coll)
    pts = [(x + s * r, y + s * r) for x, y, r in zip(xs, ys, radii)
           if math.isfinite(x) and math.isfinite(y) for s in (-1, 1)]
    tag(coll, "body", pts)
    return coll


def _check(data, radii, path):
    if not data:
        raise InputError(f"{path}: no rows (expected a trace CSV t,id,x,y,vx,vy)")
    n = max(data) + 1
    if len(radii) < n:
        raise InputError(f"--scene: has {len(radii)} particles, the trace {path} has {n}: "
                         "expected the scene the trace was run from")
    lengths = {len(d["t"]) for d in data.values()}
    if len(lengths) != 1:
        raise InputError(f"{path}: particles have different numbers of rows")


MANY = 200  # more discs than this: no start circles; the end coloured by starting height


def _not_finite_note(n_bad, t_end):
    """A disc the figure cannot draw: 'diverged' only when the run's summary says so."""
    from .. import runinfo
    why = "diverged, as the run's summary says" if runinfo.said_diverged(0) else "not finite"
    return f"{n_bad} particle(s) not drawn at t = {t_end:g} s ({why})"


def plot_discs(trace, scene, out, title=None):
    import matplotlib
    data = read_trace(trace)
    doc, planes, radii = read_scene(scene)
    _check(data, radii, trace)
    ids = sorted(data)
    fig, ax = new_figure(figsize=(6.4, 4.8))
    lims = _limits(data, planes, radii)
    _draw_planes(ax, planes, lims)
    rows = len(data[ids[0]]["t"])
    r = [radii[i] for i in ids]
    # Paths of a few particles, the start faded, the end solid.
    for i in choose_ids(ids, MAX_PATHS):
        ax.plot(data[i]["x"], data[i]["y"], lw=0.6, color="C0", alpha=0.5, zorder=3)
    if len(ids) <= MANY:
        xs, ys = state_at(data, ids, 0)
        _discs(ax, xs, ys, r, "none", 0.5, 4)
    xs, ys = state_at(data, ids, rows - 1)
    ok = [k for k in range(len(ids)) if math.isfinite(xs[k]) and math.isfinite(ys[k])]
    if len(ids) > MANY:
        # Thousands of discs at the end are one orange band: coloured by the height each
        # started from, the band shows how the discs settled (who landed first, who mixed).
        y0 = [data[ids[k]]["y"][0] for k in ok]
        coll = _discs(ax, [xs[k] for k in ok], [ys[k] for k in ok], [r[k] for k in ok], None,
                      0.9, 5, cmap=matplotlib.colormaps["viridis"], values=y0)
        fig.colorbar(coll, ax=ax, shrink=0.8, pad=0.02, label="height y at t = 0 (m)")
    else:
        _discs(ax, [xs[k] for k in ok], [ys[k] for k in ok], [r[k] for k in ok], "C1", 0.85, 5)
    t_end = data[ids[0]]["t"][-1]
    if len(ok) < len(ids):
        ax.text(0.02, 0.96, _not_finite_note(len(ids) - len(ok), t_end), transform=ax.transAxes,
                color="C3", va="top")
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(title or f"{os.path.basename(trace)}: discs at t = {t_end:g} s")
    save_figure(fig, out)


def plot_animation(trace, scene, out, fps=20, title=None):
    from ..common import finish_frame, save_animation
    try:
        import PIL  # noqa: F401  (PillowWriter needs it)
    except ImportError:
        raise InputError("animate: the Python package PIL (pillow) is missing; install "
                         "python3-pil") from None
    data = read_trace(trace)
    doc, planes, radii = read_scene(scene)
    _check(data, radii, trace)
    ids = sorted(data)
    rows = len(data[ids[0]]["t"])
    step = max(1, math.ceil(rows / MAX_FRAMES))
    frames = list(range(0, rows, step))
    if frames[-1] != rows - 1:
        frames.append(rows - 1)
    lims = _limits(data, planes, radii)
    # The frame takes the view's shape, so that the discs fill it (at 80 dpi: 640 px on
    # the long side).
    aspect = (lims[3] - lims[2]) / max(lims[1] - lims[0], 1e-12)
    w, h = (8.0, max(2.4, 8.0 * aspect + 0.9)) if aspect < 1 else (max(3.0, 8.0 / aspect + 0.6), 8.0)
    fig, ax = new_figure(figsize=(w, h))
    _draw_planes(ax, planes, lims)
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    xs, ys = state_at(data, ids, 0)
    many = len(ids) > MANY
    import matplotlib
    coll = _discs(ax, xs, ys, [radii[i] for i in ids], None if many else "C1", 0.9, 5,
                  cmap=matplotlib.colormaps["viridis"] if many else None,
                  values=[data[i]["y"][0] for i in ids] if many else None)
    if many:
        fig.colorbar(coll, ax=ax, shrink=0.8, pad=0.02, label="height y at t = 0 (m)")
    label = ax.set_title(f"{title or os.path.basename(trace)}: t = 0.000 s")  # for the layout
    fig.tight_layout()

    def draw(k):
        xs, ys = state_at(data, ids, k)
        coll.set_offsets([(x if math.isfinite(x) else 1e30, y if math.isfinite(y) else 1e30)
                          for x, y in zip(xs, ys)])
        bad = sum(1 for x, y in zip(xs, ys) if not (math.isfinite(x) and math.isfinite(y)))
        label.set_text(f"{title or os.path.basename(trace)}: t = {data[ids[0]]['t'][k]:.3f} s"
                       + (f"; {_not_finite_note(bad, data[ids[0]]['t'][k])}" if bad else ""))
        finish_frame(fig, out, inside=True)
        return coll, label

    save_animation(fig, draw, frames, out, fps, dpi=80)


def first_rebound(trace, radius, floor_y=0.0, pid=0):
    """(drop height, first rebound height) of particle pid above the floor contact height."""
    d = read_trace(trace).get(pid)
    if d is None:
        raise InputError(f"{trace}: no particle {pid}")
    y, vy = d["y"], d["vy"]
    h0 = y[0] - radius - floor_y
    k = 1
    while k < len(y) and not (vy[k] > 0 and vy[k - 1] <= 0):  # the first bounce
        k += 1
    j = k
    while j < len(y) and vy[j] > 0:  # rising until the apex
        j += 1
    if j >= len(y):
        return h0, None  # no bounce, or the run ended before the apex
    return h0, max(y[k:j + 1]) - radius - floor_y


def plot_rebound(traces, restitutions, radius, out, title=None):
    if len(traces) != len(restitutions):
        raise InputError(f"--restitutions: got {len(restitutions)} values for {len(traces)} "
                         "traces, expected one per trace")
    fig, ax = new_figure(figsize=(5.2, 4.2))
    e2, ratio, missing = [], [], []
    for tr, e in zip(traces, restitutions):
        h0, h1 = first_rebound(tr, radius)
        if h1 is None or not h0 > 0:
            missing.append(e)
            continue
        e2.append(e * e)
        ratio.append(h1 / h0)
    ax.plot([0, 1], [0, 1], color="0.4", lw=1, ls="--", label="rebound / drop = e^2")
    ax.plot(e2, ratio, "o", color="C1", label="measured (first bounce)")
    for a, b in zip(e2, ratio):
        ax.annotate(f"{b:.3f}", (a, b), textcoords="offset points", xytext=(5, -10), fontsize=8)
    if missing:
        ax.text(0.02, 0.96, "no complete first rebound for e = " + ", ".join(f"{e:g}" for e in missing),
                transform=ax.transAxes, va="top", color="C3")
    ax.set_xlabel("e^2")
    ax.set_ylabel("first rebound height / drop height")
    ax.set_xlim(-0.03, 1.05)
    ax.set_ylim(-0.03, 1.05)
    ax.set_aspect("equal")
    ax.legend(loc="lower right")
    ax.set_title(title or "Rebound height against e^2")
    save_figure(fig, out)
    return e2, ratio


# ----------------------------------------------------------------------------
# tools/plot subcommands


def add_commands(sub):
    s = sub.add_parser("discs", help="collisions: discs to scale with the scene's planes, "
                       "from a trace CSV and its scene")
    s.add_argument("trace")
    s.add_argument("--scene", required=True, help="the scene the trace was run from")
    s.add_argument("-o", "--out", required=True)
    s.add_argument("--title")
    s = sub.add_parser("animate", help="collisions: an animated GIF of a trace (discs to scale)")
    s.add_argument("trace")
    s.add_argument("--scene", required=True, help="the scene the trace was run from")
    s.add_argument("-o", "--out", required=True, help="output .gif")
    s.add_argument("--fps", type=int, default=20)
    s.add_argument("--title")
    creep.add_command(sub, "creep", "collisions")
    s = sub.add_parser("rebound", help="collisions: first rebound height / drop height "
                       "against e^2, one trace per restitution")
    s.add_argument("traces", nargs="+")
    s.add_argument("--restitutions", required=True, help="comma-separated e, one per trace")
    s.add_argument("--radius", type=float, required=True, help="the ball's radius (m)")
    s.add_argument("-o", "--out", required=True)
    s.add_argument("--title")


def run(args):
    if args.command == "discs":
        plot_discs(args.trace, args.scene, args.out, title=args.title)
    elif args.command == "animate":
        if not args.out.endswith(".gif"):
            raise InputError(f"-o: got {args.out}, expected a .gif file")
        if not 1 <= args.fps <= 60:
            raise InputError(f"--fps: got {args.fps}, expected 1 to 60")
        plot_animation(args.trace, args.scene, args.out, fps=args.fps, title=args.title)
    elif args.command == "creep":
        creep.plot_creep(args.traces, parse_list(args.labels, "--labels"), args.out,
                         after=args.after, title=args.title)
    elif args.command == "rebound":
        es = parse_list(args.restitutions, "--restitutions", float)
        plot_rebound(args.traces, es, args.radius, args.out, title=args.title)
    else:
        return False
    return True


# ----------------------------------------------------------------------------
# The report


RESTITUTIONS = [1.0, 0.8, 0.5, 0.2]
ANIMATED = {"pile", "billiards", "cradle", "mass-ratio"}


def _every(doc, n):
    try:
        steps = round(float(doc["t_end"]) / float(doc["dt"]))
    except (KeyError, TypeError, ValueError, ZeroDivisionError):
        return 1
    return max(1, math.ceil(steps / 400), math.ceil(steps * n / MAX_TRACE_ROWS),
               math.ceil(steps / 40) if n > 1000 else 1)


def _variant(ctx, name, change):
    doc = json.loads(json.dumps(ctx.doc))
    change(doc)
    path = ctx.path(name)
    with open(path, "w", encoding="utf-8") as f:
        json.dump(doc, f, indent=1)
    return path


def scene_figures(ctx):
    doc = ctx.doc
    n = len(doc.get("particles", [])) + sum(int(e.get("count", 0))
                                            for e in doc.get("emitters", []))
    desc = doc.get("description", f"Scene {ctx.stem}.")
    trace, stats = ctx.path(f"{ctx.stem}.csv"), ctx.path(f"{ctx.stem}-stats.csv")
    s = ctx.run(["--scene", ctx.scene_path, "--out", trace, "--stats", stats,
                 "--every", str(_every(doc, n))], ctx.scene_path, "scene as shipped",
                save=ctx.stem)
    if s is None:
        return
    setting = f"semi-implicit Euler, dt = {fmt_dt(doc.get('dt'))} s"
    summary = ctx.path(f"{ctx.stem}-summary.json")  # what the figures say of the run
    fig = ctx.path(f"{ctx.stem}-discs.png")
    a = ["discs", trace, "--scene", ctx.scene_path, "-o", fig, "--title",
         f"{ctx.stem}: discs at the end ({setting})", "--summary", summary]
    if ctx.plot(a):
        ctx.figure(fig, f"{desc} Discs to scale at the end of the run ("
                   + ("orange; open circles are the starts" if n <= MANY else
                      "coloured by the height each started from") + f"), paths of up to "
                   f"{MAX_PATHS} particles (blue), planes with their solid side shaded.", a)
    fig = ctx.path(f"{ctx.stem}-energy.png")
    a = ["stats", stats, "-o", fig, "--title", f"{ctx.stem}: energy and momentum ({setting})",
         "--summary", summary, "--scene", ctx.scene_path]
    if ctx.plot(a):
        e0, e1 = s.get("energy0"), s.get("energy")
        trend = ""
        if isinstance(e0, (int, float)) and isinstance(e1, (int, float)):
            if e1 < e0:
                trend = f" In this run the energy went from {e0:.4g} J to {e1:.4g} J (lost)."
            elif e1 > e0:
                trend = f" In this run the energy went from {e0:.4g} J to {e1:.4g} J (gained)."
            else:
                trend = f" In this run the energy ended where it started ({e0:.4g} J)."
        ctx.figure(fig, "Energy (total, kinetic, potential) and momentum against time; "
                   "impulses from planes change the momentum." + trend, a)
    if ctx.stem in ANIMATED:
        gif = ctx.path(f"{ctx.stem}.gif")
        a = ["animate", trace, "--scene", ctx.scene_path, "-o", gif, "--title", ctx.stem,
             "--summary", summary]
        if ctx.plot(a):
            ctx.figure(gif, f"Animation of {ctx.stem} (every recorded frame up to "
                       f"{MAX_FRAMES})." + (" Each disc is coloured by the height it started "
                                            "from." if n > MANY else ""), a)
    if ctx.stem == "pile":
        _pile_table(ctx, trace, doc)
    if ctx.stem == "bounce":
        _bounce_figures(ctx)
    if ctx.stem == "column":
        _creep_figure(ctx)


def _pile_table(ctx, trace, doc):
    data = read_trace(trace)
    _, planes, radii = read_scene(ctx.scene_path)
    outside = 0
    deepest = 0.0  # the largest overlap with a wall, in radii
    last = {i: (d["x"][-1], d["y"][-1]) for i, d in data.items()}
    for i, (x, y) in last.items():
        for (px, py), (nx, ny), _ in planes:
            gap = (x - px) * nx + (y - py) * ny
            deepest = max(deepest, 1 - gap / radii[i]) if radii[i] > 0 else deepest
            # More than the accumulated solver's slop (1 % of the radius) into the wall.
            if gap < radii[i] * (1 - 1e-2):
                outside += 1
                break
    speeds = sorted(math.hypot(d["vx"][-1], d["vy"][-1]) for d in data.values())
    t = next(iter(data.values()))["t"][-1]
    md = ("| quantity | value |\n|---|---|\n"
          f"| particles | {len(last)} |\n"
          f"| particles deeper into a wall than the slop the solver leaves on purpose (1 % of "
          f"their radius) at t = {t:g} s | {outside} |\n"
          f"| deepest overlap with a wall at t = {t:g} s, in radii (1: the disc's centre on "
          f"the wall) | {deepest:.3g} |\n"
          f"| median speed at t = {t:g} s (m/s) | {speeds[len(speeds) // 2]:.3g} |\n"
          f"| largest speed at t = {t:g} s (m/s) | {speeds[-1]:.3g} |\n")
    ctx.table("pile: containment and rest (from the run's trace)", md)


def _bounce_figures(ctx):
    stats_files, traces, labels = [], [], []
    radius = float(ctx.doc["particles"][0].get("radius", 0.0))
    for e in RESTITUTIONS:
        def change(doc, e=e):
            doc.setdefault("contact", {})["restitution"] = e
            for p in doc.get("planes", []):
                p.pop("restitution", None)
        scene = _variant(ctx, f"bounce-e{e:g}.json", change)
        st, tr = ctx.path(f"bounce-e{e:g}-stats.csv"), ctx.path(f"bounce-e{e:g}.csv")
        s = ctx.run(["--scene", scene, "--stats", st, "--out", tr], f"bounce with e = {e:g}",
                    f"e = {e:g}")
        if s is not None:
            stats_files.append(st)
            traces.append(tr)
            labels.append(f"e = {e:g}")
    if stats_files:
        fig = ctx.path("bounce-energy-restitution.png")
        a = ["energy"] + stats_files + ["--labels", ",".join(labels), "-o", fig, "--title",
                                        "bounce: total energy per restitution"]
        if ctx.plot(a):
            ctx.figure(fig, "Total energy of the dropped ball against time for each "
                       "restitution e: each bounce keeps a fraction e^2 of the kinetic "
                       "energy; e = 1 keeps it (up to the step-size error).", a)
    if traces:
        fig = ctx.path("bounce-rebound.png")
        es = [float(l.split("= ")[1]) for l in labels]
        a = ["rebound"] + traces + ["--restitutions", ",".join(f"{e:g}" for e in es),
                                    "--radius", f"{radius:g}", "-o", fig]
        if ctx.plot(a):
            ctx.figure(fig, "First rebound height over drop height, measured in each run, "
                       "against e^2 (dashed: equality). The numbers are the measured ratios.",
                       a)


def _column_solver(doc, solver):
    doc["contact"]["solver"] = solver
    doc["contact"]["iterations"] = 10


COLUMN_AFTER = 1.0  # s: the column has landed (handouts/collisions.md#c5)


def _creep_figure(ctx):
    """The column with both solvers: the largest disc speed, and the largest distance any
    disc moved since 1 s, against time; column-rest.csv for the handout's claims."""
    traces = []
    for solver, scene in creep.solver_scenes(ctx.doc, ctx.out_dir, "column",
                                             _column_solver).items():
        trace = ctx.path(f"column-{solver}.csv")
        s = ctx.run(["--scene", scene, "--out", trace, "--every", "10"],
                    f"column with solver {solver}", solver)
        if s is None:
            return
        traces.append(trace)
    creep.write_rest(ctx.path("column-rest.csv"), traces, list(creep.SOLVERS), COLUMN_AFTER)
    fig = ctx.path("column-creep.png")
    a = ["creep"] + traces + ["--labels", "passes (one-shot: 10 per step),accumulated (10 "
                              "iterations)", "--after", f"{COLUMN_AFTER:g}", "-o", fig]
    if ctx.plot(a):
        ctx.figure(fig, "The column solved by one-shot passes and by accumulated, "
                   "warm-started impulses (C5), 10 of each per step: on top the largest speed "
                   "of any disc (the velocities the solver keeps), below the largest distance "
                   "any disc has moved since 1 s (what one sees of the column). The numbers "
                   "are in column-rest.csv.", a)


# tools/claims makes this file itself when build/report has none (docs/report.md, Claims).
CLAIM_FILES = {"column-rest.csv": lambda exe, out: creep.make_rest_file(
    exe, out, "collisions", "column", _column_solver, "column-{solver}.csv", COLUMN_AFTER)}
