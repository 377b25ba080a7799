"""The main job: set up, build, run every lab's solution on its scenes, plot, write build/report/index.html."""
import argparse
import html
import json
import math
import os
import re
import shlex
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tools"))

from wbplot import cli as plot_cli  # noqa: E402
from wbplot.common import InputError, summary_line, write_text_atomic  # noqa: E402
from wbplot import sweep as wsweep  # noqa: E402
from wbplot import recipes  # noqa: E402
from wbplot.claims import strip_markers  # noqa: E402
from wbplot.recipes import fmt_dt, length_scale, offers, oscillator  # noqa: E402
from wbview.report import view_of_run  # noqa: E402
from wbtools import committed  # noqa: E402

TARGETS = "1e-2,1e-4,1e-6"  # target errors (m) of the cheapest-method tables


def rel(path):
    """A path as shown to the reader: relative to the repository when inside it."""
    p = os.path.relpath(path, ROOT)
    return path if p.startswith("..") else p


def log(msg):
    print(msg, flush=True)


class Report:
    """Everything the run found: sections per lab, failures, the commands run."""

    def __init__(self, out_dir):
        self.out_dir = out_dir
        self.failures = []   # one line each
        self.commands = []   # (lab, command line) in the order run
        self.labs = []       # LabSection
        self.facts = {}      # figure path -> what it shows (wbplot/figfacts.py)
        self.source = {}     # the commit drawn from (committed.source_stamp), set by main()
        self.live = {}       # lab -> its live page (docs/live.md), from the index
        self.live_note = None  # why there are none

    def fail(self, msg):
        self.failures.append(msg)
        log(f"report: FAILED: {msg}")


class LabSection:
    def __init__(self, lab):
        self.lab = lab
        self.status = ""         # "" or why the lab was skipped
        self.integrators = []    # [(name, order or None, description)]
        self.sweep = False
        self.help_text = ""
        self.scenes = []         # SceneSection
        self.earlier = ""        # when kept from an earlier report (--labs): its date


def save_section(report, sec, failures):
    """<report>/<lab>/section.json: what the index shows of a lab, so that a later
    `tools/report --labs other` keeps this lab's section (docs/report.md)."""
    def r(p):
        return os.path.relpath(p, report.out_dir)
    d = {"lab": sec.lab, "status": sec.status, "integrators": sec.integrators,
         "failures": failures, "generated": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
         # The commit the figures were drawn from (tools/pack reuses them only when they are
         # what HEAD would draw: wbtools/committed.py).
         "source": report.source,
         "scenes": [{"stem": sc.stem, "name": sc.name, "description": sc.description,
                     "runs": sc.runs, "tables": sc.tables,
                     "figures": [(r(f), c, [rel(x) if os.path.isabs(x) else x for x in a])
                                 for f, c, a in sc.figures]} for sc in sec.scenes]}
    folder = os.path.join(report.out_dir, sec.lab)
    if os.path.isdir(folder):
        write_text_atomic(os.path.join(folder, "section.json"), json.dumps(d, indent=1) + "\n")


def load_section(report, lab):
    """The LabSection an earlier report saved for `lab`, or None."""
    path = os.path.join(report.out_dir, lab, "section.json")
    try:
        with open(path, encoding="utf-8") as f:
            d = json.load(f)
        sec = LabSection(lab)
        sec.status, sec.earlier = d["status"], d.get("generated", "an earlier run")
        sec.integrators = [tuple(i) for i in d["integrators"]]
        for x in d["scenes"]:
            sc = SceneSection(x["stem"], {"name": x["name"], "description": x["description"]})
            sc.runs = [tuple(r) for r in x["runs"]]
            sc.tables = [tuple(t) for t in x["tables"]]
            # Arguments were saved as shown (relative to the repository).
            sc.figures = [(os.path.join(report.out_dir, f), c, a) for f, c, a in x["figures"]]
            sec.scenes.append(sc)
        return sec, d.get("failures", [])
    except (OSError, ValueError, KeyError, TypeError):
        return None, []


class SceneSection:
    def __init__(self, stem, doc):
        self.stem = stem
        self.doc = doc
        self.name = doc.get("name", stem) if isinstance(doc, dict) else stem
        self.description = strip_markers(doc.get("description", "") if isinstance(doc, dict)
                                         else "")
        self.runs = []       # (integrator label, summary dict or None, error text)
        self.figures = []    # (path, caption, command)
        self.tables = []     # (title, markdown)


# ----------------------------------------------------------------------------
# Running things


def run_cmd(report, lab, argv, timeout, quiet=False):
    """Runs argv from the repository root; returns (exit status, stdout, stderr)."""
    line = " ".join(shlex.quote(rel(a) if os.path.isabs(a) else a) for a in argv)
    report.commands.append((lab, line))
    if not quiet:
        log(f"+ {line}")
    try:
        p = subprocess.run(argv, cwd=ROOT, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, "", f"timed out after {timeout} s"
    except OSError as e:
        return None, "", f"cannot run: {e.strerror}"
    return p.returncode, p.stdout, p.stderr


def plot(report, lab, args):
    """tools/plot ARGS, in this process; False (and a failure) if it reported bad input."""
    line = "tools/plot " + " ".join(shlex.quote(rel(a) if os.path.isabs(a) else a) for a in args)
    report.commands.append((lab, line))
    log(f"+ {line}")
    import contextlib
    import io
    err = io.StringIO()
    from wbplot import figfacts
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()), \
            figfacts.recording() as seen:
        status = plot_cli.main(args)
    report.facts.update(seen)  # what each figure shows, for figcheck after the lab
    if status != 0:
        report.fail(f"{line}: {err.getvalue().strip()}")
        return False
    return True


def solution_run(report, lab, exe, argv_tail, what, timeout, save=None):
    """One run of a solution executable; a failure is an exit status other than 0. With
    `save`, the summary is also written to that file (tools/claims reads it)."""
    status, out, err = run_cmd(report, lab, [exe] + argv_tail, timeout)
    if status != 0:
        why = err.strip().splitlines()[-1] if err.strip() else f"exit status {status}"
        report.fail(f"{lab}: {what}: {why}" + (f" (exit status {status})" if status else ""))
        return None, why
    s = summary_line(out)
    if s is None and "--sweep" not in argv_tail:
        report.fail(f"{lab}: {what}: no JSON summary on the last line of stdout")
        return None, "no summary line"
    if save and s is not None:
        write_text_atomic(save, json.dumps(s) + "\n")
    if s is not None and "--out" in argv_tail:  # its viewer page, linked from the runs table
        try:
            s["_view"] = os.path.relpath(view_of_run(argv_tail, s, ROOT), report.out_dir)
        except InputError as e:
            report.fail(f"{lab}: {what}: tools/view: {e}")
    return s or {}, ""


# ----------------------------------------------------------------------------
# What a lab and a scene offer


def lab_order():
    """Labs in teaching order (the wb_lab(...) lines of CMakeLists.txt), then any other
    scenes/ folder."""
    labs = []
    try:
        with open(os.path.join(ROOT, "CMakeLists.txt"), encoding="utf-8") as f:
            labs = re.findall(r"^\s*wb_lab\(\s*([A-Za-z0-9_-]+)", f.read(), re.M)
    except OSError:
        pass
    scenes = os.path.join(ROOT, "scenes")
    if os.path.isdir(scenes):
        labs += sorted(d for d in os.listdir(scenes)
                       if os.path.isdir(os.path.join(scenes, d)) and d not in labs)
    return labs


def parse_help(text):
    """(integrators [(name, order, description)], default name, sweep?, repeats?) from --help."""
    integrators, default = [], None
    lines = text.splitlines()
    inside = False
    for ln in lines:
        if ln.startswith("Integrators"):
            inside = True
            continue
        if inside:
            s = ln.strip()
            if not s:
                break
            if s.startswith("default:"):
                default = s.split(":", 1)[1].strip()
                continue
            name, _, desc = s.partition(" ")
            m = re.search(r"\(order (\d+)", desc)
            integrators.append((name, int(m.group(1)) if m else None, desc.strip()))
    if default is None and integrators:
        default = integrators[0][0]
    return integrators, default, offers(text, "--sweep"), offers(text, "--repeats")


def diverged_args(runs):
    """--diverged for `tools/plot energy`: LABEL=STEP of each (label, summary) whose summary
    says the run diverged (the run contract's rule, docs/run-contract.md), or []."""
    items = [f"{label}={s['steps']}" for label, s in runs
             if s and s.get("status") == "diverged" and isinstance(s.get("steps"), int)]
    return ["--diverged", ",".join(items)] if items else []


def diverged_step(s):
    """--diverged STEP for `tools/plot stats` when the summary says the run diverged, or []."""
    if s and s.get("status") == "diverged" and isinstance(s.get("steps"), int):
        return ["--diverged", str(s["steps"])]
    return []


def fmt(x, digits=6):
    if x is None:
        return "null"
    if isinstance(x, float):
        return f"{x:.{digits}g}"
    return str(x)


# ----------------------------------------------------------------------------
# One lab


def do_lab(report, lab, bin_dir, args):
    sec = LabSection(lab)
    report.labs.append(sec)
    exe = os.path.join(bin_dir, f"{lab}-solution")
    scene_dir = os.path.join(ROOT, "scenes", lab)
    if not os.path.exists(exe):
        sec.status = f"not built: {rel(exe)} does not exist"
        log(f"report: {lab}: skipped, {sec.status}")
        return
    scenes = sorted(f for f in os.listdir(scene_dir) if f.endswith(".json")) \
        if os.path.isdir(scene_dir) else []
    if not scenes:
        sec.status = f"no default scenes in scenes/{lab}/"
        log(f"report: {lab}: skipped, {sec.status}")
        return
    status, out, err = run_cmd(report, lab, [exe, "--help"], 60)
    if status != 0:
        report.fail(f"{lab}: {rel(exe)} --help: exit status {status}: {err.strip()}")
        sec.status = "--help failed"
        return
    integrators, default, sec.sweep, repeats_flag = parse_help(out)
    sec.help_text = out
    sec.integrators = integrators
    out_dir = os.path.join(report.out_dir, lab)
    os.makedirs(out_dir, exist_ok=True)
    # Outputs of an earlier report: a figure this run does not redraw must not linger.
    for f in sorted(os.listdir(out_dir)):
        if f.endswith((".png", ".csv", ".md", ".json", ".html")) and \
                os.path.isfile(os.path.join(out_dir, f)):
            os.remove(os.path.join(out_dir, f))

    for scene_file in scenes:
        path = os.path.join(scene_dir, scene_file)
        stem = scene_file[:-len(".json")]
        try:
            with open(path, encoding="utf-8") as f:
                doc = json.load(f)
        except (OSError, json.JSONDecodeError) as e:
            doc = {}
            log(f"report: {rel(path)}: cannot read as JSON ({e}); the run will say more")
        if not isinstance(doc, dict):
            doc = {}
        sc = SceneSection(stem, doc)
        sec.scenes.append(sc)
        plugin = lab_plugin(lab)
        if not getattr(plugin, "REPLACES_GENERIC", False):
            do_scene(report, sec, sc, exe, rel(path), out_dir, integrators, default,
                     repeats_flag, args)
        if plugin is not None and hasattr(plugin, "scene_figures"):
            plugin.scene_figures(SceneContext(report, sec, sc, exe, rel(path), out_dir,
                                              integrators, args))


def base(out_dir, name):
    return os.path.join(out_dir, name)


def lab_plugin(lab):
    """tools/wbplot/labs/<lab>.py when the lab has one (docs/report.md), else None."""
    import importlib
    if not re.fullmatch(r"[A-Za-z0-9_]+", lab) or not os.path.exists(
            os.path.join(ROOT, "tools", "wbplot", "labs", f"{lab}.py")):
        return None
    return importlib.import_module(f"wbplot.labs.{lab}")


class SceneContext:
    """What a lab plug-in sees of one scene (tools/wbplot/labs/__init__.py)."""

    def __init__(self, report, sec, sc, exe, scene_path, out_dir, integrators, args):
        self.report, self.sec, self.sc = report, sec, sc
        self.lab, self.stem, self.doc = sec.lab, sc.stem, sc.doc
        self.exe, self.scene_path, self.out_dir = exe, scene_path, out_dir
        self.integrators, self.args = integrators, args

    def path(self, name):
        return base(self.out_dir, name)

    def run(self, argv_tail, what, label=None, save=None, again=False):
        """save: a name such as "<scene>-<integrator>" to keep the summary as
        <name>-summary.json, where `summary` claims read it (docs/report.md, Claims).
        again: the same run as the last one, with other outputs: its row replaces
        the last one in the scene's table."""
        s, why = solution_run(self.report, self.lab, self.exe, argv_tail, what, self.args.timeout,
                              save=self.path(save + "-summary.json") if save else None)
        if again and self.sc.runs:
            self.sc.runs.pop()
        self.sc.runs.append((label or what, s, why))
        return s

    def plot(self, args):
        return plot(self.report, self.lab, args)

    def diverged_args(self, labels):
        """--diverged LABEL=STEP,... for `tools/plot energy` over the runs of this scene
        labelled so (their summaries: the run contract's rule)."""
        return diverged_args([(r[0], r[1]) for r in self.sc.runs if r[0] in labels])

    def figure(self, path, caption, plot_args):
        self.sc.figures.append((path, caption, plot_args))

    def table(self, title, markdown):
        self.sc.tables.append((title, markdown))

    def fail(self, msg):
        self.report.fail(f"{self.lab}: {msg}")


def do_scene(report, sec, sc, exe, scene_path, out_dir, integrators, default, repeats_flag,
             args):
    lab, stem, doc = sec.lab, sc.stem, sc.doc
    integ = doc.get("integrator") or default or "default"
    dt = doc.get("dt")
    setting = f"{integ}, dt = {fmt_dt(dt)} s" if dt is not None else integ
    from wbplot.exact import motion
    exact_kind = motion(doc)[0]
    growth = predicted_growth(doc, [i[0] for i in integrators] + [integ])
    desc = sc.description or f"Scene {sc.name}."

    # The scene as shipped: trajectory and energy.
    trace, stats = base(out_dir, f"{stem}.csv"), base(out_dir, f"{stem}-stats.csv")
    s, why = solution_run(report, lab, exe,
                          recipes.run_argv(exe, scene_path, doc, trace, stats)[1:],
                          f"{scene_path}", args.timeout, save=base(out_dir, f"{stem}-summary.json"))
    sc.runs.append((f"{integ} (scene default)", s, why))
    if s is not None:
        fig = base(out_dir, f"{stem}-trajectory.png")
        summary = base(out_dir, f"{stem}-summary.json")  # what the figures say of the run
        a = ["trace", trace, "-o", fig, "--title", f"{sc.name}: trajectories ({setting})",
             "--summary", summary]
        if exact_kind:
            a += ["--exact", scene_path]
        if plot(report, lab, a):
            sc.figures.append((fig, f"{desc} Trajectories in the x-y plane, {setting}: "
                               "open circles are the starts, dots the ends"
                               + (f"; dashed, the exact motion ({exact_kind})." if exact_kind
                                  else "."), a))
        fig = base(out_dir, f"{stem}-energy.png")
        a = ["stats", stats, "-o", fig, "--title", f"{sc.name}: energy and momentum ({setting})",
             "--summary", summary, "--scene", scene_path]
        if integ in growth:
            a += ["--growth", f"{growth[integ]:.6g}"]
        a += diverged_step(s)
        blew = s.get("status") == "diverged"
        from wbplot.runs import energy_changers
        changes = energy_changers(doc)
        if plot(report, lab, a):
            sc.figures.append((fig, (
                f"The run diverged at step {s.get('steps')} ({s.get('diverged', '')}): |E|, "
                "|K|, |U| on a log scale up to that step, which the dotted line marks"
                + (f", beside the predicted growth ×{growth[integ]:.4g} per step "
                   f"({GROWTH_WHY})" if integ in growth else "") + ", and the momentum. "
                if blew else
                "Energy (total, kinetic, potential), E - E0 in J: the energy that "
                + ", ".join(changes) + " change on purpose (not an error), and momentum "
                "against time. " if changes else
                "Energy (total, kinetic, potential), the energy error |E - E0|/|E0| (or "
                "|E - E0| in J when E0 is 0 to rounding, as the panel says), and momentum "
                "against time: a closed conservative scene should keep its energy. ")
                + f"{setting}.", a))
        if not sec.integrators or len(sec.integrators) < 2:
            forcelaw_figure(report, sec, sc, scene_path, trace, out_dir)

    # Integration labs: each integrator on the scene (a lab with two or more of them, or a
    # sweep), then the sweep itself (only where --help offers --sweep).
    if not integrators or (len(integrators) < 2 and not sec.sweep):
        return
    names = [i[0] for i in integrators]

    # Each integrator on the scene as shipped.
    stats_files, traces, labels = [], {}, []
    for name in names:
        t = base(out_dir, f"{stem}-{name}.csv")
        st = base(out_dir, f"{stem}-{name}-stats.csv")
        s, why = solution_run(report, lab, exe,
                              recipes.run_argv(exe, scene_path, doc, t, st, name)[1:],
                              f"{scene_path} --integrator {name}", args.timeout,
                              save=base(out_dir, f"{stem}-{name}-summary.json"))
        sc.runs.append((name, s, why))
        if s is not None:
            stats_files.append(st)
            traces[name] = t
            labels.append(name)
    if stats_files:
        dt_s = f"dt = {fmt_dt(dt)} s" if dt is not None else "the scene's dt"
        fig = base(out_dir, f"{stem}-energy-compare.png")
        a = ["energy"] + stats_files + ["--labels", ",".join(labels), "-o", fig,
                                        "--title", f"{sc.name}: total energy by integrator ({dt_s})"]
        g = {n_: growth[n_] for n_ in labels if n_ in growth}
        if g:
            a += ["--growth", ",".join(f"{n_}={f:.6g}" for n_, f in g.items())]
        a += diverged_args([(r[0], r[1]) for r in sc.runs[1:] if r[0] in labels])
        diverged = [r[0] for r in sc.runs[1:] if r[1] and r[1].get("status") == "diverged"]
        if plot(report, lab, a):
            sc.figures.append((fig, f"Total energy against time for each integrator on "
                               f"{sc.name} at {dt_s}. " + (
                                   f"{', '.join(diverged)} diverged (docs/run-contract.md): "
                                   "the figure shows |E| on a log scale up to the step where "
                                   "each stopped (x, and a dotted line)"
                                   + (f", and the wide pale lines the predicted growth per "
                                      f"step ({GROWTH_WHY}) beside the measured one" if g
                                      else "") + ". " if diverged else "")
                               + "A curve drawn dashed with markers lies on top of another "
                               "(the legend says which).", a))
        e0 = [r[1].get("energy0") for r in sc.runs if r[1]]
        if any(isinstance(e, (int, float)) and e != 0 for e in e0):
            fig = base(out_dir, f"{stem}-energy-drift.png")
            a = ["energy"] + stats_files + ["--labels", ",".join(labels), "-o", fig,
                                            "--relative", "--title",
                                            f"{sc.name}: relative energy error by integrator ({dt_s})"]
            if plot(report, lab, a):
                sc.figures.append((fig, f"|E - E0|/|E0| on a log scale for each integrator on "
                                   f"{sc.name} at {dt_s} (|E - E0| in J when E0 is 0 to "
                                   "rounding, as the axis says): how fast each method's energy "
                                   "error grows. A curve drawn dashed with markers lies on top "
                                   "of another.", a))
        if exact_kind and traces:
            fig = base(out_dir, f"{stem}-trajectory-compare.png")
            a = (["paths"] + [traces[n_] for n_ in labels] + ["--labels", ",".join(labels),
                                                              "--exact", scene_path, "-o", fig,
                                                              "--title",
                                                              f"{sc.name}: each integrator "
                                                              f"against the exact motion ({dt_s})"])
            if plot(report, lab, a):
                sc.figures.append((fig, f"Each integrator's trajectory on {sc.name} at {dt_s}, "
                                   f"over the exact motion ({exact_kind}, dashed); the legend "
                                   "gives each run's final distance from it. The view is the "
                                   "exact motion's: a run that leaves it has left the exact "
                                   "motion far behind.", a))

    osc = oscillator(doc)
    if osc and traces:
        hw, zeta, anchor, linear = osc
        pair = [n_ for n_ in ("explicit-euler", "symplectic-euler") if n_ in traces]
        chosen = pair if len(pair) == 2 else [n_ for n_ in names if n_ in traces]
        axis = phase_axis(doc, anchor)
        fig = base(out_dir, f"{stem}-phase.png")
        a = ["phase"] + [traces[c] for c in chosen] + ["--labels", ",".join(chosen), "--id", "0",
                                                       "--axis", axis, "-o", fig, "--title",
                                                       f"{sc.name}: phase portrait (hω = {hw:.3g})"]
        if plot(report, lab, a):
            if linear and zeta == 0:
                what = ("The exact motion of this undamped linear oscillator is a closed "
                        "ellipse; a spiral outwards means energy is created, inwards that it "
                        "is destroyed.")
            elif linear:
                what = (f"The exact motion of this damped linear oscillator (ζ = {zeta:.3g}) "
                        "spirals inwards towards the anchor.")
            else:
                what = ("The spring has a rest length or gravity acts too, so the motion is a "
                        "nonlinear (elastic) pendulum: the exact curve is neither an ellipse "
                        "nor closed; hω is that of the spring alone.")
            sc.figures.append((fig, f"Phase portrait ({axis} against v{axis}) of the particle, "
                               f"{', '.join(chosen)}, at hω = {hw:.3g}. " + what, a))
        fig = base(out_dir, f"{stem}-stability.png")
        a = ["stability", "-o", fig, "--mark", f"{hw:.6g}",
             "--title", f"Stability regions and the {sc.name} scene (hω = {hw:.3g})"]
        if zeta > 0:
            a += ["--damping", f"{zeta:.6g}"]
        if plot(report, lab, a):
            zt = f", damping ratio ζ = {zeta:.3g}" if zeta > 0 else ""
            sc.figures.append((fig, f"Regions of absolute stability |R(z)| ≤ 1 in the plane "
                               f"z = hλ, with the {sc.name} scene's eigenvalues marked "
                               f"(hω = dt·√(k/m) = {hw:.3g}{zt}). A method is stable on the "
                               "scene when its marks lie inside its region; the legend gives "
                               "|R| - 1 at the marks (> 0: the amplitude grows every step).", a))

    # The sweep: work-precision, convergence, energy error, cheapest method.
    if not sec.sweep:
        return
    sw = base(out_dir, f"{stem}-sweep.csv")
    argv, ladder_why = recipes.sweep_argv(exe, scene_path, doc, sec.help_text, sw,
                                          repeats=args.repeats)
    timing = (f" Wall time is the least of {args.repeats} timed runs of each step loop (a "
              "single run zig-zags with the machine's load); force evaluations do not "
              "depend on the machine." if offers(sec.help_text, "--repeats") else "")
    argv = argv[1:]
    t0 = time.monotonic()
    s, why = solution_run(report, lab, exe, argv, f"{scene_path} --sweep", args.sweep_timeout)
    log(f"report: {lab}/{stem} sweep took {time.monotonic() - t0:.1f} s")
    if s is None:
        sc.runs.append(("sweep", None, why))
        return
    if not os.path.exists(sw):
        report.fail(f"{lab}: {scene_path} --sweep: exit status 0 but {rel(sw)} was not written")
        return
    prefix = base(out_dir, f"{stem}-sweep")
    scale = length_scale(doc)
    a = ["sweep", sw, "-o", prefix, "--scale", f"{scale:.6g}"]
    try:
        scenes_in = wsweep.scenes_of(wsweep.read_sweep(sw))
    except InputError as e:
        report.fail(f"{lab}: {e}")
        return
    if len(scenes_in) > 1:
        a += ["--scene", sc.name if sc.name in scenes_in else scenes_in[0]]
    if plot(report, lab, a):
        sc.figures.append((prefix + "-work-precision.png",
                           f"Work-precision on {sc.name}: final position error against wall "
                           "time (left) and against force evaluations (right), one line per "
                           "integrator over the sweep's step sizes. Lower left is cheaper for "
                           "the same accuracy." + timing
                           + (f" Ladder: {ladder_why}." if ladder_why else ""), a))
        sc.figures.append((prefix + "-convergence.png",
                           f"Convergence on {sc.name}: final position error against dt, "
                           "log-log, with guide lines of slope 1, 2 and 4. The legend gives "
                           "each integrator's measured order: the least-squares slope over "
                           f"the filled points (errors between 1e-13 and 0.1 times the scene "
                           f"size {scale:.3g} m, past any rounding plateau; docs/report.md)."
                           + (" An x on the top edge is a run that diverged." if
                              isinstance(s.get("diverged"), int) and s["diverged"] > 0 else "")
                           + (f" Ladder: {ladder_why}." if ladder_why else ""), a))
        sc.figures.append((prefix + "-energy-error.png",
                           f"Largest relative energy error over the run against dt on "
                           f"{sc.name}.", a))
        try:
            got = wsweep.orders(sw, a[a.index("--scene") + 1] if "--scene" in a else None,
                                scale)
            rows = ["| integrator | nominal order | measured order | points used |",
                    "|---|---|---|---|"]
            nominal = {i[0]: i[1] for i in integrators}
            for name, (order, pts) in got.items():
                rows.append(f"| {name} | {nominal.get(name, '?')} | "
                            f"{'n/a' if order is None else f'{order:.2f}'} | {len(pts)} |")
            sc.tables.append(("Measured order (convergence figure)", "\n".join(rows) + "\n"))
        except InputError as e:
            report.fail(f"{lab}: {e}")
    md = base(out_dir, f"{stem}-cheapest.md")
    a = ["cheapest", sw, "--targets", TARGETS, "--md", md]
    if plot(report, lab, a):
        with open(md, encoding="utf-8") as f:
            sc.tables.append(("Cheapest run reaching each target error (final position error)",
                              f.read()))


GROWTH_WHY = ("the oscillator's amplification: |R(i hω)|² per step from the spring's hω; "
              "explicit Euler 1 + (hω)², midpoint and trapezoid 1 + (hω)⁴/4, semi-implicit "
              "Euler its step matrix's larger eigenvalue squared above hω = 2")


def predicted_growth(doc, names):
    """{integrator: predicted energy factor per step} on a one-spring oscillator scene whose
    run grows (undamped), for the integrators with a known amplification factor."""
    osc = oscillator(doc)
    if not osc or osc[1] > 0:
        return {}
    z = osc[0]
    out = {}
    for n in names:
        if n == "explicit-euler":
            out[n] = 1 + z * z
        elif n in ("midpoint", "trapezoid"):
            out[n] = 1 + z ** 4 / 4
        elif n == "rk4":
            r = complex(1, 0) + 1j * z + (1j * z) ** 2 / 2 + (1j * z) ** 3 / 6 + (1j * z) ** 4 / 24
            if abs(r) > 1:
                out[n] = abs(r) ** 2
        elif n == "symplectic-euler" and z > 2:
            b = 2 - z * z
            out[n] = ((-b + math.sqrt(b * b - 4)) / 2) ** 2
    return out


def forcelaw_figure(report, sec, sc, scene_path, trace, out_dir):
    """A picture of the scene's force laws (vortex, spring, attractor), for the labs that
    write forces rather than integrators."""
    kinds = {f.get("type") for f in sc.doc.get("forces", []) or [] if isinstance(f, dict)}
    if not kinds & {"vortex", "spring", "attractor"}:
        return
    fig = base(out_dir, f"{sc.stem}-forcelaw.png")
    a = ["forcelaw", scene_path, "--trace", trace, "-o", fig]
    laws = [what for kind, what in (
        ("vortex", "the vortex's swirl speed against the distance from its centre"),
        ("spring", "each spring's force against its stretch"),
        ("attractor", "the attractor's pull against distance")) if kind in kinds]
    if plot(report, sec.lab, a):
        sc.figures.append((fig, f"The force law{'s' if len(laws) > 1 else ''} of {sc.name}, "
                           "from the scene's parameters (lines), with where the run's "
                           "particles sit on them at its last written step (dots): "
                           + "; ".join(laws) + ".", a))


def phase_axis(doc, anchor):
    """x or y: the axis along which the particle starts farther from the anchor."""
    try:
        x0 = doc["particles"][0]["x"]
        dx, dy = abs(float(x0[0]) - float(anchor[0])), abs(float(x0[1]) - float(anchor[1]))
    except (KeyError, IndexError, TypeError, ValueError):
        return "x"
    return "y" if dy > dx else "x"


# ----------------------------------------------------------------------------
# Writing index.md and index.html


def summary_table(sc):
    rows = ["| run | status | steps | t (s) | energy0 (J) | energy (J) | force_evals | wall (s) "
            "| viewer |", "|---|---|---|---|---|---|---|---|---|"]
    for label, s, why in sc.runs:
        if s is None:
            rows.append(f"| {label} | FAILED: {why} | | | | | | | |")
        elif "sweep" in s:  # a sweep's summary: how many runs, how many diverged
            rows.append(f"| {label} | {s.get('status', '?')}: {fmt(s.get('runs'))} runs, "
                        f"{fmt(s.get('diverged'))} diverged | | | | | | | |")
        elif s:
            rows.append("| " + " | ".join([
                label, str(s.get("status", "?")), fmt(s.get("steps")), fmt(s.get("t")),
                fmt(s.get("energy0"), 10), fmt(s.get("energy"), 10), fmt(s.get("force_evals")),
                fmt(s.get("wall_s"), 3),
                f"[play]({s['_view']})" if s.get("_view") else ""]) + " |")
    return "\n".join(rows) + "\n"


def write_markdown(report, path, elapsed):
    out = ["# Workbook report", ""]
    out.append(f"Generated by `tools/report` in {elapsed:.0f} s. Figures and CSV files are in "
               f"`{rel(report.out_dir)}/<lab>/`; every figure can be regenerated with the "
               "`tools/plot` command shown under it (docs/report.md).")
    out.append("")
    if report.failures:
        out += ["## Failures", ""] + [f"- {f}" for f in report.failures] + [""]
    for sec in report.labs:
        out += [f"## Lab `{sec.lab}`", ""]
        if sec.earlier:
            out += [f"(Kept from the report of {sec.earlier}: this run did not redo this lab.)",
                    ""]
        if sec.status:
            out += [f"Skipped: {sec.status}.", ""]
            continue
        if sec.integrators:
            out += ["Integrators: " + ", ".join(f"`{n}` (order {o})" for n, o, _ in sec.integrators)
                    + ".", ""]
        for sc in sec.scenes:
            out += [f"### {sc.name}", ""]
            if sc.description:
                out += [sc.description, ""]
            out += [summary_table(sc)]
            for title, table in sc.tables:
                out += [f"**{title}**", "", table]
            for fig, caption, args in sc.figures:
                r = os.path.relpath(fig, report.out_dir)
                out += [f"![{sc.name}]({r})", "", f"*{caption}*", "",
                        "`tools/plot " + " ".join(shlex.quote(rel(a) if os.path.isabs(a) else a)
                                                  for a in args) + "`", ""]
    write_text_atomic(path, "\n".join(out))


def md_table_to_html(table):
    lines = [ln for ln in table.strip().splitlines() if ln.strip()]
    if len(lines) < 2:
        return ""
    cells = [[re.sub(r"\[([^\]]+)\]\(([^)\s]+)\)", r'<a href="\2">\1</a>', html.escape(c.strip()))
              for c in ln.strip().strip("|").split("|")] for ln in lines]
    head, body = cells[0], cells[2:]
    h = "<table><thead><tr>" + "".join(f"<th>{c}</th>" for c in head) + "</tr></thead><tbody>"
    for row in body:
        cls = ' class="bad"' if any(c.startswith("FAILED") for c in row) else ""
        h += f"<tr{cls}>" + "".join(f"<td>{c}</td>" for c in row) + "</tr>"
    return h + "</tbody></table>"


CSS = """body{font-family:sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;color:#222}
h2{border-bottom:2px solid #ccc;padding-bottom:.2em;margin-top:2em}
table{border-collapse:collapse;margin:.5em 0 1em;font-size:90%}
td,th{border:1px solid #ccc;padding:.25em .6em;text-align:left}th{background:#f0f0f0}
tr.bad td{background:#fdd}figure{margin:1.2em 0 2em}figure img{max-width:100%;border:1px solid #eee}
figcaption{font-size:92%;color:#333;margin-top:.3em}code{font-size:85%;color:#555;word-break:break-all}
.fail{background:#fdd;padding:.5em 1em;border-left:4px solid #c00}"""


def write_html(report, path, elapsed):
    e = html.escape
    out = ["<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8">',
           "<title>Workbook report</title>", f"<style>{CSS}</style></head><body>",
           "<h1>Workbook report</h1>",
           f"<p>Generated by <code>tools/report</code> in {elapsed:.0f} s. Every figure can be "
           "regenerated with the <code>tools/plot</code> command under it (docs/report.md).</p>"]
    if report.failures:
        out.append('<div class="fail"><b>Failures</b><ul>'
                   + "".join(f"<li>{e(f)}</li>" for f in report.failures) + "</ul></div>")
    out.append(live_links_html(report))
    out.append("<ul>" + "".join(f'<li><a href="#{e(s.lab)}">{e(s.lab)}</a>'
                                + (f" (skipped: {e(s.status)})" if s.status else "") + "</li>"
                                for s in report.labs) + "</ul>")
    for sec in report.labs:
        out.append(f'<h2 id="{e(sec.lab)}">Lab {e(sec.lab)}</h2>')
        if sec.earlier:
            out.append(f"<p><i>Kept from the report of {e(sec.earlier)}: this run did not redo "
                       "this lab.</i></p>")
        if sec.status:
            out.append(f"<p>Skipped: {e(sec.status)}.</p>")
            continue
        if sec.integrators:
            out.append("<p>Integrators: " + ", ".join(f"<code>{e(n)}</code> (order {o})"
                                                      for n, o, _ in sec.integrators) + ".</p>")
        for sc in sec.scenes:
            out.append(f'<h3 id="{e(sec.lab)}-{e(sc.stem)}">{e(sc.name)}</h3>')
            if sc.description:
                out.append(f"<p>{e(sc.description)}</p>")
            out.append(md_table_to_html(summary_table(sc)))
            for title, table in sc.tables:
                out.append(f"<p><b>{e(title)}</b></p>" + md_table_to_html(table))
            for fig, caption, args in sc.figures:
                r = os.path.relpath(fig, report.out_dir)
                cmd = "tools/plot " + " ".join(shlex.quote(rel(a) if os.path.isabs(a) else a)
                                               for a in args)
                out.append(f'<figure><img src="{e(r)}" alt="{e(caption)}"><figcaption>'
                           f"{e(caption)}<br><code>{e(cmd)}</code></figcaption></figure>")
    out.append("</body></html>\n")
    write_text_atomic(path, "\n".join(out))


# ----------------------------------------------------------------------------


def live_pages(report, labs, build_dir):
    """A live page per lab, built from the solutions (docs/live.md), linked from the index:
    only where emscripten is installed (it is optional); else the index says so."""
    sys.path.insert(0, os.path.join(ROOT, "tools"))
    from wbview.live import build as livebuild, cli as livecli
    report.live = {}
    if not livebuild.have_emscripten():
        report.live_note = livebuild.MISSING
        log(f"report: live pages not built: {livebuild.MISSING}")
        return
    os.makedirs(os.path.join(report.out_dir, "live"), exist_ok=True)
    for lab in labs:
        out = os.path.join(report.out_dir, "live", f"{lab}.html")
        t0 = time.monotonic()
        try:
            livecli.make_page(lab, "solution", out, os.path.join(build_dir, "live"))
        except livebuild.BuildError as e:
            report.fail(f"{lab}: the live page could not be built: {e}")
            continue
        report.live[lab] = os.path.relpath(out, report.out_dir)
        log(f"report: {lab}: live page {rel(out)} ({time.monotonic() - t0:.0f} s)")


def live_links_html(report):
    e = html.escape
    if report.live:
        return ("<p>Live pages, built from the solutions (docs/live.md): the lab's C++ in "
                "WebAssembly, stepping in the browser while you turn h, the integrator and the "
                "scene's numbers: " + ", ".join(f'<a href="{e(p)}">{e(lab)}</a>'
                                               for lab, p in report.live.items()) + ".</p>")
    return f"<p>Live pages: not built ({e(report.live_note)}).</p>" if report.live_note else ""


def check_claims(report):
    """The claims of the handouts and scene descriptions (docs/report.md, Claims) against
    this report's own runs: a contradicted claim is a failure of the report. Claims about a
    lab the report skipped are not checked here (tools/claims checks them all)."""
    import glob
    from wbplot import claims as wclaims
    done = {sec.lab for sec in report.labs if not sec.status}
    files = sorted(glob.glob(os.path.join(ROOT, "handouts", "*.md"))
                   + glob.glob(os.path.join(ROOT, "scenes", "*", "*.json")))
    try:
        found = [c for f in files for c in wclaims.find_claims(rel(f))]
        mine = [c for c in found if all(n[0] in done for n in wclaims.needs(c))
                and (c.measure[0] != "csv" or c.measure[1].split("/")[0] in done)]
        data = wclaims.Data(report.out_dir, os.path.join(ROOT, "scenes"))
        bad = [(c, why) for c, _, why in wclaims.check(mine, data) if why]
    except InputError as e:
        report.fail(f"claims: {e}")
        return
    for c, why in bad:
        report.fail(f"claim contradicted by this report: {c.where}: {c.body}: {why}")
    log(f"report: {len(mine) - len(bad)} of {len(mine)} claims hold (tools/claims)")


def main():
    p = argparse.ArgumentParser(
        prog="tools/report",
        description="The main job: runs tools/setup, builds with the default preset, runs "
                    "every lab's solution on its default scenes (and, for the integration "
                    "labs, every integrator and a sweep), draws the figures and writes "
                    "<build-dir>/report/index.html and index.md.",
        epilog="Exit status: 0 when every solution run exited 0 (a diverged run is a result), "
               "1 when a run or a figure failed, 2 for bad flags or a failed setup or build. "
               "See docs/report.md.")
    p.add_argument("--no-setup", action="store_true", help="skip tools/setup")
    p.add_argument("--no-build", action="store_true", help="skip configuring and building")
    p.add_argument("--no-live", action="store_true",
                   help="skip the live pages (docs/live.md; built only where em++ is installed)")
    p.add_argument("--build-dir", default="build",
                   help="build folder (default build, the default preset's); executables in "
                        "<build-dir>/bin, the report in <build-dir>/report")
    p.add_argument("--labs", help="comma-separated labs (default: every lab with a solution "
                                  "executable)")
    p.add_argument("--repeats", type=int, default=recipes.SWEEP_REPEATS,
                   help="--repeats passed to sweeps that offer it: wall_s is the least of "
                        f"that many timed runs (default {recipes.SWEEP_REPEATS})")
    p.add_argument("--timeout", type=float, default=300,
                   help="seconds allowed for one run (default 300)")
    p.add_argument("--sweep-timeout", type=float, default=600,
                   help="seconds allowed for one sweep (default 600)")
    try:
        args = p.parse_args()
    except SystemExit as e:
        return 2 if e.code else 0
    if args.repeats < 1:
        print(f"tools/report: error: --repeats: got {args.repeats}, expected a whole number >= 1",
              file=sys.stderr)
        return 2
    labs = lab_order()
    if args.labs:
        wanted = [s.strip() for s in args.labs.split(",") if s.strip()]
        unknown = [w for w in wanted if w not in labs]
        if unknown or not wanted:
            print(f"tools/report: error: --labs: unknown lab '{(unknown or [args.labs])[0]}', "
                  "expected some of " + ",".join(labs), file=sys.stderr)
            return 2
        labs = [lab for lab in labs if lab in wanted]
    start = time.monotonic()
    build_dir = os.path.abspath(os.path.join(ROOT, args.build_dir))
    # Taken before the build: the commit and the uncommitted edits the figures are drawn from.
    source = committed.source_stamp(ROOT)

    setup = os.path.join(ROOT, "tools", "setup")
    if not args.no_setup and os.path.exists(setup):
        log("+ tools/setup")
        if subprocess.run([setup], cwd=ROOT).returncode != 0:
            print("tools/report: error: tools/setup failed (see above); --no-setup skips it",
                  file=sys.stderr)
            return 2
    if not args.no_build:
        if os.path.abspath(os.path.join(ROOT, "build")) == build_dir:
            steps = [["cmake", "--preset", "default"],
                     ["cmake", "--build", "--preset", "default", "-j2"]]
        else:
            steps = [["cmake", "--preset", "default", "-B", build_dir],
                     ["cmake", "--build", build_dir, "-j2"]]
        for cmd in steps:
            log("+ " + " ".join(rel(c) if os.path.isabs(c) else c for c in cmd))
            if subprocess.run(cmd, cwd=ROOT).returncode != 0:
                print(f"tools/report: error: {' '.join(cmd)} failed (see above); --no-build "
                      "skips the build", file=sys.stderr)
                return 2
    bin_dir = os.path.join(build_dir, "bin")
    if not os.path.isdir(bin_dir):
        print(f"tools/report: error: --build-dir: {rel(bin_dir)} does not exist (build first, "
              "or drop --no-build)", file=sys.stderr)
        return 2

    report = Report(os.path.join(build_dir, "report"))
    report.source = source
    os.makedirs(report.out_dir, exist_ok=True)
    for lab in lab_order():
        if lab not in labs:
            # Not asked for (--labs): keep the section an earlier report saved.
            sec, fails = load_section(report, lab)
            if sec is not None:
                report.labs.append(sec)
                report.failures += fails
                log(f"report: {lab}: kept from the report of {sec.earlier}")
            continue
        t0 = time.monotonic()
        n_fail = len(report.failures)
        do_lab(report, lab, bin_dir, args)
        from wbplot import figcheck  # what the figures say and show (docs/report.md)
        for f in figcheck.check_section(report.labs[-1], report.facts):
            report.fail(f"figure: {f}")
        save_section(report, report.labs[-1], report.failures[n_fail:])
        log(f"report: {lab} done in {time.monotonic() - t0:.1f} s")
    check_claims(report)
    if not args.no_live:
        live_pages(report, labs, build_dir)
    elapsed = time.monotonic() - start
    md = os.path.join(report.out_dir, "index.md")
    index = os.path.join(report.out_dir, "index.html")
    write_markdown(report, md, elapsed)
    write_html(report, index, elapsed)
    cmds = "\n".join(f"[{lab}] {c}" for lab, c in report.commands) + "\n"
    write_text_atomic(os.path.join(report.out_dir, "commands.txt"), cmds)
    if report.failures:
        log(f"report: {len(report.failures)} failure(s):")
        for f in report.failures:
            log(f"  {f}")
    log(f"report: {rel(index)}")
    return 1 if report.failures else 0


def run():
    """The entry tools/report calls: main() with the command line, its exit status."""
    sys.exit(main())
