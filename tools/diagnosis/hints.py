"""Diagnosis of a failing task: what the student's functions do on fixed probe inputs, compared
with what the solution and each catalogued mistake do on the same inputs.

Pure standard library, no grader internals, shipped in the student pack with the catalogue
(tests/mutants/<lab>/signatures.json: numbers only, written by `tools/mutants --signatures`),
so that a grade at home says what the autograder says. docs/grading.md, "Diagnosis", has the
long version.

    from diagnosis import hints as wh
    cat = wh.load_catalogue(repo, "forces")                 # None: no diagnosis, grading goes on
    d = wh.diagnose(cat, "F3", outputs, failed_tests)       # outputs: {probe id: record}
    print("\\n".join(d.lines()))

A probe record is one JSON line of a probe binary (tests/common/wb_probe.h): the inputs given
("in"), the outputs got ("out") or the exception ("error"). For one task the diagnosis is, in
this order:
  - "passed": every test of the task passed (nothing to say);
  - "not started": every probe gives what the skeleton gives;
  - "mistake": the outputs match a catalogued mistake on every probe (within the probes'
    tolerance), and every mistake that matches is of one kind: its hint is named;
  - "part": no catalogued mistake matches exactly, but the probes that go wrong are those that
    go wrong for the catalogued mistakes of one part of the computation (a '# kind:') and of no
    other (the rule: part_of below): that part is named, never a particular mistake;
  - always, when some probe differs from the solution, a counterexample: the first such probe
    in the order the probes are written (the simplest first), its inputs, expected and got, and
    what differs (the sign, a constant factor, one component, one particle, what f held);
  - "tests": every probe agrees with the solution, yet a test fails: the first failed test's
    own message (it has the expected and actual values).
A task's diagnosis depends only on that task's probes and tests: a task still at its skeleton
never changes another's.
"""
import json
import math
import os
import re

CATALOGUE_VERSION = 2
MAX_LIST = 3        # probes listed as "right on" / "wrong on"
VALUE_CHARS = 160   # characters of a value shown whole; a longer one shows the entries that differ
LINE_WIDTH = 96     # characters of one line of a diagnosis (indented by 2 under its lab: <= 100);
                    # a longer line goes on over the next ones, indented, never cut
LINE_CHARS = 400    # characters of one line kept by the grader's table (results.DIAGNOSIS_CHARS)


def catalogue_path(repo, lab):
    return os.path.join(repo, "tests", "mutants", lab, "signatures.json")


def load_catalogue(repo, lab):
    """The lab's catalogue (the parsed JSON), or None when there is none or it cannot be read (no
    diagnosis then: a missing catalogue never breaks grading)."""
    try:
        with open(catalogue_path(repo, lab), encoding="utf-8") as f:
            data = json.load(f)
    except (OSError, ValueError):
        return None
    if not isinstance(data, dict) or data.get("version") != CATALOGUE_VERSION \
            or not isinstance(data.get("mutants"), dict) or not isinstance(data.get("probes"), list):
        return None
    return data


# ------------------------------------------------------- failed tests' texts

_NUMBER = re.compile(r"[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?")
FAILURE_CHARS = 300  # characters of a blanked failure text kept in the catalogue


def failure_text(output):
    """What the catalogue keeps of a failed test (tools/mutants compares it between runs): the
    first paragraph of the grader's output for it, every number blanked to '#', whitespace
    collapsed, at most FAILURE_CHARS characters."""
    first = (output or "").split("\n\n", 1)[0]
    return " ".join(_NUMBER.sub("#", first).split())[:FAILURE_CHARS]


# ------------------------------------------------------------------ records

def parse_lines(text, limit=4096):
    """Probe records from a probe binary's standard output (bad lines skipped)."""
    out = []
    for line in (text or "").splitlines()[:limit]:
        line = line.strip()
        if not line.startswith("{"):
            continue
        try:
            rec = json.loads(line)
        except ValueError:
            continue
        if isinstance(rec, dict) and isinstance(rec.get("probe"), str):
            out.append(rec)
    return out


def _num(v):
    if isinstance(v, bool):
        return float(v)
    if isinstance(v, (int, float)):
        return float(v)
    if v == "nan":
        return math.nan
    if v == "inf":
        return math.inf
    if v == "-inf":
        return -math.inf
    return math.nan


def values(rec):
    """{output name: (rows, cols, [floats])} of a record ("out"), {} for an error."""
    out = {}
    outs = (rec or {}).get("out") if isinstance(rec, dict) else None
    for o in outs if isinstance(outs, list) else []:
        try:
            rows, cols = int(o["shape"][0]), int(o["shape"][1])
            vs = [_num(v) for v in o["v"]]
        except (KeyError, TypeError, ValueError, IndexError):
            continue
        if rows >= 0 and cols >= 0 and rows * cols == len(vs):
            out[str(o["name"])] = (rows, cols, vs)
    return out


def inputs(rec):
    out = []
    for o in (rec or {}).get("in") or []:
        try:
            out.append((str(o["name"]), int(o["shape"][0]), int(o["shape"][1]),
                        [_num(v) for v in o["v"]], bool(o.get("integer"))))
        except (KeyError, TypeError, ValueError, IndexError):
            continue
    return out


def compact(rec):
    """What the catalogue keeps of a record: the outputs (numbers rounded to 12 significant
    digits: the same on any machine that computes them to 1e-12) or the error."""
    if rec is None:
        return {"error": "no output (the probe did not run)"}
    if rec.get("error"):
        return {"error": str(rec["error"])[:300]}
    out = {}
    for name, (rows, cols, vs) in values(rec).items():
        out[name] = [rows, cols, [_round(v) for v in vs]]
    return {"out": out}


def _round(v):
    if math.isnan(v):
        return "nan"
    if math.isinf(v):
        return "inf" if v > 0 else "-inf"
    r = float(f"{v:.12g}")
    return int(r) if r == int(r) and abs(r) < 1e15 else r


def expand(c):
    """A compact record back as {name: (rows, cols, [floats])}, or None for an error."""
    if not isinstance(c, dict) or "out" not in c:
        return None
    got = c.get("out")
    if not isinstance(got, dict):
        return None
    out = {}
    for name, v in got.items():
        try:
            rows, cols, vs = int(v[0]), int(v[1]), [_num(x) for x in v[2]]
        except (TypeError, ValueError, IndexError, KeyError):
            continue
        if rows >= 0 and cols >= 0 and rows * cols == len(vs):
            out[str(name)] = (rows, cols, vs)
    return out


def error_of(c):
    return str(c.get("error") or "") if isinstance(c, dict) else "no output"


# -------------------------------------------------------------- comparison

def _close(a, b, rel, ab):
    if math.isnan(a) or math.isnan(b):
        return math.isnan(a) and math.isnan(b)
    if math.isinf(a) or math.isinf(b):
        return a == b
    return abs(a - b) <= ab + rel * max(abs(a), abs(b))


def _scale(vals):
    s = 1.0
    for _, _, vs in vals.values():
        for v in vs:
            if math.isfinite(v):
                s = max(s, abs(v))
    return s


def tolerance(probe):
    """(relative, absolute) tolerance of a probe: its own, the absolute part scaled by the largest
    expected output (so that a probe of large numbers is not held to 1e-9)."""
    try:
        rel, ab = float(probe["tol"][0]), float(probe["tol"][1])
    except (KeyError, TypeError, ValueError, IndexError):
        rel, ab = 1e-7, 1e-9
    exp = expand(probe.get("expected")) or {}
    return rel, ab * _scale(exp)


def same(a, b, tol):
    """Whether two compact records agree: the same error-ness, the same outputs within tol."""
    ea, eb = expand(a), expand(b)
    if ea is None or eb is None:
        return ea is None and eb is None
    if set(ea) != set(eb):
        return False
    rel, ab = tol
    for name, (r, c, va) in ea.items():
        rb, cb, vb = eb[name]
        if (r, c) != (rb, cb) or len(va) != len(vb):
            return False
        if not all(_close(x, y, rel, ab) for x, y in zip(va, vb)):
            return False
    return True


def units(probe, got):
    """{unit: class} for one probe: a unit is (probe, output, column) for an output whose
    columns are told apart (out_each: particles, bodies), else (probe, output, 0); the class is
    "ok", "error" (an exception where the solution returned, or the reverse), "shape", "nan"
    (not finite), "none" (what the skeleton gives, where no other output of the call was
    computed wrong: nothing was done) or "wrong"."""
    pid = probe["probe"]
    exp, skel, g = expand(probe.get("expected")), expand(probe.get("skeleton")), expand(got)
    if exp is None or g is None:
        if exp is not None:  # an error where the solution returns: every output is wrong
            flags = {str(o.get("name")): o for o in (probe.get("out") or []) if isinstance(o, dict)}
            return {(pid, str(flags.get(n, {}).get("group") or n), 0): "error" for n in exp} \
                or {(pid, "*", 0): "error"}
        return {(pid, "*", 0): "ok" if g is None else "error"}
    rel, ab = tolerance(probe)
    out = {}
    flags = {str(o.get("name")): o for o in (probe.get("out") or []) if isinstance(o, dict)}
    each = {n for n, o in flags.items() if o.get("each")}
    group = {n: str(o["group"]) for n, o in flags.items() if o.get("group")}
    asis = {}  # unit: every output of it is the skeleton's (a group is "none" only then)
    for name, (rows, cols, ev) in exp.items():
        unit = group.get(name, name)
        if name not in g or g[name][:2] != (rows, cols) or len(g[name][2]) != len(ev):
            out[(pid, unit, 0)] = "shape"
            asis[(pid, unit, 0)] = False
            continue
        gv = g[name][2]
        sv = skel[name][2] if skel and name in skel and skel[name][:2] == (rows, cols) else None
        per = name in each and cols > 1
        for c in range(cols if per else 1):
            idx = range(c * rows, (c + 1) * rows) if per else range(len(ev))
            same_as_skel = sv is not None and all(_close(gv[i], sv[i], rel, ab) for i in idx)
            if all(_close(gv[i], ev[i], rel, ab) for i in idx):
                k = "ok"
            elif any(not math.isfinite(gv[i]) for i in idx):
                k = "nan"
            elif same_as_skel:
                k = "none"
            else:
                k = "wrong"
            key = (pid, unit, c)
            asis[key] = asis.get(key, True) and same_as_skel
            prev = out.get(key, "ok")
            if prev == "ok" or (prev == "none" and k != "ok"):
                out[key] = k
    # A group goes wrong as "nothing done" only if all of it is, and an output only if no other
    # output of the call was computed wrong (a total driven to the skeleton's 0 beside a
    # velocity the code did change is a wrong value, not one left alone).
    computed = "wrong" in out.values()
    for key, k in out.items():
        if k == "none" and (not asis.get(key, False) or computed):
            out[key] = "wrong"
    return out


# -------------------------------------------------------------- the catalogue

def task_probes(cat, task):
    return [p for p in cat.get("probes", []) if isinstance(p, dict) and p.get("task") == task
            and isinstance(p.get("probe"), str)]


def task_mutants(cat, task, exclude=()):
    return {n: m for n, m in sorted(cat.get("mutants", {}).items())
            if isinstance(m, dict) and m.get("task") == task and n not in exclude}


def part_key(name, m):
    """A part of the computation: the file a mistake is in and its '# kind:'."""
    return (name.split(".")[0], str(m.get("kind") or ""))


REACH_LEVEL = "unit"   # what a part's mistakes must explain: every wrong particle, body, output
CORE_LEVEL = "unit"  # what a submission must share with every mistake of the part: units (a
                    # particle that all of a formula's mistakes get wrong, a loop's leaves right)
NEAR = 0.8  # another part that explains this share of the wrong units makes the naming unsure


CLASSES = True  # a part explains a wrong output only if one of its mistakes gets it wrong alike:
# "nothing done" (the skeleton's value, a test never reached) apart from a wrong value
_KIND = {"none": "none", "nan": "wrong", "error": "wrong", "shape": "wrong", "wrong": "wrong"}


def bad_units(probes, outputs, classes=False):
    """The units (of the probes that tell parts apart: not the simple ones) that are not ok;
    with classes, as (unit, how it is wrong): nothing done (the skeleton's value), NaN or an
    error, another size, a wrong value."""
    bad = set()
    for p in probes:
        if p.get("simple"):
            continue
        for u, k in units(p, outputs.get(p["probe"])).items():
            if k != "ok":
                bad.add((u, _KIND.get(k, "wrong")) if classes else u)
    return bad


def unit_errors(probe, got):
    """{unit: [got - expected, entry by entry]} of one probe's units whose values came back
    with the expected shape (the units of units()); what a wrong value looks like."""
    pid = probe["probe"]
    exp, g = expand(probe.get("expected")), expand(got)
    if exp is None or g is None:
        return {}
    flags = {str(o.get("name")): o for o in (probe.get("out") or []) if isinstance(o, dict)}
    out = {}
    for name, (rows, cols, ev) in exp.items():
        if name not in g or g[name][:2] != (rows, cols) or len(g[name][2]) != len(ev):
            continue
        unit = str(flags.get(name, {}).get("group") or name)
        per = bool(flags.get(name, {}).get("each")) and cols > 1
        gv = g[name][2]
        for c in range(cols if per else 1):
            idx = range(c * rows, (c + 1) * rows) if per else range(len(ev))
            out.setdefault((pid, unit, c), []).extend(gv[i] - ev[i] for i in idx)
    return out


ALIGNED = 0.999  # cosine above which two errors point the same way ("wrong alike")


def _aligned(a, b):
    if not a or len(a) != len(b) or not all(math.isfinite(x) for x in a + b):
        return False
    na, nb = math.sqrt(sum(x * x for x in a)), math.sqrt(sum(x * x for x in b))
    return na > 0 and nb > 0 and sum(x * y for x, y in zip(a, b)) >= ALIGNED * na * nb


def _at(units_, level):
    """Units seen at one level: the probe alone, the probe and output, or the whole unit."""
    if level == "probe":
        return {u[:1] for u in units_}
    if level == "output":
        return {u[:2] for u in units_}
    return set(units_)


def part_of(cat, task, outputs, exclude=()):
    """The part of the computation the wrong probes point at, or None.

    B is what goes wrong for the submission, for each part k (the catalogued mistakes of one
    file and '# kind:', those in `exclude` left out) reach_k is what any of its mistakes gets
    wrong, core_k the outputs every one of them gets wrong. k fits when B is within reach_k,
    unit by unit and alike (each output of each probe, or its particles apart: some mistake of
    k gets it wrong the same way, "nothing done" or a wrong value) and B's outputs include
    core_k (what every mistake of k gives away shows). The one part that fits is named, unless
    another part explains NEAR of B as well; a submission whose wrong outputs could come from
    two parts, or from none, gets no part named (its counterexample still says what is wrong).
    The probes written as details (P.simple) are left out. The levels and NEAR were chosen on
    the catalogue itself (docs/grading.md, "leave-one-out"), so its figures are somewhat
    optimistic."""
    probes = task_probes(cat, task)
    B = bad_units(probes, outputs, classes=True)
    if not B:
        return None
    parts, errs = {}, {}
    for name, m in task_mutants(cat, task, exclude).items():
        if not m.get("kind"):
            continue
        bad = bad_units(probes, m.get("probes") or {}, classes=True)
        if bad:
            parts.setdefault(part_key(name, m), []).append(bad)
            errs.setdefault(part_key(name, m), []).append(
                _errors(probes, m.get("probes") or {}))

    def reach_of(b):  # (unit seen at REACH_LEVEL[, how it is wrong])
        return {(_at({u}, REACH_LEVEL).pop(), k) if CLASSES else _at({u}, REACH_LEVEL).pop()
                for u, k in b}

    def core_of(b):
        return _at({u for u, _ in b}, CORE_LEVEL)
    fits, near = _fits(parts, B, reach_of, core_of)
    if not fits and not near and _partial(probes, B):
        # A loop's range: which particles it misses depends on where the range goes wrong
        # (the first, the last, every one past the second), so none of them is in every
        # mistake of the part. When the submission leaves some particles of each wrong output
        # right, the parts whose every mistake does too are seen with the particles of an
        # output taken as one (a mistake of a formula, wrong on every particle, is not one).
        ranged = {k: sets for k, sets in parts.items() if all(_partial(probes, b) for b in sets)}
        fits, near = _fits(ranged, B, lambda b: {(u[:2], k) for u, k in reach_of(b)},
                           lambda b: {u[:2] for u in core_of(b)})
    if len(fits) == 1 and not near:
        return fits[0]
    if not fits:
        return None
    # Several parts fit by which outputs go wrong: the one whose mistakes also go wrong the
    # same way (each wrong value's error points as one of its mistakes' does), if only one
    # does. Mirror-image mistakes of two stages (the trapezoid's second stage and its average:
    # a weight on a(X) too large in one, too small in the other) go wrong in the same outputs.
    mine = _errors(probes, outputs)
    valued = [u for u in mine if u in {v for v, _ in B}]
    if not valued:
        return None
    alike = [k for k in fits + near
             if all(any(_aligned(mine[u], e.get(u, [])) for e in errs[k]) for u in valued)]
    return alike[0] if len(alike) == 1 and alike[0] in fits else None


def _partial(probes, bad):
    """Whether every wrong output of `bad` (units with how they are wrong) is one recorded
    particle by particle with some of its particles right."""
    cols = {}
    for p in probes:
        exp = expand(p.get("expected")) or {}
        for o in p.get("out") or []:
            if isinstance(o, dict) and o.get("each") and str(o.get("name")) in exp:
                cols[(p["probe"], str(o.get("group") or o["name"]))] = exp[str(o["name"])][1]
    seen = {}
    for u, _ in bad:
        seen.setdefault(u[:2], set()).add(u[2])
    return bool(seen) and all(1 < cols.get(o, 1) and len(cs) < cols[o] for o, cs in seen.items())


def _fits(parts, B, reach_of, core_of):
    """(parts that fit B, parts near it): B within the part's reach and holding its core."""
    Br, Bc = reach_of(B), core_of(B)
    fits, near = [], []
    for key, sets in sorted(parts.items()):
        reach = set.union(*(reach_of(b) for b in sets))
        core = set.intersection(*(core_of(b) for b in sets))
        if not core <= Bc:
            continue
        if Br <= reach:
            fits.append(key)
        elif len(Br & reach) >= NEAR * len(Br):
            near.append(key)
    return fits, near


def _errors(probes, outputs):
    """{unit: error vector} of every probe that tells parts apart (not the simple ones)."""
    out = {}
    for p in probes:
        if not p.get("simple"):
            out.update(unit_errors(p, outputs.get(p["probe"])))
    return out


def exact_mistakes(cat, task, outputs, exclude=()):
    """The catalogued mistakes whose outputs equal the submission's on every probe of the task
    (mistakes that give the solution's outputs on every probe are never named)."""
    probes = task_probes(cat, task)
    if not probes:
        return []
    found = []
    for name, m in task_mutants(cat, task, exclude).items():
        mo = m.get("probes") or {}
        if all(same(outputs.get(p["probe"]), mo.get(p["probe"]), tolerance(p)) for p in probes) \
                and not all(same(p.get("expected"), mo.get(p["probe"]), tolerance(p))
                            for p in probes):
            found.append(name)
    return found


# ----------------------------------------------------------------- diagnosis

class Diagnosis:
    """What is said about one task. status: passed, not started, mistake, part, counterexample,
    tests (a failing test the probes do not reproduce), no probes."""

    def __init__(self, task, title=""):
        self.task, self.title = task, title
        self.status = "passed"
        self.mistakes = []        # hints of the catalogued mistake(s) matched exactly
        self.mistake_names = []   # their names (for tools/mutants)
        self.part = None          # (file, kind) pointed at
        self.counterexample = []  # lines
        self.right, self.wrong = [], []  # titles of the probes that agree / differ
        self.failed, self.total = 0, 0   # tests of the task
        self.notes = []           # lines about other tasks this one builds on
        self.test_message = ""    # the first failed test's own message (status "tests")
        self.handout = ""         # the task's handout section (handouts/<lab>.md#<task>)

    def headline(self):
        head = f"{self.task}{' ' + self.title if self.title else ''}"
        if self.status == "not started":
            return f"{head}: not started (its functions still do what the skeleton does)"
        tests = f"{self.failed} of {self.total} tests failed" if self.total else "tests failed"
        return f"{head}: {tests}"

    def lines(self):
        """The diagnosis as a student reads it: lines of at most LINE_WIDTH characters."""
        return [w for l in self._lines() for w in wrap(l, LINE_WIDTH)]

    def _lines(self):
        if self.status == "passed":
            return []
        out = [self.headline()]
        if self.status == "not started":
            return out
        out += ["  " + n for n in self.notes]
        if self.mistakes:
            if len(self.mistakes) == 1:
                out.append("  Known mistake: " + self.mistakes[0])
            else:
                out.append("  Known mistake, one of:")
                out += ["  - " + h for h in self.mistakes]
        elif self.part:
            fname, kind = self.part
            out.append(f"  The wrong probes point at the {kind} in {fname}.cpp "
                       f"({self.handout or 'handout §' + self.task}); it is none of the known "
                       "mistakes exactly.")
        out += ["  " + l for l in self.counterexample]
        if self.right and self.wrong:
            for what, titles in (("Right", self.right), ("Wrong", self.wrong)):
                more = len(titles) - MAX_LIST
                out.append(f"  {what} on: " + "; ".join(titles[:MAX_LIST]) +
                           (f"; and {more} more" if more > 0 else ""))
        if self.status == "tests":
            out.append("  The probes (fixed example inputs) do not show this mistake; the first "
                       "failed test does:")
            out += ["    " + l for l in self.test_message.splitlines()[:8]]
        if self.status == "no probes":
            out.append("  (the probes could not run: out of time, or no catalogue); the first "
                       "failed test says:")
            out += ["    " + l for l in self.test_message.splitlines()[:8]]
        return out


def wrap(line, width=LINE_WIDTH):
    """One line as lines of at most `width` characters, broken at spaces (a word longer than a
    line is broken where it must), the lines after the first indented 2 more than it. Nothing
    is cut."""
    if len(line) <= width:
        return [line]
    lead = len(line) - len(line.lstrip(" "))
    pad = " " * min(lead + 2, width // 2)
    out, cur = [], line
    while len(cur) > width:
        cut = cur.rfind(" ", len(pad) + 1 if out else lead + 1, width + 1)
        if cut <= (len(pad) if out else lead):
            cut = width
        out.append(cur[:cut].rstrip())
        cur = pad + cur[cut:].lstrip(" ")
    return out + [cur]


def wrong_outputs(probe, got):
    """The names of a probe's outputs that differ from the expected ones."""
    exp, g = expand(probe.get("expected")) or {}, expand(got)
    if g is None:
        return list(exp)
    rel, ab = tolerance(probe)
    return [n for n, (r, c, ev) in exp.items()
            if n not in g or g[n][:2] != (r, c) or not all(_close(a, b, rel, ab)
                                                         for a, b in zip(g[n][2], ev))]


def diagnose(cat, task, outputs, tests, title="", exclude=(), pristine=False):
    """The diagnosis of one task.

    cat      the lab's catalogue (load_catalogue)
    outputs  {probe id: record} of the submission's probes of this task (records as the probe
             binary printed them, or compact ones); None when the probes could not run
    tests    [(test name, passed?, output)] of this task's tests
    pristine True when the task's files are the skeleton's, byte for byte (not started, without
             running anything)
    exclude  catalogued mistakes to leave out (leave-one-out)"""
    d = Diagnosis(task, title)
    d.handout = str(((cat or {}).get("tasks") or {}).get(task, {}).get("handout") or "")
    d.total = len(tests)
    d.failed = sum(1 for t in tests if not t[1])
    if tests and not d.failed:
        return d
    probes = task_probes(cat, task) if cat else []
    if pristine:
        d.status = "not started"
        return d
    first = next((t for t in tests if not t[1]), None)
    if first:
        d.test_message = f"{first[0]}:\n" + (first[2] or "").split("\n\n")[0]
    if not probes or outputs is None:
        d.status = "no probes"
        return d
    got = {p["probe"]: compact_any(outputs.get(p["probe"])) for p in probes}
    if all(same(got[p["probe"]], p.get("skeleton"), tolerance(p)) for p in probes) and \
            not all(same(p.get("expected"), p.get("skeleton"), tolerance(p)) for p in probes):
        d.status = "not started"
        return d
    wrong = [p for p in probes if not same(got[p["probe"]], p.get("expected"), tolerance(p))]
    d.right = [p.get("title", p["probe"]) for p in probes if p not in wrong]
    d.wrong = []
    for p in wrong:  # a probe of several outputs says which of them are wrong
        bad, every = wrong_outputs(p, got[p["probe"]]), list(expand(p.get("expected")) or {})
        d.wrong.append(p.get("title", p["probe"]) + (
            f" (its {', '.join(bad)} only)" if bad and len(bad) < len(every) else ""))
    if not wrong:
        d.status = "tests"
        return d
    d.status = "counterexample"
    names = exact_mistakes(cat, task, got, exclude)
    muts = cat.get("mutants", {})
    kinds = {part_key(n, muts[n]) for n in names}
    if names and len(kinds) == 1:
        d.status = "mistake"
        d.mistake_names = names
        for n in names:
            h = str(muts[n].get("hint") or "").strip()
            if h and h not in d.mistakes:
                d.mistakes.append(h)
    else:
        d.part = part_of(cat, task, got, exclude)
        if d.part:
            d.status = "part"
    adds = ((cat.get("tasks") or {}).get(task) or {}).get("adds") or ()
    d.counterexample = counterexample(wrong[0], got[wrong[0]["probe"]], adds)
    return d


def compact_any(rec):
    """A record from a probe binary, or one already compact, as a compact record."""
    if isinstance(rec, dict) and ("in" in rec or "probe" in rec):
        return compact(rec)
    if isinstance(rec, dict) and ("out" in rec or "error" in rec):
        return rec
    return compact(None)


# ------------------------------------------------------------ counterexample

def _digits(a, b):
    """The significant digits that show a and b apart (6 when they differ there already, up to
    17, the digits of a double; 6 when they are equal)."""
    if not (math.isfinite(a) and math.isfinite(b)) or a == b:
        return 6
    for p in range(6, 18):
        if f"{a:.{p}g}" != f"{b:.{p}g}":
            return p
    return 17


def fmt_number(v, integer=False, digits=6):
    if math.isnan(v):
        return "NaN"
    if math.isinf(v):
        return "inf" if v > 0 else "-inf"
    if integer or (v == int(v) and abs(v) < 1e12):
        return str(int(v))
    return f"{v:.{digits}g}"


def _entries(rows, cols):
    """How one entry of a value is named: a point's index, a vector's index, a matrix's (row,
    column)."""
    if cols == 1:
        return lambda k: f"[{k}]"
    if rows in (2, 3) and cols != rows:
        return lambda k: f"[{k // rows}].{'xyz'[k % rows]}"
    return lambda k: f"({k % rows}, {k // rows})"


def fmt_value(rows, cols, vs, integer=False, other=None, only=None):
    """A value as a student reads it: a number, a point (x, y), points [(x, y), ...], a matrix by
    rows [a, b; c, d]. Each number has the digits that tell it from the same entry of `other`
    (the expected value for a got, the got for an expected). `only`: the entries to show (the
    ones that differ, for a value too long to show whole), named by index."""
    digits = [(_digits(v, other[k]) if other is not None and k < len(other) else 6)
              for k, v in enumerate(vs)]
    f = [fmt_number(v, integer, digits[k]) for k, v in enumerate(vs)]
    if only is not None:
        name = _entries(rows, cols)
        return ", ".join(f"{name(k)} = {f[k]}" for k in only)
    if rows * cols == 0:
        return f"(empty, {rows} x {cols})"
    if rows == 1 and cols == 1 and f:
        return f[0]
    if cols == 1 and rows in (2, 3, 4):
        return "(" + ", ".join(f) + ")"
    if cols == 1:
        return "[" + ", ".join(f) + "]"
    if rows in (2, 3) and cols != rows:  # columns are points: particles, bodies
        return "[" + ", ".join("(" + ", ".join(f[c * rows:(c + 1) * rows]) + ")"
                               for c in range(cols)) + "]"
    return "[" + "; ".join(", ".join(f[c * rows + r] for c in range(cols))  # a matrix: by rows
                           for r in range(rows)) + "]"


def counterexample(probe, got, adds=()):
    """Lines: the probe's call, expected, got, and what differs. `adds`: the outputs the task's
    header says to add to (its contract: "add, do not overwrite"), the only ones for which
    overwriting is named as the mistake."""
    lines = [f"Counterexample ({probe['probe']}: {probe.get('title', '')}):"]
    ins = probe.get("in") or []
    args = []
    for name, rows, cols, vs, integer in inputs({"in": ins}):
        args.append(f"{name} = {fmt_value(rows, cols, vs, integer)}")
    call = probe.get("call") or "called with"
    lines.append(f"  {call}({', '.join(args)})" if probe.get("call") else
                 "  inputs: " + ", ".join(args))
    for n in probe.get("notes") or []:
        lines.append(f"  where {n}")
    exp, g = expand(probe.get("expected")), expand(got)
    if g is None:
        err = error_of(got)
        if exp is None:
            lines.append(f"  expected an error, got: {err}")
        else:
            lines.append("  expected " + "; ".join(f"{n} = {fmt_value(*v)}" for n, v in exp.items()))
            lines.append(f"  got      an error: {err}")
        return lines
    if exp is None:
        lines.append(f"  expected an error ({error_of(probe.get('expected'))}), got values")
        return lines
    rel, ab = tolerance(probe)
    base = {name: (rows, cols, vs) for name, rows, cols, vs, _ in inputs({"in": ins})}
    skel = expand(probe.get("skeleton")) or {}
    for name, (rows, cols, ev) in exp.items():
        gv = g.get(name)
        if gv is not None and gv[:2] == (rows, cols) and \
                all(_close(a, b, rel, ab) for a, b in zip(gv[2], ev)):
            continue
        if gv is None:
            lines.append(f"  expected {name} = {fmt_value(rows, cols, ev)}")
            lines.append(f"  got      no {name}")
            continue
        same_shape = gv[:2] == (rows, cols)
        e_text = fmt_value(rows, cols, ev, other=gv[2] if same_shape else None)
        g_text = fmt_value(*gv, other=ev if same_shape else None)
        if same_shape and max(len(e_text), len(g_text)) > VALUE_CHARS:  # the differing entries
            bad = [k for k, (a, b) in enumerate(zip(gv[2], ev)) if not _close(a, b, rel, ab)]
            rest = f" (the other {len(ev) - len(bad)} of {len(ev)} entries agree)" \
                if len(bad) < len(ev) else ""
            e_text = fmt_value(rows, cols, ev, other=gv[2], only=bad) + rest
            g_text = fmt_value(*gv, other=ev, only=bad)
        lines.append(f"  expected {name} = {e_text}")
        lines.append(f"  got      {name} = {g_text}")
        try:
            why = explain(name, (rows, cols, ev), gv, base.get(name), rel, ab,
                          adds=adds, skeleton=skel.get(name))
        except (ValueError, ArithmeticError, IndexError):
            why = ""
        if why:
            lines.append(f"  {name}: {why}")
    return lines


FACTOR_MIN = 3  # numbers that must differ alike before a constant factor is named: with one
                # or two, any wrong value "is off by a factor", which says nothing


def _ratio(dg, de, rel, ab):
    """c with dg = c de for every entry, or None."""
    c = None
    for a, b in zip(dg, de):
        if not (math.isfinite(a) and math.isfinite(b)):
            return None
        if abs(b) <= ab:
            if abs(a) > ab:
                return None
            continue
        r = a / b
        if c is None:
            c = r
        elif not _close(r, c, 1e-6, 1e-12):
            return None
    return c


def _pretty(c):
    if not math.isfinite(c):
        return str(c)
    for den in (1, 2, 3, 4):
        if abs(c * den - round(c * den)) < 1e-9 and round(c * den) != 0:
            n = int(round(c * den))
            return str(n) if den == 1 else f"{n}/{den}"
    return fmt_number(c, digits=_digits(c, 1.0))


def _base_name(name):
    return name.rsplit(".", 1)[-1]


def explain(name, expected, got, before, rel, ab, adds=(), skeleton=None):
    """What differs between expected and got, in words ("" when nothing simple is seen). Each
    relation is said only where it holds: a constant factor across at least FACTOR_MIN
    differing numbers; a sign flip when every number is the expected one negated; "nothing
    computed" only when the output is the input's value or the skeleton's; "add, do not
    overwrite" only for an output the header says to add to (`adds`)."""
    rows, cols, ev = expected
    gr, gc, gv = got
    if (gr, gc) != (rows, cols):
        return f"the size is {gr} x {gc}, expected {rows} x {cols}"
    if any(not math.isfinite(v) for v in gv) and all(math.isfinite(v) for v in ev):
        return "not a number (NaN or inf) where the expected value is finite"

    def alike(a, b):
        return all(_close(x, y, rel, ab) for x, y in zip(a, b))
    adds = {_base_name(a) for a in adds}
    accumulates = _base_name(name) in adds
    bv = before[2] if before and before[:2] == (rows, cols) else None
    sv = skeleton[2] if skeleton and skeleton[:2] == (rows, cols) else None
    if bv is not None and alike(gv, bv):
        if accumulates:
            return f"unchanged: nothing was added to what {name} held before the call"
        return f"unchanged: {name} is what it was before the call (nothing computed?)"
    if sv is not None and alike(gv, sv) and not alike(ev, sv):
        return "what the skeleton gives (nothing computed?)"
    if bv is not None and any(abs(v) > ab for v in bv):
        contrib = [e - b for e, b in zip(ev, bv)]
        if alike(gv, contrib):
            return (f"what {name} held before the call is lost: add to {name}, do not overwrite "
                    "it" if accumulates else f"what {name} held before the call is lost")
        de, dg = contrib, [g - b for g, b in zip(gv, bv)]
        its = "its change"
    else:
        de, dg, its = ev, gv, ""
    differ = sum(1 for a, b in zip(dg, de) if not _close(a, b, rel, ab))
    if differ and all(_close(a, -b, rel, ab) for a, b in zip(dg, de)):
        return f"the sign of {its} is flipped" if its else "the sign is flipped"
    c = _ratio(dg, de, rel, ab)
    if c is not None and differ >= FACTOR_MIN and c != 0 and not _close(c, 1.0, 1e-9, 0):
        return (f"{its} is" if its else "it is") + \
            f" off by a constant factor {_pretty(c)} (in all {differ} numbers that differ)"
    if rows in (2, 3) and cols >= 1:
        comps = "xyz"[:rows]
        per = [all(_close(gv[c * rows + r], ev[c * rows + r], rel, ab) for c in range(cols))
               for r in range(rows)]
        if rows == 2 and not any(per) and all(
                _close(dg[c * 2], de[c * 2 + 1], rel, ab) and _close(dg[c * 2 + 1], de[c * 2], rel, ab)
                for c in range(cols)):
            return f"the x and y components{' of ' + its if its else ''} are swapped"
        if any(per) and not all(per):
            bad = [comps[r] for r in range(rows) if not per[r]]
            return f"only the {' and '.join(bad)} component{'s' if len(bad) > 1 else ''} differ" + \
                ("" if len(bad) > 1 else "s")
        if cols > 1:
            okc = [all(_close(gv[c * rows + r], ev[c * rows + r], rel, ab) for r in range(rows))
                   for c in range(cols)]
            if any(okc) and not all(okc):
                badc = [c for c in range(cols) if not okc[c]]
                nothing = [c for c in badc if all(abs(dg[c * rows + r]) <= ab for r in range(rows))]
                which = ", ".join(str(c) for c in badc)
                s = "s" if len(badc) > 1 else ""
                item = "particle" if rows == 2 else "column"
                if nothing == badc:
                    return (f"{item}{s} {which} (of 0..{cols - 1}) get{'' if s else 's'} nothing; "
                            "the others are right")
                return f"only {item}{s} {which} (of 0..{cols - 1}) differ{'' if s else 's'}"
    return ""


# ---------------------------------------------------------------- one lab

def task_tests(cat, task, results):
    """[(name, passed, output)] of one task's tests, from the tests' names ("F3 attractor: ...")."""
    return [r for r in results if re.match(rf"^{re.escape(task)}\b", r[0])]


def task_title(cat, task):
    t = (cat or {}).get("tasks", {}).get(task) or {}
    return str(t.get("title") or "")
