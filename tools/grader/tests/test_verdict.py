"""The verdict (tools/grader/verdict.py): what decides a test's points from how its process
ended and the test framework's XML report. Every byte of the report is hostile: these tests
guard against a forged, foreign, partial or padded report passing, and against a failure
whose reason says nothing a student can act on."""
import signal

import pytest

from grader import common
from grader.common import Defect
from grader.verdict import GraderError, judge, read_report

NONCE = "wb-0123456789abcdef"
NAME = "E1 one step: positions move with the old velocities"
TEST = common.TestCase("euler", NAME, 10, ["[E1]", "[10pts]"])
SRC = "/scratch/src/"


def report(body="", ok=True, name=NAME, nonce=NONCE, cases=1, extra=""):
    """A report in the shape Catch 2.13's XML reporter writes (catch.hpp, XmlReporter)."""
    f = "0" if ok else "1"
    tc = "".join(f'<TestCase name="{name}" tags="[E1][10pts]" filename="{SRC}tests/euler/t.cpp" '
                 f'line="12">{body}<OverallResult success="{str(ok).lower()}"/></TestCase>'
                 for _ in range(cases))
    totals = (f'<OverallResults successes="3" failures="{f}" expectedFailures="0"/>'
              f'<OverallResultsCases successes="{1 if ok else 0}" failures="{f}" '
              'expectedFailures="0"/>')
    return (f'<?xml version="1.0" encoding="UTF-8"?>\n<Catch name="{nonce}">'
            f'<Group name="{nonce}">{tc}{extra}{totals}</Group>{totals}</Catch>\n').encode()


FAILED_EXPR = (f'<Info>explicit Euler velocity (particle 0)</Info>'
               f'<Expression success="false" type="REQUIRE" filename="{SRC}tests/common/h.h" '
               'line="40"><Original>near(got, expected)</Original>'
               '<Expanded>false</Expanded></Expression>')


def test_a_complete_passing_report_passes():
    """Defect: an honest pass scored 0 (the parser stricter than Catch's own output)."""
    assert read_report(report(), NAME, NONCE, SRC)[0] == "passed"
    r = judge(TEST, ("exit", 0), report(), "", NONCE, 60, SRC)
    assert (r.status, r.score) == ("passed", 10)


def test_a_failed_assertion_gives_its_message_and_place_without_the_scratch_path():
    """Defect: a failure whose reason is not the assertion's own words (the student cannot act
    on it), or one that leaks the grader's scratch folder."""
    verdict, reason, details, check = read_report(report(FAILED_EXPR, ok=False), NAME, NONCE, SRC)
    assert verdict == "failed" and reason == "explicit Euler velocity (particle 0)"
    assert "tests/common/h.h:40: REQUIRE( near(got, expected) ) failed" in check
    assert SRC not in details and SRC not in check


@pytest.mark.parametrize("data,why", [
    (None, "larger than"),
    (b"", "no test report"),
    (report(nonce="wb-guessed"), "does not belong to this run"),
    (report(cases=2), "runs of this test case"),
    (report(extra='<TestCase name="other"><OverallResult success="true"/></TestCase>'),
     "of others"),
    (report()[:-40], "incomplete"),
    (b'<?xml version="1.0" encoding="UTF-8"?>\n<!DOCTYPE x [<!ENTITY a "b">]><Catch/>',
     "not the one"),
    (b"all tests passed\n" + report(), "not the one"),
])
def test_a_report_that_is_not_exactly_this_runs_is_missing(data, why):
    """Defect: a forged report (printed by student code, guessed nonce, another test's, a
    truncated or entity-laden one) is taken as the framework's verdict."""
    verdict, reason, _, _ = read_report(data, NAME, NONCE, SRC)
    assert verdict == "missing" and why in reason


def test_a_passing_report_with_a_failed_expression_fails():
    """Defect: totals written by student code say success while an assertion failed."""
    assert read_report(report(FAILED_EXPR, ok=True), NAME, NONCE, SRC)[0] == "failed"


def test_a_pass_needs_exit_status_zero():
    """Defect: a complete passing report from a process that then exited non-zero (or was
    killed) scores points. No byte of student code runs in the test process, so that is the
    grader's own defect (docs/grading.md, "Blame"): GraderError, the lab not scored."""
    with pytest.raises(GraderError) as e:
        judge(TEST, ("exit", 3), report(), "", NONCE, 60, SRC)
    assert "exited with status 3" in str(e.value) and "not of the submission" in str(e.value)
    with pytest.raises(GraderError) as e:
        judge(TEST, ("signal", signal.SIGKILL), report(), "", NONCE, 60, SRC)
    assert "SIGKILL" in str(e.value)


@pytest.mark.parametrize("status,words", [
    (("timeout", 60), "used its 60 s of CPU time"),
    (("idle", 10), "blocked for 10 s"),
    (("wall", (900, 0.01)), "stopped after 900 s of wall-clock time, blocked for 99 %"),
])
def test_how_the_process_ended_is_the_reason(status, words):
    """Defect: a time-out or a sleeping test reported as a bare 'failed', which tells the
    student nothing to act on."""
    r = judge(TEST, status, b"", "", NONCE, 60, SRC)
    assert r.score == 0 and words in r.reason


@pytest.mark.parametrize("status", [("timeout", 60), ("idle", 5), ("wall", (900, 0.01))])
def test_a_verdict_a_limit_decided_is_never_settled(status):
    """Defect: a verdict that a time limit decided was kept and reused by the next grade of
    the same files (build.py looked for "stopped after" while the reason said "stopped: its
    processes..."), so a slow machine's verdict stuck."""
    assert not judge(TEST, status, b"", "", NONCE, 60, SRC).settled
    body = "<Failure>the lab's code stopped answering</Failure>"
    assert not judge(TEST, ("exit", 1), report(body, ok=False), "", NONCE, 60, SRC,
                     worker_status=("signal", 24)).settled
    assert judge(TEST, ("exit", 0), report(), "", NONCE, 60, SRC).settled


def test_a_test_still_computing_on_a_busy_machine_is_not_failed():
    """Defect: a test that kept computing (or waiting for a core) past the wall-clock safety
    net failed, a verdict of the machine's load: the lab is not scored instead."""
    with pytest.raises(GraderError) as e:
        judge(TEST, ("wall", (900, 0.97)), b"", "", NONCE, 60, SRC, cpu=40.0)
    assert "too busy" in str(e.value) and "not scored" in str(e.value)


def test_a_crash_of_the_trusted_side_is_the_graders_defect():
    """Defect: a crash of the trusted test process (issue 29, "Blame") reported as the
    student's fault ("exit() called in student code?")."""
    with pytest.raises(GraderError) as e:
        judge(TEST, ("signal", signal.SIGSEGV), b"", "", NONCE, 60, SRC)
    assert "crashed (SIGSEGV" in str(e.value) and "the lab is not scored" in str(e.value)


def test_leaving_in_the_middle_of_the_test_is_the_graders_defect():
    """Defect: a report cut inside the test case read as a pass or blamed on the submission:
    student code runs in the worker, never in the test process, so only the grader can cut
    it."""
    cut = report().split(b"<OverallResult")[0]
    with pytest.raises(GraderError) as e:
        judge(TEST, ("exit", 0), cut, "", NONCE, 60, SRC)
    assert "incomplete" in str(e.value)


def test_the_workers_end_explains_but_never_passes():
    """Defect: the worker's status (student code's process) decides a pass, or its crash is
    reported as the test's own."""
    body = "<Failure>the lab's code stopped answering</Failure>"
    r = judge(TEST, ("exit", 1), report(body, ok=False), "", NONCE, 60, SRC,
              worker_status=("signal", signal.SIGSEGV))
    assert r.score == 0 and r.reason.startswith("the lab's code crashed: an invalid memory")
    r = judge(TEST, ("exit", 0), report(), "", NONCE, 60, SRC, worker_status=("signal", 11))
    assert r.score == 10


def test_a_sandbox_that_cannot_start_is_the_graders_defect():
    """Defect: the grader's own failure to start a process scored as the student's 0."""
    with pytest.raises(Defect):
        judge(TEST, ("error", "no seccomp"), b"", "", NONCE, 60, SRC)


def test_output_is_capped_and_printable():
    """Defect: a test that floods stdout or prints terminal escapes makes an unbounded or
    forged result (fake lines in the table)."""
    r = judge(TEST, ("exit", 1), report(FAILED_EXPR, ok=False), "\x1b[2J" + "x" * 100000, NONCE,
              60, SRC)
    assert "\x1b" not in r.output and len(r.output) < 20000


# ------------------------------------------------ what a student reads (issue 46)

def info(text):
    return f"<Info>{text}</Info>"


def expression(orig="near(got, expected, abs_tol, rel_tol)", expanded="false", line=43,
               inner=""):
    return (f'<Expression success="false" type="REQUIRE" filename="{SRC}tests/common/'
            f'test_helpers.h" line="{line}"><Original>{orig}</Original><Expanded>{expanded}'
            f'</Expanded>{inner}</Expression>')


HELPER = ("explicit Euler position (particle 0)\n  expected (1, 2)\n  got      (1, 1.9)\n"
          "  tolerance 1e-12 + 0 * |value|")
HARNESS = ("test_helpers.h", "REQUIRE", "with expansion", "Unknown expression", "pipe",
           "Assertion", "stl_algo", ":= ")


def test_the_failed_check_comes_first_then_its_context():
    """Defect (issue 46): a reason that opens with its context (the R7 pendulum's "crossed 4
    times in 8 s" before the period that failed; every held-out reason with its seed): the
    first line a student reads must be the check that failed."""
    body = (info("held-out inputs of E1 from seed 0x5 (replay: tools/grade ... --seed 0x5, or "
                 "WB_HELDOUT_SEED=0x5 when running the tests)") + info("step 3, t = 0.03") +
            info(HELPER) + expression())
    r = judge(TEST, ("exit", 1), report(body, ok=False), "", NONCE, 60, SRC, seed=5)
    assert r.reason.splitlines()[0] == "explicit Euler position (particle 0)"
    assert r.reason.splitlines()[-2:] == [
        "held-out inputs of E1 (the grade's seed, above)", "step 3, t = 0.03"]
    assert "0x5" not in r.reason and "0x5" not in r.output


def test_no_harness_words_reach_the_student():
    """Defect (issue 46): every failing test carried "tests/common/test_helpers.h:43: REQUIRE(
    near(...) ) failed, with expansion: false", and captures read "wbtest::str(x) := (1, 2)"."""
    body = (info("k := 0") + info("wbtest::str(x) := (1, 2)") + info(HELPER) + expression())
    r = judge(TEST, ("exit", 1), report(body, ok=False), "", NONCE, 60, SRC)
    student = r.reason + "\n" + r.output
    assert not [w for w in HARNESS if w in student], student
    assert "k = 0" in student and "x = (1, 2)" in student
    assert "test_helpers.h:43: REQUIRE( near(got, expected, abs_tol, rel_tol) )" in r.check


CLAMP = ("/usr/include/c++/12/bits/stl_algo.h:3625: constexpr const _Tp& std::clamp(const _Tp&, "
         "const _Tp&, const _Tp&) [with _Tp = double]: Assertion '!(__hi < __lo)' failed.")
GONE = ("the lab's code stopped answering during solve_contact (the other side closed the pipe): "
        "its process crashed, called exit() or hit a limit")


def test_a_crash_says_in_one_line_what_the_code_did():
    """Defect (issue 46): a C5 crash printed "CHECK( {Unknown expression after the reported
    line} )", "the other side closed the pipe" and libstdc++'s std::clamp assertion."""
    body = expression("{Unknown expression after the reported line}", "{Unknown expression "
                      "after the reported line}", inner=f"<Exception>{GONE}</Exception>")
    r = judge(TEST, ("exit", 1), report(body, ok=False), "", NONCE, 60, SRC,
              worker_status=("signal", signal.SIGABRT), worker_output=CLAMP + "\nmy print\n")
    assert r.reason == ("your solve_contact crashed: called std::clamp with hi < lo "
                        "(clamp(v, lo, hi) needs lo <= hi)")
    student = r.reason + "\n" + r.output
    assert not [w for w in HARNESS if w in student], student
    assert "my print" in r.output  # what the student's code printed stays
    r = judge(TEST, ("exit", 1), report(f"<Failure>{GONE}</Failure>", ok=False), "", NONCE, 60,
              SRC, worker_status=("signal", signal.SIGSEGV))
    assert r.reason.startswith("your solve_contact crashed: an invalid memory access")


def test_an_eigen_check_reads_as_what_the_code_did():
    """Defect (issue 46): an index out of range reported as Eigen's file, line and check."""
    text = ("your prepare_contact threw: Eigen: an index out of range, or sizes that do not match "
            "(Eigen/src/Core/DenseCoeffsBase.h:408 checks index &gt;= 0 &amp;&amp; index &lt; "
            "size())")
    body = expression(inner=f"<Exception>{text}</Exception>")
    r = judge(TEST, ("exit", 1), report(body, ok=False), "", NONCE, 60, SRC)
    assert r.reason == ("your prepare_contact threw an exception: an index out of range of an "
                        "Eigen vector or matrix (index >= 0 && index < size())")
    assert "DenseCoeffsBase" not in r.reason + r.output


def test_a_thrown_message_cannot_pass_for_a_crash():
    """Defect: the words of the lab's own exception ("the lab's code stopped answering during
    ...") taken for the grader's, so that a student's message decides what the reason says."""
    text = f"your solve_contact threw: {GONE}"
    body = expression(inner=f"<Exception>{text}</Exception>")
    r = judge(TEST, ("exit", 1), report(body, ok=False), "", NONCE, 60, SRC,
              worker_status=("exit", 0))
    assert r.reason.startswith("your solve_contact threw an exception: ")
