#!/usr/bin/python3
"""Cost per simulated second of the implicit lab's integrators, by the executable's own timing.

Runs build/bin/implicit-solution on a generated rope (N beads) and cloth (side x side), k/m of
every spring 1e6 as in scenes/implicit/stiff-rope.json, for T simulated seconds:
semi-implicit Euler at its largest stable step (searched: c / sqrt(k/m), c from 1.1 down; the
largest whose run of 5 s keeps the energy within 1 % of M g L), and backward Euler at
h = 1/60 s: one solve (baraff-witkin-fast), Newton to the default tolerance
(backward-euler-fast), both by the provided fast path, and the lab's own one-solve step
(baraff-witkin; on the cloth by CG to 1e-2 of the momenta, the scene's "newton" key). The
methods run in interleaved rounds (one run of each per round); each ratio is taken within a
round, then the median over rounds is reported, with the load average before each round. Each
run's time: its summary's wall_s and cpu_s (the step loop's CPU time, by the run's own clock:
the steadier figure on a loaded machine, and the one the ratios use), and the process's CPU time
minus that of a one-step run of the same scene (loop_cpu_s). With --sweep, also the rope's cost
against k/m (the crossover). With --exe-before, another build's semi-implicit Euler and lab step
run in the same rounds too, on the scenes without the cloth's "newton" key (its lab step as it
was measured before), each ratio taken against that build's own semi-implicit Euler.
docs/benchmarks.md, ## implicit, tables the result."""
import argparse
import json
import math
import os
import platform
import resource
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tools"))
from wbplot.labs import implicit as plug  # noqa: E402

def cpu():
    """CPU time (user + system) of this process's finished children (s)."""
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


METHODS = ["symplectic-euler", "baraff-witkin-fast", "backward-euler-fast", "baraff-witkin"]
BEFORE = ["symplectic-euler (before)", "baraff-witkin (before)"]  # --exe-before's runs


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "bin", "implicit-solution"))
    ap.add_argument("--out", required=True, help="JSON file to write")
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--rope", type=int, default=10000, help="beads of the rope")
    ap.add_argument("--cloth", type=int, default=100, help="side of the cloth")
    ap.add_argument("--t-end", type=float, default=1.0)
    ap.add_argument("--km", type=float, default=1e6)
    ap.add_argument("--lab-rounds", type=int, default=None,
                    help="rounds that also run the lab's own baraff-witkin (default: all)")
    ap.add_argument("--no-lab-cloth", action="store_true",
                    help="leave the lab's own step out on the cloth")
    ap.add_argument("--sweep", action="store_true", help="also the rope's cost against k/m")
    ap.add_argument("--only", choices=["rope", "cloth"])
    ap.add_argument("--exe-before", help="another build of implicit-solution whose semi-implicit "
                    "Euler and baraff-witkin run in the same rounds (before/after)")
    ap.add_argument("--before-lab-rounds", type=int, default=None,
                    help="rounds that run --exe-before's baraff-witkin (default: all)")
    args = ap.parse_args()
    if not os.path.exists(args.exe):
        print(f"implicit_per_second: {args.exe}: not built", file=sys.stderr)
        return 2
    tmp = tempfile.mkdtemp(prefix="wb-implicit-cost-")
    result = {"host": platform.node(), "nproc": os.cpu_count(),
              "started": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
              "exe": os.path.relpath(args.exe, ROOT), "km": args.km, "t_end": args.t_end,
              "cases": {}}
    cases = [("rope", args.rope, False), ("cloth", args.cloth ** 2, True)]
    for name, n, cloth in cases:
        if args.only and name != args.only:
            continue
        scene = os.path.join(tmp, f"{name}.json")
        doc = plug.cost_scene(n, args.km, args.t_end, cloth)
        with open(scene, "w", encoding="utf-8") as f:
            json.dump(doc, f)
        # The build before: the same network without the lab's solver choice (its defaults).
        scene_before = os.path.join(tmp, f"{name}-before.json")
        doc.pop("newton", None)
        with open(scene_before, "w", encoding="utf-8") as f:
            json.dump(doc, f)
        side = int(round(math.sqrt(n)))
        length = 0.05 * ((side if cloth else n) - 1)
        mgl = n * 0.01 * 9.81 * length
        se_dt = plug._se_limit(args.exe, scene, args.km, mgl, None)
        case = {"n": n, "se_dt": se_dt, "se_search": f"largest of c/sqrt(k/m) stable for "
                f"{plug.COST_SEARCH_T} s (|dE| <= 0.01 M g L)", "rounds": []}
        for r in range(args.rounds):
            rnd = {"loadavg": list(os.getloadavg())}
            # The CPU time of a run with one step: loading and building the scene, which
            # every run pays outside its step loop (wall_s leaves it out).
            c0 = cpu()
            plug._run(args.exe, scene, "symplectic-euler", se_dt, se_dt, 1, None)
            rnd["setup_cpu_s"] = cpu() - c0
            for m in METHODS:
                if m == "baraff-witkin" and ((args.lab_rounds is not None and r >= args.lab_rounds)
                                             or (cloth and args.no_lab_cloth)):
                    continue
                dt = se_dt if m == "symplectic-euler" else plug.COST_FRAME
                c0 = cpu()
                s = plug._run(args.exe, scene, m, dt, args.t_end, 1, None)
                rnd[m] = {"dt": dt, "wall_s": s.get("wall_s"), "status": s.get("status"),
                          "steps": s.get("steps"), "energy0": s.get("energy0"),
                          "energy": s.get("energy"), "cpu_s": s.get("cpu_s"),
                          "loop_cpu_s": cpu() - c0 - rnd["setup_cpu_s"]}
            if args.exe_before:
                c0 = cpu()
                plug._run(args.exe_before, scene_before, "symplectic-euler", se_dt, se_dt, 1,
                          None)
                setup_before = cpu() - c0
                for m in BEFORE:
                    if m == "baraff-witkin (before)" and args.before_lab_rounds is not None \
                            and r >= args.before_lab_rounds:
                        continue
                    meth = m.split(" ")[0]
                    dt = se_dt if meth == "symplectic-euler" else plug.COST_FRAME
                    c0 = cpu()
                    s = plug._run(args.exe_before, scene_before, meth, dt, args.t_end, 1, None)
                    rnd[m] = {"dt": dt, "wall_s": s.get("wall_s"), "status": s.get("status"),
                              "steps": s.get("steps"), "energy0": s.get("energy0"),
                              "energy": s.get("energy"), "cpu_s": s.get("cpu_s"),
                              "loop_cpu_s": cpu() - c0 - setup_before}
            se = rnd["symplectic-euler"]["wall_s"]
            rnd["vs_se"] = {m: rnd[m]["wall_s"] / se for m in METHODS if m in rnd}
            # The step loop's CPU time, by the run's own clock (the summary's cpu_s).
            se_cpu = rnd["symplectic-euler"]["cpu_s"]
            rnd["cpu_vs_se"] = {m: rnd[m]["cpu_s"] / se_cpu for m in METHODS if m in rnd}
            if "baraff-witkin (before)" in rnd:
                b = rnd["symplectic-euler (before)"]
                rnd["vs_se"]["baraff-witkin (before)"] = (
                    rnd["baraff-witkin (before)"]["wall_s"] / b["wall_s"])
                rnd["cpu_vs_se"]["baraff-witkin (before)"] = (
                    rnd["baraff-witkin (before)"]["cpu_s"] / b["cpu_s"])
            case["rounds"].append(rnd)
            print(f"{name} round {r + 1}: load {rnd['loadavg'][0]:.1f}: "
                  + ", ".join(f"{m} {rnd[m]['wall_s']:.3f} s ({rnd[m]['cpu_s']:.3f} cpu)"
                              for m in METHODS + BEFORE if m in rnd), flush=True)
        ran = [m for m in METHODS + BEFORE[1:] if any(m in x["vs_se"] for x in case["rounds"])]
        case["median_vs_se"] = {
            m: statistics.median(x["vs_se"][m] for x in case["rounds"] if m in x["vs_se"])
            for m in ran}
        case["median_cpu_vs_se"] = {
            m: statistics.median(x["cpu_vs_se"][m] for x in case["rounds"] if m in x["cpu_vs_se"])
            for m in ran}
        case["max_vs_se"] = {
            m: max(x["vs_se"][m] for x in case["rounds"] if m in x["vs_se"]) for m in ran}
        result["cases"][name] = case
        print(f"{name}: median cost / semi-implicit Euler's (wall_s): "
              + ", ".join(f"{m} {v:.3g}" for m, v in case["median_vs_se"].items())
              + "; (CPU of the step loop): "
              + ", ".join(f"{m} {v:.3g}" for m, v in case["median_cpu_vs_se"].items()),
              flush=True)
    if args.sweep:
        rows = plug.cost_sweep(args.exe, tmp, beads=args.rope, kms=[1e3, 1e4, 1e5, 1e6, 1e7],
                               t_end=args.t_end, repeats=3,
                               methods=["symplectic-euler", "baraff-witkin-fast",
                                        "backward-euler-fast", "baraff-witkin"])
        result["sweep"] = rows
        for r in rows:
            if r["km"] == "crossover":
                print(f"rope of {args.rope}: {r['method']} crosses semi-implicit Euler at "
                      f"k/m = {r['km_value']:.3g}")
    result["finished"] = time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())
    result["loadavg_end"] = list(os.getloadavg())
    with open(args.out, "w", encoding="utf-8") as f:
        json.dump(result, f, indent=1, default=lambda v: None if isinstance(v, float) and
                  not math.isfinite(v) else v)
        f.write("\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
