"""The table and Gradescope's results.json, written last and atomically.

Trust: formats what the verdict decided; every text from a test is capped and escaped."""
import json
import os
import sys
import tempfile

from .common import RESULTS_CAP, printable

# The hint hook: hints_for(lab, [(test name, passed?, output)]) -> [str] (tools/grader/hints.py,
# the mutant catalogue's failure signatures) adds its lines under a lab's rows in the table and
# to the output of each failed test in results.json. None: no hints.
try:
    from .hints import hints_for as HINTS_FOR
except ImportError:
    HINTS_FOR = None


def lab_hints(lab, rep):
    """The hint lines for one lab's failures (never more than 5, each one line, printable)."""
    failed = [r.test.name for r in rep.results if r.status != "passed"]
    if HINTS_FOR is None or not failed or not rep.gradable:
        return []
    try:
        hints = HINTS_FOR(lab, [(r.test.name, r.status == "passed", r.output or r.reason)
                                for r in rep.results]) or []
    except Exception as e:  # a broken hint never changes a score
        return [f"(no hints: the hint module failed: {type(e).__name__})"]
    return [printable(" ".join(str(h).split()), keep_newlines=False)[:300] for h in hints[:5]]

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


def print_table(reports, notes, out=sys.stdout):
    results = [r for rep in reports.values() for r in rep.results]
    lab_w = max([3] + [len(l) for l in reports])
    name_w = min(80, max([4] + [len(r.test.name) for r in results]))
    for lab, rep in reports.items():
        for n in notes.get(lab, []):
            print(f"{lab}: note: {printable(n, keep_newlines=False)}", file=out)
        if rep.refused:
            print(f"{lab}: REFUSED: {printable(rep.refused)}", file=out)
    print(f"{'lab':<{lab_w}}  {'points':>7}  {'status':<6}  {'test':<{name_w}}  reason", file=out)
    for r in results:
        pts = f"{r.score}/{r.test.points}"
        print(f"{r.test.lab:<{lab_w}}  {pts:>7}  {r.status:<6}  {r.test.name:<{name_w}}  {r.reason}".rstrip(),
              file=out)
    print(file=out)
    for lab, rep in reports.items():
        for h in lab_hints(lab, rep):
            print(f"{lab}: hint: {h}", file=out)
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


def summary(reports, notes, layers=""):
    lines = []
    for lab, rep in reports.items():
        failed = sum(1 for r in rep.results if r.status == "failed")
        state = ("refused: every test scores 0" if rep.refused else
                 "does not compile: every test scores 0" if rep.compile_error else
                 f"{len(rep.results) - failed} of {len(rep.results)} tests passed")
        lines.append(f"{lab}: {rep.score}/{rep.max_score} ({state})")
        if rep.refused:
            lines.append("  refused: " + printable(rep.refused).replace("\n", "\n    "))
        lines += [f"  note: {printable(n, keep_newlines=False)}" for n in notes.get(lab, [])]
    lines.append("Each test ran in its own process with a time limit; open a failed test "
                 "below for what was expected and what came out.")
    if layers:
        lines.append(layers)
    return "\n".join(lines)


def results_json(reports, notes, layers="", layer_data=None):
    """Gradescope's results.json as a dict; its JSON text is at most RESULTS_CAP bytes (each
    test's output is already capped; if they still add up to more, each is cut further)."""
    tests = []
    for lab, rep in reports.items():
        hints = "".join(f"\nhint: {h}" for h in lab_hints(lab, rep))
        for r in rep.results:
            out = r.output if r.status == "failed" else (r.output or "passed")
            if hints and r.status == "failed":
                out = out.rstrip() + "\n" + hints
            tests.append({"name": f"{r.test.lab}: {r.test.name}", "score": r.score,
                          "max_score": r.test.points, "status": r.status, "output": out,
                          "visibility": "visible"})
    data = {"score": sum(rep.score for rep in reports.values()),
            "output": summary(reports, notes, layers), "output_format": "text",
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


