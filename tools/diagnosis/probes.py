"""Diagnosis of each failing task (docs/grading.md, "Diagnosis"): the lab's pristine probe binary
(<lab>-probes, the stubs linked like the test binary: no student code in it) calls the task's
functions on fixed inputs through the sandboxed worker, as a test does; hints.py
compares what comes back with the catalogue (the solution's and every known mistake's outputs on
the same inputs, numbers only).

Trust: the probe process is the trusted side; every value in its report came from the worker
(hostile): it is parsed as data (capped, malformed lines dropped) and never changes a score."""
import hashlib
import os
import re
import time

from grader import wording
from grader.common import WORKER_OUTPUT_CAP, log
from grader.procs import signal_name
from grader.worker import watch

from . import hints as wh

PROBES_TIMEOUT = 20.0  # s, all the probes of one task (each takes milliseconds)
LAB_BUDGET = 60.0  # s, all the probes of one lab: a submission whose every task loops forever
                   # costs at most this much more than its tests
PROBES_CAP = 2 * 1024 * 1024  # bytes of one probe process's report kept
GONE = "the lab's code stopped answering"  # the stubs' words when the worker is gone


def task_of(test_name):
    m = re.match(r"^([A-Z]+\d+)\b", test_name)
    return m.group(1) if m else ""


def _pair(sandbox, binary, worker, ids, cwd, timeout):
    """Runs the probe binary on `ids` with a fresh worker; returns (records, status of the probe
    process, status of the worker)."""
    to_worker_r, to_worker_w = os.pipe()
    to_probe_r, to_probe_w = os.pipe()
    try:
        wk = sandbox.start([worker, str(to_worker_r), str(to_probe_w)], cwd,
                           pass_fds=(to_worker_r, to_probe_w), stdout_cap=WORKER_OUTPUT_CAP,
                           stderr_cap=WORKER_OUTPUT_CAP, view=True)
    finally:
        os.close(to_worker_r)
        os.close(to_probe_w)
    try:
        pp = sandbox.start([binary] + ids, cwd, pass_fds=(to_probe_r, to_worker_w),
                           env=[f"WB_WORKER_FDS={to_probe_r},{to_worker_w}"],
                           stdout_cap=PROBES_CAP + 1)
    finally:
        os.close(to_probe_r)
        os.close(to_worker_w)
    stopped, _ = watch(pp, wk, timeout)
    status, data, _ = pp.finish(0 if stopped else 5)
    w_status, _, _ = wk.finish(0 if stopped else 2)
    records = wh.parse_lines((data or b"").decode("utf-8", "replace"))
    return records, stopped or status, w_status


def _why(status, w_status):
    """Why a probe got no answer, in a student's words."""
    if status and status[0] in ("timeout", "idle", "wall"):
        return (f"the function did not return within {status[1]:g} s of CPU time (an infinite "
                "loop?)" if status[0] == "timeout" else
                "the function was blocked, neither computing nor waiting for a core (sleeping "
                "or waiting?)")
    if w_status and w_status[0] == "signal":
        return f"the function crashed ({signal_name(w_status[1])})"
    if w_status and w_status[0] == "exit":
        return f"the function ended its process (status {w_status[1]}: exit() called?)"
    return "the function stopped answering"


def run_probes(sandbox, binary, worker, ids, cwd, timeout=PROBES_TIMEOUT):
    """{probe id: record} of `ids`, in order. A probe whose call crashes the worker (or that
    runs out of time) is recorded as an error saying so, and the ones after it run again with
    a fresh worker; a probe after a time-out is not run."""
    out, todo = {}, list(ids)
    end = time.monotonic() + timeout
    while todo:
        left = end - time.monotonic()
        if left <= 0:
            break
        records, status, w_status = _pair(sandbox, binary, worker, todo, cwd, left)
        for r in records:
            if r.get("probe") in todo and r["probe"] not in out:
                if GONE in str(r.get("error", "")):
                    break  # this probe's call found the worker gone: reported below
                if r.get("error"):  # what the code did, in a student's words (no library file)
                    r = dict(r, error=wording.probe_error(str(r["error"])))
                out[r["probe"]] = r
        rest = [i for i in todo if i not in out]
        if not rest:
            break
        out[rest[0]] = {"probe": rest[0], "error": _why(status, w_status)}
        if status and status[0] in ("timeout", "idle"):
            break
        todo = rest[1:]
    return out


def pristine_tasks(overlay, tasks):
    """The tasks whose files the submission left as the skeleton's, byte for byte (the
    catalogue keeps each skeleton file's SHA-256: in a student's checkout labs/ holds the
    student's own work, not the skeleton)."""
    out = set()
    for task, info in tasks.items():
        sums = info.get("skeleton_sha256") or {}
        files = info.get("files") or []
        if files and all(f in sums and (f not in overlay or  # not submitted: the skeleton
                                        hashlib.sha256(overlay[f]).hexdigest() == sums[f])
                         for f in files):
            out.add(task)
    return out


def diagnose_lab(repo, lab, results, overlay, run, say=log):
    """{task: hints.Diagnosis} of one graded lab: every task with a failed test.

    results  [(test name, passed?, output)]
    overlay  {student file name: bytes} the submission gave for this lab
    run      run(ids) -> {probe id: record}: runs probes through the worker"""
    cat = wh.load_catalogue(repo, lab)
    by_task = {}
    for r in results:
        by_task.setdefault(task_of(r[0]), []).append(r)
    failing = [t for t, rs in by_task.items() if t and any(not r[1] for r in rs)]
    if not failing:
        return {}
    tasks = (cat or {}).get("tasks") or {}
    untouched = pristine_tasks(overlay, tasks)
    out = {}
    t0 = time.monotonic()
    for task in sorted(failing, key=lambda t: (re.sub(r"\d+", "", t), int(re.sub(r"\D", "", t) or 0))):
        title = wh.task_title(cat, task)
        ids = [p["probe"] for p in wh.task_probes(cat, task)] if cat else []
        outputs = None
        if ids and task not in untouched:
            try:
                outputs = run(ids)
            except Exception as e:  # a diagnosis that fails never changes a score
                say(f"grade: {lab} {task}: the probes could not run: {type(e).__name__}: {e}")
        try:
            d = wh.diagnose(cat, task, outputs, by_task[task], title, pristine=task in untouched)
        except Exception as e:
            say(f"grade: {lab} {task}: no diagnosis: {type(e).__name__}: {e}")
            continue
        out[task] = d
    for task, d in out.items():  # a task that builds on a failing one says so
        for dep in (tasks.get(task) or {}).get("uses") or []:
            if dep in out and d.status not in ("not started",):
                t = out[dep]
                what = "is not started" if t.status == "not started" else "fails too"
                d.notes.append(f"{task} calls your {dep} ({wh.task_title(cat, dep) or dep}), "
                               f"which {what}: fix {dep} first.")
    if out and time.monotonic() - t0 > 1:
        say(f"grade: {lab}: diagnosed {len(out)} task(s) in {time.monotonic() - t0:.1f} s")
    return out
