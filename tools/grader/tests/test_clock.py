"""The time a test's processes took, as the kernel counts it (tools/grader/clock.py), and the
watch that stops a test on it (worker.watch): guards against verdicts that change with the
machine's load (issue 42: a correct submission computing 5 s per test scored 95, 98, 100, 79
and 100 in five gradings on a busy machine)."""
import os
import signal
import subprocess
import sys
import time
from types import SimpleNamespace

import pytest

from grader import worker
from grader.clock import PairClock, _schedstat

BUSY = "import time\nt = time.process_time()\nwhile time.process_time() - t < {s}: pass\n"


def _start(code):
    return subprocess.Popen([sys.executable, "-c", code], start_new_session=True,
                            stdin=subprocess.DEVNULL)


def _wait_unreaped(proc, timeout=30):
    end = time.monotonic() + timeout
    while os.waitid(os.P_PID, proc.pid, os.WEXITED | os.WNOHANG | os.WNOWAIT) is None:
        assert time.monotonic() < end, "the process did not end"
        time.sleep(0.02)


def test_a_process_that_ended_still_counts():
    """Defect: the CPU time of a test's processes that ended between two readings vanished
    from the sum of the live ones, and a test that had computed for seconds read as idle."""
    root = _start("import subprocess, sys\n"
                  f"subprocess.run([sys.executable, '-c', {BUSY.format(s=0.3)!r}])\n")
    try:
        _wait_unreaped(root)  # the child ended and was reaped by the root, which ended too
        cpu, _ = PairClock([root.pid]).sample()
        assert cpu >= 0.28
    finally:
        root.wait()


def test_the_count_never_decreases():
    """Defect: a reading taken while a process is being reaped counted less than the one
    before, and a window of the idle rule saw negative progress."""
    root = _start("import subprocess, sys\n"
                  f"subprocess.run([sys.executable, '-c', {BUSY.format(s=0.3)!r}])\n")
    clock, seen = PairClock([root.pid]), []
    try:
        while root.poll() is None and len(seen) < 10000:
            seen.append(clock.sample()[0])
    finally:
        root.wait()
    assert seen == sorted(seen) and seen[-1] > 0


@pytest.mark.skipif(not os.path.exists("/proc/self/schedstat") or _schedstat(os.getpid()) is None,
                    reason="the kernel reports no waiting times (CONFIG_SCHED_INFO)")
def test_waiting_for_a_core_is_not_idling():
    """Defect: a test that computes while other processes hold the cores got a small share of
    CPU time and was stopped as idle (the rule read CPU time only)."""
    procs = [_start(BUSY.format(s=30)) for _ in range(3)]
    try:
        cpu0 = sorted(os.sched_getaffinity(0))[0]
        for p in procs:
            os.sched_setaffinity(p.pid, {cpu0})  # three on one core: a third of it each
        clock = PairClock([procs[0].pid])
        time.sleep(0.2)
        cpu_a, wanted_a = clock.sample()
        t0 = time.monotonic()
        time.sleep(1.0)
        cpu_b, wanted_b = clock.sample()
        wall = time.monotonic() - t0
    finally:
        for p in procs:
            p.kill()
            p.wait()
    assert cpu_b - cpu_a < 0.8 * wall  # it did not get the core to itself...
    assert wanted_b - wanted_a > 0.8 * wall  # ...but wanted it all the time


def _pair(main_code, worker_code="import time\ntime.sleep(60)\n"):
    return (SimpleNamespace(proc=_start(main_code)), SimpleNamespace(proc=_start(worker_code)))


def _reap(*running):
    for r in running:
        r.proc.kill()
        r.proc.wait()


def test_a_blocked_pair_is_stopped_as_idle(monkeypatch):
    """Defect: a test whose processes both wait for each other sits out its whole time limit."""
    monkeypatch.setattr(worker, "IDLE_LIMIT", 0.6)
    main, wk = _pair("import time\ntime.sleep(60)\n")
    t0 = time.monotonic()
    try:
        stopped, _ = worker.watch(main, wk, 30)
    finally:
        _reap(main, wk)
    assert stopped == ("idle", 0.6) and time.monotonic() - t0 < 10


def test_a_computing_pair_ends_by_itself(monkeypatch):
    """Defect: a test that computes for longer than the idle window is stopped as idle."""
    monkeypatch.setattr(worker, "IDLE_LIMIT", 0.3)
    main, wk = _pair(BUSY.format(s=0.6))
    try:
        stopped, clock = worker.watch(main, wk, 30)
    finally:
        _reap(main, wk)
    assert stopped is None and clock.cpu >= 0.55


def test_the_limit_is_cpu_time_of_the_pair():
    """Defect: the limit read the wall clock, so a busy machine timed out correct code."""
    main, wk = _pair(BUSY.format(s=60), BUSY.format(s=60))
    try:
        stopped, clock = worker.watch(main, wk, 0.6)
    finally:
        _reap(main, wk)
    assert stopped == ("timeout", 0.6) and 0.6 <= clock.cpu < 3


def test_a_pause_of_the_whole_machine_is_not_idling(monkeypatch):
    """Defect: when the grader itself got no CPU for seconds (or the machine was paused), its
    next reading saw a long window without progress and stopped a test that was computing."""
    monkeypatch.setattr(worker, "IDLE_LIMIT", 0.6)
    main, wk = _pair(BUSY.format(s=0.5))
    calls = []
    real_wait = worker._ExitWaiter.wait

    def paused(self, seconds):
        calls.append(seconds)
        if len(calls) == 3:  # the machine pauses: the test and the grader stop together,
            os.kill(main.proc.pid, signal.SIGSTOP)  # and go on together
            time.sleep(1.2)
            os.kill(main.proc.pid, signal.SIGCONT)
            return
        real_wait(self, seconds)
    monkeypatch.setattr(worker._ExitWaiter, "wait", paused)
    try:
        stopped, clock = worker.watch(main, wk, 30)
    finally:
        _reap(main, wk)
    assert stopped is None and clock.cpu >= 0.45
