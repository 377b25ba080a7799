"""The time budgets (tools/grader/build.py, time_left): each lab's tests together get
LAB_BUDGET seconds of CPU time and all the submission's tests SUBMISSION_BUDGET. Guards against
a slow submission holding the grader past Gradescope's limit, against a test cut short by a
budget that is not used up, and against budgets that a busy machine uses up (they count the
CPU time the tests used, never the wall clock)."""
from grader.build import time_left


def test_the_least_of_both_budgets_is_left():
    """Defect: a test given the lab's whole budget when the submission's ends sooner (or the
    other way round)."""
    assert time_left(600, 100, 1800, 1700.0) == (100.0, "")  # the submission's ends first
    assert time_left(600, 550, 1800, 900.0) == (50, "")       # the lab's ends first


def test_a_used_up_lab_budget_names_the_lab():
    """Defect: a test not run without saying which budget ran out (the student cannot tell a
    slow lab from a slow submission)."""
    left, why = time_left(600, 600, 1800, 900.0)
    assert left <= 0 and why.startswith("not run: the lab's CPU time budget (600 s for a lab, "
                                        "1800 s for a submission)")


def test_a_used_up_submission_budget_names_the_submission():
    """Defect: the submission's budget is used up and more tests still start."""
    left, why = time_left(600, 10, 1800, 1800.5)
    assert left < 0 and "the submission's CPU time budget" in why


def test_budgets_are_exact_at_the_boundary():
    """Defect: an off-by-one at the boundary: exactly nothing left must not start a test with a
    time limit of 0 s (which reads as a time-out of the student's code)."""
    assert time_left(600, 600.0, 1800, 600.0)[1]
    assert time_left(600, 0.0, 1800, 1800.0)[1]
    assert not time_left(600, 599.9, 1800, 1799.9)[1]
