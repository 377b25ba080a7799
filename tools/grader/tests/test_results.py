"""results.json and the table (tools/grader/results.py): the score Gradescope shows is the sum
the verdict decided, every text is capped and printable, and a task's diagnosis can add words
but never change points. Guards against a results.json that is too big for Gradescope, a
diagnosis that floods it, and a score that disagrees with the tests listed."""
import io
import json

import pytest

from grader import common, results
from grader.common import LabReport

TESTS = [common.TestCase("euler", f"E1 test {k}", 25, ["[E1]", "[25pts]"]) for k in range(4)]


def lab(passed=(0, 1), output="expected 1 got 2"):
    res = [common.TestResult(t, t.points if k in passed else 0, "passed" if k in passed else "failed",
                      "" if k in passed else "expected 1 got 2", "" if k in passed else output)
           for k, t in enumerate(TESTS)]
    return {"euler": LabReport("euler", res)}


def test_score_is_the_sum_of_the_tests_points():
    """Defect: the top-level score disagrees with the tests (Gradescope shows the top one)."""
    data = results.results_json(lab(), {})
    assert data["score"] == 50 == sum(t["score"] for t in data["tests"])
    assert [t["max_score"] for t in data["tests"]] == [25] * 4
    assert data["tests"][0]["name"] == "euler: E1 test 0"


def test_diagnosis_lines_are_few_short_and_printable():
    """Defect: a diagnosis floods the feedback or draws fake lines with control characters
    (its lines quote values that came back from student code). Where it goes and what a
    broken one does: test_diagnosis.py."""
    class Loud:
        task, title, status = "E1", "", "counterexample"

        def lines(self):
            return ["a\x1b[31m\nb" + "x" * 1000] * 90
    lines = results.task_lines(Loud())
    assert len(lines) == results.DIAGNOSIS_LINES
    assert all(len(h) <= results.DIAGNOSIS_CHARS and "\x1b" not in h and "\n" not in h
               for h in lines)


def test_results_json_is_capped(monkeypatch):
    """Defect: a results.json larger than RESULTS_CAP (Gradescope rejects it, the student gets
    an autograder failure instead of a score)."""
    monkeypatch.setattr(results, "RESULTS_CAP", 40_000)
    data = results.results_json(lab(passed=(), output="y" * 30_000), {})
    assert len(json.dumps(data, indent=2).encode()) <= 40_000
    assert data["tests"][0]["output"].endswith("[... cut: results.json is capped]")
    assert data["score"] == 0


def test_table_names_refusals_and_compile_errors():
    """Defect: a refused or uncompiled lab shown with a bare 0 (the student does not learn
    why)."""
    reps = lab(passed=())
    reps["euler"].refused = "explicit_euler.cpp:3: 'system' is not allowed"
    out = io.StringIO()
    results.print_table(reps, {"euler": ["a note"]}, out=out)
    text = out.getvalue()
    assert "euler: REFUSED: explicit_euler.cpp:3" in text and "euler: note: a note" in text
    assert "euler: 0/100 (refused: every test scores 0)" in text and "total: 0/100" in text


def test_write_atomic_leaves_no_half_file(tmp_path, monkeypatch):
    """Defect: a crash while writing leaves a half-written results.json over a good one."""
    path = tmp_path / "results.json"
    path.write_text("good")

    def boom(*_):
        raise OSError("disk full")
    monkeypatch.setattr(results.os, "fsync", boom)
    with pytest.raises(OSError):
        results.write_atomic(str(path), "new")
    assert path.read_text() == "good" and [p.name for p in tmp_path.iterdir()] == ["results.json"]
