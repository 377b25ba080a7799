"""Claims: numbers and directions that handouts and scene descriptions state about runs,
checked against those runs (tools/claims, docs/report.md "Claims").

A claim is an HTML comment right after the sentence that states it:

    E1 lands above the parabola <!-- claim: offset euler/free-fall@explicit-euler y min > 0 says "above" -->
    ... ×23 in 1296 steps <!-- claim: stats euler/oscillator@explicit-euler energy ratio = 23 ± 1 -->

    claim:  MEASURE ARGS...  OP  RHS  [says "TEXT"]
    OP RHS: = V ± T  |  = WORD  |  < V  |  > V  |  <= V  |  >= V  |  in [A, B]

With `= V ± T` the text V itself must also appear in the prose just before the marker, or,
when the prose writes it differently (LaTeX, a word such as "above"), `says "TEXT"` requires
TEXT there instead: a number or word in the sentence cannot drift from the
checked one. Markdown does not render the comment; tools/report strips it from captions.
"""
import json
import math
import os
import re
import statistics

from .common import InputError, finite, read_csv
from . import claimrules
from . import exact as wexact
from . import recipes
from . import sweep as wsweep

CLAIM_RE = re.compile(r"<!--\s*claim:\s*(.*?)\s*-->", re.S)
PROSE_WINDOW = 400  # characters before a marker in which its stated text must appear


def strip_markers(text):
    """The text without claim markers (what a reader sees)."""
    return re.sub(r"\s*<!--\s*claim:.*?-->", "", text, flags=re.S)


class Claim:
    def __init__(self, where, body, prose):
        self.where, self.body, self.prose = where, body, prose
        m = re.fullmatch(r'(.*?)\s+says\s+"([^"]*)"', body, re.S)
        self.says = m.group(2) if m else None
        core = m.group(1) if m else body
        m = re.fullmatch(r"(.+?)\s+(=|<=|>=|<|>|in)\s+(.+)", core, re.S)
        if not m:
            raise InputError(f"{where}: claim '{body}': expected MEASURE ARGS... OP VALUE "
                             "(docs/report.md, Claims)")
        self.measure = m.group(1).split()
        self.op, rhs = m.group(2), m.group(3).strip()
        self.value = self.tol = self.lo = self.hi = self.word = None
        self.stated = None
        try:
            if self.op == "in":
                mm = re.fullmatch(r"\[\s*(\S+)\s*,\s*(\S+)\s*\]", rhs)
                if not mm:
                    raise ValueError
                self.lo, self.hi = float(mm.group(1)), float(mm.group(2))
            elif self.op == "=":
                mm = re.fullmatch(r"(\S+)\s*(?:±|\+-|\+/-)\s*(\S+)", rhs)
                if mm:
                    self.stated = mm.group(1)
                    self.value, self.tol = float(mm.group(1)), float(mm.group(2))
                elif re.fullmatch(r"[A-Za-z_-]+", rhs):
                    self.word = rhs
                else:
                    raise ValueError
            else:
                self.value = float(rhs)
        except ValueError:
            raise InputError(f"{where}: claim '{body}': bad value '{rhs}' (expected V ± T, "
                             "a word, a number or [A, B])") from None

    def judge(self, got):
        """'' when the measured value `got` agrees, else why not."""
        if self.word is not None:
            return "" if str(got) == self.word else f"measured {got}"
        if isinstance(got, str) or got is None or not finite(got):
            return f"measured {got}"
        ok = {"=": lambda: abs(got - self.value) <= self.tol,
              "<": lambda: got < self.value, ">": lambda: got > self.value,
              "<=": lambda: got <= self.value, ">=": lambda: got >= self.value,
              "in": lambda: self.lo <= got <= self.hi}[self.op]()
        return "" if ok else f"measured {got:.6g}"

    def prose_problem(self):
        need = [self.says] if self.says else [t for t in (self.stated,) if t]
        plain = strip_markers(self.prose)
        for t in need:
            if t not in plain:
                return f"the text before the claim does not say '{t}'"
        return ""


def find_claims(path, text=None, where=None):
    """Claims in a Markdown file, or in the "description" of a scene JSON file."""
    if text is None:
        try:
            with open(path, encoding="utf-8") as f:
                text = f.read()
        except OSError as e:
            raise InputError(f"{path}: cannot read ({e.strerror})") from None
        if path.endswith(".json"):
            try:
                doc = json.loads(text)
            except json.JSONDecodeError as e:
                raise InputError(f"{path}: not JSON ({e})") from None
            text = doc.get("description", "") if isinstance(doc, dict) else ""
            where = f"{path} (description)"
    out = []
    for m in CLAIM_RE.finditer(text):
        line = text.count("\n", 0, m.start()) + 1
        prose = text[max(0, m.start() - PROSE_WINDOW):m.start()]
        # Only the prose of the same paragraph counts.
        prose = re.split(r"\n\s*\n", prose)[-1]
        out.append(Claim(where or f"{path}:{line}", m.group(1), prose))
    return out


# ----------------------------------------------------------------------------
# Measures: each reads the files the report writes for a run (docs/report.md).


def _target(arg):
    """LAB/SCENE[@INTEGRATOR] -> (lab, scene, integrator or None)."""
    m = re.fullmatch(r"([A-Za-z0-9_-]+)/([A-Za-z0-9_.-]+?)(?:@([A-Za-z0-9_-]+))?", arg)
    if not m:
        raise InputError(f"'{arg}': expected LAB/SCENE or LAB/SCENE@INTEGRATOR")
    return m.group(1), m.group(2), m.group(3)


def _reduce(values, how, steps=None):
    vals = [v for v in values if finite(v)]
    if not vals:
        return math.nan
    if how == "first":
        return vals[0]
    if how == "last":
        return values[-1] if values else math.nan  # nan when the run ended non-finite
    if how == "last-finite":
        return vals[-1]
    if how == "min":
        return min(vals)
    if how == "max":
        return max(vals)
    if how == "median":
        return statistics.median(vals)
    if how == "spread":  # max - min
        return max(vals) - min(vals)
    if how == "maxrise":  # the largest increase from one value to the next
        return max((b - a for a, b in zip(vals, vals[1:])), default=0.0)
    if how == "ratio":
        return vals[-1] / vals[0] if vals[0] else math.nan
    if how == "drift":  # max |c - c0| / |c0|
        return max(abs(v - vals[0]) for v in vals) / abs(vals[0]) if vals[0] else math.nan
    if how == "growth":  # per-step factor from the first to the last finite value
        n = steps if steps else len(vals) - 1
        return (vals[-1] / vals[0]) ** (1.0 / n) if vals[0] and n > 0 else math.nan
    raise InputError(f"reducer '{how}': expected first, last, last-finite, min, max, median, "
                     "spread, maxrise, ratio, drift or growth")


class Data:
    """The files of the report's runs, in `root` (build/report or tools/claims' own)."""

    def __init__(self, root, scenes_root, report_root=None):
        self.root, self.scenes_root = root, scenes_root
        self.report_root = report_root or root  # files only tools/report makes (csv)

    def file(self, lab, name, report=False):
        # A report-only file that tools/claims made itself (a plug-in's CLAIM_FILES) is
        # in root; the others come from the last tools/report.
        p = os.path.join(self.root, lab, name)
        if report and not os.path.exists(p):
            p = os.path.join(self.report_root, lab, name)
        if not os.path.exists(p):
            raise InputError(f"{p}: not found (the run behind the claim did not happen)")
        return p

    def scene(self, lab, stem):
        p = os.path.join(self.scenes_root, lab, stem + ".json")
        try:
            with open(p, encoding="utf-8") as f:
                return json.load(f)
        except (OSError, json.JSONDecodeError) as e:
            raise InputError(f"{p}: cannot read the scene ({e})") from None

    def run_name(self, stem, integ):
        return f"{stem}-{integ}" if integ else stem


def needs(claim):
    """(lab, scene, what) the claim reads: what is None (as shipped), an integrator, 'sweep'
    or 'report' (files only tools/report makes)."""
    name, args = claim.measure[0], claim.measure[1:]
    if name == "csv":  # a file a lab plug-in writes: (lab, file, "csv")
        lab, _, fname = (args[0] if args else "").partition("/")
        return [(lab, fname, "csv")] if lab and fname else []
    if not args:
        raise InputError(f"{claim.where}: claim '{claim.body}': {name} needs LAB/SCENE")
    lab, stem, integ = _target(args[0])
    if name in ("order", "sweep", "sweep-ratio", "cheapest"):
        return [(lab, stem, "sweep")]
    return [(lab, stem, integ)]


# Columns and summary keys no claim may name: wall time counts whatever else the machine
# ran meanwhile, so a ratio of two runs' wall times can flip on a loaded machine (it did: CI
# once measured 0.53 for a ratio of 4 on a quiet one). Timings in claims are CPU times.
WALL_CLOCK = ("wall_s",)


def measure(claim, data):
    name, args = claim.measure[0], claim.measure[1:]
    for a in args:
        if a in WALL_CLOCK:
            raise InputError(f"{claim.where}: claim '{claim.body}': '{a}' is wall time, which "
                             "the machine's load moves; claim on CPU time (the summary's "
                             "cpu_s; docs/report.md, Claims)")

    def want(n):
        if len(args) != n:
            raise InputError(f"{claim.where}: claim '{claim.body}': {name} takes {n} "
                             "arguments (docs/report.md, Claims)")
    if name == "order":   # order LAB/SCENE INTEGRATOR
        want(2)
        lab, stem, _ = _target(args[0])
        scale = recipes.length_scale(data.scene(lab, stem))
        runs = [r for r in wsweep.read_sweep(data.file(lab, f"{stem}-sweep.csv"))
                if r.integrator == args[1]]
        if not runs:
            raise InputError(f"{claim.where}: no runs of '{args[1]}' in {stem}-sweep.csv")
        order, _ = wsweep.measured_order(runs, scale)
        return "n/a" if order is None else order
    if name == "sweep":   # sweep LAB/SCENE INTEGRATOR COLUMN K  (the run at dt = K x scene dt)
        want(4)
        lab, stem, _ = _target(args[0])
        dt = float(data.scene(lab, stem)["dt"]) * _number(args[3])
        for r in wsweep.read_sweep(data.file(lab, f"{stem}-sweep.csv")):
            if r.integrator == args[1] and math.isclose(r.dt, dt, rel_tol=1e-9):
                return getattr(r, args[2]) if args[2] != "status" else r.status
        raise InputError(f"{claim.where}: no run of {args[1]} at dt = {dt:g} in the sweep")
    if name == "sweep-ratio":  # sweep-ratio LAB/SCENE COLUMN A B REDUCER: A/B at common dts
        want(5)
        lab, stem, _ = _target(args[0])
        scale = recipes.length_scale(data.scene(lab, stem))
        runs = wsweep.read_sweep(data.file(lab, f"{stem}-sweep.csv"))
        a = {r.dt: getattr(r, args[1]) for r in runs if r.integrator == args[2]
             and not wsweep.blew_up(r, scale)}
        b = {r.dt: getattr(r, args[1]) for r in runs if r.integrator == args[3]
             and not wsweep.blew_up(r, scale)}
        return _reduce([a[h] / b[h] for h in a if h in b and b[h]], args[4])
    if name == "cheapest":  # cheapest LAB/SCENE INTEGRATOR TARGET: fewest evaluations
        want(3)
        lab, stem, _ = _target(args[0])
        ok = [r.force_evals for r in wsweep.read_sweep(data.file(lab, f"{stem}-sweep.csv"))
              if r.integrator == args[1] and not r.diverged and r.error <= _number(args[2])]
        return min(ok) if ok else math.nan
    if name == "summary":  # summary LAB/SCENE[@I] KEY
        want(2)
        lab, stem, integ = _target(args[0])
        with open(data.file(lab, data.run_name(stem, integ) + "-summary.json"),
                  encoding="utf-8") as f:
            s = json.load(f)
        if args[1] not in s:
            raise InputError(f"{claim.where}: the summary has no key '{args[1]}'")
        v = s[args[1]]
        return math.nan if v is None else v
    if name == "stats":  # stats LAB/SCENE[@I] COLUMN REDUCER
        want(3)
        lab, stem, integ = _target(args[0])
        p = data.file(lab, data.run_name(stem, integ) + "-stats.csv")
        rows = read_csv(p, ["step", args[1]])
        col = [_float(r[args[1]]) for r in rows]
        steps = [_float(r["step"]) for r in rows]
        last = max((s for s, c in zip(steps, col) if finite(c)), default=0)
        return _reduce(col, args[2], steps=last - steps[0])
    if name in ("trace", "offset"):
        # trace LAB/SCENE[@I] QUANTITY REDUCER: over every row of every particle;
        # QUANTITY x, y, vx, vy, speed, r (from the origin), r@X,Y, disp (from the start).
        # offset LAB/SCENE[@I] x|y|r REDUCER: the last row minus the closed-form motion,
        # one value per particle (r: the distance between them).
        # A last argument id=K keeps particle K only.
        only = None
        if len(args) == 4 and args[3].startswith("id="):
            try:
                only = int(args[3][3:])
            except ValueError:
                raise InputError(f"{claim.where}: '{args[3]}': expected id=K, K a particle "
                                 "id") from None
            args = args[:3]
        want(3)
        lab, stem, integ = _target(args[0])
        run = data.run_name(stem, integ)
        try:
            p = data.file(lab, run + ".csv")
        except InputError:  # the rigid report's name for its trace
            p = data.file(lab, run + "-trace.csv")
        tr = _read_any_trace(p)
        if only is not None:
            if only not in tr:
                raise InputError(f"{claim.where}: id={only}: no such particle in {p}")
            tr = {only: tr[only]}
        if name == "offset":
            _, at = wexact.motion(data.scene(lab, stem))
            if at is None:
                raise InputError(f"{claim.where}: scene {lab}/{stem} has no closed form")
            vals = []
            for pid, d in sorted(tr.items()):
                ex, ey = at(pid, d["t"][-1])
                dx, dy = d["x"][-1] - ex, d["y"][-1] - ey
                vals.append({"x": dx, "y": dy, "r": math.hypot(dx, dy)}[_one(args[1], "xyr")])
            return _reduce(vals, args[2])
        q = args[1]
        vals = []
        if q.endswith(":end"):  # each particle's last row only
            q = q[:-len(":end")]
            tr = {pid: {c: col[-1:] for c, col in d.items()} for pid, d in tr.items()}
        if q.startswith("move@"):  # per particle: the farthest it got, from t >= T on,
            t0 = _number(q[5:])       # from where it was at the first row with t >= T
            for d in tr.values():
                ks = [k for k, t in enumerate(d["t"]) if t >= t0]
                cs = [c for c in ("x", "y", "z") if c in d]
                vals += [math.dist([d[c][k] for c in cs], [d[c][ks[0]] for c in cs])
                         for k in ks]
            return _reduce(vals, args[2])
        if q == "rchange":  # one value per particle: |x| at the end minus |x| at the start
            vals = [math.hypot(d["x"][-1], d["y"][-1]) - math.hypot(d["x"][0], d["y"][0])
                    for d in tr.values()]
            return _reduce(vals, args[2])
        for d in tr.values():
            for k in range(len(d["t"])):
                x, y, vx, vy = d["x"][k], d["y"][k], d["vx"][k], d["vy"][k]
                if q in ("x", "y", "vx", "vy"):
                    vals.append({"x": x, "y": y, "vx": vx, "vy": vy}[q])
                elif q == "speed":
                    vals.append(math.hypot(vx, vy))
                elif q == "disp":
                    vals.append(math.hypot(x - d["x"][0], y - d["y"][0]))
                elif q == "r" or q.startswith("r@"):
                    cx, cy = (0.0, 0.0) if q == "r" else (_number(c) for c in q[2:].split(","))
                    vals.append(math.hypot(x - cx, y - cy))
                else:
                    raise InputError(f"{claim.where}: quantity '{q}': expected x, y, vx, vy, "
                                     "speed, disp, r, r@X,Y, move@T or rchange")
        return _reduce(vals, args[2])
    if name == "csv":  # csv LAB/FILE COLUMN REDUCER [COL=VALUE ...]: any file of the report
        if len(args) < 3:
            raise InputError(f"{claim.where}: csv takes LAB/FILE COLUMN REDUCER [COL=VALUE...]")
        lab, _, fname = args[0].partition("/")
        rows = read_csv(data.file(lab, fname, report=True), [args[1]])
        for cond in args[3:]:
            col, _, val = cond.partition("=")
            rows = [r for r in rows if r.get(col, "").strip() == val]
        return _reduce([_float(r[args[1]]) for r in rows], args[2])
    raise InputError(f"{claim.where}: unknown measure '{name}' (expected order, sweep, "
                     "sweep-ratio, cheapest, summary, stats, trace, offset or csv)")


def _read_any_trace(path):
    """{id: {column: values}} of a particle trace, or of a rigid one (3D: x, y, z, and the
    velocities vx, vy, vz): the position quantities work on both."""
    with open(path, encoding="utf-8") as f:
        header = f.readline()
    if "qw" not in header.split(","):
        from .runs import read_trace
        return read_trace(path)
    from .labs.rigid import read_trace as rigid_trace
    return {b: {c: d[c] for c in ("t", "x", "y", "z", "vx", "vy", "vz")}
            for b, d in rigid_trace(path).items()}


def _one(s, allowed):
    if s not in allowed:
        raise InputError(f"'{s}': expected one of {', '.join(allowed)}")
    return s


def _number(s):
    if "/" in s:
        a, b = s.split("/", 1)
        return float(a) / float(b)
    return float(s)


def _float(s):
    try:
        return float(s)
    except ValueError:
        return math.nan


def check(claims, data, failed_runs=None):
    """[(claim, measured or None, why)] for every claim; why is '' when it holds."""
    out = []
    for c in claims:
        why = next((f"run failed: {w}" for n, w in (failed_runs or {}).items()
                    if n in needs(c)), "")
        got = None
        if not why:
            try:
                got = measure(c, data)
                why = c.judge(got) or claimrules.margin_problem(c, got) or c.prose_problem()
            except InputError as e:
                why = str(e)
        out.append((c, got, why))
    return out
