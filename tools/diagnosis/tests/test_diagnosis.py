"""The diagnosis of a failing task (tools/diagnosis/hints.py, run by tools/diagnosis/probes.py):
what the probes' outputs say against the catalogue. Guards against a named mistake or part
that is not the student's, a task that says nothing, a task disturbed by another, and a
diagnosis that breaks grading (hostile values, a broken catalogue)."""
import json
import math

import pytest

from diagnosis import hints as wh
from grader import build, common, results
from grader.common import LabReport


def rec(**outs):
    """A compact record: name -> list of floats (a column vector)."""
    return {"out": {n: [len(v), 1, list(v)] for n, v in outs.items()}}


def probe(pid, expected, skeleton, title="", simple=False, inputs=()):
    task = pid.split("/")[0]
    p = {"probe": pid, "task": task, "title": title or pid, "tol": [1e-7, 1e-9],
         "expected": expected, "skeleton": skeleton, "call": "f",
         "in": [{"name": n, "shape": [len(v), 1], "v": list(v)} for n, v in inputs]}
    if simple:
        p["simple"] = True
    return p


ZERO = rec(f=[0, 0])
# Task T: a simple probe, then one probe per part (a: the "spring", b: the "damper").
CAT = {
    "version": wh.CATALOGUE_VERSION, "lab": "lab", "tests": ["T one", "T two", "U one"],
    "tasks": {"T": {"title": "spring", "files": ["s.cpp"], "uses": []},
              "U": {"title": "other", "files": ["u.cpp"], "uses": []}},
    "probes": [probe("T/simple", rec(f=[1, 2]), ZERO, simple=True, inputs=[("x", [1, 0])]),
               probe("T/a", rec(f=[3, 4]), ZERO), probe("T/b", rec(f=[5, 6]), ZERO),
               probe("U/u", rec(f=[7, 8]), ZERO)],
    "mutants": {
        "s.sign": {"task": "T", "kind": "spring term", "hint": "the sign of the spring",
                   "probes": {"T/simple": rec(f=[-1, -2]), "T/a": rec(f=[-3, -4]), "T/b": rec(f=[5, 6])}},
        "s.half": {"task": "T", "kind": "spring term", "hint": "half the spring",
                   "probes": {"T/simple": rec(f=[0.5, 1]), "T/a": rec(f=[1.5, 2]), "T/b": rec(f=[5, 6])}},
        "s.damp": {"task": "T", "kind": "damper term", "hint": "the damper",
                   "probes": {"T/simple": rec(f=[1, 2]), "T/a": rec(f=[3, 4]), "T/b": rec(f=[0, 6])}},
    }}
TESTS_T = [("T one", False, "expected 1 got 2"), ("T two", True, "")]


def test_a_task_whose_tests_pass_says_nothing():
    """Defect: a passing task gets a diagnosis (a student reads about a mistake they did not make)."""
    d = wh.diagnose(CAT, "T", {}, [("T one", True, ""), ("T two", True, "")])
    assert d.status == "passed" and d.lines() == []


def test_the_skeleton_is_not_started_in_one_line():
    """Defect: a task still at its skeleton gets a counterexample, or disturbs the others."""
    outs = {"T/simple": ZERO, "T/a": ZERO, "T/b": ZERO}
    d = wh.diagnose(CAT, "T", outs, TESTS_T, "spring")
    assert d.status == "not started" and len(d.lines()) == 1
    assert wh.diagnose(CAT, "T", None, TESTS_T, pristine=True).status == "not started"


def test_an_exact_match_names_the_known_mistake():
    """Defect: outputs equal to a catalogued mistake's on every probe do not name it."""
    d = wh.diagnose(CAT, "T", CAT["mutants"]["s.sign"]["probes"], TESTS_T)
    assert d.status == "mistake" and d.mistakes == ["the sign of the spring"]
    assert any("Known mistake: the sign of the spring" in l for l in d.lines())


def test_a_new_mistake_of_one_part_names_the_part_not_a_mistake():
    """Defect: a mistake nobody catalogued is either silent or named as a catalogued one."""
    outs = {"T/simple": rec(f=[2, 4]), "T/a": rec(f=[6, 8]), "T/b": rec(f=[5, 6])}  # twice
    d = wh.diagnose(CAT, "T", outs, TESTS_T)
    assert d.status == "part" and d.part == ("s", "spring term") and not d.mistakes
    assert any("spring term in s.cpp" in l for l in d.lines())


def test_no_part_is_named_when_two_parts_could_explain_it():
    """Defect: a part named from outputs that both parts' mistakes get wrong."""
    outs = {"T/simple": rec(f=[2, 4]), "T/a": rec(f=[6, 8]), "T/b": rec(f=[9, 9])}
    d = wh.diagnose(CAT, "T", outs, TESTS_T)
    assert d.status == "counterexample" and d.part is None
    assert d.counterexample and "Counterexample" in d.counterexample[0]


def test_the_counterexample_is_the_first_wrong_probe_with_expected_and_got():
    """Defect: a failing task without a concrete input, expected and got."""
    outs = {"T/simple": rec(f=[-1, -2]), "T/a": rec(f=[3, 4]), "T/b": rec(f=[5, 6])}
    d = wh.diagnose(CAT, "T", outs, TESTS_T)
    text = "\n".join(d.lines())
    assert "f(x = (1, 0))" in text and "expected f = (1, 2)" in text and "got      f = (-1, -2)" in text
    assert "f: the sign is flipped" in text


@pytest.mark.parametrize("got, words", [
    ([1, 5], "only the y component"), ([2, 1], "swapped"), ([math.nan, 2], "NaN"),
    ([0, 0], "what the skeleton gives")])
def test_what_differs_is_said(got, words):
    """Defect: a counterexample that leaves the student to spot the pattern."""
    lines = wh.counterexample(CAT["probes"][0], rec(f=got))
    assert any(words in l for l in lines), lines


def why(expected, got, skeleton=None, inputs=(), adds=()):
    p = probe("T/w", rec(f=expected), rec(f=skeleton if skeleton is not None else [7] * len(expected)),
              inputs=inputs)
    lines = wh.counterexample(p, rec(f=got), adds)
    return " ".join(l for l in lines if l.strip().startswith("f:"))


def test_a_constant_factor_only_across_three_differing_numbers():
    """Defect (issue 46): "off by a constant factor 1.229" said of one number, or of two, where
    any wrong value has a ratio: a relation that means nothing reads as a diagnosis."""
    assert "factor" not in why([1.0], [1.229])
    assert "factor" not in why([3.0, 4.0], [6.0, 8.0])
    assert "constant factor 2 (in all 3 numbers" in why([1.0, 2.0, 3.0], [2.0, 4.0, 6.0])
    assert "factor" not in why([6.34203, 1.0, 2.0], [6.34281, 1.0, 2.0])


def test_a_sign_flip_is_called_a_sign_flip():
    """Defect (issue 46): a plain sign flip read as "off by a constant factor -16" (its change
    against what f held), or as a factor on one number."""
    assert why([2.0, -3.0, 5.0], [-2.0, 3.0, -5.0]).endswith("f: the sign is flipped")
    assert why([-0.6], [0.6]).endswith("f: the sign is flipped")
    assert "factor" not in why([2.0, -3.0, 5.0], [-2.0, 3.0, -5.0])


def test_nothing_computed_only_when_the_output_is_the_input_or_the_skeletons():
    """Defect (issue 46): "zero (nothing computed?)" on values that were computed (a singular
    matrix gives zeros too)."""
    assert "nothing" not in why([1.0, 2.0], [0.0, 0.0])
    assert "skeleton" in why([1.0, 2.0], [0.0, 0.0], skeleton=[0.0, 0.0])
    assert "nothing computed" in why([1.0, 2.0], [5.0, 6.0], inputs=[("f", [5.0, 6.0])])


def test_accumulating_outputs_say_what_was_lost_or_not_added():
    """Defect: an overwritten f or a function that adds nothing reads as a wrong formula."""
    p = probe("T/x", rec(f=[4, 6]), rec(f=[1, 2]), inputs=[("f", [1, 2])])
    assert any("lost: add to f" in l for l in wh.counterexample(p, rec(f=[3, 4]), adds=["f"]))
    assert any("nothing was added" in l for l in wh.counterexample(p, rec(f=[1, 2]), adds=["f"]))


def test_add_do_not_overwrite_only_where_the_header_says_add():
    """Defect (issue 46): R6 prepare_contact resetting the stored totals was told "add to c.Pn,
    do not overwrite it", where the header says prepare leaves them as they are: advice the
    contract does not make is not given."""
    p = probe("T/x", rec(**{"c.Pn": [0.3]}), rec(**{"c.Pn": [0.3]}), inputs=[("c.Pn", [0.3])])
    text = "\n".join(wh.counterexample(p, rec(**{"c.Pn": [0.0]}), adds=["f"]))
    assert "add to" not in text and "overwrite" not in text


def test_numbers_show_the_digits_that_differ():
    """Defect (issue 46): 1.0001 against 1.000101 printed as "1.0001" and "1.0001": the
    student cannot see what differs."""
    text = "\n".join(wh.counterexample(probe("T/d", rec(f=[1.0001, 2.0]), ZERO),
                                        rec(f=[1.000101, 2.0])))
    assert "expected f = (1.0001, 2)" in text and "got      f = (1.000101, 2)" in text


def test_a_long_value_shows_the_entries_that_differ_whole():
    """Defect (issue 46): expected and got cut with "..." mid-value."""
    ev = [float(k) for k in range(200)]
    gv = list(ev)
    gv[150] = -1.0
    text = "\n".join(wh.counterexample(probe("T/l", rec(f=ev), ZERO), rec(f=gv)))
    assert "..." not in text and "[150] = 150" in text and "[150] = -1" in text
    assert "the other 199 of 200 entries agree" in text


def test_a_task_ignores_every_other_tasks_outputs():
    """Defect: a task's diagnosis changes with another task's state (mid-lab differs from
    whole-lab)."""
    outs = {"T/simple": rec(f=[2, 4]), "T/a": rec(f=[6, 8]), "T/b": rec(f=[5, 6])}
    alone = wh.diagnose(CAT, "T", outs, TESTS_T).lines()
    outs_with_u = dict(outs, **{"U/u": rec(f=[99, 99])})
    assert wh.diagnose(CAT, "T", outs_with_u, TESTS_T).lines() == alone


def test_when_every_probe_agrees_the_failed_test_speaks():
    """Defect: a failing task that the probes do not reach is left silent."""
    outs = {"T/simple": rec(f=[1, 2]), "T/a": rec(f=[3, 4]), "T/b": rec(f=[5, 6])}
    d = wh.diagnose(CAT, "T", outs, TESTS_T)
    assert d.status == "tests" and "expected 1 got 2" in "\n".join(d.lines())


@pytest.mark.parametrize("hostile", [
    {"error": "x" * 100000}, {"out": {"f": ["a", None, "zz"]}}, {"out": {"f": [2, 1, [1e308, -1e308]]}},
    {"out": "nothing"}, None, {"out": {"f": [1000000, 1, [1, 2]]}}])
def test_hostile_outputs_are_read_as_data(hostile):
    """Defect: a value from the worker (any shape, NaN, huge) crashes the diagnosis."""
    outs = {"T/simple": hostile, "T/a": hostile, "T/b": hostile}
    lines = wh.diagnose(CAT, "T", outs, TESTS_T).lines()
    assert lines and all(len(l) <= wh.LINE_CHARS for l in lines)


def test_malformed_probe_lines_are_dropped():
    """Defect: a probe process's output that is not JSON breaks grading."""
    text = '{"probe": "T/a", "out": []}\nnot json\n{"probe": 3}\n["x"]\n'
    assert [r["probe"] for r in wh.parse_lines(text)] == ["T/a"]


def test_a_bad_catalogue_means_no_diagnosis_never_an_error(tmp_path):
    """Defect: a missing, corrupt or old catalogue breaks grading."""
    (tmp_path / "tests" / "mutants" / "lab").mkdir(parents=True)
    path = tmp_path / "tests" / "mutants" / "lab" / "signatures.json"
    assert wh.load_catalogue(str(tmp_path), "lab") is None
    path.write_text("{not json")
    assert wh.load_catalogue(str(tmp_path), "lab") is None
    path.write_text(json.dumps({"version": 1, "mutants": {}}))
    assert wh.load_catalogue(str(tmp_path), "lab") is None
    d = wh.diagnose(None, "T", {}, TESTS_T)
    assert d.status == "no probes" and d.lines()


# ----------------------------------------------------------------- results

CASES = [common.TestCase("lab", f"F1 test {k}", 25, ["[F1]", "[25pts]"]) for k in range(4)]


def report(diagnosis):
    res = [common.TestResult(t, 25 if k < 2 else 0, "passed" if k < 2 else "failed",
                             "" if k < 2 else "expected 1 got 2", "" if k < 2 else "expected 1 got 2")
           for k, t in enumerate(CASES)]
    return {"lab": LabReport("lab", res, diagnosis=diagnosis)}


def test_the_diagnosis_goes_under_failed_tests_only():
    """Defect: a diagnosis attached to a passing test, or changing the score."""
    d = wh.diagnose(CAT, "T", CAT["mutants"]["s.sign"]["probes"], TESTS_T)
    data = results.results_json(report({"F1": d}), {})
    out = [t["output"] for t in data["tests"]]
    assert "Known mistake" not in out[0] and "Known mistake" in out[2]
    assert data["score"] == 50 and "T: 1 of 2 tests failed" in data["output"]


def test_a_broken_diagnosis_changes_no_score():
    """Defect: an exception in a diagnosis stops the grading or changes points."""
    class Broken:
        task, title, status = "T", "", "counterexample"

        def lines(self):
            raise KeyError("boom")

        def headline(self):
            raise KeyError("boom")
    data = results.results_json(report({"F1": Broken()}), {})
    assert data["score"] == 50 and "(no diagnosis: KeyError)" in data["tests"][2]["output"]


def test_the_grader_internals_stay_out_of_what_students_see():
    """Defect: sandbox, seccomp or 'NOT as another user' lines in the student-visible output."""
    data = results.results_json(report({}), {}, "sandbox of each test process: seccomp ...",
                                {"sandbox": ["seccomp"]})
    assert "seccomp" not in data["output"] and data["extra_data"]["defences"]["sandbox"]


def test_a_reused_report_reads_as_the_graded_one():
    """Defect: results reused for an unchanged lab differ from the ones graded (a cached
    diagnosis that loses its part, a score that changes)."""
    d = wh.diagnose(CAT, "T", {"T/simple": rec(f=[2, 4]), "T/a": rec(f=[6, 8]),
                               "T/b": rec(f=[5, 6])}, TESTS_T)
    rep = report({"T": d})["lab"]
    back = build.report_from_json(json.loads(json.dumps(build.report_to_json(rep))))
    assert back.score == rep.score and back.diagnosis["T"].lines() == d.lines()
    assert back.results[2].output == rep.results[2].output


def test_not_started_is_the_skeletons_bytes_not_the_checkouts():
    """Defect: in a student's checkout labs/ holds the student's work, so a task compared with
    labs/ reads "not started" while it is wrong."""
    import hashlib
    from diagnosis.probes import pristine_tasks
    skel = b"void f() {}\n"
    tasks = {"T": {"files": ["s.cpp"], "skeleton_sha256": {"s.cpp": hashlib.sha256(skel).hexdigest()}},
             "U": {"files": ["u.cpp"]}}
    assert pristine_tasks({"s.cpp": skel}, tasks) == {"T"}
    assert pristine_tasks({}, tasks) == {"T"}  # not submitted: the skeleton
    assert pristine_tasks({"s.cpp": b"void f() { g(); }\n"}, tasks) == set()


def test_prebuilt_binaries_only_for_their_toolchain_and_files(tmp_path):
    """Defect: the pack's prebuilt test binaries used after the tests, the grader's C++ or the
    compiler changed (a test list or a wire format that is not this checkout's)."""
    from grader.build import Grader, prebuilt_inputs
    repo, build = tmp_path / "repo", tmp_path / "b"
    (repo / "prebuilt" / "grader").mkdir(parents=True)
    (repo / "prebuilt" / "grader" / "lab-tests").write_bytes(b"x")
    pristine = {"tests/lab/t.cpp": b"a", "labs/lab/s.cpp": b"student"}
    manifest = {"toolchain": "gcc 12", "inputs": prebuilt_inputs(pristine),
                "labs": {"lab": ["lab-tests"]}}
    (repo / "prebuilt" / "grader" / "manifest.json").write_text(json.dumps(manifest))
    g = Grader.__new__(Grader)
    g.repo, g.build, g.verbose = str(repo), str(build), False
    build.mkdir()
    (build / "wb-toolchain.txt").write_text("gcc 12\n")
    g.decide_prebuilt(pristine)
    assert list(g._prebuilt) == ["lab"]
    g.decide_prebuilt(dict(pristine, **{"labs/lab/s.cpp": b"edited"}))  # student files: no matter
    assert list(g._prebuilt) == ["lab"]
    g.decide_prebuilt(dict(pristine, **{"tests/lab/t.cpp": b"b"}))
    assert g._prebuilt == {}
    (build / "wb-toolchain.txt").write_text("clang 16\n")
    g.decide_prebuilt(pristine)
    assert g._prebuilt == {}


def test_wrong_on_names_the_outputs_that_differ():
    """Defect (issue 46): F9's "Right on: curl_noise_potential 1.3 from a disc's edge" beside
    "Wrong on: curl_noise_potential 1.3 and 2.8 ..." where only the flow of that probe was
    wrong: a probe of several outputs says which of them are wrong."""
    cat = json.loads(json.dumps(CAT))
    cat["probes"].append(probe("T/two", {"out": {"psi": [1, 1, [1.0]], "u": [2, 1, [1.0, 2.0]]}},
                               ZERO, title="psi and u near the disc"))
    outs = {"T/simple": rec(f=[1, 2]), "T/a": rec(f=[3, 4]), "T/b": rec(f=[5, 6]),
            "T/two": {"out": {"psi": [1, 1, [1.0]], "u": [2, 1, [9.0, 2.0]]}}}
    text = "\n".join(wh.diagnose(cat, "T", outs, TESTS_T).lines())
    assert "Wrong on: psi and u near the disc (its u only)" in text


def test_every_diagnosis_line_fits_a_terminal_and_nothing_is_cut():
    """Defect (issue 46): diagnosis lines of 260 characters (a call with many inputs, the lists
    of probes), cut at 400."""
    cat = json.loads(json.dumps(CAT))
    cat["probes"][1]["in"] = [{"name": f"input{k}", "shape": [3, 1], "v": [k + 0.5, -k, 2.25]}
                              for k in range(20)]
    d = wh.diagnose(cat, "T", {"T/simple": rec(f=[1, 2]), "T/a": rec(f=[7, 4]),
                               "T/b": rec(f=[5, 6])}, TESTS_T)
    lines = d.lines()
    assert max(len(l) for l in lines) <= wh.LINE_WIDTH
    assert "input19 = (19.5, -19, 2.25)" in " ".join(" ".join(lines).split())


def test_a_probe_the_failed_test_outruns_is_no_contradiction():
    """Defect (issue 46): "Every probe agrees with the solution" above a failing task reads as
    a contradiction: the probes are said not to show the mistake, the test to show it."""
    outs = {"T/simple": rec(f=[1, 2]), "T/a": rec(f=[3, 4]), "T/b": rec(f=[5, 6])}
    text = "\n".join(wh.diagnose(CAT, "T", outs, TESTS_T).lines())
    assert "agrees with the solution" not in text and "do not show this mistake" in text


def loop_cat():
    """Task L: a formula part (two mistakes that get every particle wrong) and a loop part (a
    mistake that misses the last particle); the outputs particle by particle."""
    exp = {"out": {"f": [2, 3, [1, 2, 3, 4, 5, 6]]}}
    zero = {"out": {"f": [2, 3, [0] * 6]}}
    p = probe("L/three", exp, zero)
    p["out"] = [{"name": "f", "each": True}]

    def f(vs):
        return {"L/three": {"out": {"f": [2, 3, vs]}}}
    return {"version": wh.CATALOGUE_VERSION, "lab": "lab", "tests": ["L one"],
            "tasks": {"L": {"title": "loop", "files": ["l.cpp"], "uses": []}}, "probes": [p],
            "mutants": {"l.sign": {"task": "L", "kind": "formula", "hint": "sign",
                                   "probes": f([-1, -2, -3, -4, -5, -6])},
                        "l.half": {"task": "L", "kind": "formula", "hint": "half",
                                   "probes": f([0.5, 1, 1.5, 2, 2.5, 3])},
                        "l.skip-last": {"task": "L", "kind": "particle loop", "hint": "last",
                                        "probes": f([1, 2, 3, 4, 0, 0])}}}


def test_a_loop_that_misses_a_particle_is_not_read_as_the_formula():
    """Defect (issue 46): a loop that skips the first particle (F4) read as "the drag formula",
    since no part was the loop's: every mistake of a formula gets every particle wrong, so a
    submission that leaves some particles right is not the formula's."""
    cat = loop_cat()
    first = {"L/three": {"out": {"f": [2, 3, [0, 0, 3, 4, 5, 6]]}}}
    assert wh.part_of(cat, "L", first) != ("l", "formula")
    third = {"L/three": {"out": {"f": [2, 3, [2, 4, 6, 8, 10, 12]]}}}
    assert wh.part_of(cat, "L", third) == ("l", "formula")


def test_a_loop_that_misses_another_particle_is_named_as_the_loop():
    """Defect (issue 46, fresh mistakes): a loop that skips the first particle, where the
    catalogue's loop mistake skips the last, got no part (no particle is missed by every
    mistake of a loop): the particles of an output are taken as one when no part fits them
    apart, so the loop is named, and a wrong value of one particle is still not the loop."""
    cat = loop_cat()
    first = {"L/three": {"out": {"f": [2, 3, [0, 0, 3, 4, 5, 6]]}}}
    assert wh.part_of(cat, "L", first) == ("l", "particle loop")
    one_wrong = {"L/three": {"out": {"f": [2, 3, [7, 2, 3, 4, 5, 6]]}}}
    assert wh.part_of(cat, "L", one_wrong) is None


def test_a_value_that_only_happens_to_be_the_skeletons_is_not_nothing_done():
    """Defect (issue 46, fresh mistakes): R6's warm start applied in every pass drove the
    returned total to 0, the skeleton's value, beside a body whose velocity it did change: the
    total read as "nothing done", which no warm-start mistake does, so no part was named. An
    output is "nothing done" only when no other output of its call was computed wrong; one that
    the code leaves as the skeleton does, beside outputs that are right, still is."""
    exp, skel = rec(total=[6], v=[1, 2]), rec(total=[0], v=[5, 5])
    cat = {"version": wh.CATALOGUE_VERSION, "lab": "lab", "tests": ["S one"],
           "tasks": {"S": {"title": "solve", "files": ["s.cpp"], "uses": []}},
           "probes": [probe("S/plane", exp, skel)],
           "mutants": {"s.warm-sign": {"task": "S", "kind": "warm start", "hint": "sign",
                                       "probes": {"S/plane": rec(total=[7], v=[0, 2])}},
                       "s.warm-none": {"task": "S", "kind": "warm start", "hint": "none",
                                       "probes": {"S/plane": rec(total=[6.5], v=[1, 3])}},
                       "s.no-sum": {"task": "S", "kind": "total", "hint": "sum",
                                    "probes": {"S/plane": rec(total=[0], v=[1, 2])}},
                       "s.no-sum-b": {"task": "S", "kind": "total", "hint": "sum",
                                      "probes": {"S/plane": rec(total=[0], v=[1, 2])}}}}
    assert wh.part_of(cat, "S", {"S/plane": rec(total=[0], v=[0.5, 2.5])}) == ("s", "warm start")
    assert wh.part_of(cat, "S", {"S/plane": rec(total=[0], v=[1, 2])}) == ("s", "total")


def test_mirror_image_stages_are_told_apart_by_how_they_go_wrong():
    """Defect (issue 46): the trapezoid's second stage and its average change the same outputs
    (a weight on a(X) too large in one, too small in the other), so no part was named for M2:
    where two parts fit by which outputs go wrong, the one whose mistakes err the same way is
    named."""
    exp = {"out": {"x": [2, 1, [1.0, 1.0]], "v": [2, 1, [2.0, 2.0]]}}
    p = probe("M/s", exp, {"out": {"x": [2, 1, [0, 0]], "v": [2, 1, [0, 0]]}})

    def o(dx, dv):
        return {"M/s": {"out": {"x": [2, 1, [1.0 + dx[0], 1.0 + dx[1]]],
                                "v": [2, 1, [2.0 + dv[0], 2.0 + dv[1]]]}}}
    cat = {"version": wh.CATALOGUE_VERSION, "lab": "lab", "tests": [], "probes": [p],
           "tasks": {"M": {"title": "step", "files": ["m.cpp"], "uses": []}},
           "mutants": {"m.stage-a": {"task": "M", "kind": "second stage", "probes": o((1, 2), (0, 0))},
                       "m.stage-b": {"task": "M", "kind": "second stage", "probes": o((0, 0), (3, 1))},
                       "m.avg-a": {"task": "M", "kind": "average", "probes": o((-1, -2), (0, 0))},
                       "m.avg-b": {"task": "M", "kind": "average", "probes": o((0, 0), (-3, -1))}}}
    assert wh.part_of(cat, "M", o((0.5, 1), (0, 0))) == ("m", "second stage")
    assert wh.part_of(cat, "M", o((0, 0), (-6, -2))) == ("m", "average")
    assert wh.part_of(cat, "M", o((0, 0), (1, -1))) is None  # neither way: no part named


def test_a_mutant_left_with_nothing_to_act_on_is_counted_silent_and_fails_the_floor(
        tmp_path, capsys):
    """Defect (issue 46): a mistake whose every probe agrees with the solution and whose failed
    test says nothing (an empty message) was counted as "probes blind", as if the test's message
    helped; the leave-one-out must count it silent, and --max-silent 0 must fail on it."""
    from diagnosis import catalogue
    cat = json.loads(json.dumps(CAT))
    for m in cat["mutants"].values():
        m["failed"] = {"T one": "expected 1\ngot 2"}
    cat["mutants"]["s.mute"] = {"task": "T", "kind": "spring term", "hint": "nothing shows",
                                "failed": {"T one": ""},
                                "probes": {p["probe"]: p["expected"] for p in cat["probes"]}}
    rows = {name: res for name, _, res, _ in catalogue.leave_one_out(cat)}
    assert rows["s.mute"] == "silent" and "silent" not in {rows[n] for n in CAT["mutants"]}
    d = tmp_path / "tests" / "mutants" / "lab"
    d.mkdir(parents=True)
    (d / "signatures.json").write_text(json.dumps(cat))
    assert catalogue.loo_table(str(tmp_path), ["lab"], max_silent=0) == 1
    assert "1 mutants get nothing to act on > --max-silent 0" in capsys.readouterr().out
