"""Every word the diagnosis can say of the real catalogues (tests/mutants/<lab>/signatures.json),
checked against the contract: each known mistake's hint sends the student to its own task, no
hint or part is said of correct outputs, and a generated sentence gives advice only where the
task's header gives it. Guards against advice a student takes literally and that is wrong (R6
prepare_contact told "add to c.Pn, do not overwrite it", where the header says prepare leaves
the stored totals alone)."""
import os
import re

import pytest

from diagnosis import catalogue, hints

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
LABS = sorted(d for d in os.listdir(os.path.join(ROOT, "tests", "mutants"))
              if os.path.isfile(hints.catalogue_path(ROOT, d)))


@pytest.mark.parametrize("lab", LABS)
def test_each_hint_points_at_its_own_task(lab):
    """Defect: a hint that sends the student to another task's handout section or header."""
    cat = hints.load_catalogue(ROOT, lab)
    tasks = catalogue.lab_tasks(ROOT, lab)
    lab_headers = set(os.listdir(os.path.join(ROOT, "labs", lab)))
    for name, m in cat["mutants"].items():
        hint, task = m.get("hint", ""), m["task"]
        others = {f[:-4] + ".h" for t, info in tasks.items() if t != task for f in info["files"]}
        sections = set(re.findall(r"§\s*([A-Z]\d+)", hint))
        named = set(re.findall(r"\b(\w+\.h)\b", hint)) & lab_headers
        assert sections or named, f"{lab}/{name}: the hint names no handout section or header"
        assert sections <= {task} and not named & others, f"{lab}/{name}: {hint}"


@pytest.mark.parametrize("lab", LABS)
def test_correct_outputs_get_no_mistake_and_no_part(lab):
    """Defect: a hint or a part named for code whose every probe output is the solution's (the
    alternatives must agree with the solution on every probe: tools/mutants checks it)."""
    cat = hints.load_catalogue(ROOT, lab)
    for task in cat["tasks"]:
        right = {p["probe"]: p["expected"] for p in hints.task_probes(cat, task)}
        if not right:
            continue
        d = hints.diagnose(cat, task, right, [(f"{task} a test", False, "expected 1\ngot 2")])
        assert d.status == "tests" and not d.mistakes and d.part is None, (lab, task, d.lines())


@pytest.mark.parametrize("lab", LABS)
def test_generated_advice_follows_the_header(lab):
    """Defect: "add to X, do not overwrite it" said of an output whose header does not say to
    add to it, for any catalogued mistake (what a student with exactly that mistake reads)."""
    cat = hints.load_catalogue(ROOT, lab)
    tasks = catalogue.lab_tasks(ROOT, lab)
    for t, info in cat["tasks"].items():
        info["adds"] = tasks.get(t, {}).get("adds", [])  # today's headers, not the stored copy
    for name in cat["mutants"]:
        _, _, d = catalogue.outcome(cat, name, leave_out=False)
        adds = {a.rsplit(".", 1)[-1] for a in tasks[cat["mutants"][name]["task"]]["adds"]}
        for line in d.lines():
            for what in re.findall(r"add to ([\w.\[\]]+), do not overwrite", line):
                assert what.rsplit(".", 1)[-1] in adds, f"{lab}/{name}: {line}"


# Issue 46, "parts where mistakes live": mistakes of a loop's range and of the trapezoid's
# stages, each left out of its lab's catalogue, and the part the diagnosis must name for them.
OWN_PART = {
    "forces": ["uniform_gravity.skip-first", "uniform_gravity.skip-last",
               "damping.skip-last", "damping.rows-for-cols"],
    "midpoint": ["trapezoid.half-step-xb", "trapezoid.no-average",
                 "trapezoid.xb-from-xa", "trapezoid.xb-position-old-velocity"],
}


@pytest.mark.parametrize("lab", sorted(OWN_PART))
def test_loop_and_stage_mistakes_name_their_own_part(lab):
    """Defect (issue 46): a loop that skips a particle read as the formula ("the weight", "the
    drag formula": no part was the loop's), and the trapezoid's stage mistakes never given a
    part. Left out of the catalogue, each is named as its own part, never as another."""
    cat = hints.load_catalogue(ROOT, lab)
    for name in OWN_PART[lab]:
        assert name in cat["mutants"], f"{lab}/{name}: not in the catalogue"
        _, part, d = catalogue.outcome(cat, name)
        assert part == hints.part_key(name, cat["mutants"][name]), (name, part, d.lines())
