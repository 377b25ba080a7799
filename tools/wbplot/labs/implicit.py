"""The implicit lab's report figures and its tools/plot subcommand.

Replaces the generic per-scene figures: backward-euler-1 runs only on a scene
it accepts (one particle on one anchored zero-rest spring), and only that
scene is swept (the stiff networks would make a sweep's finest steps slow).

    tools/plot amplification -o FIG.png [--mark HW,...]
draws how much one step of each method multiplies an undamped spring's
amplitude, against h*omega: the stability picture of this lab.
"""
import math

from ..recipes import fmt_dt

REPLACES_GENERIC = True

IMPLICIT = ("backward-euler", "baraff-witkin", "implicit-trapezoid", "backward-euler-1")

# The step matrix of each method on x' = v, v' = -x (omega = 1) at step size h.
METHODS = ["explicit-euler", "symplectic-euler", "midpoint", "trapezoid", "rk4",
           "backward-euler", "implicit-trapezoid"]


def step_matrix(method, h):
    import numpy as np
    A = np.array([[0.0, 1.0], [-1.0, 0.0]])
    I = np.eye(2)
    hA = h * A
    if method == "explicit-euler":
        return I + hA
    if method == "symplectic-euler":  # v' = v - h x, then x' = x + h v'
        return np.array([[1.0 - h * h, h], [-h, 1.0]])
    if method in ("midpoint", "trapezoid"):  # identical on a linear force
        return I + hA + hA @ hA / 2
    if method == "rk4":
        return I + hA + hA @ hA / 2 + hA @ hA @ hA / 6 + hA @ hA @ hA @ hA / 24
    if method == "backward-euler":
        return np.linalg.inv(I - hA)
    if method == "implicit-trapezoid":
        return np.linalg.solve(I - hA / 2, I + hA / 2)
    raise ValueError(method)


def amplification(method, hw):
    """Spectral radius of one step on the undamped oscillator at h*omega = hw."""
    import numpy as np
    return float(max(abs(np.linalg.eigvals(step_matrix(method, hw)))))


def plot_amplification(out, marks=(), title=None):
    import numpy as np
    from ..common import integrator_style, new_figure, save_figure
    hws = np.logspace(-2, 3, 600)
    fig, ax = new_figure(figsize=(7.5, 4.8))
    for m in METHODS:
        r = np.array([amplification(m, h) for h in hws])
        colour, marker = integrator_style(m, METHODS)
        # Distinguish the curves that coincide on a linear force.
        style = "--" if m == "trapezoid" else ("-." if m == "implicit-trapezoid" else "-")
        label = m + (" (same curve as midpoint)" if m == "trapezoid" else "")
        ax.plot(hws, r, style, color=colour, label=label,
                lw=2.6 if m == "implicit-trapezoid" else 1.6, zorder=3)
        above = np.nonzero(r > 1.0 + 1e-12)[0]
        if len(above) and above[0] > 0:
            ax.plot(hws[above[0]], r[above[0]], marker, color=colour, ms=7)
    ax.axhline(1.0, color="k", lw=0.6, zorder=2)
    for hw in marks:
        ax.axvline(hw, color="0.5", lw=0.8, ls=":")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_ylim(1e-3, 1e3)
    ax.set_xlabel("h ω (step size times the spring's angular frequency)")
    ax.set_ylabel("|R|: amplitude factor per step")
    ax.set_title(title or "One step on an undamped spring: growth (> 1) or decay (< 1)")
    ax.legend(fontsize=8, loc="lower left")
    save_figure(fig, out)


def add_commands(sub):
    s = sub.add_parser("amplification",
                       help="amplitude factor per step on an undamped spring against h*omega, "
                            "for the explicit and implicit methods (implicit lab)")
    s.add_argument("-o", "--out", required=True, metavar="FIG.png")
    s.add_argument("--mark", help="comma-separated h*omega values to mark")
    s.add_argument("--title")


def run(args):
    if args.command != "amplification":
        return False
    from ..common import parse_list
    marks = parse_list(args.mark, "--mark", float) if args.mark else []
    plot_amplification(args.out, marks, title=args.title)
    return True


def _one_spring(doc):
    """h*omega when backward-euler-1 accepts the scene, else None."""
    parts, forces = doc.get("particles", []), doc.get("forces", [])
    if doc.get("rope") or doc.get("cloth") or doc.get("emitters") or len(parts) != 1:
        return None
    springs = [f for f in forces if f.get("type") == "spring"]
    if len(springs) != 1 or "anchor" not in springs[0] or springs[0].get("rest", None) != 0:
        return None
    if springs[0].get("damping", 0) != 0:
        return None
    try:
        return float(doc["dt"]) * math.sqrt(float(springs[0]["k"]) / float(parts[0]["m"]))
    except (KeyError, TypeError, ValueError, ZeroDivisionError):
        return None


def _every(doc):
    try:
        steps = round(float(doc["t_end"]) / float(doc["dt"]))
    except (KeyError, TypeError, ValueError, ZeroDivisionError):
        return 1
    return max(1, math.ceil(steps / 2000))


def sweep_argv(exe, scene_path, doc, csv, names=None):
    """The lab's sweep of a one-spring scene, for the report and tools/claims alike: steps
    from 8 dt down to dt/512 (backward Euler reaches its asymptotic range only at small
    h omega), every integrator but backward-euler-1 (it takes backward-euler's steps)."""
    dts = ",".join(repr(float(doc["dt"]) * 2.0 ** k) for k in range(3, -10, -1))
    argv = [exe, "--scene", scene_path, "--sweep", csv, "--repeats", "1", "--dts", dts]
    if names is None:
        names = [n for n in ("backward-euler", "baraff-witkin", "implicit-trapezoid",
                             "explicit-euler", "symplectic-euler", "midpoint", "trapezoid",
                             "rk4")]
    return argv + ["--integrators", ",".join(names)]


def scene_figures(ctx):
    doc, stem = ctx.doc, ctx.stem
    name = doc.get("name", stem)
    dt = fmt_dt(doc.get("dt"))
    hw = _one_spring(doc)
    # backward-euler-1 takes the same steps as backward-euler wherever it runs (one linear
    # spring): it is left out of the comparisons (and one colour fewer is needed).
    names = [n for n, _, _ in ctx.integrators if n != "backward-euler-1"]
    default = doc.get("integrator") or (names[0] if names else "default")
    desc = doc.get("description", f"Scene {name}.")
    k = str(_every(doc))

    # The scene as shipped.
    trace, stats = ctx.path(f"{stem}.csv"), ctx.path(f"{stem}-stats.csv")
    s = ctx.run(["--scene", ctx.scene_path, "--out", trace, "--stats", stats, "--every", k],
                ctx.scene_path, f"{default} (scene default)", save=stem)
    if s is not None:
        fig = ctx.path(f"{stem}-trajectory.png")
        a = ["trace", trace, "-o", fig, "--title", f"{name}: trajectories ({default}, dt = {dt} s)"]
        if ctx.plot(a):
            ctx.figure(fig, f"{desc} Trajectories in the x-y plane, {default} at dt = {dt} s: "
                       "open circles are the starts, dots the ends.", a)
        fig = ctx.path(f"{stem}-energy.png")
        a = ["stats", stats, "-o", fig, "--title", f"{name}: energy and momentum ({default})"]
        if s.get("status") == "diverged":
            a += ["--diverged", str(s["steps"])]
        if ctx.plot(a):
            ctx.figure(fig, f"Energy (total, kinetic, potential) and momentum against time, "
                       f"{default} at dt = {dt} s.", a)

    # Every integrator on the scene as shipped.
    files, labels = [], []
    for n in names:
        st = ctx.path(f"{stem}-{n}-stats.csv")
        s = ctx.run(["--scene", ctx.scene_path, "--integrator", n, "--stats", st,
                     "--every", k], f"{ctx.scene_path} --integrator {n}", n,
                    save=f"{stem}-{n}")  # the summary `summary` claims read
        if s is not None:
            files.append(st)
            labels.append(n)
    implicit = [(f, n) for f, n in zip(files, labels) if n in IMPLICIT]
    if implicit:
        fig = ctx.path(f"{stem}-energy-implicit.png")
        a = ["energy"] + [f for f, _ in implicit] + [
            "--labels", ",".join(n for _, n in implicit), "-o", fig, "--title",
            f"{name}: total energy, implicit integrators (dt = {dt} s)"]
        a += ctx.diverged_args([n for _, n in implicit])
        if ctx.plot(a):
            ctx.figure(fig, f"Total energy against time of the implicit integrators alone on "
                       f"{name} at dt = {dt} s (the explicit ones are in the next figure: "
                       "their blow-ups would flatten these curves).", a)
    if files:
        fig = ctx.path(f"{stem}-energy-compare.png")
        a = ["energy"] + files + ["--labels", ",".join(labels), "-o", fig, "--title",
                                  f"{name}: total energy by integrator (dt = {dt} s)"]
        a += ctx.diverged_args(labels)
        if ctx.plot(a):
            ctx.figure(fig, f"Total energy against time for each integrator on {name} at "
                       f"dt = {dt} s. An x marks where a run diverged (the run contract's rule: not "
                       "finite, |E| past 1000 times its initial scale, or most Newton solves "
                       "failed).",
                       a)

    # The stability picture, with the scene's h*omega, and a sweep of the one-spring scene.
    if hw is None:
        return
    fig = ctx.path(f"{stem}-amplification.png")
    a = ["amplification", "-o", fig, "--mark", f"{hw:.6g}"]
    if ctx.plot(a):
        ctx.figure(fig, "Amplitude factor per step |R| on an undamped spring against hω, from "
                   "each method's step matrix (not from a run): above 1 the oscillation "
                   "grows. Backward Euler is below 1 at every hω (it damps), the implicit "
                   "trapezoid is exactly 1; midpoint and the explicit trapezoid share one "
                   f"curve (dashed). The dotted line is this scene, hω = {hw:.3g}; a marker "
                   "shows where a method that starts bounded stops being bounded.", a)
    sw = ctx.path(f"{stem}-sweep.csv")
    s = ctx.run(sweep_argv(ctx.exe, ctx.scene_path, doc, sw, names)[1:],
                f"{ctx.scene_path} --sweep", "sweep")
    if s is None:
        return
    prefix = ctx.path(f"{stem}-sweep")
    a = ["sweep", sw, "-o", prefix, "--scale", "1"]
    if ctx.plot(a):
        ctx.figure(prefix + "-work-precision.png",
                   f"Work-precision on {name}: final position error against wall time and "
                   "against force evaluations (an implicit step counts one evaluation of "
                   "the explicit forces; its Newton solves are in the wall time).", a)
        ctx.figure(prefix + "-convergence.png",
                   f"Convergence on {name}: final position error against dt, log-log; the "
                   "legend gives each integrator's measured order. On this linear spring "
                   "backward-euler and baraff-witkin take identical steps (one curve; "
                   "backward-euler-1 too, not drawn), as do midpoint and trapezoid. An x on "
                   "the top edge is a run that diverged.", a)
        ctx.figure(prefix + "-energy-error.png",
                   f"Largest relative energy error over the run against dt on {name}.", a)
