"""The rules that keep figures and claims honest (issue 32): flat.py, runinfo.py, scene3d.py,
figcheck.py, claimrules.py. Each test draws or states the wrong thing and expects the check
to say so, and the right thing and expects silence. Run: python3 -m pytest tools/wbplot/tests
"""
import json
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(os.path.dirname(HERE)))  # tools/, for `import wbplot`

from wbplot import claimrules, figcheck, figfacts, flat, runinfo, scene3d  # noqa: E402
from wbplot.claims import Claim  # noqa: E402
from wbplot.common import new_figure, save_figure  # noqa: E402


def _facts(tmp_path, draw, name="f.png"):
    """Draws with `draw(fig)` and saves while recording: the figure's facts."""
    fig, ax = new_figure()
    draw(fig, ax)
    out = os.path.join(tmp_path, name)
    with figfacts.recording() as seen:
        save_figure(fig, out)
    return seen[os.path.abspath(out)]


# ---- constant to rounding


def test_rounding_noise_is_constant_and_motion_is_not():
    """Defect: a flat line of rounding noise drawn as motion (its axis zoomed to 1e-18), or a real
    drift of 1e-8 called constant and hidden."""
    assert flat.is_constant([1e-18, -3e-18, 2e-18])          # 0 to rounding
    assert flat.is_constant([4.905, 4.905 + 1e-15], 5.0)      # a constant energy
    assert not flat.is_constant([0.0, 1e-6])                  # a micrometre is motion
    assert not flat.is_constant([1.0, 1.0 + 1e-8])            # a drift above rounding
    assert flat.label([1e-18, -1e-18], "rad/s") == " = 0 rad/s (to rounding)"


def test_an_axis_zoomed_into_noise_is_found_and_a_flat_view_is_not(tmp_path):
    """Defect: a figure whose axis matplotlib zoomed into rounding noise passes the check, so a
    quantity at rest looks like it oscillates."""
    noise = [1e-18 * math.sin(k) for k in range(50)]

    def raw(fig, ax):
        ax.plot(range(50), noise)
        ax.set_ylabel("ω (rad/s)")

    def settled(fig, ax):
        ax.plot(range(50), noise)
        ax.set_ylabel("ω (rad/s)")
        flat.flat_view(ax, [noise])
    assert figcheck.check_rounding(_facts(tmp_path, raw))
    assert not figcheck.check_rounding(_facts(tmp_path, settled))


# ---- diverged and stub, from the summary


def test_diverged_words_need_a_diverged_run(tmp_path):
    """Defect: a figure says a run blew up when its summary says it did not (issue 32's false
    'a run blew up'), or the flow's 'divergence' taken for a verdict on a run."""
    def said(fig, ax):
        ax.plot([0, 1], [0, 1])
        ax.set_title("log scale: a run blew up")
    facts = _facts(tmp_path, said)
    assert figcheck.check_diverged(facts, 0)
    assert not figcheck.check_diverged(facts, 1)
    # "divergence" of a flow is not a verdict on a run
    assert not figcheck.DIVERGED_WORDS.search("the divergence of u, rms 4e-2")


def test_a_stub_run_is_marked_on_its_figure(tmp_path):
    """Defect: a run its summary calls a stub drawn as if it were physics, with no STUB mark."""
    stub = {"status": "ok", "steps": 3, "stub": True, "warnings": ["C1 is still a stub?"]}
    runinfo.CURRENT = [stub]
    try:
        facts = _facts(tmp_path, lambda fig, ax: ax.plot([0, 1], [0, 1]))
    finally:
        runinfo.CURRENT = []
    assert not figcheck.check_stub(facts, True)
    plain = _facts(tmp_path, lambda fig, ax: ax.plot([0, 1], [0, 1]), "g.png")
    assert figcheck.check_stub(plain, True)


def test_summary_file_is_the_last_line_of_a_run_stdout(tmp_path):
    """Defect: a summary saved with `| tee` (warnings before it, blank lines after) is not read,
    so the figure cannot know the run diverged or was a stub."""
    p = os.path.join(tmp_path, "run-summary.json")
    with open(p, "w") as f:
        f.write("noise\n" + json.dumps({"status": "diverged", "steps": 7}) + "\n\n")
    s = runinfo.read_summary(p)
    assert s["steps"] == 7


# ---- pictures of bodies


def _box3d(fig, ax_unused, lims, scene=None, plane_first=True):
    fig.clf()
    ax = fig.add_subplot(1, 1, 1, projection="3d")
    body = [((-0.5, -0.1, 0.0), (0.5, 0.1, 1.0))]
    box = scene3d.view_box([p for seg in body for p in seg])
    if scene is not None:
        scene3d.draw_geometry(ax, scene, box)
    scene3d.draw_lines(ax, body, ["k"])
    scene3d.setup(ax, box, scene)
    if lims:
        ax.set_xlim(-lims, lims)
        ax.set_ylim(-lims, lims)
        ax.set_zlim(-lims, lims)
    if not plane_first:
        ax.computed_zorder = True


def test_a_view_much_larger_than_the_bodies_is_found(tmp_path):
    """Defect: a 3D picture whose view box dwarfs the bodies (they shrink to a dot) passes."""
    good = _facts(tmp_path, lambda f, a: _box3d(f, a, None))
    cube = _facts(tmp_path, lambda f, a: _box3d(f, a, 10.0), "cube.png")
    assert not [x for x in figcheck.check_frames(good) if "view spans" in x]
    assert [x for x in figcheck.check_frames(cube) if "view spans" in x]


def test_planes_and_hinges_are_drawn_where_the_scene_puts_them(tmp_path):
    """Defect: a scene's plane or hinge missing from its picture, or painted over the bodies in
    mplot3d's own depth order, passes."""
    scene = {"planes": [{"point": [0, 0, 0], "normal": [0, 0, 1]}],
             "hinges": [{"body": 0, "anchor": [0, 0, 0.5], "axis": [0, 0, 1]}]}
    facts = _facts(tmp_path, lambda f, a: _box3d(f, a, None, scene))
    assert not figcheck.check_frames(facts, scene)
    # the scene's geometry absent from the picture, or painted in mplot3d's own order
    bare = _facts(tmp_path, lambda f, a: _box3d(f, a, None), "bare.png")
    assert any("not drawn" in x for x in figcheck.check_frames(bare, scene))
    sorted_ = _facts(tmp_path, lambda f, a: _box3d(f, a, None, scene, False), "z.png")
    assert any("painted over" in x for x in figcheck.check_frames(sorted_, scene))


def test_plane_polygon_lies_in_its_plane_and_in_the_box():
    """Defect: a tilted plane drawn off its own plane or outside the view box; a plane outside the
    box drawn anyway."""
    box = ((-1, -1, -1), (1, 1, 1))
    n = (-0.5, 0.0, math.sqrt(3) / 2)
    poly = scene3d.plane_polygon((0, 0, 0.2), n, box)
    assert len(poly) >= 3
    for p in poly:
        assert abs(sum((c - o) * k for c, o, k in zip(p, (0, 0, 0.2), n))) < 1e-12
        assert all(-1 - 1e-12 <= c <= 1 + 1e-12 for c in p)
    assert scene3d.plane_polygon((0, 0, 5), (0, 0, 1), box) == []


# ---- claims


def test_a_timing_claim_needs_a_margin_of_two():
    """Defect: a timing claim that holds by less than a factor 2 (it flips on a loaded or another
    machine, as '> 2 at k/m = 1e2' did on a fresh one) is accepted."""
    c = Claim("t", "summary implicit/x cpu_s > 1", "")
    assert claimrules.margin_problem(c, 1.4)
    assert not claimrules.margin_problem(c, 2.5)
    c = Claim("t", "summary implicit/x cpu_s in [1, 10]", "")
    assert claimrules.margin_problem(c, 1.5) and not claimrules.margin_problem(c, 3.0)
    assert not claimrules.margin_problem(Claim("t", "summary a/b energy > 1", ""), 1.01)


def test_a_rest_sentence_needs_a_claim_on_positions(tmp_path):
    """Defect: a sentence about rest or motion ('never come to rest', 'wanders') with no claim
    that checks it against the run's positions or energy."""
    p = os.path.join(tmp_path, "h.md")
    with open(p, "w") as f:
        f.write("In `column` the discs never come to rest "
                "<!-- claim: csv collisions/column-rest.csv speed_max max > 0.01 -->.\n\n"
                "In `column` the column stands still "
                "<!-- claim: csv collisions/column-rest.csv moved_max max < 1e-6 -->.\n\n"
                "The energy wanders by a percent in `nbody`.\n")
    found = claimrules.lint_motion(p, {"column", "nbody"})
    assert [ln for ln, _ in found] == [1]
