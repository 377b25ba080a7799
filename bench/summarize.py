#!/usr/bin/env -S sh -c 'exec "${0%/*}/../tools/lib/start-python" "$0" "$@"'
"""Summarize a bench_integrators JSON run as a table of throughputs and ratios to its baselines."""
import argparse
import json
import math
import os
import statistics
import sys
import tempfile

TIME_UNITS = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}
# odeint: Boost.Odeint's runge_kutta4 on the machinery's dynamics; odeint_fused: a plain
# runge_kutta4_classic program with a fused right-hand side; run: a whole wb::simulate,
# timed per step by its own step-loop clock (counters step_loop_cpu_s, step_loop_wall_s)
# blocks_nosums: rk4 by blocks without the bookkeeping's sums; bookkeeping: steps without and
# with the bookkeeping taken alternately, its counter `share` the paired share (issue 34)
KINDS = ("scene", "hand_passes", "hand_fused", "odeint", "odeint_fused", "run", "blocks_nosums",
         "bookkeeping")
SINGLE = ("triad_dram", "triad_fit", "loop_check", "loop_check_separate")  # <kind>/<n>
BOOKKEEPING_TARGET = 0.05  # issue 34: the loop's bookkeeping at most 5 % of the step loop
TARGET_RATIO = 1.1  # issue target for scene / hand_passes at 10^6 particles

COLUMNS = [
    ("integrator", "integrator", "{}"),
    ("n", "n", "{}"),
    ("Mpsteps_per_s", "M particle-steps/s", "{:.1f}"),
    ("ns_per_psteps", "ns/particle-step", "{:.2f}"),
    ("vs_hand_passes", "/hand passes", "{:.3f}"),
    ("vs_hand_passes_best", "best/best", "{:.3f}"),
    ("vs_hand_passes_min", "(min", "{:.3f}"),
    ("vs_hand_passes_max", "max)", "{:.3f}"),
    ("vs_hand_fused", "/hand fused", "{:.2f}"),
    ("vs_dram_bound", "/DRAM bound", "{:.2f}"),
    ("vs_fit_bound", "/fit bound", "{:.2f}"),
    ("fused_vs_dram_bound", "fused/DRAM bound", "{:.2f}"),
    ("allocs_per_step", "allocs/step", "{:g}"),
    ("spread_pct", "spread %", "{:.1f}"),
]


class BadInput(Exception):
    pass


def parse_args():
    p = argparse.ArgumentParser(
        description="Read the --benchmark_format=json output of bench_integrators and print, "
        "for every integrator and particle count: particle-steps per second through the scene "
        "machinery, the time ratio to the hand-written loop doing the same passes, to the fused "
        "hand loop, to the memory-bandwidth bound (72 bytes per particle-step at the STREAM "
        "triad bandwidth measured in the same run, on arrays beyond the caches and on arrays of "
        "the step's own footprint), and heap allocations per step. Ratios are times: above 1 "
        "means the scene machinery is slower. With repetitions, every figure is the median of "
        "the repetitions, 'best/best' is the same ratio between the fastest repetitions, "
        "'(min max)' is the range of scene / hand passes over the repetitions "
        "(each paired with the hand repetition of the same index), and 'spread %' is "
        "(max - min) / median of the scene benchmark's repetitions. "
        "Exit status: 0, 1 when the run recorded a failure (an allocating step, an error), "
        "2 on bad input.")
    p.add_argument("json_file", help="bench_integrators --benchmark_format=json output ('-' for stdin)")
    p.add_argument("--time", choices=("cpu", "real"), default="cpu",
                   help="which time to use: cpu (default; robust when other processes share the "
                   "cores) or real (wall clock)")
    p.add_argument("--csv", metavar="PATH", help="also write the table as CSV to PATH")
    return p.parse_args()


def load(path):
    try:
        if path == "-":
            return json.load(sys.stdin)
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except OSError as e:
        raise BadInput(f"{path}: cannot read: {e.strerror}")
    except json.JSONDecodeError as e:
        raise BadInput(f"{path}: not JSON (line {e.lineno}, column {e.colno}: {e.msg}); "
                       "expected the output of bench_integrators --benchmark_format=json")


def split_name(path, i, name):
    """'scene/rk4/1000' -> ('scene', 'rk4', 1000); 'triad_dram/33554432' -> ('triad_dram', None, len)."""
    # drop min_time:, repeats:, ..., and manual_time (bookkeeping/ is timed by hand)
    parts = [p for p in name.split("/") if ":" not in p and p != "manual_time"]
    try:
        if parts[0] in SINGLE and len(parts) == 2:
            return parts[0], None, int(parts[1])
        if parts[0] in KINDS and len(parts) == 3:
            return parts[0], parts[1], int(parts[2])
    except ValueError:
        pass
    raise BadInput(f"{path}: benchmarks[{i}].run_name is {name!r}; expected "
                   f"<{'|'.join(KINDS)}>/<integrator>/<n> or <{'|'.join(SINGLE)}>/<n>")


def collect(doc, path, time_key):
    """Per benchmark: the list of repetition times (s), and the recorded failures."""
    if not isinstance(doc, dict) or not isinstance(doc.get("benchmarks"), list):
        raise BadInput(f"{path}: no \"benchmarks\" list at the top level; expected the output of "
                       "bench_integrators --benchmark_format=json")
    runs, medians, allocs, failures = {}, {}, {}, []
    shares = {}  # bookkeeping/<integrator>/<n>: the paired share of every repetition
    order = {}  # integrator -> position of its first benchmark (the program's teaching order)
    for i, b in enumerate(doc["benchmarks"]):
        if not isinstance(b, dict):
            raise BadInput(f"{path}: benchmarks[{i}] is not an object")
        name = b.get("run_name", b.get("name"))
        if not isinstance(name, str):
            raise BadInput(f"{path}: benchmarks[{i}] has no string \"run_name\"")
        key = split_name(path, i, name)
        if key[1] is not None:
            order.setdefault(key[1], len(order))
        if b.get("error_occurred"):
            failures.append(f"{name}: {b.get('error_message', 'error')}")
            continue
        run_type = b.get("run_type", "iteration")
        if run_type == "aggregate" and b.get("aggregate_name") != "median":
            continue
        if key[0] == "bookkeeping":
            share = b.get("share")
            if not isinstance(share, (int, float)) or not math.isfinite(share):
                raise BadInput(f"{path}: benchmarks[{i}] ({name}): share={share!r}; expected "
                               "a number")
            if run_type != "aggregate":
                shares.setdefault(key, []).append(float(share))
            continue
        t = b.get(time_key)
        unit = b.get("time_unit", "ns")
        if key[0] == "run":  # its own clock, per step, in seconds
            t = b.get("step_loop_cpu_s" if time_key == "cpu_time" else "step_loop_wall_s")
            unit = "s"
        if not isinstance(t, (int, float)) or unit not in TIME_UNITS or not t > 0:
            raise BadInput(f"{path}: benchmarks[{i}] ({name}): {time_key}={t!r}, "
                           f"time_unit={unit!r}; expected a positive time in ns, us, ms or s")
        seconds = t * TIME_UNITS[unit]
        if run_type == "aggregate":
            medians[key] = seconds
        else:
            rep = b.get("repetition_index", len(runs.get(key, {})))
            runs.setdefault(key, {})[rep] = seconds
        a = b.get("allocs_per_step")
        if isinstance(a, (int, float)):
            allocs[key] = max(allocs.get(key, 0.0), float(a))
    times = {}
    for key in set(runs) | set(medians):
        reps = list(runs.get(key, {}).values())
        med = statistics.median(reps) if reps else medians[key]
        spread = (max(reps) - min(reps)) / med if len(reps) > 1 else math.nan
        times[key] = (med, spread, runs.get(key, {}))
    return times, allocs, failures, order, shares


def best(entry):
    """The fastest repetition (noise from other processes only ever adds time)."""
    return min(entry[2].values()) if entry[2] else entry[0]


def ratio_range(a, b):
    """Smallest and largest a/b over the repetitions, pairing equal repetition indices."""
    if not a or not b:
        return math.nan, math.nan
    common = sorted(set(a[2]) & set(b[2]))
    if len(common) < 2:
        return math.nan, math.nan
    ratios = [a[2][k] / b[2][k] for k in common]
    return min(ratios), max(ratios)


def table(times, allocs, order, bound_bytes):
    dram = [k for k in times if k[0] == "triad_dram"]
    bw_dram = math.nan  # no bound without the triad (a filtered run)
    if dram:
        dram_len = max(k[2] for k in dram)
        bw_dram = 24 * dram_len / times[("triad_dram", None, dram_len)][0]
    rows = []
    scenes = sorted((k for k in times if k[0] == "scene"), key=lambda k: (order[k[1]], k[2]))
    for _, integ, n in scenes:
        t, spread, _ = times[("scene", integ, n)]
        passes = times.get(("hand_passes", integ, n))
        fused = times.get(("hand_fused", integ, n))
        fit = times.get(("triad_fit", None, 3 * n))
        bound = bound_bytes * n / bw_dram
        lo, hi = ratio_range(times[("scene", integ, n)], passes)
        rows.append({
            "integrator": integ,
            "n": n,
            "Mpsteps_per_s": n / t / 1e6,
            "ns_per_psteps": t / n * 1e9,
            "vs_hand_passes": t / passes[0] if passes else math.nan,
            "vs_hand_passes_best": best(times[("scene", integ, n)]) / best(passes)
            if passes else math.nan,
            "vs_hand_passes_min": lo,
            "vs_hand_passes_max": hi,
            "vs_hand_fused": t / fused[0] if fused else math.nan,
            "vs_dram_bound": t / bound,
            "vs_fit_bound": t / (bound_bytes * n / (24 * 3 * n / fit[0])) if fit else math.nan,
            "fused_vs_dram_bound": fused[0] / bound if fused else math.nan,
            "allocs_per_step": allocs.get(("scene", integ, n), math.nan),
            "spread_pct": 100 * spread,
        })
    return rows, bw_dram


def fmt(value, spec):
    if isinstance(value, float) and math.isnan(value):
        return "-"
    return spec.format(value)


def print_table(rows):
    cells = [[head for _, head, _ in COLUMNS]]
    cells += [[fmt(r[key], spec) for key, _, spec in COLUMNS] for r in rows]
    widths = [max(len(row[c]) for row in cells) for c in range(len(COLUMNS))]
    for j, row in enumerate(cells):
        print("  ".join(c.rjust(w) if k > 0 else c.ljust(w) for k, (c, w) in enumerate(zip(row, widths))))
        if j == 0:
            print("  ".join("-" * w for w in widths))


def write_csv(path, rows):
    directory = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(dir=directory, prefix=".summarize-", suffix=".csv")
    try:
        with os.fdopen(fd, "w", encoding="utf-8", newline="") as f:
            f.write(",".join(key for key, _, _ in COLUMNS) + "\n")
            for r in rows:
                f.write(",".join(fmt(r[key], spec) for key, _, spec in COLUMNS) + "\n")
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes it private; give it a normal file's mode
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise


def main():
    args = parse_args()
    try:
        doc = load(args.json_file)
        times, allocs, failures, order, shares = collect(doc, args.json_file,
                                                         args.time + "_time")
        ctx = doc.get("context", {}) if isinstance(doc.get("context"), dict) else {}
        listed = str(ctx.get("wb_integrators", "")).split(",")  # the program's teaching order
        order = {name: listed.index(name) if name in listed else len(listed) + k
                 for name, k in order.items()}
        try:
            bound_bytes = float(ctx.get("wb_bound_bytes_per_particle", 72))
        except ValueError:
            raise BadInput(f"{args.json_file}: context.wb_bound_bytes_per_particle is "
                           f"{ctx['wb_bound_bytes_per_particle']!r}; expected a number")
        rows, bw_dram = table(times, allocs, order, bound_bytes)
    except BadInput as e:
        print(f"summarize.py: {e}", file=sys.stderr)
        return 2
    print(f"host {ctx.get('host_name', '?')}, {ctx.get('num_cpus', '?')} cpus at "
          f"{ctx.get('mhz_per_cpu', '?')} MHz, load average {ctx.get('load_avg', '?')}, "
          f"{ctx.get('date', '?')}")
    print(f"{args.time} time; median of the repetitions; ratios are times (scene / baseline)")
    if math.isnan(bw_dram):
        print("no triad_dram in the run (filtered out?): no DRAM bound")
    else:
        print(f"DRAM triad bandwidth {bw_dram / 1e9:.2f} GB/s; bound = {bound_bytes:g} bytes per "
              "particle-step / bandwidth")
    fits = sorted(k for k in times if k[0] == "triad_fit")
    if fits:
        print("triad on the step's footprint (3n doubles): " + ", ".join(
            f"n={k[2] // 3}: {24 * k[2] / times[k][0] / 1e9:.1f} GB/s" for k in fits))
    print()
    print_table(rows)
    odeint = sorted(k for k in times if k[0] == "odeint" and ("scene",) + k[1:] in times)
    if odeint:
        print()
        print("against Boost.Odeint (odeint/<integrator>/<n>, the same particles and forces): "
              "odeint time / scene time, median (min max over paired repetitions); above 1 "
              "means the provided step is faster")
        for k in odeint:
            scene = ("scene",) + k[1:]
            lo, hi = ratio_range(times[k], times[scene])
            print(f"  {k[1]:<6} n={k[2]:<8} {times[k][0] / times[scene][0]:.3f} "
                  f"({lo:.3f} {hi:.3f})")
    runs = sorted((k for k in times if k[0] == "run" and ("scene",) + k[1:] in times),
                  key=lambda k: (order.get(k[1], 0), k[2]))
    if runs:
        print()
        print("the run loop (run/<integrator>/<n>: wb::simulate per step, by its own clock): "
              "bookkeeping = (run - scene) / run, the loop's share beside the bare step")
        for k in runs:
            run, scene = times[k][0], times[("scene",) + k[1:]][0]
            line = f"  {k[1]:<16} n={k[2]:<8} {(run - scene) / run:+.3f}"
            nosums = times.get(("blocks_nosums",) + k[1:])
            if nosums:
                line += f"   (run - blocks_nosums) / run {(run - nosums[0]) / run:+.3f}"
            fused = times.get(("odeint_fused",) + k[1:])
            if fused:
                lo, hi = ratio_range(fused, times[k])
                line += (f"   odeint_fused / run {fused[0] / run:.3f} ({lo:.3f} {hi:.3f}) "
                         "(above 1: the scene's run is faster)")
            print(line)
    checks = sorted(k for k in times if k[0] == "loop_check")
    if checks:
        print()
        print("the loop's bookkeeping alone (loop_check/<n>: World::checked_energy; "
              "loop_check_separate: allFinite twice and World::energy, as before issue 34), "
              f"as a share of step + bookkeeping (target <= {BOOKKEEPING_TARGET:g})")
        for k in checks:
            n = k[2]
            sep = times.get(("loop_check_separate", None, n))
            parts = []
            for integ in sorted({q[1] for q in times if q[0] == "scene" and q[2] == n},
                                key=lambda i: order.get(i, 0)):
                step = times[("scene", integ, n)][0]
                share = times[k][0] / (step + times[k][0])
                text = f"{integ} {share:.3f}"
                if sep:
                    text += f" (before {sep[0] / (step + sep[0]):.3f})"
                parts.append(text)
            print(f"  n={n:<8} {times[k][0] / n * 1e9:.2f} ns/particle"
                  + (f" (before {sep[0] / n * 1e9:.2f})" if sep else "") + ": " + ", ".join(parts))
    if shares:
        print()
        print("the bookkeeping, paired (bookkeeping/<integrator>/<n>: steps without the sums and "
              "steps with them and World::checked_energy, alternately): (with - without) / with, "
              f"median (min max) over repetitions (target <= {BOOKKEEPING_TARGET:g})")
        for k in sorted(shares, key=lambda k: (order.get(k[1], 0), k[2])):
            v = shares[k]
            print(f"  {k[1]:<6} n={k[2]:<8} {statistics.median(v):.4f} ({min(v):.4f} "
                  f"{max(v):.4f})")
    big = [r for r in rows if r["n"] == 1000000]
    for r in big:
        if r["vs_hand_passes"] > TARGET_RATIO:
            print(f"note: {r['integrator']} at n=10^6 is {r['vs_hand_passes']:.3f} x the hand "
                  f"loop doing the same passes (target <= {TARGET_RATIO})")
    for r in rows:
        if r["allocs_per_step"] > 0:
            failures.append(f"scene/{r['integrator']}/{r['n']}: {r['allocs_per_step']:g} heap "
                            "allocations per step after the warm-up step (expected 0)")
    if args.csv:
        try:
            write_csv(args.csv, rows)
        except OSError as e:
            print(f"summarize.py: --csv {args.csv}: cannot write: {e.strerror}", file=sys.stderr)
            return 2
    for f in failures:
        print(f"FAIL: {f}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
