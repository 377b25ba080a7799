"""A failed test's text as a student reads it (tools/grader/wording.py). Guards against the
harness's words and layout reaching the student: a matrix spread over lines by Eigen's
operator<<, numbers that differ printed alike, a capture's ":=", a library's file and line."""
from grader import wording


def test_an_eigen_matrix_inside_a_sentence_goes_on_one_line():
    """Defect (issue 46): the C5 held-out reason dumped raw Eigen matrices with a line break."""
    text = "contact of 0 with a plane, w = 0.5 2, v =    1 -0.5    7\n-2    1    7, e = 0.5"
    assert wording.one_line_matrices(text) == \
        "contact of 0 with a plane, w = 0.5 2, v = [1, -0.5, 7; -2, 1, 7], e = 0.5"
    assert wording.one_line_matrices("step 3\nexpected 1\ngot 2") == "step 3\nexpected 1\ngot 2"


def test_expected_and_got_show_the_digits_that_differ():
    """Defect (issue 46): "expected 1.0001 / got 1.0001" for values that differ in the 8th
    digit (E1 and E2 with h in a float lost 50 points and read nothing else)."""
    out = wording.digits("Q\n  expected 4.94760000001234\n  got      4.94760000003567")
    assert out.splitlines()[1:] == ["  expected 4.94760000001", "  got      4.94760000004"]
    same = "  expected (1, 2)\n  got      (1, 2.5)"
    assert wording.digits(same) == same


def test_a_long_value_shows_the_numbers_that_differ():
    """Defect (issue 46): expected and got cut with "..." in the table."""
    e = "(" + ", ".join(str(k) for k in range(80)) + ")"
    g = e.replace("(0, 1, 2,", "(0, 1, -2,")
    out = wording.differing(f"  expected {e}\n  got      {g}").splitlines()
    assert out == ["  expected #2 = 2 (the other 79 of 80 numbers agree)", "  got      #2 = -2"]


def test_captures_and_library_checks_read_in_plain_words():
    """Defect (issue 46): "k := 0; wbtest::str(x) := ..." and Eigen's file and line."""
    assert wording.capture("wbtest::str(x) := (1, 2)") == "x = (1, 2)"
    assert wording.capture("k := 0") == "k = 0"
    assert wording.capture('wbtest::str(x) := "(1.5, -0.25)"') == "x = (1.5, -0.25)"
    assert wording.probe_error("your f threw: Eigen: an index out of range, or sizes that do not "
                               "match (Eigen/src/Core/Block.h:120 checks startRow >= 0)") == \
        "Eigen matrices or vectors whose sizes do not match (startRow >= 0)"


def test_long_lines_of_numbers_take_no_time():
    """Defect: a pattern with two ways to match a string of digits takes exponential time on a
    line of many long numbers that does not end as the pattern wants (values from student
    code: a hostile submission could stall the grader's formatting)."""
    import time
    row = "v = " + " ".join(["12345678901234567"] * 60) + ", e = 0.5x"
    t0 = time.monotonic()
    wording.student(f"{row}\n{row}\n  expected {row}\n  got      {row}")
    assert time.monotonic() - t0 < 1.0
