"""The claims parser (tools/wbplot/claims.py, run by tools/claims and tools/report): a
number or direction a handout states about a run is checked against that run. Guards
against a malformed claim read as a different one (then it checks something else than the
sentence says), a claim that cannot fail, and a sentence that drifts from its checked
number."""
import math

import pytest

from wbplot import claims
from wbplot.common import InputError


def one(text):
    found = claims.find_claims("h.md", text)
    assert len(found) == 1
    return found[0]


@pytest.mark.parametrize("body,op,fields", [
    ("order euler/oscillator explicit-euler in [0.9, 1.1]", "in", {"lo": 0.9, "hi": 1.1}),
    ("stats euler/oscillator@explicit-euler energy ratio = 23 ± 1", "=",
     {"value": 23.0, "tol": 1.0, "stated": "23"}),
    ("stats e/x energy ratio = 23 +- 1", "=", {"value": 23.0, "tol": 1.0}),
    ("summary euler/stiff-spring@explicit-euler status = diverged", "=", {"word": "diverged"}),
    ("trace euler/x y min > 0.04", ">", {"value": 0.04}),
    ("stats e/x energy drift <= 1e-3", "<=", {"value": 1e-3}),
])
def test_each_form_parses_to_its_operator_and_values(body, op, fields):
    """Defect: a claim's right-hand side read as another form (a tolerance taken as the value,
    a word as a number), so the check tests something the sentence does not say."""
    c = one(f"It holds <!-- claim: {body} -->")
    assert c.op == op and all(getattr(c, k) == v for k, v in fields.items())


@pytest.mark.parametrize("body", ["stats e/x energy", "stats e/x energy ratio = 23",
                                  "trace e/x y min in [1 2]", "stats e/x energy ratio < big"])
def test_a_malformed_claim_is_an_error_naming_its_place(body):
    """Defect: a malformed claim skipped silently (it then checks nothing) or reported without
    its file and line."""
    with pytest.raises(InputError) as e:
        claims.find_claims("h.md", f"line 1\nline 2 <!-- claim: {body} -->")
    assert str(e.value).startswith("h.md:2: claim")


def test_judge_fails_a_non_finite_or_out_of_range_measure():
    """Defect: a diverged run's measure (inf, NaN) read as holding: 'grows more than 10
    times' holds for inf, which says the run blew up, not that it grew as stated."""
    c = one("x <!-- claim: stats e/x energy ratio < 2 -->")
    assert c.judge(1.5) == "" and c.judge(2.5) and c.judge(math.nan) and c.judge(None)
    g = one("x <!-- claim: stats e/x energy ratio > 10 -->")
    assert g.judge(23.0) == "" and g.judge(math.inf) and g.judge(-math.inf)
    w = one("x <!-- claim: summary e/x status = ok -->")
    assert w.judge("ok") == "" and w.judge("diverged")


def test_the_prose_must_state_the_checked_number():
    """Defect: the sentence says 23 while the claim checks 25 (a sentence that contradicts
    its own figure), or 'says' text missing from the sentence goes unnoticed."""
    assert one("grows 23 times <!-- claim: stats e/x energy ratio = 23 ± 1 -->"
               ).prose_problem() == ""
    assert "'25'" in one("grows 23 times <!-- claim: stats e/x energy ratio = 25 ± 3 -->"
                         ).prose_problem()
    assert one('lands above <!-- claim: offset e/x y min > 0 says "above" -->').prose_problem() == ""
    assert one('lands below <!-- claim: offset e/x y min > 0 says "above" -->').prose_problem()


def test_only_the_same_paragraph_counts_as_prose():
    """Defect: a number stated in an earlier paragraph satisfies a claim about this one."""
    text = "It grows 23 times.\n\nAnother paragraph <!-- claim: stats e/x energy ratio = 23 ± 1 -->"
    assert one(text).prose_problem()


def test_claims_in_a_scene_description(tmp_path):
    """Defect: claims in a scene's description (shown in --help and the report) never
    checked."""
    p = tmp_path / "s.json"
    p.write_text('{"description": "explodes <!-- claim: summary e/s status = diverged -->"}')
    (c,) = claims.find_claims(str(p))
    assert c.where == f"{p} (description)" and c.word == "diverged"


def test_strip_markers_leaves_what_a_reader_sees():
    """Defect: a claim marker shown in a caption or a student's handout."""
    assert claims.strip_markers("It grows. <!-- claim: a b\n = c --> Next.") == "It grows. Next."


def test_wall_clock_time_cannot_be_claimed():
    """Defect: a claim on wall time (which the machine's load moves) flips on a busy CI."""
    c = one("x <!-- claim: summary e/x wall_s < 1 -->")
    with pytest.raises(InputError) as e:
        claims.measure(c, claims.Data("/nonexistent", "/nonexistent"))
    assert "wall time" in str(e.value)


@pytest.mark.parametrize("how,want", [("first", 1.0), ("last", 4.0), ("min", 1.0), ("max", 4.0),
                                      ("spread", 3.0), ("ratio", 4.0), ("drift", 3.0),
                                      ("maxrise", 2.5), ("median", 1.75)])
def test_reducers(how, want):
    """Defect: a reducer that measures something else than its name (the claim then checks a
    different number than the sentence states)."""
    assert claims._reduce([1.0, 2.0, 1.5, 4.0], how) == pytest.approx(want)


def test_reducers_on_a_run_that_ended_non_finite():
    """Defect: 'last' of a diverged run reads the last finite value and calls it the end."""
    assert not math.isfinite(claims._reduce([1.0, 2.0, math.inf], "last"))
    assert claims._reduce([1.0, 2.0, math.inf], "last-finite") == 2.0
    with pytest.raises(InputError):
        claims._reduce([1.0], "mean")
