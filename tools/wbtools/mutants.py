"""tools/mutants: checks that the graded tests catch known-wrong code and accept correct variants."""
# For each lab with tests/mutants/<lab>/ (docs/grading.md, "Mutants and
# alternatives"):
#   - the solution itself must score 100;
#   - every *.patch (a unified diff against one file of solutions/<lab>/, with
#     '# hint: ...' and '# caught-by: ...' in its header) must score < 100, and
#     each entry of its caught-by list must be caught by at least one of the
#     tests it names;
#   - every alternatives/<name>[.<variant>].cpp (a correct <name>.cpp written
#     differently) must score 100.
#   - the mutants' failure signatures (which tests each fails, at which
#     assertion) must equal the stored tests/mutants/<lab>/signatures.json, the
#     data the grader's hints come from (tools/diagnosis/hints.py); --signatures
#     rewrites it, --leave-one-out measures the hints from it (no build);
#   - every variant is judged the same way when run again: each failed test is run a
#     second time (and a variant the grader judged is graded a second time), and a
#     difference in which tests fail or in their failure texts is FLAKY;
#   - every mutant is caught by a wide margin: its widest failing check misses by at
#     least margins.WEAK times its tolerance (tools/wbtools/margins.py), or its header
#     says why not ('# weak: ...');
#   - a mutant whose header has '# both-paths: ...' is judged twice, from its tests
#     linked directly and through the grader's worker: both must fail the same tests
#     (what the worker's proxies hide from the verdict is a gap).
# Each variant is graded by tools/grade's machinery in one scratch build per
# lab, so a variant recompiles only the files that differ from the last one
# (grade_files below is the only call into it).
# Exit status: 0 all as expected, 1 a mutant survived / an alternative lost
# points / a mutant file is broken / a variant is FLAKY, 2 bad input.

import argparse
import concurrent.futures
import threading
import importlib.machinery
import json
import importlib.util
import os
import re
import secrets
import shutil
import subprocess
import sys
import tempfile
import time

sys.dont_write_bytecode = True
TOOLS = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))  # tools/


def load_grade():
    path = os.path.join(TOOLS, "grade")
    loader = importlib.machinery.SourceFileLoader("wb_grade", path)
    spec = importlib.util.spec_from_loader("wb_grade", loader)
    mod = importlib.util.module_from_spec(spec)
    sys.modules["wb_grade"] = mod
    loader.exec_module(mod)
    return mod


grade = load_grade()
sys.path.insert(0, TOOLS)
from diagnosis import catalogue as diag  # noqa: E402
from diagnosis import hints  # noqa: E402
from diagnosis.catalogue import header_value  # noqa: E402
from wbtools import margins  # noqa: E402


def grade_files(grader, lab, files):
    """Grades one lab with `files` {student file name: bytes} in place of its student files.
    Returns (compile error or "", score, max score, [(test name, tags, passed?, output)]):
    the one thing this tool needs from the grader (output: the failure text, whose first
    paragraph is the reason, untruncated)."""
    rep = grader.grade({lab: files}, [lab])[lab]
    return (rep.compile_error, rep.score, rep.max_score,
            [(r.test.name, list(r.test.tags), r.status == "passed", failure_of(r))
             for r in rep.results])


# ------------------------------------------------------------ the direct path
# The grader runs each test case as two sandboxed processes talking through a pipe (the lab's
# code never runs in the test process): about 40 ms of launching per test, and seconds per
# variant where a test calls the lab's code many times. Our own mutants and alternatives are
# trusted code, so each is first judged from the same tests linked straight with it
# (<lab>-tests-direct, one unsandboxed process per test case, as in the grader) and the
# grader's own verdict code (grader.verdict.judge) reads each report. That is taken only when
# every test ended the plain way: the process exited, its report is complete, and nothing in
# it could read differently through the worker (no exception, crash, output or time-out):
# else the variant goes through the grader itself. Each lab's solution is judged the same
# way (tools/check grades every solution through the grader in the stage before). The
# stored signatures, made by the grader (--signatures runs everything through it), are
# compared with what the direct run found: a mutant the two would judge differently fails
# the check as stale.

DIRECT_TIMEOUT = 20.0  # s, one test case run directly (the slowest solution test takes < 1 s)
UNSURE = (b"<Exception", b"<FatalErrorCondition", b"<StdOut", b"<StdErr", b"<Warning")


def direct_build(grader, lab, files, probes=None):
    """Builds <lab>-tests-direct with `files` in place of the lab's student files. Returns
    (binary, [TestCase]), or None when the grader itself must judge them (the build failed:
    the grader reports the compile error in its own words). With `probes` (a dict), the
    lab's probes are built in the same build and their records put there (diagnosis.py)."""
    from grader.project import pristine_files
    from grader.worker import worker_files
    pristine = pristine_files(grader.repo)
    pristine.update(worker_files(grader.repo, grade.known_labs(grader.repo)))
    tests = grader.test_lists([lab], pristine)[lab]
    grader.stage_direct(lab, files, pristine)
    binary = os.path.join(grader.build, "bin", f"{lab}-tests-direct")
    if os.path.exists(binary):
        os.remove(binary)
    t0 = time.monotonic()
    with_probes = probes is not None and diag.has_probes(grader.repo, lab)
    probes_binary = os.path.join(grader.build, "bin", f"{lab}-probes-direct")
    if with_probes and os.path.exists(probes_binary):
        os.remove(probes_binary)  # never run the probes of another variant
    targets = [f"{lab}-tests-direct"] + ([f"{lab}-probes-direct"] if with_probes else [])
    proc = subprocess.run(["cmake", "--build", grader.build, "--target", *targets,
                           "-j", str(grader.jobs)], stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, timeout=600)
    if proc.returncode != 0 or not os.path.isfile(binary):
        return None
    grade.log(f"mutants: {lab}: built {lab}-tests-direct in {time.monotonic() - t0:.1f} s")
    if with_probes:  # built with the tests: only run them (diagnosis.record)
        recs, _ = diag.record(grader, lab, files, built=True)
        if recs is not None:
            probes.update(recs)
    return binary, tests


def heldout_env(seed, count=1):
    return dict(os.environ, WB_HELDOUT_SEED=str(seed), WB_HELDOUT_SEEDS=str(count))


def direct_run(grader, lab, binary, tests, again=False):
    """Runs `tests` from the direct binary, one process each, and judges each report with the
    grader's own verdict code. Returns the graded tuple (as grade_files), or None when the
    grader itself must judge them (a test did not end the plain way)."""
    from grader.verdict import judge as verdict, read_report
    from grader import heldout

    def one(t):
        nonce = "wb-" + secrets.token_hex(8)
        try:
            p = subprocess.run([binary, t.name, "-w", "NoTests", "-r", "xml", "-n", nonce],
                               cwd=grader.cwd, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, timeout=min(grader.timeout, DIRECT_TIMEOUT),
                               env=heldout_env(grader.seed))
        except subprocess.TimeoutExpired:
            return None
        if p.returncode < 0 or p.stderr.strip() or any(u in p.stdout for u in UNSURE):
            return None
        plain = read_report(p.stdout, t.name, nonce, grader.src + "/")[0]
        if plain == "missing" or (plain == "passed") != (p.returncode == 0):
            return None  # an incomplete report, or one that disagrees with the exit status
        return verdict(t, ("exit", p.returncode), p.stdout, "", nonce, grader.timeout,
                       grader.src + "/", seed=grader.seed)

    t0 = time.monotonic()
    with concurrent.futures.ThreadPoolExecutor(grader.jobs) as pool:
        results = list(pool.map(one, tests))
    grade.log(f"mutants: {lab}: ran {len(tests)} test processes{' again' if again else ''} in "
              f"{time.monotonic() - t0:.1f} s")
    if any(r is None for r in results):
        return None
    heldout.gate(results)  # as the grader does
    score = sum(r.score for r in results)
    return ("", score, sum(t.points for t in tests),
            [(r.test.name, list(r.test.tags), r.status == "passed", failure_of(r))
             for r in results])


def failure_of(r):
    """A failed test's text as tools/mutants reads it: the student's words, then the failed
    checks in the harness's (the margins are measured from both)."""
    return "\n".join(x for x in ((r.output or r.reason), r.check) if x)


# ------------------------------------------------------- the held-out checks alone
# docs/grading.md, "Held-out checks": no correct implementation may ever fail a held-out check
# (the solution and every alternative, for many seeds), and each task's held-out checks alone
# (its tests tagged [held-out], the public tests left out) must catch every catalogued mistake
# of that task on at least HELDOUT_FLOOR of the seeds (issue 42: a mistake caught on some seeds
# only is a resubmission away from full marks).

HELDOUT_FLOOR = 0.999
MIN_POINTS_LOST = 3  # points every catalogued mistake must lose (of the lab's 100)
SEED_INFO = re.compile(r"held-out inputs of (\w+) from seed (0x[0-9a-fA-F]+)")
FAILURE = re.compile(r"<Expression success=\"false\"|<Exception\b|<FatalErrorCondition\b"
                     r"|<Failure\b")


def heldout_failures(binary, cwd, seed, count=1, timeout=1800):
    """The held-out tests of a direct binary that fail with `count` seeds from `seed` (one
    process, WB_HELDOUT_SEEDS): {test name: first failure text}; every one on a crash."""
    import xml.etree.ElementTree as ET
    try:
        p = subprocess.run([binary, "[held-out]", "-w", "NoTests", "-r", "xml"], cwd=cwd,
                           stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, timeout=timeout, env=heldout_env(seed, count))
        root = ET.fromstring(p.stdout)
    except (subprocess.TimeoutExpired, ET.ParseError):
        return {"(all)": "did not finish, or no complete report"}
    failed = {}
    for tc in root.iter("TestCase"):
        res = tc.find("OverallResult")
        if res is None or res.get("success") != "true":
            infos = [" ".join("".join(e.itertext()).split())[:200] for e in tc.iter()
                     if e.tag in ("Info", "Exception", "FatalErrorCondition")]
            failed[tc.get("name")] = "; ".join(infos[-3:]) or "failed"
    if p.returncode != 0 and not failed:
        failed["(all)"] = f"exit status {p.returncode}"
    return failed


def caught_seeds(report, first, count):
    """The seeds a held-out report (Catch's XML, WB_HELDOUT_SEEDS: one run of the test case per
    seed, maybe cut short by a crash) shows failing: each failure names its seed in an Info
    before it (HeldOut::replay); a failure that names none (before the seed loop) fails them
    all. Returns (caught seeds, the seed a crash stopped at or None)."""
    caught, pending, crashed = set(), set(), None
    for m in re.finditer(SEED_INFO.pattern + "|" + FAILURE.pattern, report):
        if m.group(2):
            pending.add(int(m.group(2), 16))
            continue
        if not pending:
            return set(range(first, first + count)), None
        caught |= pending
        if m.group(0).startswith("<FatalErrorCondition"):
            crashed = max(pending)
        pending = set()
    return caught, crashed


def task_caught(binary, cwd, task, first, count, timeout=3600):
    """How many of `count` seeds from `first` the held-out tests of `task` alone catch (a
    direct binary: the lab's code linked in)."""
    caught, seed, end = set(), first, first + count
    while seed < end:
        try:
            p = subprocess.run([binary, f"[{task}][held-out]", "-w", "NoTests", "-r", "xml"],
                               cwd=cwd, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, timeout=timeout,
                               env=heldout_env(seed, end - seed))
        except subprocess.TimeoutExpired:
            return None
        got, crashed = caught_seeds(p.stdout.decode("utf-8", "replace"), seed, end - seed)
        caught |= got
        if p.returncode >= 0 or crashed is None:
            break
        seed = crashed + 1  # a crash stops the process: the seeds after it, again
    return len(caught)


def measure_heldout(grader, lab, files, expected, args, name=""):
    """For a correct variant: the held-out failures over args.heldout_seeds seeds (one
    process). For a mutant: (seeds its task's held-out tests catch, seeds tried), over
    args.heldout_mutant_seeds seeds from args.heldout_first."""
    built = direct_build(grader, lab, files)
    if built is None:
        return None
    binary = built[0]
    if expected == "100":
        return heldout_failures(binary, grader.cwd, args.heldout_first, args.heldout_seeds)
    task = diag.mutant_task(diag.lab_tasks(grader.repo, lab), name)
    n = args.heldout_mutant_seeds
    got = task_caught(binary, grader.cwd, task, args.heldout_first, n) if task else None
    return None if got is None else (task, got, n)


def print_heldout(labs, rows, args):
    """The held-out measurement's table; False when an aim is missed."""
    ok = True
    print(f"\nheld-out checks alone (tests tagged [held-out]), seeds from {args.heldout_first:#x}:")
    print(f"{'lab':<11} {'correct variants':<28} each task: the mistake its held-out tests catch on "
          "the fewest seeds")
    for lab in labs:
        mine = [r for r in rows if r.lab == lab and r.heldout is not None]
        good = [r for r in mine if r.expected == "100"]
        bad = [r for r in good if r.heldout]
        muts = [r for r in mine if r.expected == "< 100"]
        tasks = {}
        for r in muts:
            task, got, n = r.heldout
            tasks.setdefault(task, []).append((got / n, got, n, r.variant))
        worst = {t: min(v) for t, v in tasks.items()}
        low = [f"{t} {v[1]}/{v[2]} ({v[3]})" for t, v in sorted(worst.items())
               if v[0] < HELDOUT_FLOOR]
        ok &= not bad and not low and all(r.heldout is not None for r in muts)
        print(f"{lab:<11} {f'{len(good) - len(bad)}/{len(good)} pass {args.heldout_seeds} seeds':<28} "
              + ", ".join(f"{t} {v[1]}/{v[2]}" for t, v in sorted(worst.items())))
        for r in bad:
            for t, why in list(r.heldout.items())[:3]:
                print(f"    {r.variant}: FAILED {t}: {why}")
        for t, v in sorted(tasks.items()):
            for rate, got, n, name in sorted(v):
                if rate < HELDOUT_FLOOR:
                    print(f"    {t}: {name}: caught on {got} of {n} seeds")
    unmeasured = [r.variant for r in rows if r.expected == "< 100" and r.heldout is None]
    for v in unmeasured:
        print(f"    not measured (no task, no build, or out of time): {v}")
    ok &= not unmeasured
    print(f"aim: every correct variant passes every seed; each task's held-out tests catch every "
          f"mistake of the task on at least {100 * HELDOUT_FLOOR:g} % of the seeds")
    return ok


# ------------------------------------------------------------ run again, compare
# A variant judged twice on the same tree must be judged the same way: the same tests
# failed, each with the same failure text as a signature keeps it (diagnosis.hints.failure_text:
# numbers blanked). Run again, at a small cost (tools/check's mutants stage, ~1 % of it):
# every test that failed, in the direct path (the run is seconds; the build is most of a
# variant's time and is not repeated), and the whole grading of a variant the grader judged
# (a crash, an exception, a time-out: where undefined behaviour and the machine's load show).


def judged(graded):
    """{test name: (passed?, the failure text a signature keeps)} of a graded tuple."""
    return {name: (passed, "" if passed else hints.failure_text(output))
            for name, _, passed, output in graded[3]}


def differences(first, second):
    """[(test, what the first run gave, what the second gave)] for the tests of `second` that
    the two runs judged differently (graded tuples; `second` may hold fewer tests)."""
    a, b = judged(first), judged(second)
    return [(name, a.get(name), b[name]) for name in sorted(b) if a.get(name) != b[name]]


def flaky_verdict(diffs):
    """The row's verdict for a variant judged differently when run again."""
    def said(j):
        return "(not run)" if j is None else "passed" if j[0] else f"failed: {j[1][:120]!r}"
    name, a, b = diffs[0]
    return (f"FLAKY: judged differently when run again ({len(diffs)} test(s)), e.g. {name!r}: "
            f"first {said(a)}, then {said(b)}: the test or the variant depends on something "
            "else than its input (undefined behaviour, time, the machine's load)")


class PatchError(Exception):
    pass


# ----------------------------------------------------------------- patches

HUNK = re.compile(r"^@@ -(\d+)(?:,(\d+))? \+(\d+)(?:,(\d+))? @@")


def parse_patch(text):
    """Returns (header comments, [(old file name, [(old start, [(tag, line)])])])."""
    lines = text.splitlines(keepends=True)
    comments, i = [], 0
    while i < len(lines) and not lines[i].startswith("--- "):
        if lines[i].startswith("#"):
            comments.append(lines[i][1:].strip())
        i += 1
    files = []
    while i < len(lines):
        if not lines[i].startswith("--- "):
            i += 1  # "diff ...", "index ..." lines between files
            continue
        old = lines[i][4:].split("\t")[0].strip()
        if i + 1 >= len(lines) or not lines[i + 1].startswith("+++ "):
            raise PatchError(f"line {i + 2}: expected '+++ ' after '--- {old}'")
        i += 2
        hunks = []
        while i < len(lines) and lines[i].startswith("@@"):
            m = HUNK.match(lines[i])
            if not m:
                raise PatchError(f"line {i + 1}: malformed hunk header {lines[i].strip()!r}")
            start = int(m.group(1))
            old_len = int(m.group(2) if m.group(2) is not None else 1)
            new_len = int(m.group(4) if m.group(4) is not None else 1)
            i += 1
            body, o, n = [], 0, 0
            while i < len(lines) and (o < old_len or n < new_len or lines[i].startswith("\\")):
                line = lines[i]
                if line.startswith("\\"):  # "\ No newline at end of file"
                    if body:
                        tag, t = body[-1]
                        body[-1] = (tag, t.rstrip("\n"))
                    i += 1
                    continue
                tag, t = (line[0], line[1:]) if line not in ("\n", "\r\n") else (" ", line)
                if tag == " ":
                    o, n = o + 1, n + 1
                elif tag == "-":
                    o += 1
                elif tag == "+":
                    n += 1
                else:
                    raise PatchError(f"line {i + 1}: a hunk line must start with ' ', '-' or '+'")
                body.append((tag, t))
                i += 1
            if o != old_len or n != new_len:
                raise PatchError(f"hunk at line {start}: the patch ends before the hunk does")
            hunks.append((start, body))
        if not hunks:
            raise PatchError(f"no hunks for {old}")
        files.append((old, hunks))
    if not files:
        raise PatchError("no '--- <file>' line: not a unified diff")
    return comments, files


def apply_hunks(text, hunks, what):
    """Applies hunks exactly (no fuzz); a hunk may move, its lines may not differ."""
    lines = text.splitlines(keepends=True)
    offset, floor = 0, 0
    for k, (start, body) in enumerate(hunks, 1):
        old = [t for tag, t in body if tag in " -"]
        new = [t for tag, t in body if tag in " +"]
        want = max(0, start - 1 + offset) if old else start + offset
        spots = [p for p in range(floor, len(lines) - len(old) + 1) if lines[p:p + len(old)] == old]
        if not spots:
            raise PatchError(f"hunk {k} (line {start}) does not match {what}: regenerate the patch")
        p = min(spots, key=lambda s: (abs(s - want), s))
        lines[p:p + len(old)] = new
        offset += len(new) - len(old)
        floor = p + len(new)
    return "".join(lines)


def caught_by(comments):
    entries = []
    for c in comments:
        m = re.match(r"^caught-by:\s*(.*)$", c, re.IGNORECASE)
        if m:
            entries += [e.strip() for e in m.group(1).split(",") if e.strip()]
    return entries


def matches(entry, name, tags):
    if entry.startswith("["):
        return entry.lower() in (t.lower() for t in tags)
    return name.startswith(entry)


# ---------------------------------------------------------------- variants

class Row:
    def __init__(self, lab, variant, expected):
        self.lab, self.variant, self.expected = lab, variant, expected
        self.got, self.verdict, self.ok, self.details = "", "", False, []
        self.signature = None  # {failed test: assertion class} of a graded mutant
        self.comments = []
        self.how = ""  # "direct" or "grader ..." (see direct_build, direct_run)
        self.margin = None  # a caught mutant's widest miss over its tolerance (margins.py)
        self.heldout = None  # --heldout-seeds: see measure_heldout
        self.probes = None  # {probe id: record}: the diagnosis probes' outputs (diagnosis.py)


def read(path):
    with open(path, "rb") as f:
        return f.read()


def variants(repo, lab):
    """[(name, expected, files {student name: bytes} or an error string, comments)]."""
    sol_dir = os.path.join(repo, "solutions", lab)
    names = grade.student_files(repo, lab)
    solution = {n: read(os.path.join(sol_dir, n)) for n in names}
    out = [("solution", "100", dict(solution), [])]
    mdir = os.path.join(repo, "tests", "mutants", lab)
    if not os.path.isdir(mdir):
        return out
    for f in sorted(os.listdir(mdir)):
        if not f.endswith(".patch"):
            continue
        files, comments = dict(solution), []
        try:
            with open(os.path.join(mdir, f), encoding="utf-8") as fh:
                comments, patched = parse_patch(fh.read())
            for old, hunks in patched:
                target = os.path.basename(old)
                if target not in names:
                    raise PatchError(f"'--- {old}': {target} is not a student file of {lab} "
                                     f"({', '.join(names)})")
                text = apply_hunks(files[target].decode("utf-8"), hunks, f"solutions/{lab}/{target}")
                files[target] = text.encode("utf-8")
            if files == solution:
                raise PatchError("the patch changes nothing")
            if not header_value(comments, "hint"):
                raise PatchError("no '# hint: ...' line: say for students what the mistake is and "
                                 "where to look, e.g. '# hint: the position update uses the old "
                                 "velocity (handout §E2)' (docs/grading.md, Adding a mutant)")
        except (PatchError, UnicodeDecodeError) as e:
            files = f"bad patch: {e}"
        out.append((f, "< 100", files, comments))
    adir = os.path.join(mdir, "alternatives")
    for f in sorted(os.listdir(adir)) if os.path.isdir(adir) else []:
        if not f.endswith(".cpp"):
            continue
        target = f.split(".")[0] + ".cpp"
        files = dict(solution)
        if target not in names:
            files = f"bad alternative: {target} is not a student file of {lab} ({', '.join(names)})"
        else:
            files[target] = read(os.path.join(adir, f))
        out.append((os.path.join("alternatives", f), "100", files, []))
    return out


def judge(row, graded, expected, comments):
    compile_error, score, max_score, results = graded
    failed = [r for r in results if not r[2]]
    row.got = f"{score}/{max_score}"
    if expected == "100":
        row.ok = score == max_score
        row.verdict = "ok" if row.ok else "LOST POINTS"
        if compile_error:
            row.verdict = "LOST POINTS: does not compile"
            row.details.append(compile_error)
        elif not row.ok:
            row.details += [f"failed: {r[0]}: {r[3].split(chr(10) * 2)[0][:200]}" for r in failed]
        return
    entries = caught_by(comments)
    row.comments = comments
    row.details += [c for c in comments if not re.match(r"^caught-by:", c, re.IGNORECASE)][:3]
    if compile_error:
        row.verdict = "BAD MUTANT: does not compile"
        row.details.append(compile_error)
        return
    row.signature = {r[0]: hints.failure_text(r[3]) for r in failed}
    if score >= max_score:
        row.verdict = "SURVIVED"
        return
    if not entries:
        row.verdict = "BAD MUTANT: no '# caught-by:' line"
        return
    missed = []  # entries none of whose tests failed
    for e in entries:
        named = [r for r in results if matches(e, r[0], r[1])]
        if not named:
            row.verdict = f"BAD MUTANT: caught-by {e!r} matches no test"
            return
        if not any(not r[2] for r in named):
            missed.append(e)
    row.details += [f"failed: {r[0]}" for r in failed]
    if missed:
        row.verdict = "caught, but not by " + ", ".join(missed)
        return
    row.margin = margins.best([r[3] for r in failed])
    shown = margins.describe(row.margin)
    lost = max_score - score
    if lost < MIN_POINTS_LOST:  # issue 46: every mistake loses at least its task's held-out points
        row.verdict = (f"LOSES ONLY {lost} POINT{'S' if lost != 1 else ''} (at least "
                       f"{MIN_POINTS_LOST}): caught by {len(failed)} test(s) alone, not by its "
                       "task's held-out check (whose failure would zero the task): make the "
                       "held-out check catch it (docs/grading.md, Held-out checks)")
        return
    if row.margin is not None and row.margin < margins.WEAK and not header_value(comments, "weak"):
        row.verdict = (f"WEAK: its widest failing check misses by {shown} times its tolerance "
                       f"(at least {margins.WEAK:g}): add a test that catches it widely, or say "
                       "why not in '# weak: ...' (docs/grading.md, Margins)")
        return
    row.ok, row.verdict = True, f"caught (margin {shown}, loses {lost})"


def print_rows(rows, verbose):
    wl = max([3] + [len(r.lab) for r in rows])
    wv = max([7] + [len(r.variant) for r in rows])
    print(f"{'lab':<{wl}}  {'variant':<{wv}}  {'expected':<8}  {'got':>7}  verdict")
    for r in rows:
        print(f"{r.lab:<{wl}}  {r.variant:<{wv}}  {r.expected:<8}  {r.got:>7}  {r.verdict}")
        if verbose or not r.ok:
            if verbose and r.how:
                print(f"    judged: {r.how}")
            for d in r.details:
                print("    " + d.replace("\n", "\n    "))


def signature_doc(repo, lab, tests, rows, solution, skeleton, digest):
    """The catalogue of one lab (tools/diagnosis/catalogue.py): generated, compared as a whole."""
    muts = []
    for r in rows:
        if r.expected == "100" or r.signature is None:
            continue
        name = r.variant[:-len(".patch")] if r.variant.endswith(".patch") else r.variant
        muts.append((name, r.comments, r.signature, r.probes))
    return diag.catalogue(repo, lab, tests, solution, skeleton, muts, digest)


def write_json_atomic(path, data):
    tmp = path + f".tmp-{os.getpid()}"
    try:
        with open(tmp, "w", encoding="utf-8") as f:
            f.write(diag.dumps(data))
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


def check_signatures(repo, lab, doc, write):
    """None when the stored signatures equal `doc` (or were just written), else why not."""
    path = hints.catalogue_path(repo, lab)
    if write:
        write_json_atomic(path, doc)
        return None
    try:
        with open(path, encoding="utf-8") as f:
            stored = json.load(f)
    except FileNotFoundError:
        return f"{os.path.relpath(path, repo)} is missing"
    except (OSError, ValueError) as e:
        return f"{os.path.relpath(path, repo)} cannot be read ({e})"
    if stored == doc:
        return None
    why = []
    sm, dm = stored.get("mutants", {}) if isinstance(stored, dict) else {}, doc["mutants"]
    if not isinstance(stored, dict) or stored.get("tests") != doc["tests"]:
        why.append("the lab's tests changed")
    why += [f"{m}: new" for m in sorted(set(dm) - set(sm))][:3]
    why += [f"{m}: removed" for m in sorted(set(sm) - set(dm))][:3]
    why += [f"{m}: changed" for m in sorted(set(dm) & set(sm)) if dm[m] != sm[m]][:5]
    if isinstance(stored, dict):
        for key, what in (("probes", "the probes or the solution's or skeleton's outputs on them"),
                          ("tasks", "the tasks")):
            if stored.get(key) != doc.get(key):
                why.append(f"{what} changed")
    return "; ".join(why) or "the file differs from what this run measured"


def refresh_hints(repo, labs):
    """--refresh-hints: the headers' hint, kind and task into the stored signatures."""
    bad = 0
    for lab in labs:
        data = hints.load_catalogue(repo, lab)
        if data is None:
            print(f"{lab}: no signatures to refresh (tools/mutants --signatures --lab {lab})")
            bad += 1
            continue
        n = 0
        for name, files, comments in ((v[0], v[2], v[3]) for v in variants(repo, lab)
                                      if v[1] != "100"):
            key = name[:-len(".patch")]
            if isinstance(files, str):
                print(f"{lab}: {name}: {files}")
                bad += 1
            elif key not in data["mutants"]:
                print(f"{lab}: {name}: not in the stored signatures: run tools/mutants "
                      f"--signatures --lab {lab}")
                bad += 1
            else:
                m = data["mutants"][key]
                new = {"kind": header_value(comments, "kind"),
                       "hint": header_value(comments, "hint")}
                n += any(m.get(k) != v for k, v in new.items())
                m.update(new)
        write_json_atomic(hints.catalogue_path(repo, lab), data)
        print(f"{lab}: {n} mutant(s) refreshed")
    return 1 if bad else 0


def lab_groups(repo, labs, n):
    """The labs split into n groups of about the same number of variants (largest first),
    each group graded in its own scratch build while the others run: a variant's build
    uses one core, its tests the others."""
    weight = {lab: len(os.listdir(os.path.join(repo, "tests", "mutants", lab))) for lab in labs}
    groups = [[] for _ in range(min(n, len(labs)))]
    load = [0] * len(groups)
    for lab in sorted(labs, key=lambda l: -weight[l]):
        k = load.index(min(load))
        groups[k].append(lab)
        load[k] += weight[lab]
    return [g for g in groups if g]


def run_lab(repo, grader, lab, args, stop):
    """Grades every variant of one lab and runs the diagnosis probes on it; returns its rows
    (the catalogue's row last, once every variant was graded)."""
    rows, all_tests, solution = [], None, None
    for name, expected, files, comments in variants(repo, lab):
        if stop.is_set():
            return rows
        row = Row(lab, name, expected)
        rows.append(row)
        if isinstance(files, str):
            row.verdict = "BAD MUTANT: " + files if expected != "100" else files
            row.got = "-"
        else:
            grade.log(f"mutants: {lab}: {name}")
            if args.heldout_seeds and name != "solution":  # the measurement only
                row.heldout = measure_heldout(grader, lab, files, expected, args, name)
                row.got, row.verdict, row.ok = "-", "measured", row.heldout is not None
                continue
            graded = again = None
            recorded = {}
            if not args.through_grader:
                built = direct_build(grader, lab, files, recorded)
                graded = direct_run(grader, lab, *built) if built else None
                row.how = "direct" if graded else "grader (the direct run was not plain)"
                failed = [t for t in built[1] if t.name in
                          {r[0] for r in graded[3] if not r[2]}] if graded else []
                if failed and not args.no_rerun:
                    again = direct_run(grader, lab, built[0], failed, again=True)
                    if again is None:  # plain the first time, not the second
                        again = ("", 0, 0, [(t.name, t.tags, False, "(the run again was not "
                                             "plain: a crash, an exception, a time-out)")
                                            for t in failed])
            if graded is None:
                graded = grade_files(grader, lab, files)
                row.how = row.how or "grader"
                if not args.no_rerun and not args.signatures:
                    again = grade_files(grader, lab, files)
            if name == "solution":
                all_tests = sorted(r[0] for r in graded[3])
            judge(row, graded, expected, comments)
            if row.ok and header_value(comments, "both-paths"):
                both_paths(row, graded, grader, lab, files)
            diffs = differences(graded, again) if again else []
            if diffs:
                row.ok, row.verdict = False, flaky_verdict(diffs)
                row.details += [f"run again: {n}: first {a}, then {b}" for n, a, b in diffs]
            if args.heldout_seeds:
                row.heldout = measure_heldout(grader, lab, files, expected, args, name)
            elif expected == "100" and args.ci_seeds:  # a few fresh seeds on every run
                built = direct_build(grader, lab, files)
                from grader.heldout import random_seed
                first = random_seed()
                failed = heldout_failures(built[0], grader.cwd, first, args.ci_seeds) \
                    if built else {"(build)": "the direct tests do not build"}
                if failed:
                    row.ok, row.verdict = False, f"LOST POINTS on held-out seeds from {first:#x}"
                    row.details += [f"failed: {t}: {why}" for t, why in failed.items()]
            if args.heldout_seeds:
                pass  # the measurement: no probes
            elif recorded:  # recorded with the direct tests
                row.probes = recorded
            elif not graded[0]:  # it compiles: what its probes give
                row.probes, why = diag.record(grader, lab, files)
                if why:
                    row.ok, row.verdict = False, "PROBES: " + why.splitlines()[0]
                    row.details.append(why)
            if name == "solution":
                solution = row.probes
            elif expected == "100" and row.ok and solution and row.probes is not None:
                bad = diag.disagreements(solution, row.probes)
                if bad:  # a correct variant the probes tell from the solution
                    row.ok = False
                    row.verdict = "PROBE DISAGREES: " + ", ".join(bad[:3]) + \
                        " (too tight a tolerance, or a probe of unspecified behaviour)"
        if not row.ok and not args.keep_going:
            stop.set()
            return rows
    if all_tests is None or args.heldout_seeds or solution is None:
        return rows
    # Every variant of the lab was graded: its catalogue is known. The skeleton's probe
    # outputs are measured again only when what they depend on changed (or --signatures).
    digest = diag.probe_inputs_digest(repo, lab)
    stored = hints.load_catalogue(repo, lab)
    if not args.signatures and stored and stored.get("skeleton_inputs") == digest:
        skeleton = {p["probe"]: p.get("skeleton") for p in stored.get("probes", [])}
    else:
        skel_files = {n: read(os.path.join(repo, "labs", lab, n))
                      for n in grade.student_files(repo, lab)}
        skeleton, why = diag.record(grader, lab, skel_files)
        skeleton = skeleton or {}
    row = Row(lab, "signatures.json", "current")
    row.got = str(sum(1 for r in rows if r.signature is not None))
    doc = signature_doc(repo, lab, all_tests, rows, solution, skeleton, digest)
    why = check_signatures(repo, lab, doc, args.signatures)
    for r in rows:  # what the grader would tell a student with this code
        key = r.variant[:-len(".patch")]
        if r.signature is not None and key in doc["mutants"]:
            m = doc["mutants"][key]
            d = hints.diagnose(doc, m["task"], m.get("probes") or {},
                               [(t, False, x) for t, x in r.signature.items()],
                               hints.task_title(doc, m["task"]))
            r.details += ["diagnosis: " + l for l in d.lines()]
    row.ok = why is None
    row.verdict = ("written" if args.signatures else "current") if row.ok else \
        f"STALE: {why}: run tools/mutants --signatures --lab {lab} and commit it"
    rows.append(row)
    if not row.ok and not args.keep_going:
        stop.set()
    return rows


def fresh_variants(repo, folder, lab):
    """[(name, files {student name: bytes} or an error, '# kind:' expected, the file changed)]
    of folder/<lab>/: mistakes written apart from the catalogue, each a whole file
    <file>.<what>.cpp (its expected part on a '// kind: ...' line) or a patch of the solution in
    the catalogue's format (with a '# kind: ...' line). The file changed is the patch's own
    target, not a guess from the mistake's name (a writer may name it after the function)."""
    names = grade.student_files(repo, lab)
    sol = {n: read(os.path.join(repo, "solutions", lab, n)) for n in names}
    d = os.path.join(folder, lab)
    out = []
    for f in sorted(os.listdir(d)) if os.path.isdir(d) else []:
        files, kind, changed = dict(sol), "", ""
        try:
            if f.endswith(".cpp"):
                target = changed = f.split(".")[0] + ".cpp"
                if target not in names:
                    raise PatchError(f"{target} is not a student file of {lab}")
                files[target] = read(os.path.join(d, f))
                m = re.search(rb"^//\s*kind:\s*(.*?)\s*$", files[target], re.M)
                kind = m.group(1).decode("utf-8", "replace") if m else ""
            elif f.endswith(".patch"):
                with open(os.path.join(d, f), encoding="utf-8") as fh:
                    comments, patched = parse_patch(fh.read())
                kind = header_value(comments, "kind")
                for old, hunks in patched:
                    target = os.path.basename(old)
                    if target not in names:
                        raise PatchError(f"{target} is not a student file of {lab}")
                    files[target] = apply_hunks(files[target].decode("utf-8"), hunks,
                                                f"solutions/{lab}/{target}").encode("utf-8")
                    changed = changed or target
            else:
                continue
        except (PatchError, OSError, UnicodeDecodeError) as e:
            files = f"bad variant: {e}"
        out.append((f, files, kind, changed))
    return out


def fresh(repo, labs, args):
    """--fresh DIR: every mistake of DIR/<lab>/ graded through the grader, with every other file
    the solution's, and what its task's diagnosis says against the part it is in
    (diagnosis.catalogue.fresh_outcome); the table per lab, and each student's text checked
    for lines over 100 characters and the harness's words."""
    from grader import results as res
    import io
    tmp = None
    root = args.build_dir
    if root is None:
        tmp = root = tempfile.mkdtemp(prefix="wb-mutants-")
    rows = []
    labs = [lab for lab in labs if os.path.isdir(os.path.join(args.fresh, lab))]
    groups = lab_groups(repo, labs, max(1, args.parallel))

    def run_group(k, group):
        grader = grade.Grader(repo, os.path.join(root, str(k)), args.jobs, args.timeout,
                              seed=args.seed)
        grader.say = lambda *a, **kw: None
        try:
            for lab in group:
                cat = hints.load_catalogue(repo, lab)
                for name, files, kind, changed in fresh_variants(repo, args.fresh, lab):
                    if isinstance(files, str):
                        rows.append((lab, name, kind, "bad", files, [], []))
                        continue
                    grade.log(f"mutants: fresh: {lab}: {name}")
                    rep = grader.grade({lab: files}, [lab])[lab]
                    buf = io.StringIO()
                    res.print_table({lab: rep}, {}, out=buf)
                    text = buf.getvalue()
                    verdict, named, lines = diag.fresh_outcome(cat, name, kind, rep, changed)
                    rows.append((lab, name, kind, verdict, named, lines,
                                 res.student_text_problems(text)))
        finally:
            grader.close()

    try:
        with concurrent.futures.ThreadPoolExecutor(len(groups) or 1) as pool:
            for f in [pool.submit(run_group, k, g) for k, g in enumerate(groups)]:
                f.result()
    finally:
        if tmp:
            shutil.rmtree(tmp, ignore_errors=True)
    return diag.fresh_table(rows, labs, args.markdown, args.verbose)


def mid_lab(repo, labs, args):
    """--mid-lab: diagnosis.mid_lab_check of every lab with a catalogue, in one scratch build."""
    tmp = None
    root = args.build_dir
    if root is None:
        tmp = root = tempfile.mkdtemp(prefix="wb-mutants-")
    grader = grade.Grader(repo, os.path.join(root, "0"), args.jobs, args.timeout, seed=args.seed)
    problems = []
    try:
        for lab in labs:
            cat = hints.load_catalogue(repo, lab)
            if cat is None:
                problems.append(f"{lab}: no catalogue (tools/mutants --signatures --lab {lab})")
                continue
            files = {v[0][:-len(".patch")]: v[2] for v in variants(repo, lab)
                     if v[0].endswith(".patch") and not isinstance(v[2], str)}
            problems += diag.mid_lab_check(repo, grader, lab, cat, files, grade.log)
    finally:
        grader.close()
        if tmp:
            shutil.rmtree(tmp, ignore_errors=True)
    for p in problems:
        print(p)
    print(f"mutants: mid-lab: {len(problems)} problem(s) in {', '.join(labs)}")
    return 1 if problems else 0


def both_paths(row, graded, grader, lab, files):
    """'# both-paths:': the tests linked directly and the grader's worker must fail the same
    tests (the worker's proxies must not hide what the student's code does)."""
    if row.how == "direct":
        direct = graded
    else:
        built = direct_build(grader, lab, files)
        direct = direct_run(grader, lab, *built) if built else None
    through = graded if row.how.startswith("grader") else grade_files(grader, lab, files)
    if direct is None:
        row.ok, row.verdict = False, "BOTH PATHS: the direct run was not plain"
        return
    fails = [sorted(r[0] for r in g[3] if not r[2]) for g in (direct, through)]
    row.how += "; both paths compared"
    if fails[0] != fails[1]:
        row.ok = False
        row.verdict = ("BOTH PATHS DIFFER: linked directly it fails " + (", ".join(fails[0]) or
                       "nothing") + "; through the grader's worker " +
                       (", ".join(fails[1]) or "nothing"))


def main(argv):
    p = argparse.ArgumentParser(
        prog="tools/mutants",
        description="Checks that the graded tests catch known-wrong code (tests/mutants/<lab>/*.patch "
                    "must score < 100 and fail the tests named by '# caught-by:') and accept correct "
                    "code written differently (tests/mutants/<lab>/alternatives/*.cpp must score 100), "
                    "and that the stored failure signatures (tests/mutants/<lab>/signatures.json, "
                    "the data of the grader's hints) are current.",
        epilog="Exit status: 0 all as expected, 1 a mutant survived, an alternative lost points, a "
               "mutant file is broken or the signatures are stale, 2 bad input. See docs/grading.md.")
    p.add_argument("--lab", action="append", default=[], metavar="L", help="only this lab (repeatable)")
    p.add_argument("--keep-going", action="store_true", help="run every variant even after one is wrong")
    p.add_argument("--build-dir", metavar="DIR",
                   help="keep the scratch builds in DIR/0, DIR/1 ... (one per group of labs run "
                        "at once; tools/grade --build-dir DIR/0 shares the first; default: a "
                        "temporary folder)")
    p.add_argument("--parallel", type=int, default=2, metavar="N",
                   help="groups of labs graded at once, each in its own scratch build (default 2)")
    p.add_argument("--jobs", type=int, default=2, metavar="J", help="test cases run at once (default 2)")
    p.add_argument("--timeout", type=float, default=60.0, metavar="S",
                   help="time limit of each test case in seconds (default 60)")
    p.add_argument("--signatures", action="store_true",
                   help="(re)write tests/mutants/<lab>/signatures.json from this run instead of "
                        "checking it (implies --keep-going and --through-grader)")
    p.add_argument("--through-grader", action="store_true",
                   help="grade every mutant through the grader (sandboxed test and worker "
                        "processes) instead of first running the tests linked straight with it")
    p.add_argument("--no-rerun", action="store_true",
                   help="do not run again, to compare, the failed tests of each variant (and "
                        "the whole grading of one the grader judged); a variant judged "
                        "differently the second time is FLAKY")
    p.add_argument("--refresh-hints", action="store_true",
                   help="no build: rewrite only the hint, kind and task of each mutant in the stored "
                        "signatures from the patches' headers (after editing a '# hint:'); the "
                        "measured failures are kept")
    p.add_argument("--leave-one-out", action="store_true",
                   help="no build: from the stored catalogue, how often the diagnosis names the "
                        "right part of the computation when a mutant is left out of it")
    p.add_argument("--min-right", type=float, metavar="PCT",
                   help="with --leave-one-out: exit 1 unless the part is right for at least PCT %% "
                        "of the mutants that have a peer of their part")
    p.add_argument("--max-wrong", type=float, metavar="PCT",
                   help="with --leave-one-out: exit 1 unless the part is wrong for at most PCT %% "
                        "of them")
    p.add_argument("--max-wrong-alone", type=int, metavar="N",
                   help="with --leave-one-out: exit 1 if more than N mutants alone in their part "
                        "get another part named")
    p.add_argument("--max-silent", type=int, metavar="N",
                   help="with --leave-one-out: exit 1 if more than N mutants get nothing to act "
                        "on (no part, no counterexample, no failed test's message)")
    p.add_argument("--mid-lab", action="store_true",
                   help="grade, through the grader, two submissions per lab with every other task "
                        "at its skeleton and one catalogued mistake in each of the others: each "
                        "task's diagnosis must be the whole-lab one, each skeleton task 'not "
                        "started' (builds; exit 1 otherwise)")
    p.add_argument("--fresh", metavar="DIR",
                   help="grade through the grader each mistake of DIR/<lab>/ (written apart from "
                        "the catalogue: a whole file <file>.<what>.cpp with a '// kind: ...' line, "
                        "or a patch with '# kind: ...'), every other file the solution's; print "
                        "what its task's diagnosis names against that part, the figures per lab, "
                        "and any line of the student's text over 100 characters or with the "
                        "harness's words (builds)")
    p.add_argument("--markdown", action="store_true",
                   help="with --leave-one-out or --fresh: a Markdown table")
    p.add_argument("--seed", default="1", metavar="N",
                   help="the held-out inputs' seed of every grading (default 1: the stored "
                        "signatures hold for it)")
    p.add_argument("--ci-seeds", type=int, default=3, metavar="N",
                   help="also run the held-out tests of the solution and every alternative with N "
                        "fresh random seeds (default 3, printed when one fails; 0: none)")
    p.add_argument("--heldout-seeds", type=int, default=0, metavar="N",
                   help="measure the held-out checks instead (docs/grading.md): the solution and "
                        "every alternative must pass N seeds (1000 for the record), and each task's "
                        "held-out tests alone must catch each of its mutants on at least 99.9 %% "
                        "of --heldout-mutant-seeds seeds")
    p.add_argument("--heldout-mutant-seeds", type=int, default=None, metavar="M",
                   help="with --heldout-seeds: seeds per mutant (default: N, as the correct "
                        "variants)")
    p.add_argument("-v", "--verbose", action="store_true", help="list the failed tests of every variant "
                   "(with --leave-one-out: every mutant's outcome)")
    args = p.parse_args(argv)
    from grader import heldout
    args.seed = heldout.parse_seed(args.seed)
    args.heldout_first = heldout.random_seed()
    if args.heldout_mutant_seeds is None:
        args.heldout_mutant_seeds = args.heldout_seeds
    repo = grade.repo_root()
    known = grade.known_labs(repo)
    for lab in args.lab:
        if lab not in known:
            raise grade.BadInput(f"--lab {lab}: unknown lab (known: {', '.join(known)})")
    labs = args.lab or [l for l in known if os.path.isdir(os.path.join(repo, "tests", "mutants", l))]
    if args.leave_one_out:
        return diag.loo_table(repo, labs, args.markdown, args.verbose, args.min_right,
                              args.max_wrong, args.max_wrong_alone, args.max_silent)
    if args.mid_lab:
        return mid_lab(repo, labs, args)
    if args.fresh:
        if not os.path.isdir(args.fresh):
            raise grade.BadInput(f"--fresh {args.fresh}: not a folder")
        args.fresh = os.path.abspath(args.fresh)
        return fresh(repo, args.lab or [l for l in known if os.path.isdir(
            os.path.join(args.fresh, l))], args)
    if args.refresh_hints:
        return refresh_hints(repo, labs)
    if args.signatures:
        args.keep_going = args.through_grader = True
    if not labs:
        print("mutants: no lab has tests/mutants/<lab>/: nothing to check")
        return 0
    for lab in labs:
        if not os.path.isdir(os.path.join(repo, "solutions", lab)):
            raise grade.BadInput(f"solutions/{lab}/ is missing: mutants are patches of the solution")
    tmp = None
    root = args.build_dir
    if root is None:
        tmp = root = tempfile.mkdtemp(prefix="wb-mutants-")
    groups = lab_groups(repo, labs, max(1, args.parallel))
    results = {}  # lab: its rows
    stop = threading.Event()

    def run_group(k, group):
        grader = grade.Grader(repo, os.path.join(root, str(k)), args.jobs, args.timeout,
                              seed=args.seed)
        grader.direct_tests = True
        grader.diagnosis = False  # the catalogue is measured directly (diagnosis.record)
        try:
            for lab in group:
                if stop.is_set():
                    return
                results[lab] = run_lab(repo, grader, lab, args, stop)
        finally:
            grader.close()

    try:
        with concurrent.futures.ThreadPoolExecutor(len(groups)) as pool:
            for f in [pool.submit(run_group, k, g) for k, g in enumerate(groups)]:
                f.result()
    finally:
        if tmp:
            shutil.rmtree(tmp, ignore_errors=True)
    rows = [r for lab in labs for r in results.get(lab, [])]
    print_rows(rows, args.verbose)
    if args.heldout_seeds:
        return 0 if print_heldout(labs, rows, args) else 1
    bad = [r for r in rows if not r.ok]
    mut = [r for r in rows if r.expected == "< 100"]
    flaky = sum(1 for r in rows if r.verdict.startswith("FLAKY"))
    print(f"\nmutants: {sum(r.ok for r in mut)} of {len(mut)} caught; "
          f"{sum(r.ok for r in rows if r.expected == '100')} of "
          f"{sum(1 for r in rows if r.expected == '100')} correct variants kept 100"
          + (f"; {flaky} FLAKY (judged differently when run again)" if flaky else "")
          + (" (stopped at the first wrong one: --keep-going runs them all)" if stop.is_set()
             else ""))
    weak = [r for r in mut if r.margin is not None and r.margin < margins.WEAK]
    print(f"mutants: {len(weak)} caught within a factor {margins.WEAK:g} of a tolerance"
          + (": " + ", ".join(f"{r.lab}/{r.variant} ({margins.describe(r.margin)})" for r in weak)
             if weak else ""))

    def direct(rs):
        return f"{sum(1 for r in rs if r.how == 'direct')} of {len(rs)}"
    alts = [r for r in rows if r.expected == "100" and r.variant != "solution"]
    sols = [r for r in rows if r.variant == "solution"]
    again = "" if args.no_rerun or args.signatures else (
        " (each failed test run again, to compare)")
    print(f"mutants: {direct(mut)} mutants, {direct(alts)} alternatives and {direct(sols)} "
          f"solutions judged from their tests run directly{again}, the others through the "
          "grader" + ("" if again == "" else " (graded twice, to compare)"))
    return 1 if bad else 0


def run():
    """The entry tools/mutants calls: main() with the command line, its exit status."""
    try:
        sys.exit(main(sys.argv[1:]))
    except grade.BadInput as e:
        grade.log(f"mutants: {e}")
        sys.exit(2)
    except grade.Defect as e:
        grade.log(f"mutants: internal error:\n{e}")
        sys.exit(1)
    except KeyboardInterrupt:
        grade.kill_all()
        grade.log("mutants: interrupted")
        sys.exit(130)
