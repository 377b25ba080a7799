"""tools/view's reading and packing (tools/wbview: the trace, stats and summary into one page).
Guards against a run shown other than it ran (positions far from the origin rounded away, a
diverged run drawn as fine, steps invented), a page a scene's text can break, and bad input
that leaves a half-written page over a good one. Each test names the defect it guards."""
import base64
import json
import math
import os
import re
import struct
import subprocess
import sys

import pytest

TOOLS = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, TOOLS)

from wbview import cli, model, page  # noqa: E402
from wbview.data import InputError, particle_scene, read_summary, read_trace  # noqa: E402

ROOT = os.path.dirname(TOOLS)


def write(tmp_path, name, text):
    p = tmp_path / name
    p.write_text(text)
    return str(p)


def trace_2d(frames, n, dt=0.1, f=lambda k, i: (k + 0.5 * i, -k)):
    rows = ["t,id,x,y,vx,vy"]
    for k in range(frames):
        for i in range(n):
            x, y = f(k, i)
            rows.append(f"{k * dt!r},{i},{x!r},{y!r},0,0")
    return "\n".join(rows) + "\n"


def floats(b64):
    raw = base64.b64decode(b64)
    return struct.unpack(f"<{len(raw) // 4}f", raw)


# -- reading


def test_trace_read_frames_and_ids(tmp_path):
    """Rows are grouped into written steps of ids 0 ... n-1 (a wrong grouping would draw
    particle 3 of step k at particle 0 of step k+1)."""
    t = read_trace(write(tmp_path, "r.csv", trace_2d(4, 3)))
    assert (t.kind, t.n, t.frames) == ("particles", 3, 4)
    assert t.t == [0.0, 0.1, 0.2, 0.30000000000000004]
    assert t.at(2, 1, "x") == 2.5 and t.at(2, 1, "y") == -2


def test_trace_blocks_keep_frames_whole(tmp_path, monkeypatch):
    """A trace longer than one parsing block reads the same as one block (a block cut in
    the middle of a written step would shift every later id)."""
    monkeypatch.setattr("wbview.data.CHUNK_ROWS", 7)
    t = read_trace(write(tmp_path, "r.csv", trace_2d(9, 4)))
    assert t.frames == 9 and t.at(8, 3, "x") == 8 + 1.5


def test_trace_non_finite_values_are_kept(tmp_path):
    """A diverged run writes nan and inf: they are values to show as missing, not errors."""
    text = trace_2d(2, 1) + "0.2,0,nan,inf,0,0\n0.30000000000000004,0,-nan,-inf,0,0\n"
    t = read_trace(write(tmp_path, "r.csv", text))
    assert t.frames == 4 and math.isnan(t.at(2, 0, "x")) and t.at(3, 0, "y") == -math.inf


@pytest.mark.parametrize("text, says", [
    ("t,id,x,y\n0,0,1,2\n", "header is 't,id,x,y'"),
    ("t,id,x,y,vx,vy\n", "no data rows"),
    ("t,id,x,y,vx,vy\n0,0,1,2,0\n", ":2: 5 fields, expected 6"),
    ("t,id,x,y,vx,vy\n0,0,1,two,0,0\n", "row 2, column 'y': got 'two'"),
    ("t,id,x,y,vx,vy\n0,0,1,2,0,0\n0,1,1,2,0,0\n0.1,0,1,2,0,0\n0.1,2,1,2,0,0\n",
     "row 5: id 2, expected 1"),
    ("t,id,x,y,vx,vy\n0,0,1,2,0,0\n0,1,1,2,0,0\n0.1,0,1,2,0,0\n",
     "not a whole number of written steps"),
    ("t,id,x,y,vx,vy\n0,0,1,2,0,0\n0.1,1,1,2,0,0\n", "do not share one t"),
    ("t,id,x,y,vx,vy\n0.1,0,1,2,0,0\n0,0,1,2,0,0\n", "expected written steps in increasing time"),
])
def test_trace_bad_input_named(tmp_path, text, says):
    """Bad input gets one message naming the file and the row (docs/view.md)."""
    path = write(tmp_path, "bad.csv", text)
    with pytest.raises(InputError) as e:
        read_trace(path)
    assert path in str(e.value) and says in str(e.value)


def test_summary_is_the_last_line(tmp_path):
    """A saved stdout holds warnings before the summary: the last line is the summary."""
    p = write(tmp_path, "s.json", 'something\n{"status": "ok", "steps": 3}\n\n')
    assert read_summary(p)["steps"] == 3
    with pytest.raises(InputError, match="not a run's summary"):
        read_summary(write(tmp_path, "x.json", "[1, 2]\n"))


# -- the scene's drawable parts


def test_scene_counts_and_generated_springs():
    """Radii come in the loader's order (particles, emitters, rope, cloth), and the cloth's
    springs are the driver's: structural, shear, bend (framework/drivers/implicit)."""
    doc = {"particles": [{"x": [0, 0], "m": 1, "radius": 0.5}],
           "emitters": [{"count": 2, "min": [0, 0], "max": [1, 1], "m": 1, "radius": 0.1}],
           "cloth": {"origin": [0, 0], "rows": 3, "cols": 3, "spacing": 1, "m": 1, "k": 1,
                     "k_bend": 1, "pin": "top"}}
    s = particle_scene(doc, 12, "s.json")
    assert s["radii"][:3] == [0.5, 0.1, 0.1] and len(s["radii"]) == 12
    # 3x3: 12 structural, 8 shear, 6 bend
    assert len(s["springs"]) == 26 and s["pinned"] == [3, 4, 5]
    with pytest.raises(InputError, match="declares 12 particles, the trace has 11"):
        particle_scene(doc, 11, "s.json")


# -- packing


def test_kept_frames_bounded_with_first_and_last():
    """Decimation keeps the first and the last written step (a diverged run's last step is
    the one the student came to see)."""
    keep, k = model.kept_frames(1001, 10, 2000)
    assert keep[0] == 0 and keep[-1] == 1000 and k == 6 and len(keep) * 10 <= 2000 + 10
    assert model.kept_frames(5, 10, 2000) == ([0, 1, 2, 3, 4], 1)


def test_packed_positions_round_trip(tmp_path):
    """Positions are stored as float32 relative to the scene's centre: far from the origin
    they keep their digits (absolute float32 at x = 1e6 would be 6 cm coarse)."""
    t = read_trace(write(tmp_path, "r.csv", trace_2d(3, 2, f=lambda k, i: (1e6 + 1e-3 * k, i))))
    meta = model.build(t, None, None, None, None)
    got = floats(meta["runs"][0]["data"])
    ox, oy = meta["origin"]
    c = len(meta["cols"])
    assert abs(got[(2 * 2 + 0) * c] + ox - (1e6 + 2e-3)) < 1e-9  # frame 2, id 0, x
    assert abs(got[(2 * 2 + 1) * c + 1] + oy - 1) < 1e-9          # frame 2, id 1, y


def test_velocities_kept_unless_they_would_thin_the_steps(tmp_path):
    """Defect: a picked particle with no velocity although the page could hold it, or a
    large run that loses written steps to make room for velocities (positions come first)."""
    rows = ["t,id,x,y,vx,vy"] + [f"{0.1 * k!r},{i},{k},{i},{2.5 + k},-1" for k in range(3)
                                 for i in range(2)]
    t = read_trace(write(tmp_path, "v.csv", "\n".join(rows) + "\n"))
    meta = model.build(t, None, None, None, None)
    got = floats(meta["runs"][0]["data"])
    assert meta["cols"] == ["x", "y", "vx", "vy"] and got[(2 * 2 + 1) * 4 + 2] == 4.5
    small = model.MAX_STORED_VALUES
    try:
        model.MAX_STORED_VALUES = 3 * 2 * 3  # room for positions only
        meta = model.build(t, None, None, None, None)
    finally:
        model.MAX_STORED_VALUES = small
    assert meta["cols"] == ["x", "y"] and meta["runs"][0]["kept_every"] == 1


def test_step_numbers_from_stats_else_summary():
    """Defect: the viewer's step counter wrong or invented when the stats file is absent (the
    summary's steps, else the scene's dt, else no step numbers at all)."""
    times = [0.0, 0.5, 1.0]
    stats = {"t": times, "step": [0.0, 5.0, 10.0]}
    assert model.step_numbers(times, stats, None, None)[0] == [0, 5, 10]
    summary = {"steps": 10, "t": 1.0}
    assert model.step_numbers(times, None, summary, None)[0] == [0, 5, 10]
    assert model.step_numbers(times, None, None, {"dt": 0.1})[0] == [0, 5, 10]
    assert model.step_numbers(times, None, None, None)[0] is None


def test_frame_budget_from_cpu_s():
    """CPU per simulated 1/60 s = cpu_s / (60 t); the count that fits scales as n, or as
    the square root for O(n^2) forces (a linear rule would promise 100x too many bodies
    for newton at a 1 % share)."""
    s = {"status": "ok", "steps": 600, "t": 6.0, "cpu_s": 0.6}
    b = model.frame_budget(s, {"forces": [{"type": "gravity"}]}, 100, "particles")
    assert b["ms_per_frame"] == pytest.approx(1000 * 0.6 / 360)
    assert b["fit"] == math.floor(100 * (1000 / 60) / (1000 * 0.6 / 360))
    q = model.frame_budget(s, {"forces": [{"type": "newton"}]}, 100, "particles")
    assert q["fit"] == math.floor(100 * math.sqrt((1000 / 60) / (1000 * 0.6 / 360)))
    assert not model.frame_budget(dict(s, cpu_s=None), None, 1, "particles")["available"]


def test_difference_interpolates_and_stops_at_the_end(tmp_path):
    """The second run is compared at the first's times: linearly between its written steps,
    and not at all after it ended (a diverged second run is not 'zero apart')."""
    a = read_trace(write(tmp_path, "a.csv", trace_2d(5, 1, dt=0.1, f=lambda k, i: (0.0, 0.0))))
    b = read_trace(write(tmp_path, "b.csv", trace_2d(2, 1, dt=0.2, f=lambda k, i: (k * 2.0, 0.0))))
    d = model.difference(a, b)
    assert d["v"][:3] == [0.0, pytest.approx(1.0), pytest.approx(2.0)]
    assert d["v"][3:] == [None, None] and not d["identical"]


def test_exact_motion_not_for_scenes_with_planes():
    """The parabola ignores contacts: a ball bouncing on a plane has no exact overlay."""
    doc = {"particles": [{"x": [0, 1], "v": [1, 0], "m": 1}],
           "forces": [{"type": "gravity", "g": [0, -9.81]}]}

    class T:
        kind, n = "particles", 1
    assert model.exact_motion(doc, T())[0] == "parabola"
    walled = dict(doc, planes=[{"point": [0, 0], "normal": [0, 1]}])
    assert model.exact_motion(walled, T())[0] is None


# -- the page


def test_page_text_cannot_end_its_script(tmp_path):
    """A scene description holding '</script>' or '{{JS}}' must stay text in the page."""
    t = read_trace(write(tmp_path, "r.csv", trace_2d(2, 1)))
    doc = {"name": "x", "description": "</script><b>{{JS}}</b>",
           "particles": [{"x": [0, 0], "m": 1}]}
    meta = model.build(t, None, None, doc, "s.json")
    html = page.render(meta)
    assert html.count("</script>") == html.count("<script")
    m = re.search(r'id="wb-meta">(.*?)</script>', html, re.S)
    assert json.loads(m.group(1))["description"] == "</script><b>{{JS}}</b>"


def test_cli_writes_nothing_on_bad_input(tmp_path, capsys):
    """Exit 2 with one line, and no page written over a good one."""
    good = tmp_path / "v.html"
    good.write_text("good")
    bad = write(tmp_path, "bad.csv", "t,id\n")
    assert cli.main([bad, "-o", str(good)]) == 2
    assert good.read_text() == "good"
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("tools/view: error: ") and bad in err[0]


def test_cli_finds_stats_and_summary_beside(tmp_path):
    """Defect: `tools/view run.csv` ignores the run's stats and summary written beside it, so a
    diverged run is shown without its divergence."""
    run = write(tmp_path, "run.csv", trace_2d(3, 1))
    write(tmp_path, "run-stats.csv", "step,t,energy,kinetic,potential,px,py,force_evals\n"
          "0,0,1,1,0,0,0,0\n1,0.1,1,1,0,0,0,1\n2,0.2,1,1,0,0,0,2\n")
    write(tmp_path, "run-summary.json", '{"status":"diverged","diverged":"x","steps":2,"t":0.2,'
          '"cpu_s":0.001}\n')
    meta, what = cli.make_view(run, str(tmp_path / "v.html"))
    r = meta["runs"][0]
    assert r["steps"] == [0, 1, 2] and r["diverged"]["step"] == 2
    assert "run-stats.csv" in what and "run-summary.json" in what


def test_view_help_runs():
    """Defect: `tools/view --help` (what the README tells a student to run) fails or does not
    name its argument."""
    p = subprocess.run([sys.executable, os.path.join(ROOT, "tools", "view"), "--help"],
                       capture_output=True, text=True)
    assert p.returncode == 0 and "RUN.csv" in p.stdout


def test_summary_with_nan_still_makes_a_page(tmp_path):
    """Python reads NaN in a summary file; the page's JSON cannot hold it (a traceback
    instead of a page, for a hand-edited or foreign summary)."""
    run = write(tmp_path, "run.csv", trace_2d(2, 1))
    write(tmp_path, "run-summary.json", '{"status": "ok", "steps": 1, "t": 0.1, '
          '"energy": NaN, "momentum": [Infinity, 0]}\n')
    meta, _ = cli.make_view(run, str(tmp_path / "v.html"))
    assert meta["runs"][0]["summary"]["momentum"] == [None, 0]
