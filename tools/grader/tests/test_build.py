"""The graded test list's rules (tools/grader/build.py, check_list): the points a lab can
give come from the pristine test binary, checked before any grading. Guards against a lab
whose points do not add up to 100, a test hidden or allowed to fail, and names that Catch or
CTest would read as several tests."""
import pytest

from grader import build, common
from grader.common import Defect


def case(name, tags, points):
    return common.TestCase("forces", name, points, tags)


GOOD = [case("F5 spring: -k (L - rest)", ["[forces]", "[F5]", "[60pts]"], 60),
        case("F5 damper along the spring", ["[forces]", "[F5]", "[25pts]"], 25),
        case("F5 held-out: random springs", ["[forces]", "[F5]", "[held-out]", "[15pts]"], 15)]


def test_a_good_list_passes():
    """Defect: the rules refuse an honest test list (every submission gets an internal error)."""
    build.check_list("forces", GOOD)


@pytest.mark.parametrize("tests,words", [
    ([GOOD[0], GOOD[2]], "add up to 75, expected 100"),
    (GOOD[:2] + [case("F5 more", ["[forces]", "[F5]", "[15pts]"], 15)], "F5 has no test tagged"),
    (GOOD[:2] + [case("x", ["[forces]", "[held-out]", "[15pts]"], 15)], "exactly one task tag"),
    ([GOOD[0], case("F5 x", ["[F5]", "[40pts]", "[1pts]"], 40)], "2 points tags"),
    ([GOOD[0], case("F5 x", ["[F5]"], 40)], "0 points tags"),
    ([GOOD[0], case("F5 x", ["[F5]", "[40pts]"], 30)], "30 points, but tagged [40pts]"),
    ([GOOD[0], case("F5 x", ["[F5]", "[40pts]", "[!mayfail]"], 40)], "cannot be hidden"),
    ([GOOD[0], case("F5 a; b", ["[F5]", "[40pts]"], 40)], "the name contains ;"),
    ([GOOD[0], case("f5 SPRING: -K (L - REST)", ["[F5]", "[40pts]"], 40)], "up to case"),
    ([GOOD[0], case(" F5 x", ["[F5]", "[40pts]"], 40)], "starts or ends with a space"),
    ([], "no test cases"),
])
def test_a_list_that_is_not_gradable_is_the_labs_defect(tests, words):
    """Defect: a lab whose points do not add up to 100, a test that may fail or is hidden, or
    a name Catch or CTest reads as several tests (a ';' splits a CTest name) is graded
    anyway, with scores out of something else than 100."""
    with pytest.raises(Defect) as e:
        build.check_list("forces", tests)
    assert words in str(e.value)
