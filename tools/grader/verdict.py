"""The verdict of one test case: how its process ended (from the launcher) and the test
framework's report (from a pipe only the grader reads), checked for this run and this test.

Trust: decides the score; reads untrusted bytes as data only (capped, parsed defensively)."""
import re
import signal
import xml.etree.ElementTree as ET

from . import wording
from .common import (MESSAGE_CAP, OUTPUT_CAP, REPORT_CAP, TEST_OUTPUT_CAP, WALL_BUSY_SHARE,
                     Defect, TestResult, capped, printable)
from .procs import signal_name

# -------------------------------------------------------------- the XML report

def _text(el):
    """One message of the report: printable, at most MESSAGE_CAP characters."""
    lines = [l.strip() for l in "".join(el.itertext()).strip().splitlines()]
    return printable(capped("\n".join(l for l in lines if l), MESSAGE_CAP))


def read_report(data, name, nonce, strip, seed=None):
    """Checks and reads Catch's XML report (the test process's standard output).
    Returns (verdict, reason, details, check).

    verdict: "passed", "failed" (the test case ran and failed) or "missing"
    (no complete, well-formed report of exactly this run: the process died or
    exited before Catch finished, or wrote something else).
    reason: the first failure in a student's words (wording.py): the failed check's own
    message first, then its context; details: every failure so, and the test's output;
    check: the failed checks in the harness's words (file:line, expression, expansion), for
    the TAs' tools only (tools/mutants' margins), never shown to a student."""
    if data is None:
        return "missing", f"the test report is larger than {REPORT_CAP // (1024 * 1024)} MiB", "", ""
    if not data.strip():
        return "missing", "no test report was written", "", ""
    head = data[:4096]
    if b"<!DOCTYPE" in data or b"<!ENTITY" in data or not head.lstrip().startswith(b"<?xml") \
            or not re.match(rb'<\?xml version="1\.0" encoding="UTF-8"\?>', head.lstrip()):
        return "missing", "the test report is not the one the test framework writes", "", ""
    try:
        root = ET.fromstring(data)
    except Exception:  # any parser failure (truncated, bad encoding...) is no report
        return "missing", "the test report is incomplete", "", ""
    if root.tag != "Catch" or root.get("name") != nonce:
        return "missing", "the test report does not belong to this run", "", ""
    cases = [tc for tc in root.iter("TestCase") if tc.get("name") == name]
    others = [tc for tc in root.iter("TestCase") if tc.get("name") != name]
    if len(cases) != 1 or others:
        return ("missing", f"the report has {len(cases)} runs of this test case and "
                f"{len(others)} of others", "", "")
    tc = cases[0]
    overall = tc.find("OverallResult")
    totals = root.find("OverallResults")
    case_totals = root.find("OverallResultsCases")
    lines, checks, infos, first = [], [], [], ""
    inside = {id(x) for e in tc.iter("Expression") for x in e.iter("Exception")}

    def words(el):
        return wording.capture(_text(el))

    def failure(message):
        """The failed check's message, then its context (the messages in scope, outermost
        first): what failed comes first."""
        context = [i for i in infos if i != message]
        return wording.student("\n".join([message] + context), seed)
    for el in tc.iter():
        loc = f"{el.get('filename', '').replace(strip, '')}:{el.get('line', '')}"
        if el.tag in ("Info", "Message", "Warning"):
            infos.append(words(el))
        elif el.tag == "Expression" and el.get("success") == "false":
            orig = _text(el.find("Original")) if el.find("Original") is not None else ""
            expd = _text(el.find("Expanded")) if el.find("Expanded") is not None else ""
            exc = el.find("Exception")
            if exc is not None:  # thrown while the check was evaluated
                message = wording.exception(_text(exc))
            elif infos:
                message = infos[-1]  # the innermost message in scope: the check's own words
            else:
                message = f"a check failed: {orig}"
            checks.append(f"{message}\n{loc}: {el.get('type', 'CHECK')}( {orig} ) failed, with "
                          f"expansion: {expd}" + (f" ({_text(exc)})" if exc is not None else ""))
            text = failure(message)
            lines.append(text)
            first = first or text
            infos = []
        elif el.tag == "Exception":
            if id(el) in inside:
                continue  # thrown inside a check: reported with it above
            checks.append(f"{loc}: unexpected exception: {_text(el)}")
            text = failure(wording.exception(_text(el)))
            lines.append(text)
            first = first or text
            infos = []
        elif el.tag == "FatalErrorCondition":
            checks.append(f"{loc}: fatal error: {_text(el)}")
            lines.append(f"crashed: {_text(el)}")
            first = first or f"crashed: {_text(el)}"
        elif el.tag == "Failure":
            checks.append(f"{loc}: failed: {_text(el)}")
            text = failure(wording.exception(_text(el)) if "stopped answering" in _text(el)
                           else words(el))
            lines.append(text)
            first = first or text
            infos = []
        elif el.tag in ("StdOut", "StdErr"):
            t = _text(el)
            if len(t) > OUTPUT_CAP:
                t = t[:OUTPUT_CAP] + f"\n[... {len(t) - OUTPUT_CAP} more characters not shown]"
            lines.append(f"{'std::cout' if el.tag == 'StdOut' else 'std::cerr'} during the test:\n{t}")
    details = "\n\n".join(lines)
    check = "\n".join(checks)
    if overall is None or totals is None or case_totals is None:
        return "missing", "the test report is incomplete", details, check
    ok = (overall.get("success") == "true" and totals.get("failures") == "0"
          and totals.get("expectedFailures") == "0" and case_totals.get("failures") == "0"
          and case_totals.get("successes") == "1"
          and not any(e.get("success") == "false" for e in tc.iter("Expression")))
    if ok:
        return "passed", "", details, check
    return "failed", (first or "failed").strip(), details, check


class GraderError(Defect):
    """The trusted side failed (the test process crashed, ended outside the test framework, or
    wrote no complete report): a defect of the grader or of its tests, never the submission's
    fault. The run ends with status 1 and the lab is not scored (docs/grading.md, "Blame")."""


def judge(test, status, data, captured, nonce, timeout, strip, worker_status=None,
          worker_output="", seed=None, cpu=0.0):
    """The TestResult of one run: `status` from the launcher ("exit"/"signal"/"error", value)
    or from the grader's watch (worker.py: "timeout" after `timeout` s of CPU time, "idle",
    "wall"), `data` the report read from the test's standard output (None: too big),
    `captured` its (capped) other output, `nonce` this run's random name, `cpu` the s of CPU
    time the test's processes used. The worker's status and output only explain a failure;
    they never make a test pass. A verdict that a limit decided (a time limit, the idle rule,
    a crash of the worker, which may be its memory limit) is not `settled`: it is never
    reused without running the test again (build.py).

    Blame: no byte of student code runs in the test process, and every value it reads from
    the worker is checked before use, so a test process that crashes, ends in the middle of
    the test or writes no complete report is the grader's own defect: GraderError, never a
    failure of the submission. What the worker does (crash, exit, garbage, silence) fails
    the test, through the test's own report."""
    verdict, reason, details, check = read_report(data, test.name, nonce, strip, seed)
    kind, value = status
    if kind == "error":
        raise Defect(f"the sandbox could not start a test process: {value}")
    if kind == "exit" and worker_status and worker_status[0] == "error":
        raise Defect(f"the sandbox could not start a worker process: {worker_status[1]}")
    if kind == "timeout":
        reason = f"timed out: used its {timeout:g} s of CPU time (an infinite loop?)"
    elif kind == "idle":
        reason = (f"stopped: its processes were blocked for {value:g} s, neither computing nor "
                  "waiting for a core (sleeping or waiting in the lab's code?)")
    elif kind == "wall":
        seconds, share = value
        if share >= WALL_BUSY_SHARE:  # it was computing, or waiting for a core: the machine
            raise GraderError(
                f"'{test.name}' ({test.lab}) was still computing after {seconds:.0f} s of "
                f"wall-clock time ({cpu:.1f} s of CPU): the machine is too busy to grade it in "
                "time; the lab is not scored (grade it again)")
        reason = (f"stopped after {seconds:.0f} s of wall-clock time, blocked for "
                  f"{100 * (1 - share):.0f} % of it (sleeping or waiting in the lab's code?)")
    elif data is None:  # the report is over its cap: the tests print values the worker chose
        reason = (f"the test's report is larger than {REPORT_CAP // (1024 * 1024)} MiB: the lab's "
                  "code returned values too large to report (a huge matrix?)")
    else:
        crashed = kind == "signal" or b"<FatalErrorCondition" in data
        incomplete = verdict == "missing"
        disagree = (verdict == "passed") != (kind == "exit" and value == 0)
        if crashed or incomplete or disagree:
            how = (f"crashed ({signal_name(value)})" if kind == "signal" else
                   "crashed (" + reason.removeprefix("crashed: ") + ")" if crashed else
                   f"exited with status {value}: {reason}" if incomplete else
                   f"reported '{verdict}' but exited with status {value}")
            raise GraderError(
                f"the trusted test process of '{test.name}' ({test.lab}) {how}: a defect of the "
                "grader or its tests, not of the submission; the lab is not scored")
    passed = kind == "exit" and value == 0 and verdict == "passed"
    settled = kind == "exit" and not (worker_status and worker_status[0] == "signal")
    fn = wording.function_gone(check)
    gone = fn is not None
    if not passed and gone and worker_status:
        wkind, wvalue = worker_status
        who = f"your {fn}" if fn else "the lab's code"
        if wkind == "signal":
            try:
                bare = signal.Signals(wvalue).name
            except ValueError:
                bare = f"signal {wvalue}"
            what, worker_output = wording.crash(bare, worker_output)
            reason = f"{who} crashed: {what}"
        elif wkind == "exit":
            reason = (f"{who} ended its process with status {wvalue} in the middle of the test "
                      "(exit(), _Exit() or quick_exit() called in student code?)")
        details = ""  # the test's side of it (the call that found the process gone) says no more
    # A failed assertion's details start with the same message: no need to repeat it.
    repeats = verdict == "failed" and kind == "exit" and details and not gone
    parts = [] if passed or repeats else [reason]
    if details:
        parts.append(details)
    if captured.strip():
        parts.append("output of the test process:\n" + printable(captured.rstrip()))
    if worker_output.strip():
        parts.append("output of your code:\n" + printable(worker_output.rstrip()))
    return TestResult(test, test.points if passed else 0, "passed" if passed else "failed",
                      "" if passed else reason,
                      capped("\n\n".join(parts), TEST_OUTPUT_CAP), check, settled, cpu)
