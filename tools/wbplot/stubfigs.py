"""tools/pattern stubfigs: a student's figure of a stub run says so on the figure.

For every lab (labs/<lab>/), the skeleton (build/bin/<lab>) runs the lab's first default
scene exactly as the student pack's README says (`--out out/run.csv --stats
out/run-stats.csv | tee out/run-summary.json`, here in build/pattern/stubfigs/<lab>/), and
each of the README's plot commands (the plug-in's PACK_PLOTS, else GENERIC_PLOTS) draws its
figure in-process; each must say "STUB" on the figure (figcheck.check_stub over the
figure's recorded words). A skeleton's run is a stub's by the workbook's own rule (every
skeleton warns on every default scene: the stubs stage), so the check holds for every lab,
present and future. Cost: one skeleton run and two figures per lab, a few seconds.
"""
import glob
import os
import shlex
import subprocess


def _plots(lab):
    import importlib
    plots = importlib.import_module("wbplot.labs").GENERIC_PLOTS
    try:
        mod = importlib.import_module(f"wbplot.labs.{lab}")
        plots = getattr(mod, "PACK_PLOTS", plots)
    except ImportError:
        pass
    return [cmd for cmd, _ in plots]


def stage(root, build, labs, timeout=300):
    """Findings (one line each) over every lab's README figures of its skeleton's run."""
    from . import cli, figcheck, figfacts
    findings = []
    for lab in labs:
        exe = os.path.join(build, "bin", lab)
        scenes = sorted(glob.glob(os.path.join(root, "scenes", lab, "*.json")))
        if not os.path.exists(exe) or not scenes:
            findings.append(f"{lab}: no skeleton ({os.path.relpath(exe, root)}) or no default "
                            "scene to draw")
            continue
        out = os.path.join(build, "pattern", "stubfigs", lab)
        os.makedirs(out, exist_ok=True)
        scene = os.path.relpath(scenes[0], root)
        run, stats = os.path.join(out, "run.csv"), os.path.join(out, "run-stats.csv")
        try:
            p = subprocess.run([exe, "--scene", scene, "--out", run, "--stats", stats], cwd=root,
                               capture_output=True, text=True, timeout=timeout)
        except subprocess.TimeoutExpired:
            findings.append(f"{lab}: the skeleton's run of {scene} timed out")
            continue
        with open(os.path.join(out, "run-summary.json"), "w", encoding="utf-8") as f:
            f.write(p.stdout)
        if p.returncode != 0:
            findings.append(f"{lab}: the skeleton's run of {scene} exited {p.returncode}")
            continue
        for cmd in _plots(lab):
            argv = shlex.split(cmd.replace("{scene}", scene).replace("out/", out + "/"))
            if argv[:1] != ["tools/plot"]:
                continue
            with figfacts.recording() as seen:
                import contextlib
                import io
                err = io.StringIO()
                with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
                    status = cli.main(argv[1:])
            if status != 0:
                findings.append(f"{lab}: `{cmd}` on the skeleton's run failed: "
                                f"{err.getvalue().strip()[:200]}")
                continue
            import json
            doc = json.load(open(os.path.join(root, scene), encoding="utf-8"))
            for facts in seen.values():
                # Every check of the report's figures, on a stub's run (what a student sees
                # first), the stub mark included.
                findings += [f"{lab}: {f} (`{cmd}`)" for f in figcheck.check_figure(
                    facts, diverged_runs=int('"status":"diverged"' in p.stdout), scene=doc,
                    stub=True)]
    return findings
