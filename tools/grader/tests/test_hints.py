"""The hint matching (tools/wbgrade_hints.py, called by tools/grader/hints.py): names the known
mistake closest to a submission's failures. Guards against a hint that names a mistake the
student did not make, against run-to-run noise (numbers) making a signature unmatched, and
against a hint when there is no pattern to match (nothing or everything failed)."""
import json

import pytest

import wbgrade_hints as hints

TESTS = [f"t{k}" for k in range(8)]


def sigs(**mutants):
    return {"version": hints.SIGNATURES_VERSION, "lab": "euler", "tests": TESTS,
            "mutants": {name: {"hint": f"hint of {name}", "kind": "k", "task": "",
                               "failed": failed} for name, failed in mutants.items()}}


CATALOGUE = sigs(sign={"t0": "expected # got #", "t1": "energy grows"},
                 mass={"t2": "expected # got #", "t3": "a"},
                 half={"t0": "expected # got #", "t4": "b"})


def test_failure_text_blanks_numbers_and_keeps_the_first_paragraph():
    """Defect: a signature that keeps the values a wrong program prints (they differ from run
    to run, so the stored signature goes stale at random) or the captured output after the
    reason."""
    a = hints.failure_text("step 3: expected 1.25e-3 got -7\n\noutput of the test process:\nx 42")
    assert a == "step #: expected # got #"
    assert hints.failure_text("  a   b\n c ") == "a b c"
    assert len(hints.failure_text("x" * 1000)) == hints.CLASS_CHARS


def test_the_exact_signature_names_its_mistake():
    """Defect: a submission that fails exactly like a known mistake gets no hint, or another's."""
    failed = {"t0": "expected 3 got 4", "t1": "energy grows"}
    assert [m[1] for m in hints.matches(failed, TESTS, CATALOGUE)] == ["sign"]
    assert hints.hints_for("euler", failed, TESTS, CATALOGUE) == [
        "These failures match a known mistake: hint of sign"]


def test_nothing_is_said_without_a_pattern():
    """Defect: a hint for a skeleton or a build error (every test failed), for a clean pass, or
    for failures far from every known mistake."""
    assert hints.matches({}, TESTS, CATALOGUE) == []
    assert hints.matches({t: "x" for t in TESTS}, TESTS, CATALOGUE) == []
    assert hints.matches({"t5": "x", "t6": "y", "t7": "z"}, TESTS, CATALOGUE) == []


def test_another_labs_signatures_give_no_hint():
    """Defect: the catalogue of one lab used for another's failures."""
    assert hints.hints_for("forces", {"t0": "expected # got #", "t1": "energy grows"}, TESTS,
                           CATALOGUE) == []


def test_ties_are_named_together_up_to_max_hints():
    """Defect: one of two equally close mistakes named as if certain."""
    cat = sigs(a={"t0": "x", "t1": "y"}, b={"t0": "x", "t1": "y"})
    cat["mutants"]["b"]["hint"] = "another hint"
    lines = hints.hints_for("euler", {"t0": "x", "t1": "y"}, TESTS, cat)
    assert lines[0].startswith("These failures match known mistakes") and len(lines) == 3


def test_the_failure_text_tells_apart_mistakes_failing_the_same_tests():
    """Defect: two mistakes that fail the same tests at different assertions cannot be told
    apart (the assertion half of the score ignored)."""
    cat = sigs(a={"t0": "velocity wrong", "t1": "y"}, b={"t0": "position wrong", "t1": "y"})
    scores = {name: s for s, name, _ in hints.scores({"t0": "velocity wrong", "t1": "y"},
                                                     TESTS, cat)}
    assert scores["a"] == pytest.approx(1.0) and scores["b"] < scores["a"]


def test_a_bad_catalogue_gives_no_hints_never_an_error(tmp_path):
    """Defect: a missing, corrupt or old-version signatures file breaks grading."""
    (tmp_path / "tests" / "mutants" / "euler").mkdir(parents=True)
    path = tmp_path / "tests" / "mutants" / "euler" / "signatures.json"
    assert hints.load_signatures(str(tmp_path), "euler") is None
    path.write_text("{not json")
    assert hints.load_signatures(str(tmp_path), "euler") is None
    path.write_text(json.dumps(dict(CATALOGUE, version=0)))
    assert hints.load_signatures(str(tmp_path), "euler") is None
    path.write_text(json.dumps(CATALOGUE))
    assert hints.load_signatures(str(tmp_path), "euler") == CATALOGUE


def test_the_graders_hook_reads_the_verdicts_rows(monkeypatch):
    """Defect: the grader's hook (grader/hints.py) passes passed tests as failed, or its rows
    in another shape than hints_for_results reads."""
    from grader import hints as hook
    rows = [("t0", False, "expected 1 got 2"), ("t1", True, ""), ("t2", True, "")]
    assert hook.hints_for("no-such-lab", rows) == []
    failed = {}
    monkeypatch.setattr(hints, "hints_for", lambda lab, f, all_tests, s: failed.update(f) or [])
    hints.hints_for_results("/nonexistent", "euler", rows)
    assert failed == {"t0": "expected 1 got 2"}
