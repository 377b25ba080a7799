"""The student pack's rules (tools/wbtools/pack.py) and the Gradescope zip's
(tools/gradescope/make_zip.py): which files ship, how the README and the handouts are made,
what --verify reads. A pack that drops a file its tools need fails only after a full CI run
(68 minutes, the first time: a path filter matched "build" and dropped tools/grader/build.py);
a pack that ships an answer cannot be taken back."""
import ast
import json
import os
import subprocess
import sys

import pytest

from wbtools import pack

ROOT = pack.ROOT
TOOLS = os.path.join(ROOT, "tools")
LABS = pack.known_labs()
ALL = set(LABS)


def repo_files(*tops):
    """Every file under the given top-level folders of the checkout, relative, skipping build
    trees and byte code (what the pack's own walk sees)."""
    out = []
    for top in tops:
        for d, dirs, names in os.walk(os.path.join(ROOT, top)):
            dirs[:] = [x for x in dirs if not x.startswith("build") and x != "__pycache__"]
            out += [os.path.relpath(os.path.join(d, n), ROOT) for n in names]
    return sorted(out)


def ships(rel, labs=ALL):
    return pack.shipped(rel, labs, ALL)


def test_every_file_of_the_student_tools_ships():
    """Defect: a path filter drops a file the student tools need (the pack once dropped
    tools/grader/build.py because a filter for build trees matched the name "build")."""
    for rel in repo_files("tools"):
        top = rel.split(os.sep)[1]
        if top in pack.STUDENT_TOOLS and f"{os.sep}tests{os.sep}" not in rel \
                and not rel.endswith(".pyc"):
            assert ships(rel), f"{rel} is a student tool's file but the pack leaves it out"
    assert ships(os.path.join("tools", "grader", "build.py"))


@pytest.mark.parametrize("rel", [
    "build/bin/euler", "build-debug/x.o", "labs/euler/build/CMakeCache.txt",
    "solutions/euler/explicit_euler.cpp", "tests/mutants/euler/explicit_euler.sign.patch",
    "tests/mutants/euler/alternatives/explicit_euler.loop.cpp", "tests/hostile/x/case.json",
    "tests/badinput/run_badinput.py", "bench/bench_step.cpp", "fuzz/fuzz_scene.cpp",
    ".ci/run", "tools/pack", "tools/wbtools/pack.py", "tools/mutants", "tools/check",
    "tools/gradescope/make_zip.py", "tools/pack.d/README.md", "tools/grader/tests/test_x.py",
    "tools/grader/__pycache__/build.cpython-311.pyc", "labs/euler/explicit_euler.cpp.orig",
    "docs/grading.md", "docs/benchmarks.md"])
def test_answers_instructor_material_and_build_trees_never_ship(rel):
    """Defect: a solution, a mutant (a known answer), instructor tools or docs, a build tree
    or the tools' own unit tests end up in the student pack."""
    assert not ships(rel)


def test_the_hints_data_ships_but_not_the_mutants():
    """Defect: the grader's hints lose their data in the pack (signatures.json left out), or
    the mutants that made it come along."""
    assert ships("tests/mutants/euler/signatures.json", {"euler", "forces"})
    assert not ships("tests/mutants/rigid/signatures.json", {"euler", "forces"})


def test_a_lab_pack_holds_its_labs_and_no_others():
    """Defect: a pack of one lab ships another lab's files (its tests, scenes, driver, handout,
    report plug-in), or leaves out a lab it depends on."""
    labs = pack.with_deps(["euler"], LABS)
    assert labs == {"euler", "forces"}
    for rel in ["labs/forces/gravity.h", "tests/euler/test_E1_explicit_euler.cpp",
                "scenes/euler/oscillator.json", "handouts/euler.md", "tests/common/test_helpers.h",
                "framework/drivers/euler/main.cpp"]:
        assert ships(rel, labs), rel
    for rel in ["labs/rigid/inertia.cpp", "tests/rigid/test_R1_inertia.cpp", "scenes/rigid/a.json",
                "handouts/rigid.md", "framework/drivers/rigid/main.cpp",
                "tools/wbplot/labs/rigid.py"]:
        assert not ships(rel, labs), rel


def imports_of(path):
    """The modules a Python file imports: (name, level) pairs; relative ones with level > 0."""
    with open(path, encoding="utf-8") as f:
        tree = ast.parse(f.read(), path)
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            out += [(a.name, 0) for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            out += [(node.module or "", node.level)] + \
                [((node.module + "." if node.module else "") + a.name, node.level)
                 for a in node.names]
    return out


def python_files(selected):
    """The Python files among `selected`: *.py, and the entries that start with Python."""
    def entry(rel):
        with open(os.path.join(ROOT, rel), "rb") as f:
            return b"python" in f.readline()
    return [rel for rel in selected if rel.endswith(".py") or (
        rel.startswith("tools/") and "." not in os.path.basename(rel) and entry(rel))]


def unresolved_imports(selected):
    """Imports of the selected Python files that resolve to a project module outside the
    selection: [(file, module)]."""
    have = set(selected)
    missing = []
    for rel in python_files(selected):
        for name, level in imports_of(os.path.join(ROOT, rel)):
            if level:
                base = os.path.dirname(rel)
                for _ in range(level - 1):
                    base = os.path.dirname(base)
            else:
                base = "tools"
            parts = [p for p in name.split(".") if p]
            cands = [os.path.join(base, *parts[:k]) for k in range(len(parts), 0, -1)]
            found = next((c for c in cands if os.path.isfile(os.path.join(ROOT, c + ".py"))
                          or os.path.isdir(os.path.join(ROOT, c))), None)
            if found is None:
                continue  # the standard library or matplotlib
            target = found + ".py" if os.path.isfile(os.path.join(ROOT, found + ".py")) \
                else os.path.join(found, "__init__.py")
            if target not in have:
                missing.append((rel, name))
    return missing


def test_the_packs_python_imports_only_what_the_pack_holds():
    """Defect: a student tool imports a module the pack leaves out (an instructor module in
    tools/wbtools/, a new grader file under a filtered name): tools/grade or tools/plot
    would stop with an ImportError on the student's machine."""
    selected = [rel for rel in repo_files("tools") if ships(rel)]
    assert "tools/grade" in selected and "tools/plot" in selected
    assert unresolved_imports(selected) == []


def test_the_gradescope_zip_holds_what_the_grader_imports():
    """Defect: the autograder zip leaves out a grader file (Gradescope reports an autograder
    failure for every submission), or ships the tools' unit tests, other labs' tests or the
    mutants."""
    sys.path.insert(0, os.path.join(TOOLS, "gradescope"))
    import make_zip
    files = [rel for rel in repo_files("tools", "tests") if make_zip.wanted(rel, "euler")]
    assert "tools/grader/build.py" in files and "tools/diagnosis/hints.py" in files
    assert "tests/mutants/euler/signatures.json" in files
    assert not [f for f in files if f.startswith(("tests/rigid/", "tools/grader/tests/"))
                or f.endswith(".patch")]
    assert unresolved_imports(files) == []


def test_known_labs_reads_deps_up_to_the_next_keyword(tmp_path, monkeypatch):
    """Defect: a keyword after DEPS (TEST_UNITS 2) read as a lab the pack must ship, or a lab
    without a folder listed."""
    (tmp_path / "CMakeLists.txt").write_text(
        "wb_lab(forces)\nwb_lab(implicit DEPS forces euler TEST_UNITS 2)\n  wb_lab( euler DEPS "
        "forces)\nwb_lab(ghost)\n")
    for lab in ("forces", "implicit", "euler"):
        (tmp_path / "labs" / lab).mkdir(parents=True)
    monkeypatch.setattr(pack, "SRC", str(tmp_path))
    assert pack.known_labs() == {"forces": [], "implicit": ["forces", "euler"],
                                 "euler": ["forces"]}


def test_readme_commands_join_continuations_and_skip_blank_lines():
    """Defect: --verify runs a half command (a line continued with a backslash split in two)
    or misses a block, so a README command that fails goes unnoticed."""
    text = ("intro\n```sh\ntools/setup   # install\n\ncmake --preset default \\\n"
            "  && cmake --build --preset default\n```\nprose\n```\nnot sh\n```\n"
            "```sh\nbuild/bin/euler --help\n```\n")
    assert [" ".join(c.split()) for c in pack.commands_of(text)] == [
        "tools/setup # install", "cmake --preset default && cmake --build --preset default",
        "build/bin/euler --help"]


def test_the_instructor_readme_has_a_row_for_every_lab():
    """Defect: a new lab without a row in the README's lab table gets an empty topic and task
    list in the pack's README."""
    rows = pack.lab_rows()
    for lab in LABS:
        assert lab in rows and all(rows[lab]), lab


def test_the_pack_readme_is_complete_for_every_lab():
    """Defect: a placeholder left in the pack's README, a lab table that lists labs the pack
    lacks, or example commands naming another lab than the one featured."""
    for lab in LABS:
        labs = pack.with_deps([lab], LABS)
        text = pack.make_readme(labs, list(LABS), featured=lab)
        assert "{" not in text.replace("${", ""), lab
        table = [line for line in text.splitlines() if line.startswith("| `") and "](handouts/" in line]
        assert sorted(line.split("`")[1] for line in table) == sorted(labs)
        assert f"build/bin/{lab} --help" in text


def test_handouts_lose_instructor_blocks_and_claim_markers_and_keep_figures():
    """Defect: an instructor paragraph (how the answer is checked) or a claim marker reaches
    students, or a figure link points at the instructor's build."""
    text = ("Intro.<!-- instructor --> secret how-to <!-- /instructor -->\nIt grows <!-- claim: "
            "stats euler/x energy ratio > 1 -->.\n![fig](../build/report/euler/orbit.png)\n")
    out, figures = pack.pack_handout(text, "/r")
    assert "secret" not in out and "claim" not in out
    assert "](figures/euler/orbit.png)" in out
    assert figures == [("/r/euler/orbit.png", "figures/euler/orbit.png")]
    listed = ("<!-- points E1: written by tools/pattern points --write -->\nTests:\n\n- `E1 x` (3)\n"
              "<!-- /points -->\n")
    assert pack.pack_handout(listed, "/r")[0] == "Tests:\n\n- `E1 x` (3)\n"  # the list, no markers


def test_shared_docs_drop_only_sections_of_labs_not_packed():
    """Defect: a student doc keeps a section about a lab the pack lacks (its commands fail),
    or drops a section of a packed lab."""
    text = "# Doc\n## Top\na\n## The rigid lab\nr\n### detail\nr2\n## collisions\nc\n## End\ne"
    out = pack.drop_other_labs(text, {"collisions"}, ALL)
    assert "r2" not in out and "## The rigid lab" not in out
    assert "## collisions\nc" in out and "## End\ne" in out


def test_a_doc_keeps_no_row_or_command_of_a_lab_the_pack_lacks():
    """Defect: docs/live.md's example `tools/view --live --lab euler` and its table's row of
    every lab shipped in a pack of forces alone: a command that fails in the pack."""
    text = ("```\ntools/view --live --lab euler       # writes build/live/euler.html\n```\n"
            "| lab | try |\n|---|---|\n| forces | f |\n| euler | e |\n| `rigid` | r |\n\n"
            "| key | type |\n|---|---|\n| `euler` | a key named as a lab |\n")
    out = pack.drop_other_labs(text, {"forces"}, ALL, "forces")
    assert "tools/view --live --lab forces       # writes build/live/forces.html" in out
    assert "| forces | f |" in out and "| euler |" not in out and "rigid" not in out
    assert "| `euler` | a key named as a lab |" in out  # not a table of labs: kept
    kept = pack.drop_other_labs(text, {"forces", "euler"}, ALL, "forces")
    assert "--lab euler" in kept and "| euler | e |" in kept


def test_check_references_reports_what_does_not_resolve(tmp_path):
    """Defect: --verify misses a link or a named path that the pack does not hold."""
    (tmp_path / "docs").mkdir()
    (tmp_path / "tools").mkdir()
    (tmp_path / "tools" / "grade").write_text("")
    (tmp_path / "README.md").write_text(
        "[ok](docs) [web](https://x.org) [gone](docs/gone.md) `tools/grade` `tools/report` "
        "`build/bin/euler` `build/bin/rigid`\n")
    problems = pack.check_references(str(tmp_path), {"euler"})
    assert len(problems) == 3
    assert any("docs/gone.md" in p for p in problems)
    assert any("`tools/report`" in p for p in problems)
    assert any("`build/bin/rigid`" in p for p in problems)


def _clone(tmp_path):
    """A clone of this checkout's HEAD (objects shared: fast), as an instructor's checkout."""
    clone = tmp_path / "clone"
    subprocess.run(["git", "clone", "--quiet", "--shared", ROOT, str(clone)], check=True)
    for k, v in (("user.name", "t"), ("user.email", "t@t")):
        subprocess.run(["git", "-C", str(clone), "config", k, v], check=True)
    return clone


def test_the_pack_is_made_from_head_never_the_work_tree(tmp_path, monkeypatch, capsys):
    """Defect (issue 44): an instructor tried an exercise in labs/ (F5 written, a file added)
    and tools/pack shipped those files to every student, with no warning."""
    monkeypatch.setattr(pack, "SRC", pack.SRC)  # restored after the test
    clone = _clone(tmp_path)
    spring = clone / "labs" / "forces" / "spring.cpp"
    skeleton = spring.read_text()
    spring.write_text(skeleton + "\n// an instructor's try: the F5 answer\n")
    (clone / "labs" / "forces" / "scratch.cpp").write_text("// not committed\n")
    (tmp_path / "t").mkdir()
    _, stage, _, labs, _ = pack.stage_committed(str(clone), str(tmp_path / "t"), ["forces"],
                                                str(clone / "build" / "report"))
    assert labs == {"forces"}
    assert open(os.path.join(stage, "labs", "forces", "spring.cpp")).read() == skeleton
    assert not os.path.exists(os.path.join(stage, "labs", "forces", "scratch.cpp"))
    said = capsys.readouterr().out
    assert "labs/forces/spring.cpp" in said and "labs/forces/scratch.cpp" in said


def test_figures_are_reused_only_when_drawn_from_heads_inputs(tmp_path, capsys):
    """Defect (issue 44): tools/pack ran the whole tools/report (six minutes) every time, and
    would have drawn uncommitted edits of a solution into the handouts' figures."""
    clone = _clone(tmp_path)
    report = clone / "build" / "report"
    (report / "forces").mkdir(parents=True)
    head = subprocess.run(["git", "-C", str(clone), "rev-parse", "HEAD"], check=True,
                          stdout=subprocess.PIPE).stdout.decode().strip()
    section = {"lab": "forces", "failures": [], "source": {"commit": head, "uncommitted": []}}
    (report / "forces" / "section.json").write_text(json.dumps(section))
    pack.current_figures({"forces"}, str(report), str(clone))  # current: nothing to draw
    assert "current for HEAD" in capsys.readouterr().out
    # A commit that changes a solution: the figures are no longer HEAD's.
    sol = clone / "solutions" / "forces" / "spring.cpp"
    sol.write_text(sol.read_text() + "\n")
    subprocess.run(["git", "-C", str(clone), "commit", "--quiet", "-am", "t"], check=True)
    assert "changed since commit" in pack.report_not_current(str(report), {"forces"},
                                                             str(clone))["forces"]
    # ... and with an uncommitted edit to what the report draws from, it cannot draw them.
    sol.write_text(sol.read_text() + "// uncommitted\n")
    with pytest.raises(pack.PackError, match="solutions/forces/spring.cpp"):
        pack.current_figures({"forces"}, str(report), str(clone))
    # A drawing made with uncommitted edits is never current.
    section["source"]["uncommitted"] = ["solutions/forces/spring.cpp"]
    (report / "forces" / "section.json").write_text(json.dumps(section))
    assert "uncommitted" in pack.report_not_current(str(report), {"forces"}, str(clone))["forces"]
