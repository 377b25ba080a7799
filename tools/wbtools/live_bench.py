"""tools/live-check --bench: the WebAssembly step against the native one, in the same run
(docs/benchmarks.md, "Live pages"). Each case is a lab's scene stepped from its start, n
steps in one call: in the lab's live page (window.wbLive.bench, headless Chromium) and
natively by bench/bench_live (the same live layer and solution, Google Benchmark). Both are
timed in CPU seconds, which the other jobs of a shared machine do not inflate: the native
program's own CPU time, and for the page the browser's (all its processes, from /proc,
over calls of a second or more of stepping; the page's loop is idle meanwhile). The page
picks n (a run of 20 ms or more); the native program takes the same n, between the page's
two measurements (the lower of which counts). The ratio must stay at or under
BENCH_RATIO."""
import json
import os
import subprocess
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
REPEATS = 5
BENCH_RATIO = 2.0      # the WebAssembly step costs at most this many native steps
# (lab, scene, integrator or None for the scene's): every lab's opening scene (euler's
# with semi-implicit Euler: explicit Euler's run would diverge before its steps) and a
# heavier one where it has one.
CASES = [("forces", "flock", None), ("forces", "smoke", None),
         ("euler", "oscillator", "symplectic-euler"), ("midpoint", "orbit-eccentric", None),
         ("implicit", "stiff-rope", None), ("implicit", "hanging-cloth", None),
         ("collisions", "billiards", None), ("collisions", "pile", None),
         ("rigid", "dzhanibekov", None), ("rigid", "door", None)]
RUN_MS = 20.0     # one run of n steps lasts this long or more (wall, in the page)
CPU_S = 1.0       # the page's measurement: this much CPU of stepping or more


def log(msg):
    print(msg, flush=True)


def page_bench(b, page, scene, integrator, n=None):
    """(CPU ms per step, n) in the page. n doubled from 16 until one run lasts RUN_MS; then
    runs of n steps, as many as make CPU_S, timed on the browser's CPU."""
    b.open("file://" + os.path.abspath(page), ready="window.wbLive && window.wbLive.ready")
    b.evaluate("document.getElementById('b-play').click()")  # pause the page's own run
    call = f"wbLive.bench({json.dumps(scene)}, {json.dumps(integrator)}, null, "
    if n is None:
        n = 16
        while True:
            r = b.evaluate(call + f"{n}, 1)")
            if "error" in r:
                raise RuntimeError(f"{scene}: {r['error']}")
            if r["ms"] * n >= RUN_MS or n >= 1 << 22:
                break
            n *= 2
    r = b.evaluate(call + f"{n}, 1)")
    runs = max(2, int(CPU_S * 1e3 / max(r["ms"] * n, 1e-3)) + 1)
    c0 = b.cpu_seconds()
    r = b.evaluate(call + f"{n}, {runs})", timeout=600)
    cpu = b.cpu_seconds() - c0
    if "error" in r:
        raise RuntimeError(f"{scene}: {r['error']}")
    return 1e3 * cpu / (runs * n), n


def native_bench(cases):
    """{(lab, scene): ms per step} from bench/bench_live, the fastest repetition."""
    exe = os.path.join(ROOT, "build", "bin", "bench_live")
    args = [f"{lab}/{scene}" + (f"/{integ}" if integ else "") + f":{n}"
            for (lab, scene, integ), n in cases.items()]
    p = subprocess.run([exe, "--benchmark_format=json", f"--benchmark_repetitions={REPEATS}"]
                       + args, capture_output=True, text=True, cwd=ROOT)
    if p.returncode != 0:
        raise RuntimeError(f"bench_live failed: {p.stderr.strip()[-500:]}")
    out = {}
    for bm in json.loads(p.stdout)["benchmarks"]:
        if bm.get("run_type") != "iteration" or "error_occurred" in bm:
            continue
        _, lab, scene = bm["run_name"].split("/")[:3]
        out[(lab, scene)] = min(out.get((lab, scene), float("inf")), bm["ms_per_step"])
    return out


def build_native():
    """bench_live in the native build (configured with the default preset if need be)."""
    if not os.path.isfile(os.path.join(ROOT, "build", "build.ninja")):
        subprocess.run(["cmake", "--preset", "default"], cwd=ROOT, check=True,
                       stdout=subprocess.DEVNULL)
    p = subprocess.run(["cmake", "--build", "--preset", "default", "--target", "bench_live"],
                       cwd=ROOT, capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError("building bench_live failed: " + p.stdout[-1500:])


def run(b, pages, shots):
    """Times every case whose lab has a page; returns problems (ratios over the limit)."""
    t0 = time.monotonic()
    try:
        build_native()
    except (RuntimeError, subprocess.CalledProcessError) as e:
        return [f"bench: {e}"]
    cases = [c for c in CASES if c[0] in pages]
    wasm, steps = {}, {}
    try:
        for c in cases:
            wasm[c], steps[c] = page_bench(b, pages[c[0]], c[1], c[2])
        native = native_bench(steps)
        for c in cases:
            wasm[c] = min(wasm[c], page_bench(b, pages[c[0]], c[1], c[2], steps[c])[0])
    except RuntimeError as e:
        return [f"bench: {e}"]
    problems, rows = [], []
    log("live-check: bench: lab/scene: WebAssembly / native CPU ms per step = ratio (n steps "
        f"from the scene's start; native: the fastest of {REPEATS}; the page: the lower of two)")
    for c in cases:
        n_ms = native.get((c[0], c[1]))
        ratio = wasm[c] / n_ms if n_ms else float("inf")
        rows.append({"lab": c[0], "scene": c[1], "integrator": c[2], "steps": steps[c],
                     "wasm_ms": wasm[c], "native_ms": n_ms, "ratio": ratio})
        log(f"live-check: bench: {c[0]}/{c[1]}: {wasm[c]:.5g} / {n_ms:.5g} ms = {ratio:.2f} "
            f"({steps[c]} steps)")
        if not ratio <= BENCH_RATIO:
            problems.append(f"bench: {c[0]}/{c[1]}: the WebAssembly step costs {ratio:.2f} "
                            f"native steps, expected at most {BENCH_RATIO}")
    with open(os.path.join(shots, "bench.json"), "w", encoding="utf-8") as f:
        json.dump(rows, f, indent=1)
    log(f"live-check: bench: {len(cases)} cases in {time.monotonic() - t0:.0f} s")
    return problems
