"""tools/adversary's generated worker and the hostile suite's generated submissions
(tools/wbtools/adversary.py, nonfinite.py): made from the same headers as the grader's stubs.
Guards against an adversary that answers a call other than the one asked (its ids shifted
from the grader's), a lab function the adversary or the non-finite submission leaves out
(then nothing hostile reaches that function's tests), and outputs left untouched."""
import os
import re

import pytest

from grader import project, stubs
from wbtools import adversary, nonfinite

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
LABS = project.known_labs(REPO)


@pytest.mark.parametrize("lab", LABS)
def test_the_adversary_answers_every_call_the_grader_dispatches(lab):
    """Defect: the adversary's dispatcher numbered the calls differently from the grader's, or
    skipped one (a new lab function, a kernel)."""
    worker = stubs.generate(REPO, lab)[f"{lab}_worker.cpp"]
    adv = adversary.adversary_files(REPO, [lab])[f"grader-worker/{lab}_adversary.cpp"].decode()
    cases = re.findall(r"case (\d+):", worker)
    assert cases and re.findall(r"case (\d+):", adv) == cases
    assert adv.count("ServeAdversary<") == len(cases) and "static_cast" not in adv.split(
        "void wbrpc::dispatch")[1]


@pytest.mark.parametrize("lab", LABS)
def test_the_adversary_poisons_every_struct_field(lab):
    """Defect: a struct field the wire sends but the adversary leaves as the call gave it."""
    rpc = stubs.generate(REPO, lab)[f"{lab}_rpc.h"]
    adv = adversary.adversary_files(REPO, [lab])[f"grader-worker/{lab}_adversary.cpp"].decode()
    for q, body in adversary.STRUCT_PUT.findall(rpc):
        for f in re.findall(r"put\(o, v\.(\w+)\);", body):
            assert f"poison(a, v.{f});" in adv, (q, f)


@pytest.mark.parametrize("lab", LABS)
@pytest.mark.parametrize("value", ["inf", "nan"])
def test_the_nonfinite_submission_defines_every_function_and_fills_every_output(lab, value):
    """Defect: a lab function missing from the submission (it keeps the skeleton, which scores
    0 anyway, and the case proves nothing), or an output it does not fill."""
    files = nonfinite.submission(REPO, lab, value)
    assert sorted(files) == project.student_files(REPO, lab)
    for cpp, text in files.items():
        for ns, ret, name, params in stubs.parse(
                os.path.join(REPO, "labs", lab, cpp[:-4] + ".h")).functions:
            assert f" {name}(" in text
            for p, n in params:
                if "&" in p and not p.lstrip().startswith("const "):
                    assert f"  fill({n});" in text
            if ret != "void":
                assert f"return filled<{ret}>();" in text
        assert ("quiet_NaN" in text) == (value == "nan")


def test_the_inputs_classifier_tells_apart_only_what_differs():
    """Defect: the --inputs rule scored on the calls it was trained on (any two samples look
    separable), or missed a feature that separates them (short decimals against full doubles,
    the case of issue 42)."""
    import random
    rng = random.Random(1)
    same = [(rng.random(), rng.uniform(1, 4), rng.uniform(-1, 2), 2.0) for _ in range(400)]
    acc, _, _ = adversary.stump(same[:200], same[200:])
    assert acc <= adversary.CHANCE + adversary.MARGIN
    public = [(1.0, rng.uniform(1, 4), rng.uniform(-1, 2), 2.0) for _ in range(200)]
    held = [(0.0, rng.uniform(1, 4), rng.uniform(-1, 2), 2.0) for _ in range(200)]
    acc, feature, _ = adversary.stump(public, held)
    assert acc == 1.0 and feature == "share of short decimals"
    # a rule that is wrong on the other half as often as a good one is right tells them apart
    assert adversary.told_apart(0.23) and adversary.told_apart(0.77)
    assert not adversary.told_apart(0.5) and not adversary.told_apart(0.45)
    assert adversary.call_features("3 10 4 2.5 3 9") == pytest.approx(
        (0.4, 2.0, 0.39794, 2.25), 1e-4)
    # the digits alone: public calls of one or two digits, held-out draws of three
    public = [(1.0, 2.0, 0.5, rng.choice((1.0, 1.5, 2.0))) for _ in range(100)]
    held = [(1.0, 2.0, 0.5, rng.choice((2.5, 3.0))) for _ in range(100)]
    acc, feature, _ = adversary.stump(public, held)
    assert acc == 1.0 and feature == "mean digits of short decimals"


def test_few_public_calls_are_measured_by_where_they_fall_among_the_held_out_ones():
    """Defect: a task with fewer than MIN_CALLS public calls was reported unmeasurable (so a
    port that fixed it could not pass), or passed with a published value outside the drawn
    range or at its edge (a call told apart by that alone)."""
    import random
    rng = random.Random(2)
    held = [(1.0, 2.0, rng.uniform(0.0, 1.0), 2.0) for _ in range(100)]
    assert adversary.atypical([(1.0, 2.0, 0.5, 2.0), (1.0, 2.0, 0.3, 2.0)], held) is None
    assert adversary.atypical([(1.0, 2.0, 0.5, 2.0), (1.0, 2.0, 1.5, 2.0)], held)[:2] == (
        1, "log10 largest |number|")
    assert adversary.atypical([(1.0, 2.0, 0.001, 2.0)], held) is not None  # at the range's edge
    assert adversary.atypical([(1.0, 3.0, 0.5, 2.0)], held)[1] == "log2 particles"  # another size


def test_the_halves_do_not_follow_the_calls_order():
    """Defect: the rule was trained on the even calls and tried on the odd ones, so a public
    test alternating a large and a small call (F8's turning sense) read as told apart in
    reverse against held-out calls of the same two kinds in any order."""
    import random
    rng = random.Random(3)
    public = [(1.0, 2.0, 1.0, 2.0), (1.0, 2.0, -1.0, 2.0)] * 50
    held = [(1.0, 2.0, rng.choice((1.0, -1.0)), 2.0) for _ in range(100)]
    acc, _, _ = adversary.stump(public, held)
    assert not adversary.told_apart(acc)
