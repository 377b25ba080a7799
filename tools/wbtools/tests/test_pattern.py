"""tools/pattern's static stages (tools/wbtools/pattern.py: testnames; docrefs.py: docrefs):
one naming scheme for graded test files, and docs that quote the code truthfully. Guards
against a new test file named another way (a student looking for the tests of task F5 does
not find them), and docs that quote a flag, a signature or a path the code no longer has."""
import os

import pytest

from wbtools import docrefs, pattern

TASKS = ["F1", "F5"]
GOOD = 'TEST_CASE("F5 spring: the force is -k (L - rest)", "[forces][F5][6pts]") {}\n'


def findings(files, texts=None, tasks=TASKS):
    texts = texts or {}
    return pattern.test_name_findings("forces", files, tasks, lambda n: texts.get(n, GOOD))


def test_the_schemes_names_pass():
    """Defect: the check refuses the one scheme (a check that fails right code)."""
    assert findings(["test_F5_spring.cpp", "test_F1_uniform_gravity.cpp"],
                    {"test_F1_uniform_gravity.cpp": GOOD.replace("F5", "F1")}) == []


@pytest.mark.parametrize("name", ["explicit_euler_test.cpp", "test_spring.cpp",
                                  "test_F5_Spring.cpp", "test_F5-spring.cpp", "F5_spring.cpp"])
def test_other_schemes_fail(name):
    """Defect: a test file named another way (the three schemes the tree once had:
    test_F1_uniform_gravity.cpp, explicit_euler_test.cpp, ...) slips in."""
    out = findings([name, "test_F1_x.cpp", "test_F5_y.cpp"],
                   {"test_F1_x.cpp": GOOD.replace("F5", "F1")})
    assert len(out) == 1 and out[0].startswith(f"tests/forces/{name}: graded test files are named")


def test_a_file_for_an_unknown_task_or_a_task_without_a_file():
    """Defect: a file named after a task the lab does not have, or a task whose tests a
    student cannot find by its name."""
    out = findings(["test_F7_boids.cpp"], {"test_F7_boids.cpp": GOOD.replace("F5", "F7")})
    assert any("names task F7" in f for f in out)
    assert any("task F1 has no test file" in f for f in out)
    assert any("task F5 has no test file" in f for f in out)


def test_every_case_carries_its_files_task_tag():
    """Defect: a test of another task hidden in F5's file (filtered out of [F5] runs)."""
    text = GOOD + 'TEST_CASE("F5 damper " "along the spring",\n  "[forces][F1][4pts]") {}\n'
    out = findings(["test_F5_spring.cpp"], {"test_F5_spring.cpp": text}, ["F5"])
    assert out == ['tests/forces/test_F5_spring.cpp: test "F5 damper along the spring" lacks '
                   "the tag [F5] of the task its file is named after: tag it, or move it to "
                   "its task's file"]


@pytest.mark.parametrize("name", ["F5 spring, damped", "F5 spring; damped", "F5 spring [k]",
                                  " F5 spring", "F5 spring "])
def test_a_name_the_grader_refuses_is_found(name):
    """Defect: a test name the grader refuses (a , or ; or [ ]: Catch's test-spec syntax)
    passed tools/pattern and was found only when a lab was graded (a new lab's first
    tools/grade stopped with an internal error)."""
    text = GOOD.replace("F5 spring: the force is -k (L - rest)", name)
    assert any("the grader refuses" in f for f in findings(["test_F5_spring.cpp"],
                                                           {"test_F5_spring.cpp": text}))


def test_the_repositorys_labs_follow_the_scheme():
    """Defect: a lab of the repository breaks the scheme (every lab, present and future)."""
    assert pattern.stage_testnames(None, None, False) == []


def write(root, rel, text):
    path = os.path.join(root, rel)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)


@pytest.fixture
def repo(tmp_path):
    """A small repository: a Python tool, a bash tool, a lab header and the labs' CLI."""
    root = str(tmp_path)
    write(root, "tools/pack", "#!/usr/bin/env -S sh -c 'exec start-python'\n"
                              "from wbtools.pack import run\n")
    write(root, "tools/wbtools/pack.py", "import argparse\ndef run():\n"
          "    ap = argparse.ArgumentParser()\n    ap.add_argument('--verify')\n"
          "    ap.add_argument('-o', '--out')\n\ndef commands_of(text, strict=False):\n"
          "    pass\n")
    write(root, "tools/check", "#!/usr/bin/env bash\ncase $a in\n  --quick) ;;\n"
                               "  -h|--help) ;;\nesac\n")
    write(root, "labs/forces/spring.h", "#pragma once\nvoid spring_force(const Vec2& xi, "
                                        "const Vec2& xj, double k, Vec2& f);\n")
    write(root, "framework/src/cli.cpp", 'app.add_option("--scene", s);\n'
                                         'app.add_option("-o,--out", o);\n')
    return root


def doc_findings(root, text):
    write(root, "docs/x.md", text)
    return docrefs.check(root, ["docs/x.md"])


def test_flags_of_tools_and_lab_executables(repo):
    """Defect: a doc quotes a flag a tool or a lab executable does not have (renamed, removed,
    or never there): the reader's command fails."""
    found, counts = doc_findings(repo, "Run `tools/pack --verify --out p`, then\n```sh\n"
                                       "tools/check --quick --fast\nbuild/bin/forces --scene "
                                       "s.json --seed 3\nbuild/bin/forces-tests --list-tests\n"
                                       "```\n")
    assert counts["flags"] == 6
    assert [f.split(": ", 1)[1].split(":")[0] for f in found] == [
        "`tools/check --fast`", "`build/bin/forces --seed`"]


def test_calls_quote_the_headers_parameters_and_the_codes_arity(repo):
    """Defect: a doc quotes a task function with other arguments than its header (a student
    writes the wrong signature) or a tool's function with an old signature (the hint hook's
    hints_for once did)."""
    found, counts = doc_findings(repo, "`spring_force(xi, xj, k, f)` `spring_force(xi, k, f)`"
                                       " `commands_of(text)` `pack.commands_of(a, b, c)` "
                                       "`commands_of(text, loose=True)` `sqrt(x)` "
                                       "`commands_of(a, ...)`\n")
    assert counts["calls"] == 5 and len(found) == 3
    assert "the header declares spring_force(xi, xj, k, f)" in found[0]
    assert "pack.commands_of(a, b, c)" in found[1] and "loose=True" in found[2]


def test_paths_and_links_must_exist(repo):
    """Defect: a doc names a file that moved or never existed (the tools' modules moved to
    tools/wbtools/; a stale framework/src path was found this way)."""
    found, counts = doc_findings(repo, "`tools/pack` `tools/report` `labs/<lab>/spring.h` "
                                       "`labs/L/*.cpp` `framework/src/gone.cpp` [a](../tools/check)"
                                       " [b](missing.md) [c](https://x.org)\n")
    assert counts["paths"] == 7
    assert len(found) == 4 and "`tools/report`" in found[0] and "labs/L/*.cpp" in found[1]
    assert "gone.cpp" in found[2] and "missing.md" in found[3]


def test_every_doc_of_the_repository_is_covered():
    """Defect: a Markdown file the check never reads (a new doc, a README in a folder)."""
    docs = docrefs.markdown_files()
    for must in ("README.md", "docs/grading.md", "handouts/euler.md", "tools/pack.d/README.md",
                 "tools/gradescope/README.md", "fuzz/README.md"):
        assert must in docs


# Test files written before the rule was checked, whose tests do not all have a docstring
# yet: the rule holds for every other file, and for any new one.
WITHOUT_DOCSTRINGS = {"tools/wbplot/tests/test_figure_rules.py", "tools/wbview/tests/test_view.py"}


def test_every_unit_test_names_the_defect_it_guards():
    """Defect: a unit test that does not say which defect class it guards (then nobody can
    tell whether it still guards anything when the code moves)."""
    import ast
    import glob
    root = os.path.dirname(docrefs.TOOLS)
    missing = []
    for path in sorted(glob.glob(os.path.join(docrefs.TOOLS, "*", "tests", "test_*.py"))):
        rel = os.path.relpath(path, root)
        if rel in WITHOUT_DOCSTRINGS:
            continue
        with open(path, encoding="utf-8") as f:
            tree = ast.parse(f.read(), path)
        missing += [f"{rel}: {node.name}" for node in tree.body
                    if isinstance(node, ast.FunctionDef) and node.name.startswith("test_")
                    and not (ast.get_docstring(node) or "").strip()]
    assert missing == []


def test_points_that_do_not_add_up_or_disagree_with_the_handout_are_found():
    """Defect: two branches that each keep 100 points merge into 102 (issue 29's held-out tests
    and issue 36's new ones did), found only when a CI run grades; or a handout heading keeps a
    task's old points."""
    handout = "## F1 Gravity (60 points)\n\n## F2 Springs (40 points)\n"
    assert pattern.points_findings("forces", {"F1": 60, "F2": 40}, handout) == []
    merged = pattern.points_findings("forces", {"F1": 60, "F2": 42}, handout)
    assert any("add up to 102, expected 100" in f for f in merged)
    assert any("'## F2' says 40 points" in f and "carry 42" in f for f in merged)
    missing = pattern.points_findings("forces", {"F1": 60, "F2": 40}, "## F1 Gravity (60 points)")
    assert missing == ["handouts/forces.md: no heading '## F2 ... (40 points)'"]


def test_points_lists_are_the_tests_tags_held_out_included():
    """Defect (issue 44): the handouts' points disagreed with the grader's (17 of 44 forces tests;
    F5's list added up to 16 of its 15), the held-out tests were not listed at all, and three
    labs had no list: students quote the handout to their TA."""
    tests = {"F1": [("F1 gravity: m g", 3, False), ("F1 held-out: random masses", 2, True)],
             "F2": [("F2 pairs: G m m / r^2", 5, False)]}
    text = ("## F1 Gravity (5 points)\n\nProse.\n\n<a id=\"f2\"></a>\n## F2 Pairs (5 points)\n\n"
            "Prose.\n\n## Questions\n")
    written = pattern.points_write("forces", text, tests)
    assert pattern.points_list_findings("forces", written, tests) == []
    assert written.index("<!-- points F1") < written.index('<a id="f2">')
    assert written.index("<!-- points F2") < written.index("## Questions")
    assert "- `F1 held-out: random masses` (2, held-out)" in written
    assert "The other 3 points count only when the held-out test passes" in written
    assert "count only when" not in written[written.index("<!-- points F2"):]  # no held-out
    assert pattern.points_write("forces", written, tests) == written  # stable
    # One number changed in the handout, or in a tag: both fail, naming the line.
    edited = written.replace("m g` (3)", "m g` (4)")
    found = pattern.points_list_findings("forces", edited, tests)
    assert len(found) == 1 and "(4)" in found[0] and "(3)" in found[0]
    retagged = dict(tests, F1=[("F1 gravity: m g", 4, False), tests["F1"][1]])
    assert pattern.points_list_findings("forces", written, retagged)
    assert pattern.points_list_findings("forces", text, tests)  # no lists at all


def test_every_handout_lists_its_tests_points():
    """The repository's handouts agree with their tests' tags (tools/pattern points)."""
    assert pattern.stage_points(None, None, False) == []


# nanfree: a comparison an infinity or a NaN passes (docs/grading.md, "Every value from the
# worker is hostile").

def nanfree_findings(tmp_path, body):
    p = tmp_path / "test_F5_spring.cpp"
    p.write_text(body)
    return pattern.lint_nanfree(str(p))


@pytest.mark.parametrize("assertion", [
    "REQUIRE(energy > E0);",            # +inf passes
    "REQUIRE(turn * omega < 0);",       # -inf passes
    "CHECK(x != x0);",                  # NaN passes
    "REQUIRE(static_cast<double>(r) >= 1.0);",
])
def test_an_ordering_comparison_of_raw_values_is_refused(tmp_path, assertion):
    """Defect: a submission returning +inf (or -inf, or NaN) passes an assertion that orders
    a raw value against a bound (issue 42: a forces submission of infinities scored 66)."""
    out = nanfree_findings(tmp_path, f'TEST_CASE("F5 x", "[F5]") {{\n  {assertion}\n}}\n')
    assert len(out) == 1 and out[0][0] == 2 and "wbtest::finite" in out[0][1]


@pytest.mark.parametrize("assertion", [
    "REQUIRE(wbtest::finite(energy) > E0);",
    "REQUIRE(wbtest::max_abs_diff(a, b) <= tol);",
    "REQUIRE(wbtest::worst_of(w, x) < 1);",
    "REQUIRE(k < A.nonZeros());  // nanfree: integers",
    "REQUIRE(near(a, b, 1e-9));",
    "REQUIRE(std::vector<int>(3).size() == 3);",
])
def test_guarded_or_explained_comparisons_pass(tmp_path, assertion):
    """Defect: the check refuses a comparison that no infinity can pass (a check that fails
    right code), or one whose sides are all integers and says so."""
    assert nanfree_findings(tmp_path, f'TEST_CASE("F5 x", "[F5]") {{\n  {assertion}\n}}\n') == []
