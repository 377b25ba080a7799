"""The implicit lab's report figures and its tools/plot subcommand.

Replaces the generic per-scene figures: backward-euler-1 runs only on a scene
it accepts (one particle on one anchored zero-rest spring), and only that
scene is swept (the stiff networks would make a sweep's finest steps slow).

    tools/plot amplification -o FIG.png [--mark HW,...]
draws how much one step of each method multiplies an undamped spring's
amplitude, against h*omega: the stability picture of this lab.
"""
import math

from ..common import summary_line
from ..recipes import fmt_dt

REPLACES_GENERIC = True

IMPLICIT = ("backward-euler", "baraff-witkin", "implicit-trapezoid", "backward-euler-1",
            "backward-euler-fast", "baraff-witkin-fast")

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
    c = sub.add_parser("implicit-cost",
                       help="cost per simulated second and energy lost against k/m, from the "
                            "cost-per-second.csv tools/report writes (implicit lab)")
    c.add_argument("csv", metavar="COST.csv")
    c.add_argument("-o", "--out", required=True, metavar="FIG.png")
    c.add_argument("--title")
    s = sub.add_parser("amplification",
                       help="amplitude factor per step on an undamped spring against h*omega, "
                            "for the explicit and implicit methods (implicit lab)")
    s.add_argument("-o", "--out", required=True, metavar="FIG.png")
    s.add_argument("--mark", help="comma-separated h*omega values to mark")
    s.add_argument("--title")


def run(args):
    if args.command == "implicit-cost":
        plot_cost(args.csv, args.out, title=args.title)
        return True
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
        summary = ctx.path(f"{stem}-summary.json")  # what the figures say of the run
        a = ["trace", trace, "-o", fig, "--title", f"{name}: trajectories ({default}, dt = {dt} s)",
             "--summary", summary]
        if ctx.plot(a):
            ctx.figure(fig, f"{desc} Trajectories in the x-y plane, {default} at dt = {dt} s: "
                       "open circles are the starts, dots the ends.", a)
        fig = ctx.path(f"{stem}-energy.png")
        a = ["stats", stats, "-o", fig, "--title", f"{name}: energy and momentum ({default})",
             "--summary", summary, "--scene", ctx.scene_path]
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
                       "their blow-ups would flatten these curves). backward-euler-fast and "
                       "baraff-witkin-fast take the same steps as backward-euler and "
                       "baraff-witkin by the provided fast path: their curves lie on top.", a)
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

    if stem == COST_SCENE:
        cost_figure(ctx)

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
                   "backward-euler and baraff-witkin take identical steps, and so do their "
                   "-fast versions (one curve; backward-euler-1 too, not drawn), as do "
                   "midpoint and trapezoid. An x on "
                   "the top edge is a run that diverged.", a)
        ctx.figure(prefix + "-energy-error.png",
                   f"Largest relative energy error over the run against dt on {name}.", a)


# ----------------------------------------------------------------------------
# What it costs: cost per simulated second against k/m (handouts/implicit.md,
# "What it costs"). A quick run: a rope generated at each stiffness, semi-implicit
# Euler at its largest stable step (searched), backward Euler at one frame.

COST_CSV = "cost-per-second.csv"
COST_SCENE = "stiff-rope"  # the scene whose report section gets the figure
COST_COLUMNS = ["km", "km_value", "method", "dt", "steps", "wall_s", "cpu_s", "cost", "vs_se",
                "vs_fast", "status", "energy_lost", "n"]
# Columns measured by a clock (and k/m where two clocks cross): a claim on them must hold by
# a factor 2 (wbplot/claimrules.py).
TIMED_COLUMNS = {"cost-per-second.csv": ("wall_s", "cpu_s", "cost", "vs_se", "vs_fast",
                                         "km_value")}
# The cost is the step loop's CPU time (the summary's cpu_s), not its wall time: the report is
# drawn on shared machines (CI runs it beside compilers), where a run descheduled for a few
# hundred ms would move a ratio by several times and contradict the handout's claims.
COST_CLOCK = "cpu_s"
COST_METHODS = ["symplectic-euler", "baraff-witkin-fast", "backward-euler-fast", "baraff-witkin"]
COST_FRAME = 1.0 / 60.0
COST_KM = [1e2, 1e3, 1e4, 1e5, 1e6, 1e7]
COST_BEADS = 1000  # the report's rope: large enough that a step is not all overhead


def cost_scene(beads, km, t_end, cloth=False):
    """A rope of `beads` beads of 10 g (or a side x side cloth) with k = km * m, pinned, under
    gravity: the stiff-rope scene at another size and stiffness."""
    m = 0.01
    doc = {"name": f"cost-{'cloth' if cloth else 'rope'}", "dt": COST_FRAME, "t_end": t_end,
           "forces": [{"type": "gravity", "g": [0.0, -9.81]}]}
    if cloth:
        side = int(round(math.sqrt(beads)))
        doc["cloth"] = {"origin": [0.0, 0.0], "rows": side, "cols": side, "spacing": 0.05,
                        "m": m, "k": km * m, "k_bend": 0.1 * km * m, "pin": "corners"}
    else:
        doc["rope"] = {"start": [0.0, 0.0], "end": [0.05 * (beads - 1), 0.0], "beads": beads,
                       "m": m, "k": km * m, "pin": "start"}
    return doc


def _run(exe, scene, integrator, dt, t_end, repeats, log, clock="wall_s"):
    """The fastest of `repeats` runs by the summary's `clock` (its summary), or the first
    failure."""
    import subprocess
    best = None
    for _ in range(repeats):
        argv = [exe, "--scene", scene, "--integrator", integrator, "--dt", repr(dt),
                "--t-end", repr(t_end)]
        if log:
            log(" ".join(argv))
        p = subprocess.run(argv, capture_output=True, text=True)
        s = summary_line(p.stdout)
        if p.returncode != 0 or s is None:
            raise RuntimeError(f"{' '.join(argv)}: exit status {p.returncode}: "
                               + (p.stderr.strip().splitlines() or [""])[-1])
        if s.get("status") != "ok":
            return s
        if not isinstance(s.get(clock), (int, float)):
            raise RuntimeError(f"{' '.join(argv)}: the summary has no number `{clock}`")
        if best is None or s[clock] < best[clock]:
            best = s
    return best


COST_SEARCH_T = 5.0  # s: a step just above the limit may take seconds to blow up


def _se_limit(exe, scene, km, mgl, log):
    """Semi-implicit Euler's largest stable step (at most one frame): the largest of
    c / sqrt(k/m), c from 1.1 down, whose run of COST_SEARCH_T seconds stays finite and
    changes the energy by at most 1 % of M g L (an unstable step makes it grow without
    bound; a stable one keeps it within a small fraction). On a free rope the whip of its
    end makes later seconds need smaller steps still: this limit holds for the timed runs
    (1 s), not for ever."""
    for c in (1.1, 1.05, 1.0, 0.95, 0.9, 0.85, 0.8, 0.7, 0.6, 0.5, 0.4, 0.3, 0.2):
        dt = min(COST_FRAME, c / math.sqrt(km))
        s = _run(exe, scene, "symplectic-euler", dt, COST_SEARCH_T, 1, log)
        e0, e1 = s.get("energy0"), s.get("energy")
        if (s.get("status") == "ok" and isinstance(e0, (int, float))
                and isinstance(e1, (int, float)) and abs(e1 - e0) <= 0.01 * mgl):
            return dt
    return None


def cost_sweep(exe, out_dir, beads=1000, kms=COST_KM, t_end=1.0, repeats=3, cloth=False,
               methods=COST_METHODS, log=None):
    """Runs every method on the rope (or cloth) at each k/m; writes out_dir/COST_CSV (and
    the generated scenes beside it); returns the rows."""
    import json
    import os
    m = 0.01
    rows = []
    for km in kms:
        label = f"{km:.0e}".replace("e+0", "e").replace("e+", "e")
        scene = os.path.join(out_dir, f"cost-{'cloth' if cloth else 'rope'}-{label}.json")
        with open(scene, "w", encoding="utf-8") as f:
            json.dump(cost_scene(beads, km, t_end, cloth), f, indent=1)
        n = beads if not cloth else int(round(math.sqrt(beads))) ** 2
        length = 0.05 * ((beads - 1) if not cloth else (math.sqrt(n) - 1))
        mgl = n * m * 9.81 * length
        se_dt = _se_limit(exe, scene, km, mgl, log)
        per = {}
        for meth in methods:
            dt = se_dt if meth == "symplectic-euler" else COST_FRAME
            if dt is None:
                continue
            s = _run(exe, scene, meth, dt, t_end, repeats, log, COST_CLOCK)
            e0, e1 = s.get("energy0"), s.get("energy")
            spent = s.get(COST_CLOCK)  # a diverged run's too: it is drawn with an x
            lost = (e0 - e1) / mgl if isinstance(e0, (int, float)) and isinstance(
                e1, (int, float)) else math.nan
            per[meth] = {"km": label, "km_value": km, "method": meth, "dt": dt,
                         "steps": s.get("steps"), "wall_s": s.get("wall_s"),
                         "cpu_s": s.get("cpu_s"),
                         "cost": spent / t_end if isinstance(spent, (int, float)) else math.nan,
                         "status": s.get("status"), "energy_lost": lost, "n": n}
        se_cost = per.get("symplectic-euler", {}).get("cost", math.nan)
        fast_cost = per.get("baraff-witkin-fast", {}).get("cost", math.nan)
        for r in per.values():
            r["vs_se"] = r["cost"] / se_cost if se_cost and se_cost > 0 else math.nan
            # Against the provided one-solve path: the same step, written for speed.
            r["vs_fast"] = r["cost"] / fast_cost if fast_cost and fast_cost > 0 else math.nan
            rows.append(r)
    # Where each implicit method's cost crosses semi-implicit Euler's (log-log interpolation
    # between the two stiffnesses around the sign change of log(vs_se)).
    for meth in methods[1:]:
        pts = [(r["km_value"], r["vs_se"]) for r in rows if r["method"] == meth
               and r["status"] == "ok" and r["vs_se"] > 0]
        cross = math.nan
        for (k0, r0), (k1, r1) in zip(pts, pts[1:]):
            if r0 > 1.0 >= r1:
                t = math.log(r0) / (math.log(r0) - math.log(r1))
                cross = math.exp(math.log(k0) + t * (math.log(k1) - math.log(k0)))
                break
        rows.append({"km": "crossover", "km_value": cross, "method": meth, "dt": COST_FRAME,
                     "steps": "", "wall_s": "", "cpu_s": "", "cost": "", "vs_se": "",
                     "vs_fast": "", "status": "", "energy_lost": "", "n": ""})
    path = os.path.join(out_dir, COST_CSV)
    tmp = path + ".tmp"
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(",".join(COST_COLUMNS) + "\n")
        for r in rows:
            f.write(",".join(_cell(r.get(c, "")) for c in COST_COLUMNS) + "\n")
    os.replace(tmp, path)
    return rows


def _cell(v):
    if isinstance(v, float):
        return f"{v:.6g}"
    return str(v)


def plot_cost(path, out, title=None):
    """Two panels from COST_CSV: cost per simulated second against k/m (the crossover
    marked), and the energy each run lost (in units of M g L)."""
    from ..common import InputError, integrator_style, new_figure, read_csv, save_figure
    rows = read_csv(path, COST_COLUMNS, "cost-per-second CSV (tools/report writes it)")

    def num(s):
        try:
            return float(s)
        except ValueError:
            return math.nan

    methods = [m for m in COST_METHODS if any(r["method"] == m for r in rows)]
    if not methods:
        raise InputError(f"{path}: no rows of the methods {', '.join(COST_METHODS)}")
    fig, (ax, bx) = new_figure(1, 2, figsize=(11, 5.2))
    names = {"symplectic-euler": "semi-implicit Euler at its largest stable step",
             "baraff-witkin-fast": "backward Euler, one solve (provided fast path), h = 1/60",
             "backward-euler-fast": "backward Euler, Newton to tol (fast path), h = 1/60",
             "baraff-witkin": "backward Euler, one solve (the lab's I3-I4), h = 1/60"}
    for m in methods:
        pts = [r for r in rows if r["method"] == m and r["km"] != "crossover"]
        ok = [r for r in pts if r["status"] == "ok"]
        colour, marker = integrator_style(m, methods)
        style = "--" if m == "baraff-witkin" else "-"
        ax.plot([num(r["km_value"]) for r in ok], [num(r["cost"]) for r in ok], style,
                color=colour, marker=marker, label=names.get(m, m))
        bad = [r for r in pts if r["status"] != "ok"]
        if bad:  # never expected: shown, not hidden
            ax.plot([num(r["km_value"]) for r in bad], [num(r["cost"]) for r in bad], "x",
                    color=colour, ms=9, label=f"{m}: run {bad[0]['status']}")
        lost = [(num(r["km_value"]), num(r["energy_lost"])) for r in ok]
        bx.plot([k for k, _ in lost], [max(abs(e), 1e-12) for _, e in lost], style,
                color=colour, marker=marker, label=m)
    for r in rows:
        if r["km"] == "crossover" and r["method"] == "baraff-witkin-fast":
            k = num(r["km_value"])
            if math.isfinite(k):
                ax.axvline(k, color="0.3", ls=":", lw=1.0)
                ax.annotate(f"crossover\nk/m ≈ {k:.2g} s⁻² ", (k, 0.03), xycoords=("data",
                            "axes fraction"), ha="right", va="bottom", fontsize=8)
    for a in (ax, bx):
        a.set_xscale("log")
        a.set_yscale("log")
        a.set_xlabel("k/m (s⁻²) of every spring")
    ax.set_ylabel("CPU time of the step loop per simulated second (s/s)")
    ax.set_title(title or "Cost per simulated second (lower is cheaper)")
    handles, labels = ax.get_legend_handles_labels()
    fig.legend(handles, labels, fontsize=8, loc="lower center", ncol=2)
    bx.set_ylabel("energy lost over the run / (M g L)")
    lost = {m: [r["energy_lost"] for r in rows if r["method"] == m and r["km"] != "crossover"]
            for m in methods if m != "symplectic-euler"}
    same = len(lost) > 1 and all(
        all(abs(num(a) - num(b)) <= 0.02 * abs(num(b)) for a, b in zip(v, next(iter(lost.values()))))
        for v in lost.values())
    bx.set_title("What each pays in accuracy: energy lost"
                 + ("\n(the backward Euler curves coincide)" if same else ""))
    bx.legend(fontsize=7.5, loc="lower left")
    fig.tight_layout(rect=(0, 0.1, 1, 1))
    save_figure(fig, out)


def cost_figure(ctx):
    """The report's cost figure: cost_sweep on a rope of COST_BEADS, then plot_cost."""
    try:
        rows = cost_sweep(ctx.exe, ctx.out_dir, beads=COST_BEADS)
    except (RuntimeError, OSError) as e:
        ctx.fail(f"cost per simulated second: {e}")
        return
    ctx.table("Cost per simulated second (rope of %d beads, 1 s simulated; CPU time of the "
              "step loop, fastest of 3 runs)" % COST_BEADS, _cost_table(rows))
    fig = ctx.path("cost-per-second.png")
    a = ["implicit-cost", ctx.path(COST_CSV), "-o", fig]
    if ctx.plot(a):
        ctx.figure(fig, f"Left: CPU time per simulated second on a rope of {COST_BEADS} beads "
                   "of 10 g, pinned at one end, for stiffnesses k/m from 1e2 to 1e7: "
                   "semi-implicit Euler at its largest stable step (found by trying steps "
                   "c/sqrt(k/m), at most 1/60 s), backward Euler at h = 1/60 s with one "
                   "linear solve and with Newton to the default tolerance (the provided fast "
                   "path), and the lab's own one-solve step (dashed). The dotted line marks "
                   "where one solve becomes cheaper than the explicit method. Right: the "
                   "energy each run lost in 1 s, in units of M g L (the rope's weight times "
                   "its length): backward Euler pays for its large step in damping. "
                   "Timings are the step loop's CPU time (time the machine gave to other "
                   "work does not count), the fastest of 3 runs on the machine that drew this "
                   "report.",
                   a)


def _cost_table(rows):
    out = ["| k/m | method | dt (s) | CPU s per simulated s | / semi-implicit Euler | "
           "energy lost / MgL |", "|---|---|---|---|---|---|"]
    for r in rows:
        if r["km"] == "crossover":
            out.append(f"| crossover | {r['method']} | | | 1 (k/m ≈ {_cell(r['km_value'])}) | |")
        else:
            out.append(f"| {r['km']} | {r['method']} | {_cell(r['dt'])} | {_cell(r['cost'])} | "
                       f"{_cell(r['vs_se'])} | {_cell(r['energy_lost'])} |")
    return "\n".join(out)


# tools/claims makes this file itself when build/report has none (docs/report.md, Claims).
CLAIM_FILES = {COST_CSV: lambda exe, out: cost_sweep(exe, out, beads=COST_BEADS)}
