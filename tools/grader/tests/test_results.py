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


# ------------------------------------------------ what a student reads (issue 46)

SEED = 0xa8025cd52d8e4f17
LONG = ("C2 collide_particles: receding particles get no impulse but are separated without "
        "moving the centre of mass")


def half_done():
    """A lab with a long test name, a held-out failure and a failure with a long value."""
    tests = [common.TestCase("collisions", LONG, 3, ["[C2]", "[3pts]"]),
             common.TestCase("collisions", "C2 held-out: random pairs", 4,
                             ["[C2]", "[held-out]", "[4pts]"]),
             common.TestCase("collisions", "C3 grid_pairs: pairs", 5, ["[C3]", "[5pts]"])]
    long_value = "(" + ", ".join(f"{k}.25" for k in range(60)) + ")"
    res = [common.TestResult(tests[0], 3, "passed", "", ""),
           common.TestResult(tests[1], 0, "failed",
                             "impulse along n (pair 3)\n  expected (1, 2)\n  got      (1, 1.5)\n"
                             "  tolerance 1e-12 + 0 * |value|\n"
                             "held-out inputs of C2 (the grade's seed, above)", "details"),
           common.TestResult(tests[2], 0, "failed", f"pairs\n  expected {long_value}\n"
                             f"  got      {long_value.replace('59.25', '-1')}", "details")]
    return {"collisions": LabReport("collisions", res)}


def table(reports, seed=SEED):
    buf = io.StringIO()
    results.print_table(reports, {"collisions": ["x" * 150]}, out=buf, seed=seed)
    return buf.getvalue()


def test_every_line_of_the_table_fits_a_terminal():
    """Defect (issue 46): table lines past 200 characters (lab, points, status, a name of up to
    112 characters and the reason on one line), and reasons cut with "..."."""
    text = table(half_done())
    assert max(len(l) for l in text.splitlines()) <= results.LINE_LIMIT
    assert "expected #59 = 59.25 (the other 59 of 60 numbers agree)" in text  # what differs
    assert "got      #59 = -1" in text
    assert "moving the centre of mass" in " ".join(text.split()) and "..." not in text


def test_the_failed_check_is_the_first_line_under_its_test():
    """Defect (issue 46): a reason that starts elsewhere than at the check that failed."""
    lines = table(half_done()).splitlines()
    k = next(i for i, l in enumerate(lines) if "C2 held-out: random pairs" in l)
    assert lines[k + 1].strip() == "impulse along n (pair 3)"
    assert lines[k + 2].strip() == "expected (1, 2)" and lines[k + 3].strip() == "got      (1, 1.5)"


def test_one_seed_line_never_cut():
    """Defect (issue 46): the seed printed twice in the header, again in each held-out reason,
    and cut mid-hex in the table (--seed 0xa8025cd52d8e...): a student who copies it replays
    the wrong inputs."""
    text = table(half_done())
    assert text.count(f"{SEED:#x}") == 2 and len(text.split(f"{SEED:#x}")) == 3
    line = next(l for l in text.splitlines() if f"{SEED:#x}" in l)
    assert f"--seed {SEED:#x} replays this grade" in line
    assert "the grade's seed, above" in text
    data = results.results_json(half_done(), {}, seed=SEED)
    assert data["output"].count(f"--seed {SEED:#x}") == 1
    assert not any(f"{SEED:#x}" in t["output"] for t in data["tests"])


def test_a_tasks_diagnosis_is_given_once():
    """Defect (issue 46): the whole diagnosis block repeated under every failed test of a task
    (7 times for E1) in results.json."""
    class D:
        task, title, status = "E1", "", "counterexample"

        def lines(self):
            return ["E1: 3 of 4 tests failed", "  Counterexample ..."]

        def headline(self):
            return "E1: 3 of 4 tests failed"
    reps = lab(passed=(0,))
    reps["euler"].diagnosis = {"E1": D()}
    outs = [t["output"] for t in results.results_json(reps, {})["tests"]]
    assert sum("Counterexample" in o for o in outs) == 1 and "Counterexample" in outs[1]
    assert "under its first failed test" in outs[2]


def test_a_regrade_keeps_one_seed():
    """Defect (issue 46): an unchanged re-grade printed a new random seed, then the reused
    report's: two seeds, one of which does not replay what the student reads."""
    from grader.build import one_seed
    seed, cached = one_seed(7, False, {"euler": 5, "forces": 5, "rigid": 9},
                            {"euler": "E", "forces": "F", "rigid": "R"})
    assert seed == 5 and cached == {"euler": "E", "forces": "F"}  # rigid is graded again with 5
    assert one_seed(7, True, {"euler": 7, "forces": 5}, {"euler": "E", "forces": "F"}) == \
        (7, {"euler": "E"})
    assert one_seed(7, False, {}, {}) == (7, {})


def test_every_line_of_results_json_fits_a_terminal():
    """Defect (issue 46, a half-done lab read as a student would): the table fit 100 characters
    but results.json, which the course platform shows as text, held lines of up to 385 (a
    held-out test's inputs, a task's "not started" headline, the summary's last line)."""
    class D:
        task, title, status = "C2", "collide two particles with an impulse", "not started"

        def lines(self):
            return ["C2 collide two particles: not started (its functions still do what the "
                    "skeleton does)"]

        def headline(self):
            return self.lines()[0] + " and more words to pass the limit of a line"
    reps = half_done()
    reps["collisions"].results[1].output = "x = [" + ", ".join(["-0.233283"] * 40) + "]"
    reps["collisions"].diagnosis = {"C2": D()}
    data = results.results_json(reps, {"collisions": ["x" * 150]}, seed=SEED)
    texts = [data["output"]] + [t["output"] for t in data["tests"]]
    assert max(len(l) for t in texts for l in t.splitlines()) <= results.LINE_LIMIT
    assert " ".join(data["tests"][1]["output"].split()).count("-0.233283") == 40  # nothing cut
    assert f"--seed {SEED:#x} replays this grade" in data["output"]
