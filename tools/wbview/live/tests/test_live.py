"""The live pages' Python side (tools/wbview/live: the build, the recorded runs, the page). Guards
against a page a scene's text can break, a recorded run that shows other positions or steps
than the run had, a student without emscripten told nothing useful, a build that cannot find
Debian's node modules, and a page that needs the network. Each test names the defect it
guards. (The pages themselves are opened in Chromium by tools/live-check.)"""
import base64
import json
import os
import struct
import sys

TOOLS = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__)))))
sys.path.insert(0, TOOLS)

from wbview.live import build, cli, page, recorded  # noqa: E402
from wbview.data import read_stats, read_trace  # noqa: E402

ROOT = os.path.dirname(TOOLS)


def test_scene_text_cannot_end_the_pages_script(tmp_path):
    """Defect: a scene description holding '</script>' or a claim marker '<!--' ends or
    comments out the page's data element (the page then starts with a JSON error)."""
    scene = tmp_path / "s.json"
    scene.write_text(json.dumps({"description": "a </script><!-- claim: x --> b", "dt": 0.1,
                                 "particles": [{"x": [0, 0], "m": 1}]}))
    block = page.scene_block(str(scene), "particles", None)
    html = page.render("euler", "particles", [block], {"student": "var wbLiveModule = 1;"},
                       "student", {"from": "labs/euler/", "command": "tools/view --live"})
    meta = html.split('id="wb-live">', 1)[1].split("</script>", 1)[0]
    assert "<" not in meta
    assert json.loads(meta)["scenes"][0]["text"].count("</script>") == 1  # the text is kept
    assert block["description"] == "a </script> b"  # what a reader sees: no claim markers


def test_page_needs_no_network():
    """Defect: a page that loads a script, a style or the WebAssembly from elsewhere (it
    must open from disk, offline: no src= or href= to fetch)."""
    block = page.scene_block(os.path.join(ROOT, "scenes", "euler", "oscillator.json"),
                             "particles", None)
    html = page.render("euler", "particles", [block], {"student": "var wbLiveModule = 1;"},
                       "student", {"from": "labs/euler/", "command": "tools/view --live"})
    assert " src=" not in html and " href=" not in html and "import(" not in html


def test_a_module_holding_a_script_end_is_refused():
    """Defect: a module text that ends its own <script> element mid-way (a broken page)."""
    try:
        page.module_script("student", "var a = '</script>';")
    except AssertionError:
        return
    raise AssertionError("accepted")


def test_particle_count_counts_emitters_and_generators():
    """Defect: the scene's drawing model built for the wrong number of particles (every
    default scene of every particle lab is read as the executable reads it)."""
    doc = {"particles": [{"x": [0, 0], "m": 1}], "emitters": [{"count": 5}],
           "rope": {"beads": 3}, "cloth": {"rows": 2, "cols": 4}}
    assert page.particle_count(doc) == 1 + 5 + 3 + 8
    for lab in ("forces", "euler", "midpoint", "implicit", "collisions"):
        for name in os.listdir(os.path.join(ROOT, "scenes", lab)):
            page.scene_block(os.path.join(ROOT, "scenes", lab, name), "particles", None)


def test_oscillator_omega_is_sqrt_k_over_m():
    """Defect: the readout of explicit Euler's 1 + h^2 w^2 with a wrong w."""
    doc = {"exact": "oscillator", "particles": [{"m": 4.0}], "forces": [{"k": 36.0}]}
    assert page.oscillator_omega(doc) == 3.0
    assert page.oscillator_omega({"particles": [{"m": 1}]}) is None


def test_missing_emscripten_says_so_in_one_line(monkeypatch):
    """Defect: a student without em++ gets a traceback or a CMake error instead of one line
    naming the package (emscripten is optional: nothing else needs it)."""
    monkeypatch.setattr(build.shutil, "which", lambda name: None)
    try:
        build.build("euler", ["student"], "/nonexistent")
    except build.BuildError as e:
        assert "emscripten" in str(e) and "\n" not in str(e) and e.status == 2
        return
    raise AssertionError("no error")


def test_debian_node_modules_join_node_path(monkeypatch):
    """Defect: emscripten's JavaScript tools fail to find acorn when the machine's node is
    not Debian's (Debian's modules folder must be on NODE_PATH, beside what was there)."""
    monkeypatch.setattr(build.os.path, "isdir", lambda p: True)
    monkeypatch.setenv("NODE_PATH", "/mine")
    assert build.environment()["NODE_PATH"].split(os.pathsep) == ["/mine", "/usr/share/nodejs"]


def test_unknown_lab_is_named():
    """Defect: a mistyped --lab that fails deep in CMake instead of naming the labs."""
    try:
        cli.make_page("eulr", "student", "/tmp/x.html", "/tmp/none")
    except build.BuildError as e:
        assert "eulr" in str(e) and "euler" in str(e)
        return
    raise AssertionError("no error")


def test_recorded_run_keeps_positions_steps_and_energy(tmp_path):
    """Defect: a recorded run drawn at other positions or times than the solution's run
    (positions are float32 relative to the run's centre; the energy is the stats' at the
    same written steps; the step numbers are the stats')."""
    rows = ["t,id,x,y,vx,vy"]
    stats = ["step,t,energy,kinetic,potential,px,py,force_evals"]
    for k in range(4):
        for i in range(2):
            rows.append(f"{0.5 * k!r},{i},{1000 + k + i!r},{-2.0 * k!r},0,0")
        stats.append(f"{5 * k},{0.5 * k!r},{10.0 + k!r},1,2,0,0,{5 * k}")
    (tmp_path / "a.csv").write_text("\n".join(rows) + "\n")
    (tmp_path / "a-stats.csv").write_text("\n".join(stats) + "\n")
    trace = read_trace(str(tmp_path / "a.csv"))
    block = recorded.pack(trace, read_stats(str(tmp_path / "a-stats.csv"), "particles"),
                          {"status": "ok"})
    vals = struct.unpack(f"<{4 * 2 * 2}f", base64.b64decode(block["pos"]))
    assert block["steps"] == [0, 5, 10, 15] and block["energy"] == [10.0, 11.0, 12.0, 13.0]
    x = [v + block["origin"][0] for v in vals[0::2]]
    assert abs(x[7] - 1004.0) < 1e-4 and block["diverged"] is None


def test_recorded_run_is_found_in_a_report(tmp_path):
    """Defect: the student page of an instructor checkout that never shows the solution's
    recorded run although tools/report made it (build/report/<lab>/<scene>.csv)."""
    (tmp_path / "euler").mkdir()
    (tmp_path / "euler" / "s.csv").write_text("t,id,x,y,vx,vy\n0,0,1,2,0,0\n0.1,0,1,3,0,0\n")
    (tmp_path / "euler" / "s-summary.json").write_text(
        '{"status": "diverged", "diverged": "why", "steps": 1, "t": 0.1}\n')
    block = recorded.from_report(str(tmp_path), "euler", "s")
    assert block["diverged"] == {"step": 1, "t": 0.1, "why": "why"}
    assert recorded.from_report(str(tmp_path), "euler", "other") is None
