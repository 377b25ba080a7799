"""Parts of the real catalogues (tests/mutants/<lab>/signatures.json) that a mistake of one could
be read as the other's: the probes must tell them apart, or name neither. A wrong part is worse
than a counterexample: the student fixes what was right."""
import math
import os

import pytest

from diagnosis import hints

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))


def friction(n, jn, mu, m, v, slide):
    """friction_impulse (labs/collisions/friction_impulse.h) with the sliding change
    slide(bound, m) instead of bound / m: (returned impulse, new v)."""
    dot = v[0] * n[0] + v[1] * n[1]
    vt = (v[0] - dot * n[0], v[1] - dot * n[1])
    speed = math.hypot(*vt)
    stop, bound = m * speed, mu * jn
    if stop <= bound:
        return stop, (v[0] - vt[0], v[1] - vt[1])
    k = slide(bound, m) / speed
    return bound, (v[0] - k * vt[0], v[1] - k * vt[1])


def c4_outputs(cat, slide):
    """The C4 probes' outputs of friction_impulse with a sliding change of its own, computed from
    the probes' recorded inputs, as compact records."""
    out = {}
    for p in hints.task_probes(cat, "C4"):
        ins = {name: vs for name, _, _, vs, _ in hints.inputs(p)}
        names = list(hints.expand(p["expected"]))
        if "v" in ins:
            j, v = friction(ins["n"], ins["jn"][0], ins["mu"][0], ins["m"][0], ins["v"], slide)
            out[p["probe"]] = {"out": {"returned": [1, 1, [j]], "v": [2, 1, list(v)]}}
            continue
        cases = next(vs for name, vs in ins.items() if name.startswith("each column"))
        state, gap = [], []
        for k in range(len(cases) // 5):
            jn, mu, m, vx, vy = cases[5 * k:5 * k + 5]
            j, v = friction(ins["n"], jn, mu, m, (vx, vy), slide)
            state += [j, v[0], v[1]]
            gap.append(m * math.hypot(v[0] - vx, v[1] - vy) - j)
        vals = {n: ([3, len(gap), state] if n.startswith("each column: returned") else
                    [1, len(gap), gap]) for n in names}
        out[p["probe"]] = {"out": vals}
    return out


def test_the_model_of_friction_impulse_is_the_solutions():
    """Defect: a test below that builds its wrong outputs from a model that is not the
    solution's (a change of the probes' inputs or outputs it did not follow) would prove
    nothing: the model with the right sliding change gives the catalogue's expected outputs."""
    cat = hints.load_catalogue(ROOT, "collisions")
    got = c4_outputs(cat, lambda bound, m: bound / m)
    for p in hints.task_probes(cat, "C4"):
        assert hints.same(got[p["probe"]], p["expected"], hints.tolerance(p)), p["probe"]


@pytest.mark.parametrize("slide", [lambda b, m: b, lambda b, m: b * m, lambda b, m: 2 * b / m],
                         ids=["no 1/m", "times m", "twice"])
def test_a_sliding_change_off_from_its_impulse_is_not_the_friction_cone(slide):
    """Defect (issue 46, fresh mistakes): C4's sliding change without the 1/m read as "the
    friction cone": at the probes it looks like a wrong bound. The cone probe records, case by
    case, whether v changed by the impulse returned (the header's "impulse magnitude
    applied"): a mistake of the cone is wrong and consistent, one in applying the impulse is
    not, so the cone is not named for it."""
    cat = hints.load_catalogue(ROOT, "collisions")
    outputs = c4_outputs(cat, slide)
    assert any(not hints.same(outputs[p["probe"]], p["expected"], hints.tolerance(p))
               for p in hints.task_probes(cat, "C4"))
    assert hints.part_of(cat, "C4", outputs) != ("friction_impulse", "friction cone")
    d = hints.diagnose(cat, "C4", outputs, [("C4 x", False, "")])
    assert d.status == "counterexample" and d.counterexample
