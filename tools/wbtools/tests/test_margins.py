"""Margins (tools/wbtools/margins.py, run by tools/mutants): how widely a graded test catches a
mutant, read from the test's own failure message. Guards against a mutant caught by a hair
(within a factor 10 of a tolerance) counted as safely caught, and against a catch that
nothing measured (values printed alike, an outer helper's message) counted as weak or wide."""
import math
from wbtools.margins import best, describe, margin


def helper_text(expected, got, tol, rel=None):
    rel_part = f" + {rel} * |value|" if rel is not None else ""
    return (f"the law\nexpected {expected}\ngot      {got}\ntolerance {tol}{rel_part}\n"
            "tests/common/test_helpers.h:50: REQUIRE( near(got, expected, abs_tol, rel_tol) ) "
            "failed, with expansion: false")


def test_scalar_helper_message_gives_difference_over_tolerance():
    """Defect: a helper's miss read as something other than |got - expected| / tolerance, so a weak catch looks wide (or a wide one weak)."""
    assert math.isclose(margin(helper_text("1", "1.5", "0.01")), 50.0)


def test_relative_tolerance_is_scaled_by_the_larger_value():
    """Defect: a relative tolerance ignored or scaled by the wrong value, misjudging catches on large quantities."""
    # |2 - 2.2| / (0 + 0.01 * 2.2)
    assert math.isclose(margin(helper_text("2", "2.2", "0", "0.01")), 0.2 / 0.022)


def test_vectors_take_the_worst_component():
    """Defect: a vector's margin taken from its first or best component instead of its worst."""
    assert math.isclose(margin(helper_text("(1, 2, 3)", "(1, 2.5, 3.1)", "0.1")), 5.0)


def test_the_innermost_helper_message_counts_not_an_outer_one():
    """Defect: an outer INFO message's numbers measured instead of the failing check's own."""
    text = ("outer\nexpected 0\ngot 100\ntolerance 1\n" + helper_text("0", "3", "1"))
    assert math.isclose(margin(text), 3.0)


def test_values_printed_alike_are_unknown_not_weak():
    """Defect: numbers printed too short to differ counted as a weak catch (margin 0) instead of unknown."""
    assert margin(helper_text("0.333333", "0.333333", "1e-12")) is None


def test_a_non_finite_value_is_categorical():
    """Defect: a NaN or inf result measured as a finite (maybe weak) margin."""
    assert margin(helper_text("1", "nan", "1e-12")) == math.inf


def test_zero_tolerance_with_a_difference_is_categorical():
    """Defect: an exact check (tolerance 0) divided by zero or reported weak."""
    assert margin(helper_text("1", "2", "0", "0")) == math.inf


def test_a_comparison_of_two_numbers_in_the_expansion():
    """Defect: an 'a <= b' expansion not measured, so a bound missed by a hair passes as a wide catch."""
    text = "x.cpp:3: REQUIRE( err <= tol ) failed, with expansion: 0.5 <= 0.000000000001"
    assert math.isclose(margin(text), 5e11)
    text = "x.cpp:3: REQUIRE( u_max > 0.1 ) failed, with expansion: 0.05 > 0.1"
    assert math.isclose(margin(text), 2.0)


def test_a_zero_where_a_bound_was_required_is_categorical():
    """Defect: a zero compared against a bound divided by zero instead of counted categorical."""
    text = "x.cpp:3: REQUIRE( d > 1e-3 ) failed, with expansion: 0.0 > 0.001"
    assert margin(text) == math.inf


def test_flags_exceptions_and_crashes_are_categorical():
    """Defect: an exception, a crash or a false flag given a finite margin (a weak catch that cannot be moved by a tolerance)."""
    assert margin("x.cpp:9: REQUIRE( r.solver_failed ) failed, with expansion: false") == math.inf
    assert margin("x.cpp:9: REQUIRE( n == 3 ) failed, with expansion: 2 == 3") == math.inf
    assert margin("x.cpp:9: unexpected exception: not implemented") == math.inf
    assert margin("crashed (SIGSEGV)") == math.inf


def test_a_mutant_takes_its_widest_catch_and_ignores_unknown_ones():
    """Defect: a mutant's margin taken from its narrowest catch, or an unknown one, so a widely caught mutant is flagged weak."""
    outs = [helper_text("1", "1.05", "0.01"), helper_text("0.5", "0.5", "1e-12")]
    assert math.isclose(best(outs), 5.0)
    assert best([helper_text("0.5", "0.5", "1e-12")]) is None
    assert describe(None) == "?" and describe(math.inf) == "inf" and describe(12.345) == "12.3"
