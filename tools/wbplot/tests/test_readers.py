"""The readers of runs (tools/wbplot: the trace and stats CSV, the sweep CSV, the summary
line): every figure, claim and report number starts here. Guards against a bad file read as
data (a figure of nonsense) instead of one clear error naming the file, the row and the
column, and against a diverged run's NaN and inf being dropped or refused."""
import math

import pytest

from wbplot import common, runs, sweep
from wbplot.common import InputError


def write(tmp_path, text, name="run.csv"):
    p = tmp_path / name
    p.write_text(text)
    return str(p)


def test_trace_groups_rows_by_particle_in_file_order(tmp_path):
    """Defect: particles' rows mixed up, or out of time order, in a trajectory."""
    p = write(tmp_path, "t,id,x,y,vx,vy\n0,0,1,2,0,0\n0,1,5,5,0,0\n0.1,0,1.1,2,1,0\n")
    tr = runs.read_trace(p)
    assert sorted(tr) == [0, 1] and tr[0]["x"] == [1.0, 1.1] and tr[1]["t"] == [0.0]


def test_a_diverged_runs_values_are_read_not_refused(tmp_path):
    """Defect: a run that diverged (inf, nan in the CSV) cannot be drawn or measured."""
    p = write(tmp_path, "t,id,x,y,vx,vy\n0,0,1,2,0,0\n0.1,0,inf,nan,-inf,0\n")
    d = runs.read_trace(p)[0]
    assert math.isinf(d["x"][1]) and math.isnan(d["y"][1])


@pytest.mark.parametrize("text,words", [
    ("", "empty file"),
    ("t,id,x,y,vx\n0,0,1,2,0\n", "missing column 'vy'"),
    ("t,id,x,y,vx,vy\n", "no data rows"),
    ("t,id,x,y,vx,vy\n0,0,1,2,0\n", ":2: 5 fields, expected 6"),
    ("t,id,x,y,vx,vy\n0,zero,1,2,0,0\n", "row 2, column 'id': got 'zero'"),
    ("t,id,x,y,vx,vy\n0,0,one,2,0,0\n", "row 2, column 'x': got 'one'"),
])
def test_a_bad_trace_is_one_error_naming_file_row_and_column(tmp_path, text, words):
    """Defect: a malformed CSV crashes with a traceback or is drawn as data."""
    p = write(tmp_path, text)
    with pytest.raises(InputError) as e:
        runs.read_trace(p)
    assert str(e.value).startswith(p) and words in str(e.value)


def test_a_rigid_trace_is_refused_with_the_figures_that_draw_it(tmp_path):
    """Defect: a 3D rigid-body trace drawn as particles (a wrong figure, no error)."""
    p = write(tmp_path, "t,id,x,y,z,vx,vy,vz,qw,qx,qy,qz\n0,0,0,0,0,0,0,0,1,0,0,0\n")
    with pytest.raises(InputError) as e:
        runs.read_trace(p)
    assert "rigid-frames" in str(e.value)


def test_stats_columns_and_empty_cells(tmp_path):
    """Defect: an empty or 'nan' cell refused (a run that stopped early) or read as 0."""
    cols = ",".join(runs.STATS_COLUMNS)
    p = write(tmp_path, f"{cols}\n0,0,1,1,0,0,0,1\n1,0.1,,0.5,nan,0,0,2\n", "s.csv")
    s = runs.read_stats(p)
    assert s["energy"][0] == 1.0 and math.isnan(s["energy"][1]) and math.isnan(s["potential"][1])


def test_a_missing_file_or_a_folder_names_what_was_expected(tmp_path):
    """Defect: a typo in a path gives a traceback instead of the file and what it should be."""
    with pytest.raises(InputError) as e:
        runs.read_stats(str(tmp_path / "nope.csv"))
    assert "no such file (expected a stats CSV" in str(e.value)
    with pytest.raises(InputError) as e:
        runs.read_stats(str(tmp_path))
    assert "is a folder" in str(e.value)


def test_sweep_merges_repeats_by_the_fastest_and_refuses_a_bad_dt(tmp_path):
    """Defect: repeated timing runs of one step size drawn as several points (or the slowest
    kept), or a zero step size read as a run."""
    cols = ",".join(sweep.SWEEP_COLUMNS)
    row = "osc,rk4,0.01,100,400,{w},1e-8,1e-9,exact,ok"
    assert len(sweep.SWEEP_COLUMNS) == len(row.split(","))
    p = write(tmp_path, f"{cols}\n{row.format(w=2.0)}\n{row.format(w=1.0)}\n", "sw.csv")
    (r,) = sweep.read_sweep(p)
    assert r.wall_s == 1.0 and r.integrator == "rk4" and r.dt == 0.01
    p = write(tmp_path, f"{cols}\n{row.replace('0.01', '0').format(w=1.0)}\n", "bad.csv")
    with pytest.raises(InputError) as e:
        sweep.read_sweep(p)
    assert "column 'dt'" in str(e.value)


@pytest.mark.parametrize("stdout,want", [
    ('step 1\n{"status": "ok", "steps": 3}\n\n', {"status": "ok", "steps": 3}),
    ("", None), ("no summary\n", None), ("[1, 2]\n", None),
    ('{"status": "ok"}\nwarning after\n', None),
])
def test_the_summary_is_the_last_non_empty_line_and_an_object(stdout, want):
    """Defect: a run without its summary line (the run contract broken) read as a summary, or
    a summary missed after a trailing blank line (docs/run-contract.md, "The summary line")."""
    assert common.summary_line(stdout) == want
