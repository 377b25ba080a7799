"""Checks every claim marker in the handouts and scene descriptions against the runs.

A claim (docs/report.md, "Claims") is an HTML comment after the sentence that states a
measured number or a direction, e.g. <!-- claim: order euler/oscillator explicit-euler in
[0.9, 1.1] -->. By default tools/claims runs, with the solution executables in
<build-dir>/bin, only the runs the claims need, with the very commands tools/report uses
(tools/wbplot/recipes.py), into <build-dir>/claims/; with --report it reads the data of the
last tools/report in <build-dir>/report/ instead and runs nothing.
Exit status: 0 every claim holds, 1 a claim is contradicted (or its run failed), 2 bad input
(a malformed claim, a missing executable, a bad flag)."""
import argparse
import glob
import json
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tools"))

from wbplot import claims as wclaims  # noqa: E402
from wbplot import recipes  # noqa: E402
from wbplot.common import InputError, summary_line  # noqa: E402


def rel(p):
    r = os.path.relpath(p, ROOT)
    return p if r.startswith("..") else r


def lab_plugin(lab):
    """tools/wbplot/labs/<lab>.py when the lab has one (it may define its own sweep_argv)."""
    import importlib
    if not os.path.exists(os.path.join(ROOT, "tools", "wbplot", "labs", f"{lab}.py")):
        return None
    return importlib.import_module(f"wbplot.labs.{lab}")
def claim_files(lab):
    """{file: make(exe, out_dir)}: the CSV files a lab plug-in can write for claims without
    the whole report (its CLAIM_FILES), else {}."""
    import importlib
    if not os.path.exists(os.path.join(ROOT, "tools", "wbplot", "labs", f"{lab}.py")):
        return {}
    return getattr(importlib.import_module(f"wbplot.labs.{lab}"), "CLAIM_FILES", {})


def produce(lab, stem, what, bin_dir, out_root, help_cache, verbose):
    """Runs what one claim needs; '' when done, else why not."""
    exe = os.path.join(bin_dir, f"{lab}-solution")
    if not os.path.exists(exe):
        raise InputError(f"{rel(exe)}: not built (a claim needs lab {lab}); build first")
    if what == "csv":  # a lab plug-in's file: made here when the plug-in offers it quickly
        out = os.path.join(out_root, lab)
        os.makedirs(out, exist_ok=True)
        make = claim_files(lab).get(stem)
        if make is None:
            return ""  # read from the last tools/report
        if verbose:
            print(f"+ {lab} plug-in: {stem}", flush=True)
        try:
            make(exe, out)
        except (RuntimeError, OSError) as e:
            return str(e)
        return ""
    scene = os.path.join("scenes", lab, stem + ".json")
    try:
        with open(os.path.join(ROOT, scene), encoding="utf-8") as f:
            doc = json.load(f)
    except (OSError, json.JSONDecodeError) as e:
        raise InputError(f"{scene}: cannot read ({e})") from None
    out = os.path.join(out_root, lab)
    os.makedirs(out, exist_ok=True)
    if exe not in help_cache:
        help_cache[exe] = subprocess.run([exe, "--help"], capture_output=True, text=True).stdout
    if what == "sweep":
        csv = os.path.join(out, f"{stem}-sweep.csv")
        plugin = lab_plugin(lab)
        if plugin is not None and hasattr(plugin, "sweep_argv"):
            argv = plugin.sweep_argv(exe, scene, doc, csv)  # the lab's own ladder (its figure's)
        else:
            argv, _ = recipes.sweep_argv(exe, scene, doc, help_cache[exe], csv, repeats=1)
        name = f"{stem}-sweep"
    else:
        name = f"{stem}-{what}" if what else stem
        argv = recipes.run_argv(exe, scene, doc, os.path.join(out, name + ".csv"),
                                os.path.join(out, name + "-stats.csv"), what)
    if verbose:
        print("+ " + " ".join(rel(a) if os.path.isabs(a) else a for a in argv), flush=True)
    p = subprocess.run(argv, cwd=ROOT, capture_output=True, text=True)
    if p.returncode != 0:
        return (p.stderr.strip().splitlines() or [f"exit status {p.returncode}"])[-1]
    s = summary_line(p.stdout)
    if s is not None:
        with open(os.path.join(out, name + "-summary.json"), "w", encoding="utf-8") as f:
            json.dump(s, f)
    return ""


def main():
    ap = argparse.ArgumentParser(prog="tools/claims", description=__doc__.split("\n\n")[0],
                                 epilog="docs/report.md, section Claims, lists the measures.")
    ap.add_argument("files", nargs="*", metavar="FILE",
                    help="Markdown or scene JSON files (default: handouts/*.md, scenes/*/*.json)")
    ap.add_argument("--build-dir", default="build", help="executables in DIR/bin (default build)")
    ap.add_argument("--report", action="store_true",
                    help="check against DIR/report (the last tools/report) without running")
    ap.add_argument("-v", "--verbose", action="store_true", help="print each run and claim")
    try:
        args = ap.parse_args()
    except SystemExit as e:
        return 2 if e.code else 0
    files = args.files or sorted(glob.glob(os.path.join(ROOT, "handouts", "*.md"))
                                 + glob.glob(os.path.join(ROOT, "scenes", "*", "*.json")))
    build = os.path.join(ROOT, args.build_dir)
    data_root = os.path.join(build, "report" if args.report else "claims")
    t0 = time.monotonic()
    try:
        found = [c for f in files for c in wclaims.find_claims(rel(os.path.abspath(f)))]
        runs = []
        for c in found:
            for n in wclaims.needs(c):
                if n not in runs:
                    runs.append(n)
        failed_runs = {}
        if not args.report:
            help_cache = {}
            for lab, stem, what in runs:
                why = produce(lab, stem, what, os.path.join(build, "bin"), data_root,
                              help_cache, args.verbose)
                if why:
                    failed_runs[(lab, stem, what)] = why
        data = wclaims.Data(data_root, os.path.join(ROOT, "scenes"),
                            os.path.join(build, "report"))
        bad = 0
        for c, got, why in wclaims.check(found, data, failed_runs):
            if why:
                bad += 1
                print(f"{c.where}: CONTRADICTED: {c.body}: {why}")
            elif args.verbose:
                shown = f"{got:.6g}" if isinstance(got, float) else got
                print(f"{c.where}: ok: {c.body} (measured {shown})")
    except InputError as e:
        print(f"tools/claims: error: {e}", file=sys.stderr)
        return 2
    print(f"claims: {len(found) - bad} of {len(found)} hold ({len(runs)} runs, "
          f"{time.monotonic() - t0:.1f} s)")
    return 1 if bad else 0


def run():
    """The entry tools/claims calls: main() with the command line, its exit status."""
    sys.exit(main())
