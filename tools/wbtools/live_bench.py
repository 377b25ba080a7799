"""tools/live-check --bench: the WebAssembly step against the native one, in the same run
(docs/benchmarks.md, "Live pages"). Each case is a lab's scene stepped from its start, n
steps in one call: in the lab's live page (window.wbLive.bench, headless Chromium) and
natively by bench/bench_live (the same live layer and solution, Google Benchmark). Both are
timed in CPU seconds of the thread that steps, which the other jobs of a shared machine do
not inflate: Google Benchmark's CPU time of its thread, and for the page its renderer's main
thread, where the WebAssembly and the page's JavaScript run (/proc's schedstat, over calls of
a second or more of stepping; the page's loop is idle meanwhile). The browser's other
processes and threads (about 0.4 CPU second a second in all when idle) are not the step's:
their CPU over the same calls is printed beside it. The page picks n (a run of 20 ms or
more); then the page and the native program are measured in turns, PAGE_REPEATS times the
page, the fastest on each side counts (Google Benchmark's repetitions: the fastest of
REPEATS). The ratio must stay at or under BENCH_RATIO."""
import json
import os
import subprocess
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
REPEATS = 5
PAGE_REPEATS = 3  # the page's measurements, before, between and after the native ones
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
    """(CPU ms per step of the page's thread, of the whole browser, n) in the page. n doubled
    from 16 until one run lasts RUN_MS; then runs of n steps, as many as make CPU_S, timed on
    the CPU of the renderer's main thread (and of the whole browser, for the record)."""
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
    c0, p0 = b.cpu_seconds(), b.page_cpu_seconds()
    r = b.evaluate(call + f"{n}, {runs})", timeout=600)
    cpu, page_cpu = b.cpu_seconds() - c0, b.page_cpu_seconds() - p0
    if "error" in r:
        raise RuntimeError(f"{scene}: {r['error']}")
    return 1e3 * page_cpu / (runs * n), 1e3 * cpu / (runs * n), n


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
    wasm, browser_ms, steps, native = {}, {}, {}, {}
    try:
        for c in cases:
            wasm[c], browser_ms[c], steps[c] = page_bench(b, pages[c[0]], c[1], c[2])
        for turn in range(PAGE_REPEATS - 1):  # native, page, native, page...
            for key, ms in native_bench(steps).items():
                native[key] = min(native.get(key, float("inf")), ms)
            for c in cases:
                w, a, _ = page_bench(b, pages[c[0]], c[1], c[2], steps[c])
                wasm[c], browser_ms[c] = min(wasm[c], w), min(browser_ms[c], a)
    except RuntimeError as e:
        return [f"bench: {e}"]
    problems, rows = [], []
    log("live-check: bench: lab/scene: WebAssembly / native CPU ms per step = ratio (n steps "
        f"from the scene's start; the page's thread, the fastest of {PAGE_REPEATS}; native: "
        f"the fastest of {PAGE_REPEATS - 1} x {REPEATS}; in brackets the whole browser's CPU)")
    for c in cases:
        n_ms = native.get((c[0], c[1]))
        ratio = wasm[c] / n_ms if n_ms else float("inf")
        rows.append({"lab": c[0], "scene": c[1], "integrator": c[2], "steps": steps[c],
                     "wasm_ms": wasm[c], "browser_ms": browser_ms[c], "native_ms": n_ms,
                     "ratio": ratio})
        log(f"live-check: bench: {c[0]}/{c[1]}: {wasm[c]:.5g} / {n_ms:.5g} ms = {ratio:.2f} "
            f"({steps[c]} steps; the whole browser {browser_ms[c]:.5g} ms = "
            f"{browser_ms[c] / n_ms if n_ms else float('inf'):.2f})")
        if not ratio <= BENCH_RATIO:
            problems.append(f"bench: {c[0]}/{c[1]}: the WebAssembly step costs {ratio:.2f} "
                            f"native steps, expected at most {BENCH_RATIO}")
    with open(os.path.join(shots, "bench.json"), "w", encoding="utf-8") as f:
        json.dump(rows, f, indent=1)
    log(f"live-check: bench: {len(cases)} cases in {time.monotonic() - t0:.0f} s")
    return problems
