"""tools/mutants (tools/wbtools/mutants.py): applies each known-wrong patch to the solution,
judges the graded run, and compares the failure signatures with the stored ones. Guards
against a patch applied somewhere else than it says (then the mutant is not the mistake its
hint names), a malformed patch read as a smaller one, and a stored signature that keeps
what changes from run to run."""
import os

import pytest

from wbtools import mutants

SOLUTION = "a\nb\nc\nd\ne\nf\n"
PATCH = """# hint: the velocity uses the new position (handout E1)
# kind: order
# caught-by: E1 one step, [E1]
--- solutions/euler/explicit_euler.cpp
+++ solutions/euler/explicit_euler.cpp
@@ -2,3 +2,3 @@
 b
-c
+C
 d
"""


def test_a_patch_parses_into_its_header_and_hunks():
    """Defect: a header line ('# caught-by:') lost, or a hunk cut short."""
    comments, files = mutants.parse_patch(PATCH)
    assert mutants.header_value(comments, "hint").startswith("the velocity uses")
    assert mutants.caught_by(comments) == ["E1 one step", "[E1]"]
    (old, hunks), = files
    assert old == "solutions/euler/explicit_euler.cpp" and hunks[0][0] == 2


def test_hunks_apply_exactly_even_when_moved():
    """Defect: a patch applied with fuzz (to other lines than it names), or refused after a
    harmless change above it in the solution."""
    _, [(_, hunks)] = mutants.parse_patch(PATCH)
    assert mutants.apply_hunks(SOLUTION, hunks, "s") == "a\nb\nC\nd\ne\nf\n"
    assert mutants.apply_hunks("new\n" + SOLUTION, hunks, "s") == "new\na\nb\nC\nd\ne\nf\n"
    with pytest.raises(mutants.PatchError):
        mutants.apply_hunks(SOLUTION.replace("c", "x"), hunks, "s")


@pytest.mark.parametrize("text", [
    "# hint: x\nno diff here\n",
    "--- a\n+++ a\n@@ -1,2 +1,2 @@\n a\n",
    "--- a\n@@ -1 +1 @@\n-a\n+b\n",
    "--- a\n+++ a\n@@ bad @@\n",
    "--- a\n+++ a\n@@ -1 +1 @@\n?a\n",
])
def test_a_malformed_patch_is_an_error(text):
    """Defect: a truncated or malformed patch read as a smaller mutant (a mistake other than
    the one its hint names)."""
    with pytest.raises(mutants.PatchError):
        mutants.parse_patch(text)


def test_caught_by_matches_a_name_prefix_or_a_tag():
    """Defect: '# caught-by: [E1]' matching a test not tagged [E1], or a name prefix matching
    any test."""
    assert mutants.matches("[E1]", "x", ["[e1]", "[10pts]"])
    assert not mutants.matches("[E1]", "E1 x", ["[E2]"])
    assert mutants.matches("E1 one", "E1 one step", []) and not mutants.matches("E1 two", "E1 one", [])


def graded(failed_texts, score=50):
    results = [(name, ["[E1]"], False, text) for name, text in failed_texts.items()]
    results.append(("E1 other", ["[E1]"], True, ""))
    return ("", score, 100, results)


def test_a_signature_keeps_only_what_is_stable_across_runs():
    """Defect: a stored signature keeps the numbers a wrong program prints or the output after
    the failure reason, so the check reports it stale at random (one run in three, before)."""
    rows = []
    for got in ("1.25", "7.5e+300"):
        row = mutants.Row("euler", "explicit_euler.sign.patch", "< 100")
        mutants.judge(row, graded({"E1 one step": f"expected 1 got {got}\n\nstdout: {got}"}),
                      "< 100", mutants.parse_patch(PATCH)[0])
        rows.append(row)
    assert rows[0].verdict.startswith("caught") and rows[0].signature == rows[1].signature
    assert rows[0].signature == {"E1 one step": "expected # got #"}
    repo = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(
        os.path.abspath(__file__)))))
    docs = [mutants.signature_doc(repo, "euler", ["E1 one step", "E1 other"], [r], {}, {}, "d")
            for r in rows]
    assert docs[0] == docs[1]


def test_a_mutant_that_scores_full_marks_survives():
    """Defect: a mutant that the tests do not catch counted as caught."""
    row = mutants.Row("euler", "m.patch", "< 100")
    mutants.judge(row, ("", 100, 100, [("E1 one step", ["[E1]"], True, "")]), "< 100",
                  mutants.parse_patch(PATCH)[0])
    assert row.verdict == "SURVIVED" and not row.ok


def test_caught_by_the_wrong_tests_is_reported():
    """Defect: a mutant caught only by tests other than those its header names passes, so the
    test meant to catch that mistake may have stopped catching it."""
    row = mutants.Row("euler", "m.patch", "< 100")
    results = [("E1 one step", [], True, ""), ("E1 other", [], False, "x")]
    mutants.judge(row, ("", 50, 100, results), "< 100", ["hint: h", "caught-by: E1 one"])
    assert row.verdict == "caught, but not by E1 one" and not row.ok


def test_check_signatures_names_what_changed(tmp_path, monkeypatch):
    """Defect: a stale signatures file reported without saying which mutant changed."""
    monkeypatch.setattr(mutants.hints, "catalogue_path",
                        lambda repo, lab: str(tmp_path / "signatures.json"))
    doc = {"version": 1, "lab": "euler", "tests": ["t"],
           "mutants": {"a": {"failed": {"t": "x"}}, "b": {"failed": {"t": "y"}}}}
    assert "missing" in mutants.check_signatures("/r", "euler", doc, write=False)
    assert mutants.check_signatures("/r", "euler", doc, write=True) is None
    assert mutants.check_signatures("/r", "euler", doc, write=False) is None
    changed = dict(doc, mutants={"a": {"failed": {"t": "z"}}, "b": doc["mutants"]["b"]})
    assert mutants.check_signatures("/r", "euler", changed, write=False) == "a: changed"


def test_run_again_finds_a_variant_judged_differently():
    """Defect: a variant whose failure depends on something else than its input (undefined
    behaviour: the rows-for-cols mutants read past a matrix and were judged stale one run in
    three) passes the check, and its signature changes from run to run."""
    first = ("", 50, 100, [("t1", [], False, "expected 1 got nan"), ("t2", [], True, "")])
    same_numbers_differ = ("", 50, 100, [("t1", [], False, "expected 1 got 3.5")])
    text_differs = ("", 50, 100, [("t1", [], False, "expected 1 got -nan")])
    passes_now = ("", 50, 100, [("t1", [], True, "")])
    assert mutants.differences(first, ("", 0, 0, [("t1", [], False, "expected 7 got nan")])) == []
    assert mutants.differences(first, same_numbers_differ) == [
        ("t1", (False, "expected # got nan"), (False, "expected # got #"))]
    assert mutants.differences(first, text_differs)
    (diff,) = mutants.differences(first, passes_now)
    assert mutants.flaky_verdict([diff]).startswith(
        "FLAKY: judged differently when run again (1 test(s)), e.g. 't1': first failed: "
        "'expected # got nan', then passed")


def test_a_mistake_that_loses_fewer_than_three_points_fails():
    """Defect (issue 46): a mistake caught by one small public test while its task's held-out
    check misses it loses 1 or 2 points: the check passed it as caught."""
    row = mutants.Row("euler", "m.patch", "< 100")
    results = [("E1 one step", ["[E1]"], False, "expected 1 got 2"), ("E1 other", ["[E1]"], True, "")]
    mutants.judge(row, ("", 98, 100, results), "< 100", ["hint: h", "caught-by: [E1]"])
    assert row.verdict.startswith("LOSES ONLY 2 POINTS") and not row.ok
    row = mutants.Row("euler", "m.patch", "< 100")
    mutants.judge(row, ("", 80, 100, results), "< 100", ["hint: h", "caught-by: [E1]"])
    assert row.ok and "loses 20" in row.verdict


def info(seed):
    return f"<Info>held-out inputs of E1 from seed {seed:#x} (replay: ...)</Info>"


def test_caught_seeds_reads_each_failure_seed():
    """Defect (issue 42): the held-out measurement counted a mutant caught when one seed of
    many caught it; each seed must be counted (GENERATE runs the test once per seed)."""
    report = ("<TestCase name='E1 held-out'>" + info(11) + "<Expression success=\"false\">" +
              info(13) + "<Exception>boom</Exception>" + "<OverallResult success=\"false\"/>")
    assert mutants.caught_seeds(report, 10, 5) == ({11, 13}, None)
    assert mutants.caught_seeds("<OverallResult success=\"true\"/>", 10, 5) == (set(), None)


def test_caught_seeds_a_failure_before_the_seed_loop_fails_every_seed():
    """Defect: a failure that names no seed (a check before the loop over seeds) read as
    catching none."""
    assert mutants.caught_seeds("<Expression success=\"false\">", 10, 3) == ({10, 11, 12}, None)


def test_caught_seeds_a_crash_names_where_to_go_on():
    """Defect: a crash on one seed ends the process; the seeds after it were never tried."""
    report = info(7) + "<Expression success=\"false\">" + info(8) + "<FatalErrorCondition>"
    assert mutants.caught_seeds(report, 5, 10) == ({7, 8}, 8)
