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

from .common import IDLE_LIMIT, IDLE_SHARE, WORKER_OUTPUT_CAP
from .procs import _descendants, _kill_tree
from .stubs import generate
from .verdict import judge

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


def _cpu_ticks(pids):
    """CPU time (clock ticks) used so far by these processes and everything below them."""
    total = 0
    for pid in set(pids) | {p for q in pids for p in _descendants(q)}:
        try:
            with open(f"/proc/{pid}/stat", "rb") as f:
                fields = f.read().rsplit(b")", 1)[1].split()
            total += int(fields[11]) + int(fields[12])
        except (OSError, ValueError, IndexError):
            pass
    return total


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


def run_test(sandbox, binary, worker, test, timeout, strip, cwd, seed=None):
    """Runs one test case; returns its TestResult. `timeout` is this test's wall-clock limit;
    `seed` the held-out inputs' seed (heldout.py), given to the test process only.

    The test process's report (its standard output, read only by the grader, this run's
    random name) and how it ended (from the launcher) decide; the worker's own end (a crash,
    exit()) only explains a failure. A test whose processes use less than IDLE_SHARE of one
    core over the last IDLE_LIMIT s of wall-clock time (sleeping, waiting on each other, a
    few ticks now and then) is stopped then, like one that runs out of time.
    The worker is started with nothing of the test's: its argv is its binary and two pipe
    numbers, its environment the sandbox's clean one, and it sees no other process."""
    nonce = "wb-" + secrets.token_hex(16)
    to_worker_r, to_worker_w = os.pipe()
    to_test_r, to_test_w = os.pipe()
    try:
        wk = sandbox.start([worker, str(to_worker_r), str(to_test_w)], cwd,
                           pass_fds=(to_worker_r, to_test_w), stdout_cap=WORKER_OUTPUT_CAP,
                           stderr_cap=WORKER_OUTPUT_CAP, view=True)
    finally:
        os.close(to_worker_r)
        os.close(to_test_w)
    try:
        env = [f"WB_WORKER_FDS={to_test_r},{to_worker_w}"]
        if seed is not None:
            env.append(f"WB_HELDOUT_SEED={seed:#x}")
        tp = sandbox.start([binary, test.name, "-w", "NoTests", "-r", "xml", "-n", nonce], cwd,
                           pass_fds=(to_test_r, to_worker_w), env=env)
    finally:
        os.close(to_test_r)
        os.close(to_worker_w)
    start = time.monotonic()
    deadline, stopped = start + timeout, None
    history = collections.deque()  # (time, CPU ticks) over the last IDLE_LIMIT s and a bit
    hz = os.sysconf("SC_CLK_TCK")
    pids = [tp.proc.pid, wk.proc.pid]
    waiter = _ExitWaiter(tp.proc.pid)  # opened before the first poll: the pid is not reaped yet
    try:
        while tp.proc.poll() is None:
            now = time.monotonic()
            if now >= deadline:
                stopped = ("timeout", None)
                break
            ticks = _cpu_ticks(pids)
            history.append((now, ticks))
            while len(history) > 1 and history[1][0] <= now - IDLE_LIMIT:
                history.popleft()
            t_old, ticks_old = history[0]
            if now - t_old >= IDLE_LIMIT and (ticks - ticks_old) / hz < IDLE_SHARE * (now - t_old):
                stopped = ("idle", IDLE_LIMIT)
                break
            waiter.wait(min(0.05 if now - start < 0.5 else 0.25, max(0.0, deadline - now)))
    finally:
        waiter.close()
    if stopped:
        _kill_tree(tp.proc.pid)
        _kill_tree(wk.proc.pid)
    status, data, captured = tp.finish(0 if stopped else 5)
    # The test process is gone: the worker reads the end of its pipe and exits; it gets a
    # moment, then is stopped.
    w_status, w_stdout, w_stderr = wk.finish(0 if stopped else 2)
    w_output = ((w_stdout or b"").decode("utf-8", "replace") + w_stderr)[:2 * WORKER_OUTPUT_CAP]
    if stopped:
        status = stopped
    return judge(test, status, data, captured, nonce, timeout, strip, w_status, w_output, seed)
