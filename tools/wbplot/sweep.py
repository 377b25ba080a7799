"""Figures and tables from a sweep CSV (one row per run of one integrator at one dt)."""
import math

from matplotlib.lines import Line2D
from matplotlib.transforms import blended_transform_factory

from .common import (InputError, finite, integrator_style, new_figure, number, read_csv,
                     save_figure)

SWEEP_COLUMNS = ["scene", "integrator", "dt", "steps", "force_evals", "wall_s", "error",
                 "energy_error", "reference", "status"]

# The asymptotic range used to measure a convergence order (see docs/report.md):
FLOOR_REL = 1e-13    # error below FLOOR_REL * scale: rounding floor, excluded
CEILING_REL = 0.1    # error at or above CEILING_REL * scale: O(1), not asymptotic
PLATEAU_SLOPE = 0.5  # smallest-dt points whose local slope is below this: plateau, excluded
BLOWUP_REL = 1e3    # a finite error past this times the scene size is drawn on the top edge
# What the top edge's marks say: "diverged" only from the run's status column (the run
# contract's rule); a finite error off the scale is said to be just that.
DIVERGED_LABEL = "diverged (its status): top edge"
OFF_SCALE_LABEL = "finite error > 1000 x scene size\n(status ok): top edge"
MIN_POINTS = 3       # fewer points left in the range: no order is given ("n/a")


class Run:
    """One (integrator, dt) of one scene; repeats merged (least wall time kept)."""

    def __init__(self, scene, integrator, dt, steps, force_evals, wall_s, error, energy_error,
                 reference, status):
        self.scene, self.integrator, self.dt = scene, integrator, dt
        self.steps, self.force_evals, self.wall_s = steps, force_evals, wall_s
        self.error, self.energy_error = error, energy_error
        self.reference, self.status = reference, status

    @property
    def diverged(self):
        return self.status == "diverged" or not finite(self.error)


def read_sweep(path):
    """Runs in file order of first appearance, repeats of the same (scene, integrator, dt) merged."""
    rows = read_csv(path, SWEEP_COLUMNS, "sweep CSV (" + ",".join(SWEEP_COLUMNS) + ")")
    runs, index = [], {}
    for i, r in enumerate(rows):
        vals = {c: number(path, i, r, c) for c in ("dt", "steps", "force_evals", "wall_s",
                                                    "error", "energy_error")}
        if not (finite(vals["dt"]) and vals["dt"] > 0):
            raise InputError(f"{path}: row {i + 2}, column 'dt': got '{r['dt']}', expected a "
                             "number > 0")
        scene, integ, status = r["scene"].strip(), r["integrator"].strip(), r["status"].strip()
        if not integ:
            raise InputError(f"{path}: row {i + 2}, column 'integrator': empty, expected a name")
        key = (scene, integ, vals["dt"])
        if key in index:
            old = index[key]
            if finite(vals["wall_s"]) and (not finite(old.wall_s) or vals["wall_s"] < old.wall_s):
                old.wall_s = vals["wall_s"]
            continue
        run = Run(scene, integ, vals["dt"], vals["steps"], vals["force_evals"], vals["wall_s"],
                  vals["error"], vals["energy_error"], r["reference"].strip(), status)
        index[key] = run
        runs.append(run)
    return runs


def scenes_of(runs):
    out = []
    for r in runs:
        if r.scene not in out:
            out.append(r.scene)
    return out


def select_scene(path, runs, scene):
    names = scenes_of(runs)
    if scene is None:
        if len(names) > 1:
            raise InputError(f"{path}: holds scenes {', '.join(names)}: pick one with --scene")
        return runs, names[0]
    picked = [r for r in runs if r.scene == scene]
    if not picked:
        raise InputError(f"--scene: got '{scene}', {path} holds scenes {', '.join(names)}")
    return picked, scene


def by_integrator(runs):
    groups = {}
    for r in runs:
        groups.setdefault(r.integrator, []).append(r)
    for g in groups.values():
        g.sort(key=lambda r: r.dt)
    # Known integrators in teaching order, the others by name.
    from .common import KNOWN_INTEGRATORS
    order = sorted(groups, key=lambda n: (KNOWN_INTEGRATORS.index(n) if n in KNOWN_INTEGRATORS
                                          else len(KNOWN_INTEGRATORS), n))
    return [(n, groups[n]) for n in order]


def asymptotic_points(runs, scale=1.0):
    """The (dt, error) points used for the order, sorted by dt (rule in docs/report.md)."""
    # The range is contiguous from the smallest dt up: it ends at the first step that
    # diverged or whose error reached the ceiling (a larger step that lands near the exact
    # answer by a lucky phase is not in the asymptotic range).
    pts = []
    for r in sorted(runs, key=lambda r: r.dt):
        if r.diverged or not finite(r.error) or r.error >= CEILING_REL * scale:
            break
        if r.error > 0 and r.error >= FLOOR_REL * scale:
            pts.append((r.dt, r.error))
    # A rounding plateau at the smallest steps: the error stops falling with dt.
    while len(pts) >= 3:
        (h0, e0), (h1, e1) = pts[0], pts[1]
        if math.log(e1 / e0) / math.log(h1 / h0) < PLATEAU_SLOPE:
            pts.pop(0)
        else:
            break
    # Error must grow with dt across the range: drop the largest steps until it does.
    while len(pts) >= 2 and any(pts[i + 1][1] <= pts[i][1] for i in range(len(pts) - 1)):
        pts.pop()
    return pts


def fit_slope(pts):
    """Least-squares slope of log(error) against log(dt), None below MIN_POINTS points."""
    if len(pts) < MIN_POINTS:
        return None
    xs = [math.log(h) for h, _ in pts]
    ys = [math.log(e) for _, e in pts]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    sxx = sum((x - mx) ** 2 for x in xs)
    if sxx == 0:
        return None
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx


def measured_order(runs, scale=1.0):
    pts = asymptotic_points(runs, scale)
    return fit_slope(pts), pts


def _mark_diverged(ax, xs, color, off_scale=False):
    """Runs off the scale as marks on the top edge of the axes, at their x value: an x for
    a run whose status is diverged, an open triangle for a finite error off the scale."""
    if not xs:
        return
    tr = blended_transform_factory(ax.transData, ax.transAxes)
    kw = dict(marker="^", mfc="white", mec=color, ms=6) if off_scale else dict(
        marker="x", color=color, ms=7, mew=1.8)
    ax.plot(xs, [0.97] * len(xs), ls="", transform=tr, clip_on=False, **kw)


def _top_edge(ax, group, scale, color, x_of):
    """Marks the group's runs off the scale (see _mark_diverged); which kinds it drew."""
    div = [r for r in group if r.diverged]
    off = [r for r in group if not r.diverged and blew_up(r, scale)]
    for rs, off_scale in ((div, False), (off, True)):
        xs = [x_of(r) for r in rs]
        _mark_diverged(ax, [x for x in xs if finite(x) and x > 0], color, off_scale)
    return {"div": bool(div), "off": bool(off)}


def _top_edge_handles(kinds):
    out = []
    if any(k["div"] for k in kinds):
        out.append(Line2D([], [], ls="", marker="x", color="0.3", mew=1.8,
                          label=DIVERGED_LABEL))
    if any(k["off"] for k in kinds):
        out.append(Line2D([], [], ls="", marker="^", mfc="white", mec="0.3",
                          label=OFF_SCALE_LABEL))
    return out


def blew_up(r, scale):
    """Diverged, or finite but with an error past BLOWUP_REL times the scene size."""
    return r.diverged or r.error > BLOWUP_REL * scale


def plot_work_precision(runs, scene, out, scale=1.0):
    fig, (a1, a2) = new_figure(1, 2, figsize=(10.0, 4.4))
    names = [n for n, _ in by_integrator(runs)]
    kinds = []
    for name, group in by_integrator(runs):
        color, marker = integrator_style(name, names)
        ok = [r for r in group if not blew_up(r, scale) and r.error > 0]
        kinds.append(_top_edge(a1, group, scale, color, lambda r: r.wall_s))
        _top_edge(a2, group, scale, color, lambda r: r.force_evals)
        for ax, attr in ((a1, "wall_s"), (a2, "force_evals")):
            pts = sorted((getattr(r, attr), r.error) for r in ok
                         if finite(getattr(r, attr)) and getattr(r, attr) > 0)
            ax.plot([p for p, _ in pts], [e for _, e in pts], marker=marker, color=color,
                    ms=4.5, label=name)
    for ax, label in ((a1, "wall time (s)"), (a2, "force evaluations")):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(label)
        ax.set_ylabel("final position error (m)")
    a1.set_title("Error against wall time")
    a2.set_title("Error against force evaluations")
    handles, _ = a2.get_legend_handles_labels()
    handles += _top_edge_handles(kinds)
    a2.legend(handles=handles, loc="best", framealpha=0.85)
    fig.suptitle(f"Work-precision, scene {scene}: lower left is better", fontsize=11)
    fig.tight_layout()
    save_figure(fig, out)


def plot_convergence(runs, scene, out, scale=1.0):
    fig, ax = new_figure(figsize=(8.4, 4.6))
    groups = by_integrator(runs)
    names = [n for n, _ in groups]
    all_pts, used_all = [], []
    kinds = []
    for name, group in groups:
        color, marker = integrator_style(name, names)
        order, used = measured_order(group, scale)
        used_set = set(used)
        used_all += used
        ok = [(r.dt, r.error) for r in group if not blew_up(r, scale) and r.error > 0]
        all_pts += ok
        label = f"{name}: order {order:.2f}" if order is not None else f"{name}: order n/a"
        ax.plot([h for h, _ in ok], [e for _, e in ok], color=color, lw=1.2, label=label)
        fit = [p for p in ok if p in used_set]
        rest = [p for p in ok if p not in used_set]
        ax.plot([h for h, _ in fit], [e for _, e in fit], ls="", marker=marker, color=color,
                ms=5)
        ax.plot([h for h, _ in rest], [e for _, e in rest], ls="", marker=marker, mfc="white",
                mec=color, ms=5)
        all_pts += [(r.dt, None) for r in group if blew_up(r, scale)]
        kinds.append(_top_edge(ax, group, scale, color, lambda r: r.dt))
    ax.set_xscale("log")
    ax.set_yscale("log")
    hs = [h for h, _ in all_pts]
    es = [e for _, e in all_pts if e is not None]
    if hs and es:
        ax.set_ylim(min(es) / 3, max(es) * 3)
        h0, h1 = min(hs), max(hs)
        # Guides start just above the fitted points' top right corner and fall with dt.
        anchor = used_all or [(h, e) for h, e in all_pts if e is not None]
        ha = max(h for h, _ in anchor)
        ea = 2 * max(e for _, e in anchor)
        for p, style in ((1, (0, (6, 3))), (2, (0, (3, 3))), (4, (0, (1, 2)))):
            ax.plot([h0, ha], [ea * (h0 / ha) ** p, ea], color="0.45", lw=0.9, ls=style,
                    label=f"slope {p} (guide)")
        ax.set_xlim(h0 / 1.3, h1 * 1.3)
    ax.set_xlabel("time step dt (s)")
    ax.set_ylabel("final position error (m)")
    ax.set_title(f"Convergence, scene {scene}")
    handles, labels = ax.get_legend_handles_labels()
    handles.append(Line2D([], [], ls="", marker="o", mfc="white", mec="0.3",
                          label="not used for the order"))
    handles += _top_edge_handles(kinds)
    ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=8,
              frameon=False)
    fig.tight_layout()
    save_figure(fig, out)


def plot_energy_error(runs, scene, out, scale=1.0):
    fig, ax = new_figure(figsize=(8.4, 4.6))
    groups = by_integrator(runs)
    names = [n for n, _ in groups]
    kinds = []
    for name, group in groups:
        color, marker = integrator_style(name, names)
        pts = [(r.dt, r.energy_error) for r in group
               if not blew_up(r, scale) and finite(r.energy_error) and r.energy_error > 0]
        ax.plot([h for h, _ in pts], [e for _, e in pts], marker=marker, color=color, ms=4.5,
                label=name)
        kinds.append(_top_edge(ax, group, scale, color, lambda r: r.dt))
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("time step dt (s)")
    ax.set_ylabel("max relative energy error |E - E0| / |E0|")
    ax.set_title(f"Energy error against step size, scene {scene}")
    handles, _ = ax.get_legend_handles_labels()
    handles += _top_edge_handles(kinds)
    ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.02, 1.0), frameon=False)
    fig.tight_layout()
    save_figure(fig, out)


def plot_sweep(path, prefix, scene=None, scale=1.0):
    runs, scene = select_scene(path, read_sweep(path), scene)
    if not any(finite(r.force_evals) and r.force_evals > 0 for r in runs):
        raise InputError(f"{path}: nothing to plot: force_evals is 0 in every row (the "
                         "integrators evaluated no forces: are the step functions still stubs?)")
    if not any(not r.diverged and finite(r.error) and r.error > 0 for r in runs):
        raise InputError(f"{path}: nothing to plot: no run has a finite error > 0")
    if len({r.error for r in runs if not r.diverged}) == 1 and len(runs) > 1:
        raise InputError(f"{path}: nothing to plot: every run has the same error "
                         f"{runs[0].error:g} whatever dt (did any step move anything?)")
    outs = [prefix + "-work-precision.png", prefix + "-convergence.png",
            prefix + "-energy-error.png"]
    plot_work_precision(runs, scene, outs[0], scale)
    plot_convergence(runs, scene, outs[1], scale)
    plot_energy_error(runs, scene, outs[2], scale)
    return outs


def orders(path, scene=None, scale=1.0):
    """{integrator: (order or None, points used)} for one scene of a sweep."""
    runs, _ = select_scene(path, read_sweep(path), scene)
    return {n: measured_order(g, scale) for n, g in by_integrator(runs)}


def _fmt_run(r):
    return f"{r.integrator}, dt = {r.dt:g}"


def cheapest(runs, targets):
    """[(scene, target, fastest run or None, fewest-evals run or None)]."""
    out = []
    for scene in scenes_of(runs):
        mine = [r for r in runs if r.scene == scene and not r.diverged]
        for target in targets:
            ok = [r for r in mine if r.error <= target]
            fast = min((r for r in ok if finite(r.wall_s)),
                       key=lambda r: (r.wall_s, r.force_evals, r.integrator, r.dt), default=None)
            few = min((r for r in ok if finite(r.force_evals)),
                      key=lambda r: (r.force_evals, r.wall_s, r.integrator, r.dt), default=None)
            out.append((scene, target, fast, few))
    return out


def cheapest_markdown(runs, targets):
    lines = ["| scene | target error (m) | least wall time | wall time (s) | error (m) "
             "| fewest force evaluations | force evaluations | error (m) |",
             "|---|---|---|---|---|---|---|---|"]
    for scene, target, fast, few in cheapest(runs, targets):
        cells = [scene, f"{target:g}"]
        for r, attr in ((fast, "wall_s"), (few, "force_evals")):
            if r is None:
                cells += ["none", "", ""]
            else:
                v = getattr(r, attr)
                cells += [_fmt_run(r), f"{v:.3g}" if attr == "wall_s" else f"{int(v)}",
                          f"{r.error:.2e}"]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"
