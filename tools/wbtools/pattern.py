"""Checks that every lab, present and future, keeps the workbook's pattern (docs/grading.md, "The pattern").

Each stage covers every lab folder it finds (labs/<lab>/, scenes/<lab>/, handouts/<lab>.md,
tests/<lab>/), so a new lab is checked without anyone remembering it:

  stubs     every lab's skeleton (build/bin/<lab>) on every default scene prints a stub
            warning on stderr ("<lab>: warning: ...") and in its summary's "warnings";
            its solution (build/bin/<lab>-solution, where solutions/<lab> exists) on the
            same scenes warns of nothing (about 10 s)
  periods   every lab's skeleton sweep on every scene with an exact solution ("exact" key)
            gives each integrator an error well above round-off: no scene ends where a step
            that does nothing scores 0 (a whole period); on a scene whose exact values are
            conserved ones (the rigid lab's torque-free scenes, where doing nothing is exact
            at any time), the sweep must print a stub warning naming the integrator
  claims    every handout sentence that states a number or a direction about a run carries
            a claim marker (<!-- claim: ... -->, checked by tools/claims) or says why not
            (<!-- not-a-claim: ... -->)
  asserts   every REQUIRE/CHECK in tests/<lab>/*.cpp carries words a student can act on: a
            wbtest::require_* helper with a message, or an INFO/CAPTURE in scope before it
  nanfree   no comparison in tests/<lab>/ can be passed by a NaN or an infinity: no
            maxCoeff()/minCoeff() compared with a tolerance or inside an assertion
            (wbtest::max_abs_diff, max_abs), no running maximum or minimum by std::max/std::min
            (wbtest::worst_of, least_of), no ordering comparison of raw values in an assertion
            (wbtest::finite, or '// nanfree: integers' when every side is an integer);
            and every task has a [held-out] test (tests/common/heldout.h)
  answers   no provided source of the pack of all labs computes what a task's solution
            computes (tools/wbtools/answers.py: the fast path ships compiled only)
  reportdoc docs/report.md names every figure the last report drew (build/report), and
            names no figure file the report does not draw
  stubfigs  the student pack's plot commands, on each lab's skeleton run of its first
            scene, draw figures that say "STUB RUN" (wbplot/stubfigs.py; a few seconds)
  testnames every graded test file tests/<lab>/*.cpp is named test_<task>_<what>.cpp
            (<task> a TODO(<task>) of labs/<lab>/, <what> lower-case words joined by _),
            every test case in it carries the tag [<task>], and every task has such a file:
            the tests of task F5 are in tests/forces/test_F5_*.cpp
  points    every handout lists, task by task, every graded test with its points and the
            held-out ones marked, with what the held-out gate means for the task's points, in
            a block (<!-- points F5: ... --> ... <!-- /points -->) that is exactly what the
            tests' [Npts] tags give: a point changed on one side only fails here (--write
            writes the blocks from the tags)
  docrefs   what every Markdown file of the repository quotes from the code exists there:
            the flags of a tool's or a lab's command, the arguments of a task function or
            a tool's Python function, the paths (tools/wbtools/docrefs.py says how)
  imports   no module of tools/ imports one that imports it back, directly or around a ring
            (a lazy import inside a function counts: tools/wbtools/imports.py)

With no stage, all of them. Exit status: 0 every stage passed, 1 a stage found something
(each finding on one line: file, what, what to do), 2 bad input (a flag, a missing build)."""
import argparse
import glob
import json
import os
import re
import subprocess
import sys
import textwrap
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tools"))
sys.dont_write_bytecode = True

from grader.common import FORBIDDEN_NAME_CHARS  # noqa: E402
from wbplot import recipes  # noqa: E402
from wbplot.common import summary_line  # noqa: E402

STAGES = ["stubs", "periods", "claims", "asserts", "nanfree", "answers", "reportdoc", "stubfigs",
          "testnames", "points", "docrefs", "imports"]
RUN_TIMEOUT = 300  # seconds for one skeleton run or sweep
# The smallest error a skeleton's sweep may show for an integrator, relative to the scene
# size: a stub that does nothing is off by O(1) of the motion, rounding by 1e-16; a whole
# period lands a stub on the exact answer to rounding (6e-16 on one-spring).
ROUNDOFF_REL = 1e-9


def rel(p):
    r = os.path.relpath(p, ROOT)
    return p if r.startswith("..") else r


ONLY_LABS = []  # tools/pattern --lab: the labs the per-lab stages look at (empty: every lab)


def all_labs():
    """Every lab: a folder labs/<lab>/ (the student side)."""
    d = os.path.join(ROOT, "labs")
    return sorted(x for x in os.listdir(d) if os.path.isdir(os.path.join(d, x))) \
        if os.path.isdir(d) else []


def labs():
    """The labs the stages look at: every lab, or those given with --lab."""
    return [lab for lab in all_labs() if not ONLY_LABS or lab in ONLY_LABS]


def scenes(lab):
    return sorted(glob.glob(os.path.join(ROOT, "scenes", lab, "*.json")))


def run(argv, timeout=RUN_TIMEOUT):
    try:
        p = subprocess.run(argv, cwd=ROOT, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, "", f"timed out after {timeout} s"
    return p.returncode, p.stdout, p.stderr


def skeleton(lab, build):
    exe = os.path.join(build, "bin", lab)
    if not os.path.exists(exe):
        raise SystemExit(f"tools/pattern: error: {rel(exe)}: not built (the skeleton of lab "
                         f"{lab}); build first (cmake --build --preset default)")
    return exe


# ----------------------------------------------------------------------------
# stubs: every skeleton run says it is a stub


def _run_scene(exe, scene, where, findings):
    """The run's summary and stderr, or (None, stderr) with a finding when it failed."""
    status, stdout, stderr = run([exe, "--scene", rel(scene)])
    s = summary_line(stdout)
    if status != 0 or s is None:
        why = (stderr.strip().splitlines() or [f"exit status {status}"])[-1]
        findings.append(f"{where}: the run failed: {why}")
        return None, stderr
    return s, stderr


def stage_stubs(build, out, verbose):
    findings = []
    for lab in labs():
        exe = skeleton(lab, build)
        for scene in scenes(lab):
            where = f"{rel(scene)} on the skeleton ({rel(exe)})"
            s, stderr = _run_scene(exe, scene, where, findings)
            if s is None:
                continue
            warned = [ln for ln in stderr.splitlines() if f"{lab}: warning:" in ln]
            if not warned or not s.get("warnings"):
                findings.append(
                    f"{where}: no stub warning (\"{lab}: warning: ...\" on stderr and "
                    f"\"warnings\" in the summary; status {s.get('status')}): a run of "
                    "untouched stubs must say so (docs/run-contract.md, \"warnings\"); make "
                    "the lab's glue detect what its stubs do")
            elif verbose:
                print(f"ok: {where}: {warned[0].strip()}")
        # The converse: the solution runs every default scene without being called a stub
        # (a warning there would mark the solution's figures "stub" too).
        sol = os.path.join(build, "bin", f"{lab}-solution")
        if not os.path.isdir(os.path.join(ROOT, "solutions", lab)):
            continue  # a student's pack: no solution to run
        if not os.path.exists(sol):
            findings.append(f"{rel(sol)}: not built (the solution of lab {lab}); build first "
                            "(cmake --build --preset default)")
            continue
        for scene in scenes(lab):
            where = f"{rel(scene)} on the solution ({rel(sol)})"
            s, _ = _run_scene(sol, scene, where, findings)
            if s is not None and (s.get("stub") or s.get("warnings")):
                findings.append(f"{where}: called a stub: {(s.get('warnings') or ['?'])[0]}: "
                                "the lab's stub warnings must hold only for what stubs do")
    return findings


# ----------------------------------------------------------------------------
# periods: no scene lets a stub score zero error


def _rigid_torque_free(doc):
    return "bodies" in doc and not (doc.get("forces") or doc.get("planes") or doc.get("hinges"))


def stage_periods(build, out, verbose):
    from wbplot import sweep as wsweep
    findings = []
    os.makedirs(out, exist_ok=True)
    for lab in labs():
        exe = skeleton(lab, build)
        status, help_text, _ = run([exe, "--help"])
        if "--sweep" not in help_text:
            continue
        for scene in scenes(lab):
            with open(scene, encoding="utf-8") as f:
                doc = json.load(f)
            if not ("exact" in doc or _rigid_torque_free(doc)):
                continue
            csv = os.path.join(out, f"{lab}-{os.path.basename(scene)[:-5]}-sweep.csv")
            argv, _ = recipes.sweep_argv(exe, rel(scene), doc, help_text, csv, repeats=1)
            status, stdout, stderr = run(argv)
            where = f"{rel(scene)}: the skeleton's sweep"
            if status != 0:
                why = (stderr.strip().splitlines() or [f"exit status {status}"])[-1]
                findings.append(f"{where} failed: {why}")
                continue
            scale = recipes.length_scale(doc)
            rows = wsweep.read_sweep(csv)
            for name in sorted({r.integrator for r in rows}):
                errs = [r.error for r in rows if r.integrator == name and not r.diverged]
                small = [e for e in errs if abs(e) <= ROUNDOFF_REL * scale]
                # A closed-form motion ("exact"): a stub can only score 0 where the motion
                # returns to its start, so any small error is a finding. A conservation law
                # (the rigid lab's torque-free scenes): doing nothing conserves everything at
                # any end time, so the sweep must say it is a stub instead.
                warned = "exact" not in doc and any(
                    "warning" in ln and f" {name} " in ln for ln in stderr.splitlines())
                if small and not warned:
                    findings.append(
                        f"{where}: {name} scores error {max(small):.2g} (at most "
                        f"{ROUNDOFF_REL:g} x the scene size {scale:.3g}) at "
                        f"{len(small)} of {len(errs)} step sizes with the stubs untouched: the "
                        "scene ends where doing nothing is exact (a whole period?); change its "
                        "t_end (docs/report.md, \"Scenes never end on a whole period\")")
                elif verbose:
                    print(f"ok: {where}: {name}: least error "
                          f"{min(errs) if errs else float('nan'):.3g}"
                          + (" (stub warned)" if warned else ""))
    return findings


# ----------------------------------------------------------------------------
# claims: every statement about a run is marked

CLAIM = re.compile(r"<!--\s*claim:.*?-->", re.S)
NOT_A_CLAIM = re.compile(r"<!--\s*not-a-claim:\s*(.*?)\s*-->", re.S)
# Words that say what a run did. A sentence with one of them and a number or a direction
# (below) states something about a run.
RUN_WORDS = re.compile(
    r"\b(diverg\w*|blows? up|blew up|blow-?ups?|explod\w*|stays? (?:bounded|finite|put|on)"
    r"|stay (?:bounded|finite)|bounded|lands?|ends? (?:at|up|with|on)"
    r"|measured|coincid\w*|grows?|grew|gains?|loses?|lost|decays?|drifts?|spirals?"
    r"|flips?|precess\w*|slides?|sticks?|bounces?|tunnels?|passes? through|falls? through"
    r"|comes? to rest|swings?|converg\w*|keeps?|kept|damps?|vanish\w*|oscillates?"
    r"|holds? (?:the|it|up|still)|sinks?"
    r"|widens?|shrinks?|settles?)\b", re.I)
DIRECTION = re.compile(
    r"\b(above|below|left|right|outwards?|inwards?|up|down|faster|slower|more|less|larger"
    r"|smaller|higher|lower|twice|half|never|always|exactly|at once|within)\b", re.I)
NUMBER = re.compile(r"(?<![\w.\-/])[−-]?\d+(?:[.,]\d+)?(?:e[−-]?\d+)?(?![\w])")
TASK_VERB = re.compile(r"[\s*_(]*(Show|Prove|Derive|Use|Run|Compare|Plot|Measure|Explain|"
                       r"Time|Remove|Turn|Halve|Edit|Try|Write|Check)\b")
TASK_HEADING = re.compile(r"^#{1,6}\s+[A-Z]\d+\b")  # "## I4 Backward Euler ...": a task


def _plain(text):
    """A paragraph as a reader sees its words: no math, code, links' targets, HTML."""
    t = re.sub(r"\$\$.*?\$\$", " FORMULA ", text, flags=re.S)
    t = re.sub(r"\$[^$]*\$", " FORMULA ", t)
    t = re.sub(r"`[^`]*`", " CODE ", t)
    t = re.sub(r"!\[[^\]]*\]\([^)]*\)", " ", t)
    t = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", t)
    t = re.sub(r"<!--.*?-->", " ", t, flags=re.S)
    t = re.sub(r"<[^>]+>", " ", t)
    return t


def _sentences(par):
    """(sentence with its markers, plain text) pairs of a paragraph. A marker right after a
    sentence's full stop belongs to that sentence."""
    out = []
    # Split after . ! ? ; followed by space and a capital letter or a marker-free start.
    parts = re.split(r"(?<=[.!?])\s+(?=[A-Z*(`$])", par)
    for p in parts:
        if out and re.match(r"\s*<!--", p):
            out[-1] += " " + p
        else:
            out.append(p)
    return [(s, _plain(s)) for s in out]


def lint_claims(path):
    """Unmarked statements about runs in one handout: [(line, sentence)]."""
    with open(path, encoding="utf-8") as f:
        text = f.read()
    findings = []
    lines = text.split("\n")
    in_code, in_task = False, False
    par, par_line = [], 0

    def flush():
        if not par:
            return
        body = "\n".join(par)
        for sent, plain in _sentences(body):
            if CLAIM.search(sent) or NOT_A_CLAIM.search(sent):
                continue
            words = plain.strip()
            if words.endswith("?") and not re.search(r"\bwhy\b", words, re.I):
                continue  # a question asks; it states nothing ("why ...?" states its premise)
            if TASK_VERB.match(words):
                continue  # "Show that ...", "Run ...": a task for the student
            if not RUN_WORDS.search(words):
                continue
            if NUMBER.search(words) or DIRECTION.search(words):
                findings.append((par_line, " ".join(sent.split())[:160]))

    for i, ln in enumerate(lines, 1):
        if ln.strip().startswith("```"):
            flush()
            par = []
            in_code = not in_code
            continue
        if in_code:
            continue
        if ln.startswith("#"):
            flush()
            par = []
            in_task = bool(TASK_HEADING.match(ln))
            continue
        if not ln.strip():
            flush()
            par = []
            continue
        if in_task:
            continue  # a task's statement: its numbers are the task's, not a run's
        # A table row, a list item: a unit of its own (a table cell, a question).
        if re.match(r"\s*(\||[-*+]\s|\d+\.\s)", ln):
            flush()
            par = []
            if re.match(r"\s*\|[-:| ]+\|\s*$", ln):
                continue  # a table's rule
            if ln.lstrip().startswith("|"):
                # Cells split on the | outside math ($|g|$ is not a cell's edge).
                masked = re.sub(r"\$[^$]*\$", lambda m: m.group(0).replace("|", "\0"), ln)
                for cell in masked.strip().strip("|").split("|"):
                    cell = cell.replace("\0", "|")
                    par, par_line = [cell], i
                    flush()
                par = []
                continue
        if not par:
            par_line = i
        par.append(ln)
    flush()
    return findings


def stage_claims(build, out, verbose):
    findings = []
    handouts = sorted(glob.glob(os.path.join(ROOT, "handouts", "*.md")))
    if ONLY_LABS:
        handouts = [h for h in handouts if os.path.basename(h)[:-3] in ONLY_LABS]
    for path in handouts:
        for line, sent in lint_claims(path):
            findings.append(f"{rel(path)}:{line}: states a number or a direction about a run "
                            f"without a claim marker: \"{sent}\": add <!-- claim: ... --> "
                            "(docs/report.md, Claims), or <!-- not-a-claim: why --> when it is "
                            "not about a run")
        # A sentence about bodies at rest is checked on positions (wbplot/claimrules.py).
        from wbplot import claimrules
        stems = {os.path.basename(f)[:-5] for f in glob.glob(os.path.join(ROOT, "scenes", "*",
                                                                          "*.json"))}
        for line, sent in claimrules.lint_motion(path, stems):
            findings.append(f"{rel(path)}:{line}: says bodies rest, stand still or move "
                            f"without a claim on positions: \"{sent}\": add a claim that reads "
                            "positions (trace ... move@T, a csv column of distances moved; "
                            "wbplot/claimrules.py), not only speeds or energies")
        if verbose:
            n = len(CLAIM.findall(open(path, encoding="utf-8").read()))
            print(f"{rel(path)}: {n} claim markers")
    return findings


# ----------------------------------------------------------------------------
# asserts: every graded assertion carries words

ASSERT = re.compile(r"\b(REQUIRE|CHECK|REQUIRE_FALSE|CHECK_FALSE|REQUIRE_THAT|CHECK_THAT"
                    r"|REQUIRE_NOTHROW|CHECK_NOTHROW|REQUIRE_THROWS\w*|CHECK_THROWS\w*)\s*\(")
WORDS = re.compile(r"\b(INFO|CAPTURE|UNSCOPED_INFO)\s*\(")


def _strip_comments_and_strings(src):
    """The source with comments and string literals blanked (same length, same lines)."""
    out, i, n = [], 0, len(src)
    while i < n:
        c = src[i]
        if src.startswith("//", i):
            j = src.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif src.startswith("/*", i):
            j = src.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", src[i:j]))
            i = j
        elif c == '"' or c == "'":
            j = i + 1
            while j < n and src[j] != c:
                j += 2 if src[j] == "\\" else 1
            out.append(c + re.sub(r"[^\n]", " ", src[i + 1:j]) + c)
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def lint_asserts(path):
    """[(line, text)] of bare assertions with no INFO/CAPTURE before them in an enclosing
    scope (the same block or one around it, from its opening brace)."""
    with open(path, encoding="utf-8") as f:
        raw = f.read()
    src = _strip_comments_and_strings(raw)
    findings = []
    # Scopes: for each position, the stack of open-brace positions.
    stack, opens = [], {}
    for i, c in enumerate(src):
        if c == "{":
            stack.append(i)
        elif c == "}" and stack:
            stack.pop()
        opens[i] = stack[-1] if stack else 0
    for m in ASSERT.finditer(src):
        start = m.start()
        # Skip macro definitions and the helpers' own bodies (namespace wbtest).
        line_start = src.rfind("\n", 0, start) + 1
        if src[line_start:start].lstrip().startswith("#"):
            continue
        # Scope text: from the outermost enclosing function body (brace depth >= 1 inside a
        # TEST_CASE) to the assertion; an INFO/CAPTURE in an enclosing, still-open scope
        # before it counts. Approximation: the text from the innermost '{' that is still open
        # at `start`, walking outwards, minus closed inner blocks.
        visible = _visible_before(src, start)
        if WORDS.search(visible):
            continue
        line = raw.count("\n", 0, start) + 1
        end = raw.find("\n", start)
        findings.append((line, raw[start:end if end > 0 else None].strip()[:120]))
    return findings


def _visible_before(src, pos):
    """The text of the scopes open at `pos`, before it, without the blocks already closed
    (an INFO inside an earlier, closed block is out of scope)."""
    out, depth = [], 0
    i = pos - 1
    while i >= 0:
        c = src[i]
        if c == "}":
            depth += 1
        elif c == "{":
            if depth == 0:
                # Stop at a TEST_CASE/SECTION body? No: enclosing scopes stay visible up to
                # the test case's opening brace, which is reached when the text before it is
                # a TEST_CASE(...) header.
                header = src[max(0, i - 400):i]
                out.append(c)
                if re.search(r"\b(TEST_CASE|TEST_CASE_METHOD|SCENARIO)\s*\([^{}]*$", header):
                    break
            else:
                depth -= 1
        elif depth == 0:
            out.append(c)
        i -= 1
    return "".join(reversed(out))


def stage_asserts(build, out, verbose):
    findings = []
    for lab in labs():
        for path in sorted(glob.glob(os.path.join(ROOT, "tests", lab, "*.cpp"))):
            for line, text in lint_asserts(path):
                findings.append(f"{rel(path)}:{line}: \"{text}\" has no words for the student: "
                                "put an INFO(...) or CAPTURE(...) before it in the same scope "
                                "(what was expected, what came out, what that usually "
                                "means), or use a wbtest::require_* helper with a message "
                                "(docs/grading.md, \"Words on every assertion\")")
    return findings


# ----------------------------------------------------------------------------
# nanfree: a value that came back from student code may be NaN anywhere (docs/grading.md,
# "Every value from the worker is hostile"). Eigen's maxCoeff() may skip a NaN that is not
# the first entry and std::max(acc, NaN) returns acc: both let a NaN pass a tolerance.

_CMP = r"(?<![<>=!])(?:<=|>=|==|!=|<(?![<=])|>(?![>=]))"  # a comparison, not << or >>
NAN_COMPARE = re.compile(r"\.(max|min)Coeff\([^()]*\)\s*" + _CMP + "|" + _CMP +
                         r"\s*[\w.()]*\.(max|min)Coeff\(")
NAN_ACCUMULATE = re.compile(r"\b(\w+)\s*=\s*std::(max|min)\(\s*\1\s*,")


# Ordering comparisons (and !=) inside an assertion; template arguments blanked first.
ORDERING = re.compile(r"<=|>=|!=|(?<![<>-])[<>](?![<>=])")
TEMPLATE_ARGS = re.compile(r"\b\w+\s*<[\w:,\s]*>")
# The helpers that turn a value that is not finite into NaN, which fails every comparison.
NAN_STICKY = re.compile(r"\b(finite|max_abs_diff|max_abs|worst_of|least_of)\s*\(")


def lint_nanfree(path):
    with open(path, encoding="utf-8") as f:
        raw = f.read()
    src = _strip_comments_and_strings(raw)
    findings = []
    for m in NAN_COMPARE.finditer(src):
        findings.append((raw.count("\n", 0, m.start()) + 1,
                         "a maxCoeff()/minCoeff() compared: Eigen may skip a NaN there; use "
                         "wbtest::max_abs_diff(got, expected) or wbtest::max_abs(x), which are "
                         "+infinity for a NaN or an infinity"))
    for m in ASSERT.finditer(src):  # inside an assertion: REQUIRE(x.maxCoeff() ...)
        depth, i = 1, m.end()
        while i < len(src) and depth:
            depth += {"(": 1, ")": -1}.get(src[i], 0)
            i += 1
        if re.search(r"\.(max|min)Coeff\(", src[m.end():i]):
            findings.append((raw.count("\n", 0, m.start()) + 1,
                             "a maxCoeff()/minCoeff() inside an assertion: use "
                             "wbtest::max_abs_diff or wbtest::max_abs (NaN-safe)"))
    for m in ASSERT.finditer(src):  # an ordering comparison lets one infinity through
        depth, i = 1, m.end()
        while i < len(src) and depth:
            depth += {"(": 1, ")": -1}.get(src[i], 0)
            i += 1
        body = re.sub(TEMPLATE_ARGS, "T", src[m.end():i - 1])
        if not ORDERING.search(body) or NAN_STICKY.search(body):
            continue
        end = raw.find("\n", i)
        if re.search(r"//\s*nanfree:\s*\S", raw[m.start():end if end >= 0 else len(raw)]):
            continue  # a reason given (integers, values the test computed itself)
        findings.append((raw.count("\n", 0, m.start()) + 1,
                         "an ordering comparison (<, <=, >, >=, !=) of raw values inside an "
                         "assertion: +inf passes '> bound', -inf passes '< bound', NaN passes "
                         "'!='; wrap the value that came from the lab's code in "
                         "wbtest::finite(...) (NaN unless finite), or compare through "
                         "max_abs_diff, max_abs, worst_of, least_of; if every side is an "
                         "integer or the test's own, say so: '// nanfree: integers'"))
    for m in NAN_ACCUMULATE.finditer(src):
        findings.append((raw.count("\n", 0, m.start()) + 1,
                         f"a running {m.group(2)}imum by std::{m.group(2)}: a NaN is dropped "
                         f"there; use wbtest::{'worst_of' if m.group(2) == 'max' else 'least_of'}"))
    return sorted(set(findings))


def stage_nanfree(build, out, verbose):
    findings = []
    for lab in labs():
        files = sorted(glob.glob(os.path.join(ROOT, "tests", lab, "*.cpp")) +
                       glob.glob(os.path.join(ROOT, "tests", lab, "*.h")) +
                       glob.glob(os.path.join(ROOT, "tests", lab, "kernels", "*")))
        tasks, held = set(), set()
        for path in files:
            findings += [f"{rel(path)}:{line}: {what}" for line, what in lint_nanfree(path)]
            with open(path, encoding="utf-8") as f:
                for tags in re.findall(r'TEST_CASE\(\s*(?:"[^"]*"\s*)+,\s*"([^"]*)"', f.read()):
                    task = re.search(r"\[([A-Z]\d+)\]", tags)
                    if task:
                        tasks.add(task.group(1))
                        if "[held-out]" in tags.lower():
                            held.add(task.group(1))
        findings += [f"tests/{lab}/: task {t} has no test tagged [held-out]: its points could be "
                     "earned by replaying the public tests' answers (tests/common/heldout.h, "
                     "docs/grading.md \"Held-out checks\")" for t in sorted(tasks - held)]
    for path in sorted(glob.glob(os.path.join(ROOT, "tests", "common", "*.h"))):
        findings += [f"{rel(path)}:{line}: {what}" for line, what in lint_nanfree(path)]
    return findings


# ----------------------------------------------------------------------------
# testnames: one naming scheme for graded test files, the task's own

TEST_FILE = re.compile(r"^test_([A-Z][0-9]+)_([a-z0-9]+(?:_[a-z0-9]+)*)\.cpp$")
_LITERALS = r'((?:"(?:[^"\\\n]|\\.)*"\s*)+)'
TEST_CASE = re.compile(r"\bTEST_CASE\(\s*" + _LITERALS + r"(?:,\s*" + _LITERALS + r")?\)")


def lab_tasks(lab):
    """The tasks of a lab, in order: the TODO(<task>) tags of its student files."""
    found = set()
    for path in glob.glob(os.path.join(ROOT, "labs", lab, "*")):
        if os.path.isfile(path):
            with open(path, encoding="utf-8") as f:
                found |= set(re.findall(r"TODO\(([A-Z][0-9]+)\)", f.read()))
    return sorted(found, key=lambda t: (t[0], int(t[1:])))


def test_cases(text):
    """[(name, tags)] of the TEST_CASEs of a test file (adjacent literals joined), and the
    number of TEST_CASE( it holds (more than read: one the pattern cannot read)."""
    def joined(lits):
        return "".join(re.findall(r'"((?:[^"\\\n]|\\.)*)"', lits or ""))
    cases = [(joined(m.group(1)), joined(m.group(2))) for m in TEST_CASE.finditer(text)]
    return cases, len(re.findall(r"\bTEST_CASE\(", text))


def test_name_findings(lab, files, tasks, read):
    """The findings for one lab's graded test files (names in tests/<lab>/, a reader of their
    text): the naming scheme, the tags, a file for every task."""
    findings, covered = [], set()
    where = f"tests/{lab}"
    for name in files:
        m = TEST_FILE.match(name)
        if not m:
            findings.append(f"{where}/{name}: graded test files are named test_<task>_<what>.cpp "
                            f"(<task> one of the TODO tags of labs/{lab}/: "
                            f"{', '.join(tasks) or 'none'}; <what> lower-case words joined by _, "
                            "e.g. test_F5_spring.cpp): rename it")
            continue
        task = m.group(1)
        if task not in tasks:
            findings.append(f"{where}/{name}: names task {task}, but labs/{lab}/ has no "
                            f"TODO({task}) (its tasks: {', '.join(tasks) or 'none'})")
            continue
        covered.add(task)
        cases, n = test_cases(read(name))
        if len(cases) != n:
            findings.append(f"{where}/{name}: {n - len(cases)} TEST_CASE(...) not read as "
                            "TEST_CASE(\"name\", \"[tags]\"): write name and tags as string "
                            "literals")
        for case, tags in cases:
            bad = sorted(set(case) & FORBIDDEN_NAME_CHARS)
            if bad or case != case.strip() or case.startswith(("#", "-")):
                findings.append(f"{where}/{name}: test \"{case}\": the grader refuses a name "
                                f"with {' '.join(bad) or 'a space at an end or a leading # or -'}"
                                " (Catch's test-spec syntax, tools/grader/build.py check_list): "
                                "reword it")
            if f"[{task}]" not in tags:
                findings.append(f"{where}/{name}: test \"{case}\" lacks the tag [{task}] of "
                                "the task its file is named after: tag it, or move it to its "
                                "task's file")
    for task in tasks:
        if task not in covered:
            findings.append(f"{where}/: task {task} has no test file test_{task}_<what>.cpp")
    return findings


POINTS_TAG = re.compile(r"\[(\d+)pts\]")
HANDOUT_TASK = re.compile(r"^##\s+([A-Z][0-9]+)\b.*\((\d+) points\)\s*$", re.MULTILINE)


def points_findings(lab, points, handout):
    """The points of a lab's tests ({task: sum of its tests' [Npts] tags}) against the lab's
    handout ("## F5 ... (16 points)" headings) and the grader's total of 100: two branches that
    each keep 100 can merge into 102, which only a grading would find (a CI run later)."""
    findings = []
    total = sum(points.values())
    if total != 100:
        findings.append(f"tests/{lab}/: the tests' points add up to {total}, expected 100 "
                        "(the grader refuses the list): " +
                        ", ".join(f"{t} {n}" for t, n in points.items()))
    if handout is None:
        return findings
    stated = {t: int(n) for t, n in HANDOUT_TASK.findall(handout)}
    for task, n in points.items():
        if task not in stated:
            findings.append(f"handouts/{lab}.md: no heading '## {task} ... ({n} points)'")
        elif stated[task] != n:
            findings.append(f"handouts/{lab}.md: '## {task}' says {stated[task]} points, its "
                            f"tests in tests/{lab}/ carry {n}: make them agree")
    return findings


def stage_testnames(build, out, verbose):
    findings = []
    for lab in labs():
        d = os.path.join(ROOT, "tests", lab)
        if not os.path.isdir(d):
            findings.append(f"tests/{lab}/: missing: every lab has graded tests")
            continue

        def read(name):
            with open(os.path.join(d, name), encoding="utf-8") as f:
                return f.read()
        files = sorted(n for n in os.listdir(d) if n.endswith(".cpp")
                       and os.path.isfile(os.path.join(d, n)))
        findings += test_name_findings(lab, files, lab_tasks(lab), read)
        points = {}
        for name in files:
            m = TEST_FILE.match(name)
            if m:
                points[m.group(1)] = points.get(m.group(1), 0) + sum(
                    sum(int(n) for n in POINTS_TAG.findall(tags))
                    for _, tags in test_cases(read(name))[0])
        handout = os.path.join(ROOT, "handouts", f"{lab}.md")
        text = open(handout, encoding="utf-8").read() if os.path.isfile(handout) else None
        findings += points_findings(lab, points, text)
    return findings


# ----------------------------------------------------------------------------
# points: one source for the points, the tests' [Npts] tags; every handout lists them

POINTS_OPEN = re.compile(r"^<!-- points ([A-Z][0-9]+):[^\n]*-->\n", re.M)
POINTS_CLOSE = "<!-- /points -->\n"


def lab_test_list(lab, read_file=None):
    """{task: [(name, points, held_out)]} of a lab's graded tests, in file order (the files of
    a task sorted by name), read from tests/<lab>/test_<task>_*.cpp."""
    d = os.path.join(ROOT, "tests", lab)
    read_file = read_file or (lambda n: open(os.path.join(d, n), encoding="utf-8").read())
    out = {}
    for name in sorted(n for n in os.listdir(d) if TEST_FILE.match(n)):
        task = TEST_FILE.match(name).group(1)
        for case, tags in test_cases(read_file(name))[0]:
            pts = sum(int(n) for n in POINTS_TAG.findall(tags))
            out.setdefault(task, []).append((case, pts, "[held-out]" in tags))
    return out


def points_block(lab, task, tests):
    """The handout's list of one task's graded tests and their points, as tools/pattern points
    --write writes it between <!-- points TASK: ... --> and <!-- /points -->."""
    total = sum(p for _, p, _ in tests)
    held = sum(p for _, p, h in tests if h)
    n_held = sum(1 for _, _, h in tests if h)
    lines = [f"<!-- points {task}: written by tools/pattern points --write from the tests' "
             "[Npts] tags; change the tags, not this list -->",
             f"Tests, `build/bin/{lab}-tests \"[{task}]\"`, {total} points:", ""]
    for name, pts, held_out in tests:
        lines.append(f"- `{name}` ({pts}{', held-out' if held_out else ''})")
    if n_held:
        it = "the held-out test passes" if n_held == 1 else "every held-out test passes"
        lines += [""] + textwrap.wrap(
            f"The other {total - held} points count only when {it} ({held} "
            f"point{'s' if held != 1 else ''} of its own, on inputs drawn when you are graded): "
            "a public test passed alone scores 0.", width=76)
    return "\n".join(lines) + "\n" + POINTS_CLOSE


def points_blocks(text):
    """{task: (start, end)} of the points blocks of a handout's text (end past the close)."""
    out = {}
    for m in POINTS_OPEN.finditer(text):
        end = text.find(POINTS_CLOSE, m.end())
        out[m.group(1)] = (m.start(), len(text) if end < 0 else end + len(POINTS_CLOSE))
    return out


def task_section_end(text, task):
    """Where a new points block goes in a handout: the end of the task's "## <task> ..."
    section (before the anchor and blank lines that open the next), or None."""
    m = re.search(rf"^##\s+{task}\b.*$", text, re.M)
    if not m:
        return None
    nxt = re.search(r"^##\s", text[m.end():], re.M)
    end = m.end() + nxt.start() if nxt else len(text)
    body = text[:end]
    while True:  # step back over blank lines and the next section's <a id="..."></a>
        stripped = body.rstrip("\n")
        last = stripped[stripped.rfind("\n") + 1:]
        if re.fullmatch(r'<a id="[^"]*"></a>', last.strip()):
            body = stripped[:stripped.rfind("\n") + 1]
            continue
        return len(stripped) + 1 if stripped != body else len(body)


def points_write(lab, text, tests):
    """The handout's text with every task's points block written (replaced, or added at the
    end of the task's section)."""
    for task in sorted(tests, key=lambda t: (t[0], int(t[1:]))):
        block = points_block(lab, task, tests[task])
        blocks = points_blocks(text)
        if task in blocks:
            a, b = blocks[task]
            text = text[:a] + block + text[b:]
            continue
        at = task_section_end(text, task)
        if at is None:
            continue  # the testnames stage says the heading is missing
        text = text[:at].rstrip("\n") + "\n\n" + block + "\n" + text[at:].lstrip("\n")
    return text


def points_list_findings(lab, text, tests):
    """The findings of one handout's points blocks against its lab's tests."""
    where = f"handouts/{lab}.md"
    findings = []
    blocks = points_blocks(text)
    for task in sorted(tests, key=lambda t: (t[0], int(t[1:]))):
        want = points_block(lab, task, tests[task])
        if task not in blocks:
            findings.append(f"{where}: task {task} has no list of its tests and their points "
                            "(<!-- points ... --> block): run tools/pattern points --write")
            continue
        a, b = blocks[task]
        got = text[a:b]
        if got != want:
            g, w = got.split("\n"), want.split("\n")
            diff = [k for k in range(max(len(g), len(w)))
                    if k >= len(g) or k >= len(w) or g[k] != w[k]]
            for k in diff[:3]:
                findings.append(f"{where}: {task}'s list says {g[k] if k < len(g) else '(nothing)'!r}"
                                f" where the tests' tags in tests/{lab}/ give "
                                f"{w[k] if k < len(w) else '(nothing)'!r}: change the [Npts] tag "
                                "or run tools/pattern points --write, so that both agree")
    for task in blocks:
        if task not in tests:
            findings.append(f"{where}: a points block for {task}, which has no graded test")
    return findings


WRITE_POINTS = False  # tools/pattern points --write


def stage_points(build, out, verbose):
    findings = []
    for lab in labs():
        handout = os.path.join(ROOT, "handouts", f"{lab}.md")
        if not os.path.isdir(os.path.join(ROOT, "tests", lab)) or not os.path.isfile(handout):
            continue  # testnames says so
        tests = lab_test_list(lab)
        with open(handout, encoding="utf-8") as f:
            text = f.read()
        if WRITE_POINTS:
            new = points_write(lab, text, tests)
            if new != text:
                with open(handout + ".tmp", "w", encoding="utf-8") as f:
                    f.write(new)
                os.replace(handout + ".tmp", handout)
                print(f"pattern: points: wrote the lists of handouts/{lab}.md")
            text = new
        findings += points_list_findings(lab, text, tests)
    return findings


# ----------------------------------------------------------------------------
# answers: the student pack holds no task's answer (tools/wbtools/answers.py)

def stage_answers(build, out, verbose):
    from . import answers
    everything = labs()
    found = answers.overlaps(answers.repo_shipped(everything), everything)
    if verbose:
        for rel, sol, share, why in found:
            if why:
                print(f"answers: {rel} holds {100 * share:.0f} % of solutions/{sol}: allowed: {why}")
    return [f"{rel} holds {100 * share:.0f} % of solutions/{sol}: a source the pack ships computes "
            "what the task's solution computes; ship it compiled only or make it call the "
            "student's function (tools/wbtools/answers.py)" for rel, sol, share, why in found
            if not why]
    return findings


# ----------------------------------------------------------------------------
# docrefs: what the docs quote from the code exists there (tools/wbtools/docrefs.py)

def stage_docrefs(build, out, verbose):
    from wbtools import docrefs
    findings, counts = docrefs.check(ROOT)
    if verbose or not findings:
        print(f"pattern: docrefs: {counts['docs']} Markdown files: {counts['flags']} flags, "
              f"{counts['calls']} calls and {counts['paths']} paths quoted, checked")
    return findings


# ----------------------------------------------------------------------------
# imports: no import circle in tools/ (tools/wbtools/imports.py)

def stage_imports(build, out, verbose):
    from wbtools import imports
    findings, n = imports.check(ROOT)
    if verbose or not findings:
        print(f"pattern: imports: {n} modules of tools/, no module imports one that imports it back")
    return findings


# ----------------------------------------------------------------------------
# reportdoc: docs/report.md and the report's figures agree

FIG_EXT = (".png", ".gif")


def _pattern_of(name, lab_scenes):
    """A figure file name -> its pattern in docs/report.md: the scene's stem as <scene>."""
    for stem in sorted(lab_scenes, key=len, reverse=True):
        if name.startswith(stem + "-") or name.startswith(stem + "."):
            return "<scene>" + name[len(stem):]
        if name.endswith("-" + stem + name[name.rfind("."):]):
            return name[:-len(stem + name[name.rfind("."):])] + "<scene>" + name[name.rfind("."):]
    return name


def stage_reportdoc(build, out, verbose):
    report = os.path.join(build, "report")
    if not os.path.isdir(report):
        raise SystemExit(f"tools/pattern: error: {rel(report)}: no report (run tools/report "
                         "first: this stage checks docs/report.md against its figures)")
    with open(os.path.join(ROOT, "docs", "report.md"), encoding="utf-8") as f:
        doc = f.read()
    findings = []
    for lab in labs():
        folder = os.path.join(report, lab)
        if not os.path.isdir(folder):
            findings.append(f"{rel(folder)}: the report has no section for lab {lab} (run "
                            "tools/report)")
            continue
        stems = [os.path.basename(s)[:-5] for s in scenes(lab)]
        missing = {}  # pattern -> the files drawn under it
        for name in sorted(f for f in os.listdir(folder) if f.endswith(FIG_EXT)):
            pat = _pattern_of(name, stems)
            if f"`{pat}`" not in doc and f"`{name}`" not in doc:
                missing.setdefault(pat, []).append(name)
            elif verbose:
                print(f"ok: {lab}: {name}")
        for pat, names in sorted(missing.items()):
            findings.append(f"docs/report.md: names no figure `{pat}` (lab {lab}: "
                            f"{', '.join(names[:3])}{' ...' if len(names) > 3 else ''}, "
                            "drawn by the last tools/report): add it to the lab's table")
    if ONLY_LABS:
        return findings  # the names the other labs' figures have are theirs to check
    # Names docs/report.md lists that no lab's report drew.
    every = set()
    for lab in labs():
        folder = os.path.join(report, lab)
        stems = [os.path.basename(s)[:-5] for s in scenes(lab)]
        if os.path.isdir(folder):
            every |= {_pattern_of(f, stems) for f in os.listdir(folder) if f.endswith(FIG_EXT)}
            every |= {f for f in os.listdir(folder) if f.endswith(FIG_EXT)}
    for pat in sorted(set(re.findall(r"`([^`\s]*<scene>[^`\s]*\.(?:png|gif))`", doc))
                      | set(re.findall(r"`([\w.-]+\.(?:png|gif))`", doc))):
        if pat not in every and not pat.startswith(("FIG", "F.", "x.", "amp.")):
            findings.append(f"docs/report.md: names `{pat}`, which the last tools/report did "
                            "not draw for any lab: remove it, or make the report draw it")
    return findings


def stage_stubfigs(build, out, verbose):
    from wbplot import stubfigs
    for lab in labs():
        skeleton(lab, build)
    return stubfigs.stage(ROOT, build, labs())


# ----------------------------------------------------------------------------


def main():
    ap = argparse.ArgumentParser(prog="tools/pattern", description=__doc__.split("\n\n")[0],
                                 epilog="\n\n".join(__doc__.split("\n\n")[1:]),
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("stages", nargs="*", metavar="STAGE",
                    help="some of: " + ", ".join(STAGES) + " (default: all)")
    ap.add_argument("--build-dir", default="build",
                    help="executables in DIR/bin, the report in DIR/report (default build)")
    ap.add_argument("--lab", action="append", default=[], metavar="LAB",
                    help="only this lab (repeatable): the stages that go lab by lab look at it "
                         "alone (claims: its handout); docrefs and imports still read the whole "
                         "repository (tools/newlab-check uses it on its throwaway lab)")
    ap.add_argument("-v", "--verbose", action="store_true", help="print what passed too")
    ap.add_argument("--write", action="store_true",
                    help="with the points stage: write every handout's lists of tests and "
                         "points from the tests' tags first (then check them)")
    try:
        args = ap.parse_args()
    except SystemExit as e:
        return 2 if e.code else 0
    stages = args.stages or STAGES
    bad = [s for s in stages if s not in STAGES]
    if bad:
        print(f"tools/pattern: error: stage '{bad[0]}': expected some of {', '.join(STAGES)}",
              file=sys.stderr)
        return 2
    if args.write and "points" not in stages:
        print("tools/pattern: error: --write: goes with the points stage", file=sys.stderr)
        return 2
    unknown = [lab for lab in args.lab if lab not in all_labs()]
    if unknown:
        print(f"tools/pattern: error: --lab {unknown[0]}: no folder labs/{unknown[0]}/ "
              f"(expected one of: {', '.join(all_labs())})", file=sys.stderr)
        return 2
    global WRITE_POINTS
    WRITE_POINTS = args.write
    ONLY_LABS[:] = args.lab
    build = os.path.join(ROOT, args.build_dir)
    out = os.path.join(build, "pattern")
    total = 0
    for stage in stages:
        t0 = time.monotonic()
        try:
            findings = globals()[f"stage_{stage}"](build, out, args.verbose)
        except SystemExit as e:
            print(e, file=sys.stderr)
            return 2
        for f in findings:
            print(f"{stage}: {f}")
        print(f"pattern: {stage}: {len(findings)} finding(s) ({time.monotonic() - t0:.1f} s)")
        total += len(findings)
    return 1 if total else 0


def entry():
    """The entry tools/pattern calls: main() with the command line, its exit status (not named
    run: that is the subprocess helper above, which the stubs and periods checks call)."""
    sys.exit(main())
