"""tools/newlab-check's throwaway lab (tools/newlab.d/) and the places it writes into, checked
in seconds: the stage itself takes minutes, and fails late on what these find at once."""
import os
import re

from wbtools import newlab_check as nl

ROOT = nl.ROOT


def fixture_file(rel):
    path = os.path.join(ROOT, nl.FIXTURE, rel)
    return path if os.path.exists(path) else path + ".in"


def test_every_break_finds_its_text_in_the_throwaway_lab():
    """Defect: an edit of the throwaway lab removes the text a break replaces: the stage
    then fails after its build, on a step that proves nothing about tools/pattern."""
    for stage, rel, old, _ in nl.BREAKS:
        with open(fixture_file(rel), encoding="utf-8") as f:
            assert old in f.read(), f"{stage}: {rel} lacks {old!r}"


def test_the_lab_line_and_the_readme_row_have_a_place():
    """Defect: CMakeLists.txt or the README's labs table changes shape and the stage cannot
    add the lab's one line or its row (it fails naming the file, but only after minutes)."""
    with open(os.path.join(ROOT, "CMakeLists.txt"), encoding="utf-8") as f:
        assert any(re.match(r"^wb_lab\(", ln) for ln in f)
    with open(os.path.join(ROOT, "README.md"), encoding="utf-8") as f:
        assert any(re.match(r"^\| `[a-z0-9_-]+` \|", ln) for ln in f)


def test_the_throwaway_lab_is_new_and_complete():
    """Defect: a real lab named like the throwaway one (the copy would refuse to add it), or
    a throwaway lab missing a part every lab has."""
    assert not os.path.exists(os.path.join(ROOT, "labs", nl.LAB))
    for rel in [f"labs/{nl.LAB}", f"solutions/{nl.LAB}", f"tests/{nl.LAB}", f"scenes/{nl.LAB}",
                f"framework/drivers/{nl.LAB}/main.cpp", f"handouts/{nl.LAB}.md.in"]:
        assert os.path.exists(os.path.join(ROOT, nl.FIXTURE, rel)), rel
