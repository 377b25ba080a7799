"""tools/view-check: the viewer's browser test (docs/view.md, "The browser test").

Opens every viewer page of a report (build/report/<lab>/*-view.html, one per run that
wrote a trace: every lab's default scenes among them) in headless Chromium and checks,
from the page itself:
  - no console error, no exception;
  - at a playhead, the positions drawn are the trace CSV's at that written step (read
    back from the page), and on a screenshot the pixel where the CSV's position lands
    (through the page's own camera) has the run's colour;
  - the energy chart's cursor sits at the playhead's t (read back, and on a screenshot);
  - a run whose summary says it diverged is marked at the summary's step and t;
then makes two runs of its own (a diverged one with a second run beside it, and a
10^4-particle run of 300 written steps) and measures the large page's load time and
frame rate. The viewer's unit tests (pytest) run first."""
import argparse
import csv
import glob
import io
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

from wbview.data import InputError

from . import browser

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
COLOR_TOL = 12        # per channel: the centre of a filled disc or line is its exact colour
LOAD_LIMIT_S = 3.0    # the issue's: a 10^4-particle run of 300 frames opens in under 3 s
FPS_LIMIT = 30.0      # and plays at 30 frames per second or better
LARGE_N, LARGE_FRAMES = 10_000, 300


def log(msg):
    print(msg, flush=True)


def page_meta(path):
    """The page's metadata (its wb-meta script element), read from the file."""
    with open(path, encoding="utf-8") as f:
        text = f.read()
    m = re.search(r'<script type="application/json" id="wb-meta">(.*?)</script>', text, re.S)
    if not m:
        raise InputError(f"{path}: not a tools/view page (no wb-meta element)")
    return json.loads(m.group(1).replace("<\\/", "</"))


def resolve(from_page, page):
    """A file the page names, by its path from the page's folder."""
    return os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(page)), from_page))


def hexrgb(h):
    v = int(h[1:], 16)
    return (v >> 16) & 255, (v >> 8) & 255, v & 255


def close(rgb, want):
    return rgb is not None and all(abs(a - b) <= COLOR_TOL for a, b in zip(rgb, want))


def screen_of(view, p):
    """Page pixel of world point p through the page's own mapping (2D scale and centre,
    or the 3D camera), computed here from the CSV's numbers."""
    if view["kind"] == "2d":
        return (view["left"] + view["W"] / 2 + (p[0] - view["cx"]) * view["s"],
                view["top"] + view["H"] / 2 - (p[1] - view["cy"]) * view["s"])
    d = [a - b for a, b in zip(p, view["eye"])]
    z = sum(a * b for a, b in zip(d, view["f"]))
    if not z > 0:
        return None
    return (view["left"] + view["W"] / 2 + view["F"] * sum(a * b for a, b in zip(d, view["r"])) / z,
            view["top"] + view["H"] / 2 - view["F"] * sum(a * b for a, b in zip(d, view["u"])) / z)


class Frame:
    """One written step of a trace CSV, read here with the csv module (not with tools/view's
    reader, which the check is testing): `rows[id]` is {column: float}, `n` the ids per
    written step, `kind` "rigid" or "particles"."""

    def __init__(self, path, t):
        with open(path, "rb") as f:
            lines = f.read().split(b"\n")
        header = lines[0].decode().strip().split(",")
        body = [x for x in lines[1:] if x.strip()]
        self.n = next((i for i in range(1, len(body)) if body[i].split(b",", 2)[1] == b"0"),
                      len(body))  # the rows up to the second id 0
        self.kind = "rigid" if "qw" in header else "particles"
        self.times = [float(body[k].split(b",", 1)[0]) for k in range(0, len(body), self.n)]
        self.rows = None
        if t in self.times:
            k = self.times.index(t)
            text = b"\n".join(body[k * self.n:(k + 1) * self.n]).decode()
            self.rows = [{c: float(v) for c, v in zip(header, rec)}
                         for rec in csv.reader(io.StringIO(text))]


def sample_ids(n, count):
    return sorted({(k * (n - 1)) // max(count - 1, 1) for k in range(min(n, count))})


class PageCheck:
    """The checks of one page; `problems` lists what failed, `facts` what was measured."""

    def __init__(self, b, path, shot=None):
        self.b, self.path, self.shot = b, path, shot
        self.problems, self.facts = [], {}

    def fail(self, msg):
        self.problems.append(f"{rel(self.path)}: {msg}")

    def run(self):
        b = self.b
        meta = page_meta(self.path)
        run = meta["runs"][0]
        trace_path = resolve(run["from_page"], self.path)
        c0 = b.cpu_seconds()
        self.facts["load_wall_s"] = b.open("file://" + os.path.abspath(self.path))
        b.pump(0.05)
        self.facts["load_cpu_s"] = b.cpu_seconds() - c0
        self.facts["load_page_s"] = b.evaluate("wbView.loadMs()") / 1000
        state = b.evaluate("wbView.state()")
        k = b.evaluate(f"wbView.seek({int(0.6 * (state['frames'] - 1))})")
        if self.shot:  # as a student sees it, overlays on
            b.screenshot(self.shot)
        b.evaluate("wbView.set({exact: false, run2: false, trails: false, springs: false, "
                   "pick: null, legend: false})")
        state = b.evaluate("wbView.state()")
        trace = Frame(trace_path, state["t"])
        if state["n"] != trace.n:
            self.fail(f"the page draws {state['n']} particles or bodies, the trace "
                      f"{trace_path} has {trace.n}")
            return self
        self.positions(trace, trace_path, meta, state)
        self.cursor(meta, state)
        self.diverged(meta, run)
        b.pump(0.05)
        if b.errors:
            self.fail("console errors: " + " | ".join(b.errors[:3]))
        self.facts["frame"] = k
        return self

    def positions(self, trace, trace_path, meta, state):
        """The drawn positions are the CSV's at the playhead's written step."""
        b = self.b
        if trace.rows is None:
            self.fail(f"the playhead's t = {state['t']!r} is no written step of {trace_path}")
            return
        ids = sample_ids(trace.n, 12)
        drawn = b.evaluate(f"wbView.drawn({json.dumps(ids)})")
        dims = 3 if trace.kind == "rigid" else 2
        names = ["x", "y", "z"][:dims]
        size = max([h - lo for lo, h in zip(meta["box"]["lo"], meta["box"]["hi"])] + [1e-12]) \
            if meta.get("box") else 1.0
        worst = 0.0
        for d in drawn:
            want = [trace.rows[d["id"]][c] for c in names]
            for w, got, o in zip(want, d["world"], meta["origin"]):
                if not math.isfinite(w):
                    continue
                # 32-bit floats relative to the scene's centre: 2^-24 of that offset.
                tol = 1.2e-7 * (abs(w - o) + size) + 1e-300
                err = abs((got if got is not None else math.nan) - w)
                worst = max(worst, err / tol)
                if not err <= tol:
                    self.fail(f"step t = {state['t']}: id {d['id']} drawn at {d['world']}, the "
                              f"CSV says {want} ({trace_path})")
                    return
            if trace.kind == "rigid":
                q = [trace.rows[d["id"]][c] for c in ("qw", "qx", "qy", "qz")]
                if any(abs(a - b_) > 1e-6 for a, b_ in zip(q, d["q"]) if math.isfinite(a)):
                    self.fail(f"id {d['id']}: orientation drawn {d['q']}, the CSV says {q}")
                    return
        self.facts["positions_checked"] = len(drawn)
        # On a screenshot: the pixel where the CSV's position lands has the run's colour.
        view = b.evaluate("wbView.view()")
        colors = b.evaluate("wbView.colors()")
        want = hexrgb(colors["com"] if trace.kind == "rigid" else colors["run"])
        checked = 0
        for d in drawn:
            if checked >= 3:
                break
            p = screen_of(view, [trace.rows[d["id"]][c] for c in names])
            if p is None or not (view["left"] + 6 < p[0] < view["left"] + view["W"] - 6
                                 and view["top"] + 6 < p[1] < view["top"] + view["H"] - 6):
                continue
            rgb = b.pixels(p[0], p[1], 0).pixel(p[0], p[1])
            if not close(rgb, want):
                self.fail(f"id {d['id']}: the screenshot at ({p[0]:.1f}, {p[1]:.1f}), where the "
                          f"CSV's position lands, is {rgb}, expected the run's colour {want}")
                return
            checked += 1
        self.facts["pixels_checked"] = checked

    def cursor(self, meta, state):
        """The energy chart's cursor is at the playhead's t, on the page and on a screenshot."""
        charts = {c["id"]: c for c in self.b.evaluate("wbView.charts()")}
        if not meta["runs"][0].get("stats"):
            return
        e = charts.get("energy")
        if e is None or e["cursor"] is None:
            self.fail("no energy chart with a cursor although the run has stats")
            return
        if e["cursor"]["t"] != state["t"]:
            self.fail(f"energy cursor at t = {e['cursor']['t']}, the playhead at {state['t']}")
            return
        (p0, p1), (t0, t1) = e["px_range"], e["t_of_px"]
        at = p0 + (state["t"] - t0) / (t1 - t0) * (p1 - p0)  # the chart's t axis, computed here
        if abs(e["cursor"]["px"] - at) > 0.51:
            self.fail(f"energy cursor drawn at x = {e['cursor']['px']}, the playhead's t = "
                      f"{state['t']} is at x = {at:.1f} on the chart's axis")
        want = hexrgb(self.b.evaluate("wbView.colors()")["cursor"])
        y = (e["top"] + e["bottom"]) / 2
        rgb = self.b.pixels(e["cursor"]["px"], y, 0).pixel(e["cursor"]["px"], y)
        if not close(rgb, want):
            self.fail(f"the screenshot at the energy cursor ({e['cursor']['px']}, {y:.0f}) is "
                      f"{rgb}, expected the cursor's colour {want}")
        self.facts["cursor_checked"] = True

    def diverged(self, meta, run):
        """A run whose summary says diverged is marked at the summary's step and t."""
        s = run.get("summary") or {}
        if s.get("status") != "diverged":
            return
        b = self.b
        marks = b.evaluate("wbView.diverged()")[0]
        if not marks or marks["step"] != s.get("steps") or marks["t"] != s.get("t"):
            self.fail(f"the summary says diverged at step {s.get('steps')} (t = {s.get('t')}), "
                      f"the page marks {marks}")
            return
        charts = {c["id"]: c for c in b.evaluate("wbView.charts()")}
        e = charts.get("energy")
        if e is not None:
            m = [x for x in e["marks"] if x["step"] == s["steps"]]
            if not m:
                self.fail(f"the energy chart has no divergence mark at step {s['steps']}")
                return
            want = hexrgb(b.evaluate("wbView.colors()")["diverged"])
            hits = 0
            for frac in (0.3, 0.4, 0.5, 0.6, 0.7, 0.8):
                y = e["top"] + frac * (e["bottom"] - e["top"])
                hits += close(b.pixels(m[0]["px"], y, 0).pixel(m[0]["px"], y), want)
            if not hits:
                self.fail(f"the screenshot shows no divergence mark at x = {m[0]['px']}")
                return
        last = b.evaluate("wbView.seek(1e9)")
        st = b.evaluate("wbView.state()")
        if st["step"] is not None and st["step"] != s["steps"]:
            self.fail(f"the last frame is step {st['step']}, the summary says the run diverged "
                      f"at step {s['steps']}")
        self.facts["diverged_checked"] = last


UNIT_TESTS = ["tools/wbview/tests", "tools/wbtools/tests/test_view_check.py"]


def unit_tests():
    """The viewer's unit tests (pytest), first: the readers and packing the pages rest on."""
    t0 = time.monotonic()
    p = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider"]
                       + [os.path.join(ROOT, t) for t in UNIT_TESTS],
                       cwd=ROOT, capture_output=True, text=True,
                       env=dict(os.environ, PYTHONDONTWRITEBYTECODE="1"))
    last = (p.stdout.strip().splitlines() or ["no output"])[-1]
    log(f"view-check: unit tests ({', '.join(UNIT_TESTS)}): {last} "
        f"({time.monotonic() - t0:.1f} s)")
    if p.returncode != 0:
        print(p.stdout[-3000:] + p.stderr[-1000:], flush=True)
        return [f"the viewer's unit tests failed (python3 -m pytest {' '.join(UNIT_TESTS)})"]
    return []


def default_scene_pages(report, pages):
    """Every scenes/<lab>/<stem>.json must have a page of the report (problems)."""
    named = set()
    for p in pages:
        sp = page_meta(p).get("scene_from_page")
        if sp:
            named.add(os.path.relpath(resolve(sp, p), ROOT))
    missing = []
    for scene in sorted(glob.glob(os.path.join(ROOT, "scenes", "*", "*.json"))):
        r = os.path.relpath(scene, ROOT)
        if r not in named:
            missing.append(f"{rel(report)}: no viewer of the default scene {r} (tools/report "
                           "writes one for every run that writes a trace)")
    return missing


def rel(p):
    r = os.path.relpath(p, ROOT)
    return p if r.startswith("..") else r


def own_runs(bin_dir, work):
    """The stage's own runs: a diverged run with a second run beside it (euler lab), and
    the large run (forces lab: 10^4 particles, 300 written steps). Returns the pages."""
    view = [os.path.join(ROOT, "tools", "view"), "--no-setup"]
    pages = {}
    exe = os.path.join(bin_dir, "euler-solution")
    if os.path.exists(exe):
        # One spring with h w = 10: explicit Euler grows by 1 + (h w)^2 a step and passes the
        # divergence rule's factor 1000 within a few steps; semi-implicit Euler at h w = 0.1
        # is the second run.
        scene = os.path.join(work, "stiff.json")
        with open(scene, "w") as f:
            json.dump({"name": "stiff (the view test's)", "dt": 0.01, "t_end": 0.5,
                       "particles": [{"x": [1, 0], "v": [0, 0], "m": 1, "radius": 0.05}],
                       "forces": [{"type": "spring", "i": 0, "anchor": [0, 0], "k": 1e6,
                                   "rest": 0}]}, f)
        for name, extra in (("stiff-ee", ["--integrator", "explicit-euler"]),
                            ("stiff-se", ["--integrator", "symplectic-euler", "--dt", "1e-4"])):
            base = os.path.join(work, name)
            with open(base + "-summary.json", "w") as out:
                subprocess.run([exe, "--scene", scene, "--out", base + ".csv", "--stats",
                                base + "-stats.csv"] + extra, stdout=out, check=True)
        subprocess.run(view + [os.path.join(work, "stiff-ee.csv"),
                               os.path.join(work, "stiff-se.csv"), "--scene", scene,
                               "-o", os.path.join(work, "diverged.html")],
                       check=True, stdout=subprocess.DEVNULL)
        pages["diverged"] = os.path.join(work, "diverged.html")
    exe = os.path.join(bin_dir, "forces-solution")
    if os.path.exists(exe):
        scene = os.path.join(work, "large.json")
        with open(scene, "w") as f:
            json.dump({"name": f"{LARGE_N} particles in a vortex (the view test's)", "dt": 0.01,
                       "emitters": [{"count": LARGE_N, "seed": 1, "min": [-3, -3], "max": [3, 3],
                                     "speed": 0.2, "m": 1, "radius": 0.01}],
                       "forces": [{"type": "vortex", "omega": 2, "core": 0.8, "drag": 1}]}, f)
        base = os.path.join(work, "large")
        t0 = time.monotonic()
        with open(base + "-summary.json", "w") as out:
            subprocess.run([exe, "--scene", scene, "--steps", str(LARGE_FRAMES - 1), "--out",
                            base + ".csv", "--stats", base + "-stats.csv"], stdout=out, check=True)
        t1 = time.monotonic()
        subprocess.run(view + [base + ".csv", "--scene", scene, "-o", base + ".html"], check=True,
                       stdout=subprocess.DEVNULL)
        log(f"view-check: the large run: {LARGE_N} particles x {LARGE_FRAMES} written steps, "
            f"{os.path.getsize(base + '.csv') / 1e6:.0f} MB of CSV in {t1 - t0:.1f} s; its page "
            f"{os.path.getsize(base + '.html') / 1e6:.1f} MB by tools/view in "
            f"{time.monotonic() - t1:.1f} s")
        pages["large"] = base + ".html"
    return pages


def measure_large(b, page, seconds=3.0):
    """Load time and frame rate of the large page: wall clock (what a viewer sees here) and
    per CPU second of the browser's processes (what the page costs, whatever else the
    machine runs: the check's 2 cores are shared with the fresh machines)."""
    c0 = b.cpu_seconds()
    wall = b.open("file://" + os.path.abspath(page))
    page_s = b.evaluate("wbView.loadMs()") / 1000
    c1 = b.cpu_seconds()
    r = b.evaluate(f"wbView.benchmark({seconds})", await_promise=True, timeout=seconds + 60)
    c2 = b.cpu_seconds()
    return {"load_page_s": page_s, "load_wall_s": wall, "load_cpu_s": c1 - c0,
            "fps": r["fps"], "frames": r["frames"], "fps_cpu": r["frames"] / max(c2 - c1, 1e-9),
            "draw_ms_mean": r["draw_ms_mean"], "draw_ms_p95": r["draw_ms_p95"],
            "size_mb": os.path.getsize(page) / 1e6}


def run():
    """The entry tools/view-check calls: main() with the command line, its exit status."""
    sys.exit(main())


def main(argv=None):
    p = argparse.ArgumentParser(prog="tools/view-check", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter,
                                epilog="Exit status: 0 every check passed, 1 a check failed "
                                       "(one line each), 2 no Chromium or no viewer pages.")
    p.add_argument("--report", default=os.path.join(ROOT, "build", "report"),
                   help="the report whose viewers are checked (default build/report)")
    p.add_argument("--bin", default=os.path.join(ROOT, "build", "bin"),
                   help="the solution executables for the stage's own runs (default build/bin)")
    p.add_argument("--shots", default=os.path.join(ROOT, "build", "view-check"),
                   help="screenshots of every page checked go here (default build/view-check)")
    p.add_argument("--no-setup", action="store_true", help="install nothing first")
    args = p.parse_args(argv)
    t_start = time.monotonic()
    if not browser.find_chromium():
        print("tools/view-check: error: no Chromium (Debian package chromium: "
              "tools/setup --browser installs it)", file=sys.stderr)
        return 2
    pages = sorted(glob.glob(os.path.join(args.report, "*", "*-view.html")))
    if not pages:
        print(f"tools/view-check: error: --report: no viewer pages in {rel(args.report)}/<lab>/ "
              "(run tools/report first)", file=sys.stderr)
        return 2
    problems = unit_tests() + default_scene_pages(args.report, pages)
    shutil.rmtree(args.shots, ignore_errors=True)
    os.makedirs(args.shots)
    work = tempfile.mkdtemp(prefix="wb-view-check-")
    facts = {}
    try:
        own = own_runs(args.bin, work)
        for what in ("diverged", "large"):
            if what not in own:
                problems.append(f"the stage's {what} run was not made: {rel(args.bin)} lacks "
                                f"its executable")
        with browser.Browser() as b:
            loads, t_pages = [], time.monotonic()
            for page in pages + [own[k] for k in ("diverged", "large") if k in own]:
                lab = os.path.basename(os.path.dirname(page))
                name = os.path.basename(page)[:-len(".html")]
                shot = os.path.join(args.shots, f"{lab}-{name}.png" if page in pages
                                    else f"own-{name}.png")
                try:
                    c = PageCheck(b, page, shot).run()
                except (browser.BrowserError, InputError, KeyError, TypeError, ValueError) as e:
                    problems.append(f"{rel(page)}: {type(e).__name__}: {e}")
                    continue
                problems += c.problems
                loads.append(c.facts.get("load_page_s", 0))
                if "diverged_checked" in c.facts:
                    facts["diverged_pages"] = facts.get("diverged_pages", 0) + 1
            facts["pages"] = len(loads)
            facts["pages_s"] = time.monotonic() - t_pages
            if "large" in own:
                m = measure_large(b, own["large"])
                facts["large"] = m
                b.screenshot(os.path.join(args.shots, "own-large-played.png"))
                if not m["load_cpu_s"] < LOAD_LIMIT_S:
                    problems.append(f"the large page ({LARGE_N} particles, {LARGE_FRAMES} "
                                    f"frames) took {m['load_cpu_s']:.2f} s of CPU to open, "
                                    f"expected under {LOAD_LIMIT_S} s")
                if not m["fps_cpu"] >= FPS_LIMIT:
                    problems.append(f"the large page played {m['fps_cpu']:.1f} frames per CPU "
                                    f"second, expected at least {FPS_LIMIT}")
        if not facts.get("diverged_pages"):
            problems.append("no page of a diverged run was checked (the stage's own diverged "
                            "run is missing)")
    finally:
        shutil.rmtree(work, ignore_errors=True)
    for pr in problems:
        log(f"view-check: FAILED: {pr}")
    large = facts.get("large")
    if large:
        log(f"view-check: large page ({LARGE_N} particles x {LARGE_FRAMES} frames, "
            f"{large['size_mb']:.1f} MB): opened in {large['load_page_s']:.2f} s "
            f"({large['load_cpu_s']:.2f} s of CPU), played {large['fps']:.0f} frames per second "
            f"here ({large['fps_cpu']:.0f} per CPU second; drawing {large['draw_ms_mean']:.1f} ms "
            f"a frame on average, {large['draw_ms_p95']:.1f} ms at the 95th percentile)")
    log(f"view-check: {facts.get('pages', 0)} pages checked in {facts.get('pages_s', 0):.0f} s, "
        f"screenshots in {rel(args.shots)}/; {len(problems)} problem(s); "
        f"{time.monotonic() - t_start:.0f} s in all")
    return 1 if problems else 0
