"""The table and Gradescope's results.json, written last and atomically.

Trust: formats what the verdict decided; every text from a test is capped and escaped."""
import json
import os
import re
import sys
import tempfile

from .common import RESULTS_CAP, printable

DIAGNOSIS_LINES = 40  # lines of one task's diagnosis kept
DIAGNOSIS_CHARS = 400  # characters of one line kept (diagnosis.hints.LINE_CHARS, capped here too)


LINE_LIMIT = 100  # characters of a line a student reads in a terminal
# Words of the test harness, the grader's plumbing and the standard library's internals: none may
# reach a student's text (docs/grading.md, "The output").
INTERNALS = re.compile(r"test_helpers\.h|\.h:\d+|\.cpp:\d+|REQUIRE|CHECK\(|with expansion|"
                       r"Unknown expression|:= |\bpipe\b|sandbox|\bworker\b|Catch2?\b|"
                       r"libstdc\+\+|__glibcxx|_GLIBCXX|Assertion .* failed|std::__|"
                       r"/usr/include|terminate called")


def student_text_problems(text):
    """What a student's text breaks: a line over LINE_LIMIT characters, a word of the harness."""
    out = []
    for k, line in enumerate(text.splitlines(), 1):
        if len(line) > LINE_LIMIT:
            out.append(f"line {k} has {len(line)} characters: {line[:60]}...")
        m = INTERNALS.search(line)
        if m:
            out.append(f"line {k} has the harness's {m.group(0)!r}: {line.strip()[:80]}")
    return out


def task_lines(d):
    """One task's diagnosis (a diagnosis.hints.Diagnosis) as printable lines."""
    try:
        lines = d.lines()
    except Exception as e:  # a broken diagnosis never changes a score
        return [f"{getattr(d, 'task', '?')}: (no diagnosis: {type(e).__name__})"]
    return [printable(str(l), keep_newlines=False)[:DIAGNOSIS_CHARS]
            for l in list(lines)[:DIAGNOSIS_LINES]]


def lab_diagnosis(lab, rep):
    """The lines under a lab: each failing task's diagnosis, the tasks not started on one line."""
    if not rep.gradable or not rep.diagnosis:
        return []
    out, idle = [], []
    for task, d in rep.diagnosis.items():
        if getattr(d, "status", "") == "not started":
            idle.append(f"{task}{' ' + d.title if d.title else ''}")
        elif getattr(d, "status", "") != "passed":
            out += task_lines(d)
    if idle:
        out.append("not started (still the skeleton): " + ", ".join(idle))
    return out


# ---------------------------------------------------------------- reporting

def layers_text(grader):
    """Which defences were active for this run (never one that was not)."""
    lines = ["screening: " + ("active (allow-listed headers, denied identifiers, regular files)"
                              if grader.screen else "OFF (--no-screen: for testing the sandbox)"),
             "sandbox of each test process:", grader.sandbox.describe(),
             "build (compiler, assembler, linker): " + grader.build_isolation,
             f"held-out inputs: seed {grader.seed:#x} (tools/grade --seed {grader.seed:#x} "
             "replays them)"]
    return "\n".join(lines)


def layers_data(grader):
    return {"screening": bool(grader.screen), "sandbox": list(grader.sandbox.layers),
            "build": grader.build_isolation,
            "sandbox_missing": dict(grader.sandbox.missing)}


REASON_LINES = 8  # lines of a failed test's reason under it in the table (-v: all of it)
INDENT = 10  # the points' column and its gap: a test's name and its reason start here


def wrap(line, width=LINE_LIMIT, indent=0):
    """`line` (printable) as lines of at most `width` characters, the first indented by
    `indent`, the others 2 more; broken at spaces, never cut."""
    from diagnosis.hints import wrap as _wrap
    return _wrap(" " * indent + line, width)


def wrap_text(text):
    """A text of several lines, each line that is longer than LINE_LIMIT broken as wrap does
    (results.json: the course platform shows it as the terminal does, line for line)."""
    return "\n".join(w for l in text.split("\n") for w in (wrap(l) if len(l) > LINE_LIMIT
                                                             else [l]))


def reason_lines(r, limit=REASON_LINES):
    """A failed test's reason under its name: the check that failed (what, expected, got),
    then its context; the tolerance stays in the details (-v, results.json)."""
    from . import wording
    lines = [l for l in wording.differing(printable(r.reason or "")).split("\n")
             if l.strip() and not l.strip().startswith("tolerance ")]
    out = []
    for l in lines:
        lead = len(l) - len(l.lstrip(" "))
        out += wrap(l.strip(), indent=INDENT + lead)
    if len(out) > limit:
        out = out[:limit - 1] + [" " * INDENT + f"[... {len(out) - limit + 1} more lines: "
                                 "tools/grade -v shows the whole test]"]
    return out


def print_table(reports, notes, out=sys.stdout, seed=None):
    """The student's table: every line at most LINE_LIMIT characters. Per lab, each test's
    points and name, a failed test's reason under it; then what the lab's functions do on the
    probes; then the scores. `seed`: the grade's held-out seed, printed once, whole."""
    for lab, rep in reports.items():
        for n in notes.get(lab, []):
            for l in wrap(f"{lab}: note: {printable(n, keep_newlines=False)}"):
                print(l, file=out)
        if rep.refused:
            for k, l in enumerate(printable(rep.refused).split("\n")):
                for w in wrap((f"{lab}: REFUSED: " if k == 0 else "  ") + l):
                    print(w, file=out)
    if seed is not None:
        for l in wrap(f"held-out inputs from seed {seed:#x} (--seed {seed:#x} replays this "
                      "grade)"):
            print(l, file=out)
    for lab, rep in reports.items():
        print(f"{lab}: the tests, each with its points (a failed test says why under it)",
              file=out)
        for r in rep.results:
            pts = f"{r.score}/{r.test.points}"
            name = wrap(r.test.name, indent=INDENT)
            print(f"{pts:>{INDENT - 2}}  {name[0][INDENT:]}", file=out)
            for l in name[1:]:
                print(l, file=out)
            if r.status != "passed" or r.score < r.test.points:
                for l in reason_lines(r):
                    print(l, file=out)
    print(file=out)
    for lab, rep in reports.items():
        lines = lab_diagnosis(lab, rep)
        if lines:
            print(f"{lab}: what your functions do on the probes (fixed example inputs; no points):",
                  file=out)
            print("\n".join(w for l in lines for w in wrap("  " + l)) + "\n", file=out)
    for lab, rep in reports.items():
        extra = (" (refused: every test scores 0)" if rep.refused else
                 " (does not compile: every test scores 0)" if rep.compile_error else "")
        print(f"{lab}: {rep.score}/{rep.max_score}{extra}", file=out)
    total = sum(rep.score for rep in reports.values())
    total_max = sum(rep.max_score for rep in reports.values())
    print(f"total: {total}/{total_max}", file=out)
    for lab, rep in reports.items():
        if rep.compile_error:
            print(f"\n{lab}: compiler output (last lines):\n{rep.compile_error}", file=out)


def summary(reports, notes, layers="", seed=None):
    lines = []
    if seed is not None:  # the one line that names the seed (a reason refers to it)
        lines.append(f"Held-out inputs from seed {seed:#x} (--seed {seed:#x} replays this "
                     "grade).")
    for lab, rep in reports.items():
        failed = sum(1 for r in rep.results if r.status == "failed")
        state = ("refused: every test scores 0" if rep.refused else
                 "does not compile: every test scores 0" if rep.compile_error else
                 f"{len(rep.results) - failed} of {len(rep.results)} tests passed")
        lines.append(f"{lab}: {rep.score}/{rep.max_score} ({state})")
        if rep.refused:
            lines.append("  refused: " + printable(rep.refused).replace("\n", "\n    "))
        lines += [f"  note: {printable(n, keep_newlines=False)}" for n in notes.get(lab, [])]
        for task, d in (rep.diagnosis or {}).items() if rep.gradable else ():
            try:
                lines.append("  " + printable(d.headline(), keep_newlines=False))
            except Exception:
                pass
    lines.append("Open a failed test below for what was expected and what came out, and what "
                 "the task's functions do on the probes (fixed example inputs).")
    return "\n".join(lines)


def results_json(reports, notes, layers="", layer_data=None, seed=None):
    """Gradescope's results.json as a dict; its JSON text is at most RESULTS_CAP bytes (each
    test's output is already capped; if they still add up to more, each is cut further). A
    task's diagnosis goes under its first failed test, once."""
    tests = []
    for lab, rep in reports.items():
        diag = {task: "\n".join(task_lines(d)) for task, d in (rep.diagnosis or {}).items()} \
            if rep.gradable else {}
        shown = set()
        for r in rep.results:
            out = r.output if r.status == "failed" else (r.output or "passed")
            task = re.match(r"^([A-Z]+\d+)\b", r.test.name)
            task = task.group(1) if task else ""
            extra = diag.get(task, "")
            if extra and r.status == "failed":
                out = out.rstrip() + ("\n\nDiagnosis of the task:\n" + extra if task not in shown
                                      else f"\n\n(The diagnosis of {task} is under its first "
                                      "failed test.)")
                shown.add(task)
            tests.append({"name": f"{r.test.lab}: {r.test.name}", "score": r.score,
                          "max_score": r.test.points, "status": r.status,
                          "output": wrap_text(out), "visibility": "visible"})
    data = {"score": sum(rep.score for rep in reports.values()),
            "output": wrap_text(summary(reports, notes, layers, seed)), "output_format": "text",
            "test_output_format": "text", "test_name_format": "text",
            "visibility": "visible", "stdout_visibility": "hidden", "tests": tests,
            "extra_data": {"defences": layer_data or {}}}
    size = len(json.dumps(data, indent=2).encode("utf-8"))
    if size > RESULTS_CAP and tests:
        each = max(256, (RESULTS_CAP - 64 * 1024) // (2 * len(tests)))
        for t in tests:
            if len(t["output"]) > each:
                t["output"] = t["output"][:each] + "\n[... cut: results.json is capped]"
    return data


def write_atomic(path, text):
    d = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(prefix=".results-", dir=d)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(text)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        try:
            os.remove(tmp)
        except OSError:
            pass
        raise


