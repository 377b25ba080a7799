"""Runs one test case as two sandboxed processes: the trusted test process (the pristine tests,
linked with generated stubs: no student code in it) and the worker (the lab's code, which the
stubs call through a pair of pipes). The verdict comes from the test process only (verdict.py);
the worker can only send values back (docs/grading.md "The worker").

Trust: starts the process that runs student code (the worker), always inside the sandbox,
and stops both when the test ends, idles, or runs out of time."""
import collections
import os
import secrets
import select
import time

from .clock import PairClock
from .common import IDLE_LIMIT, IDLE_SHARE, WORKER_OUTPUT_CAP, wall_limit
from .procs import _kill_tree
from .stubs import generate
from .verdict import judge

WATCH_GAP = 1.0  # s: a longer gap between two readings of a test's clock is not watched time
WORKER_DIR = "grader-worker"  # in the scratch copy: tools/grader/cpp/ and the generated stubs
CPP_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "cpp")


def worker_files(repo, labs):
    """{relative path in the scratch copy: bytes}: the worker's C++ and every lab's stubs."""
    files = {}
    for name in sorted(os.listdir(CPP_DIR)):
        with open(os.path.join(CPP_DIR, name), "rb") as f:
            files[os.path.join(WORKER_DIR, name)] = f.read()
    for lab in labs:
        for name, text in generate(repo, lab).items():
            files[os.path.join(WORKER_DIR, name)] = text.encode("utf-8")
    return files


class _ExitWaiter:
    """Sleeps until a process ends or a time passes, whichever comes first: through a pidfd
    (Linux 5.3), so that a test of a few milliseconds is seen to end at once instead of at
    the next poll; a plain sleep where pidfds are not available."""

    def __init__(self, pid):
        try:
            self.fd = os.pidfd_open(pid)
        except (AttributeError, OSError):
            self.fd = None

    def wait(self, seconds):
        if self.fd is None:
            time.sleep(seconds)
        else:
            select.select([self.fd], [], [], seconds)

    def close(self):
        if self.fd is not None:
            os.close(self.fd)
            self.fd = None


def _ended(pid):
    """Whether the child `pid` has ended, without reaping it: its counts stay readable."""
    try:
        return os.waitid(os.P_PID, pid, os.WEXITED | os.WNOHANG | os.WNOWAIT) is not None
    except ChildProcessError:
        return True


def watch(main, worker, limit):
    """Waits until `main` (the test or probe process, a sandbox Running) ends, or stops the pair
    first. Returns (stopped, clock): `clock` the pair's PairClock (read last after `main`
    ended, before anything is reaped); `stopped` None, or why it was stopped:

    - ("timeout", limit): the two processes together used `limit` s of CPU time;
    - ("idle", IDLE_LIMIT): over the last IDLE_LIMIT s of wall-clock time they neither ran nor
      waited for a core for IDLE_SHARE of it: both are blocked (a process of a test blocks
      only on the other one's pipe, so it would block for good);
    - ("wall", (seconds, share)): still running after wall_limit(limit) s of wall-clock time,
      `share` the part of it the pair ran or waited for a core (judge: a busy machine, or a
      wait this design does not know of).
    Each reading is the kernel's count, not the wall clock: a test that computes is never
    idle however busy the machine, and its CPU limit is the same on any machine load. The
    wall-clock time the rules see is only what the grader watched: a gap of more than
    WATCH_GAP s between two of its readings (the grader itself starved of CPU, or the whole
    machine paused) starts the idle window again and does not count towards the safety net."""
    clock = PairClock([main.proc.pid, worker.proc.pid])
    start = last = time.monotonic()
    watched = 0.0  # s of wall-clock time watched, gaps left out
    stopped, history = None, collections.deque()  # (time, s wanted) over the last IDLE_LIMIT s
    waiter = _ExitWaiter(main.proc.pid)  # opened before the first poll: the pid is not reaped
    try:
        while not _ended(main.proc.pid):
            now = time.monotonic()
            cpu, wanted = clock.sample()
            if cpu >= limit:
                stopped = ("timeout", limit)
                break
            if now - last > WATCH_GAP:
                history.clear()
            watched += min(now - last, WATCH_GAP)
            last = now
            history.append((now, wanted))
            while len(history) > 1 and history[1][0] <= now - IDLE_LIMIT:
                history.popleft()
            t_old, wanted_old = history[0]
            if now - t_old >= IDLE_LIMIT and wanted - wanted_old < IDLE_SHARE * (now - t_old):
                stopped = ("idle", IDLE_LIMIT)
                break
            if watched >= wall_limit(limit):
                stopped = ("wall", (now - start, min(1.0, wanted / watched)))
                break
            waiter.wait(0.05 if now - start < 0.5 else 0.25)
    finally:
        waiter.close()
    clock.sample()
    if stopped:
        _kill_tree(main.proc.pid)
        _kill_tree(worker.proc.pid)
    return stopped, clock


def run_test(sandbox, binary, worker, test, limit, strip, cwd, seed=None):
    """Runs one test case; returns its TestResult. `limit` is this test's CPU time limit (s,
    its two processes together); `seed` the held-out inputs' seed (heldout.py), given to the
    test process only.

    The test process's report (its standard output, read only by the grader, this run's
    random name) and how it ended (from the launcher) decide; the worker's own end (a crash,
    exit()) only explains a failure. A test that uses up its CPU time, or whose processes are
    both blocked (watch: neither running nor waiting for a core), is stopped.
    The worker is started with nothing of the test's: its argv is its binary's name and two
    pipe numbers, its environment the sandbox's clean one, and it sees no other process."""
    nonce = "wb-" + secrets.token_hex(16)
    to_worker_r, to_worker_w = os.pipe()
    to_test_r, to_test_w = os.pipe()
    try:
        wk = sandbox.start([worker, str(to_worker_r), str(to_test_w)], cwd,
                           pass_fds=(to_worker_r, to_test_w), stdout_cap=WORKER_OUTPUT_CAP,
                           stderr_cap=WORKER_OUTPUT_CAP, view=True, cpu=limit)
    finally:
        os.close(to_worker_r)
        os.close(to_test_w)
    try:
        env = [f"WB_WORKER_FDS={to_test_r},{to_worker_w}"]
        if seed is not None:
            env.append(f"WB_HELDOUT_SEED={seed:#x}")
        tp = sandbox.start([binary, test.name, "-w", "NoTests", "-r", "xml", "-n", nonce], cwd,
                           pass_fds=(to_test_r, to_worker_w), env=env, cpu=limit)
    finally:
        os.close(to_test_r)
        os.close(to_worker_w)
    stopped, clock = watch(tp, wk, limit)
    status, data, captured = tp.finish(0 if stopped else 5)
    # The test process is gone: the worker reads the end of its pipe and exits; it gets a
    # moment, then is stopped.
    w_status, w_stdout, w_stderr = wk.finish(0 if stopped else 2)
    w_output = ((w_stdout or b"").decode("utf-8", "replace") + w_stderr)[:2 * WORKER_OUTPUT_CAP]
    if stopped:
        status = stopped
    return judge(test, status, data, captured, nonce, limit, strip, w_status, w_output, seed,
                 clock.cpu)
