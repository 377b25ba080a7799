"""tools/live-check --pack's student edits: they apply to the skeleton files the pack ships.
Guards against a check that edits nothing (the skeleton's region changed shape, and the
student's force is never written) and one that passes a page whose gravity was not turned."""
import os
import shutil
import sys

import pytest

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

from wbtools import live_pack  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__)))))


def test_student_edits_fill_the_skeletons_and_flip_gravity(tmp_path):
    """F6 and F1 written into labs/forces' own skeletons, then gravity's sign turned once."""
    for name, body in live_pack.STUDENT.items():
        path = tmp_path / name
        shutil.copy(os.path.join(ROOT, "labs", live_pack.LAB, name), path)
        live_pack.fill(str(path), body)
        text = path.read_text()
        assert body in text and "(void)" not in text
    live_pack.replace_once(str(tmp_path / "uniform_gravity.cpp"), *live_pack.FLIP)
    assert live_pack.FLIP[1] in (tmp_path / "uniform_gravity.cpp").read_text()


def test_an_edit_that_finds_nothing_to_edit_fails(tmp_path):
    """A file without the skeleton's region, or a flip that is not there once: an error."""
    path = tmp_path / "f.cpp"
    path.write_text("void f() {}\n")
    with pytest.raises(live_pack.PackLiveError):
        live_pack.fill(str(path), "  x;\n")
    with pytest.raises(live_pack.PackLiveError):
        live_pack.replace_once(str(path), *live_pack.FLIP)
