"""Running processes for the grader: wall-clock limits, capped and linear-time capture of
their output, killing whole process trees.

Trust: used for untrusted processes (the build, the worker); reads at most a cap of bytes."""
import collections
import os
import signal
import subprocess
import threading
import time

from .common import REPORT_FSIZE

# ----------------------------------------------------------- running processes

class _Capture(threading.Thread):
    """Drains a pipe, keeping the first `cap` bytes (or the last, keep_tail) and counting the
    rest. Linear time: chunks are kept in a list, the tail in a bounded deque of chunks."""

    def __init__(self, stream, cap, keep_tail=False):
        super().__init__(daemon=True)
        self.stream, self.cap, self.keep_tail = stream, cap, keep_tail
        self._chunks, self._kept, self.total = collections.deque(), 0, 0

    def run(self):
        try:
            while True:
                chunk = self.stream.read1(65536)
                if not chunk:
                    break
                self.total += len(chunk)
                if self.keep_tail:
                    self._chunks.append(chunk)
                    self._kept += len(chunk)
                    while self._kept - len(self._chunks[0]) >= self.cap:
                        self._kept -= len(self._chunks.popleft())
                elif self._kept < self.cap:
                    part = chunk[:self.cap - self._kept]
                    self._chunks.append(part)
                    self._kept += len(part)
        except (OSError, ValueError):
            pass

    @property
    def data(self):
        data = b"".join(self._chunks)
        return data[-self.cap:] if self.keep_tail else data

    def text(self):
        data = self.data
        s = data.decode("utf-8", errors="replace")
        dropped = self.total - len(data)
        if dropped > 0:
            s = (f"[... {dropped} earlier bytes not shown]\n" + s if self.keep_tail
                 else s + f"\n[... {dropped} more bytes not shown]")
        return s


_active = set()  # process groups running now, killed on interrupt
_active_lock = threading.Lock()


def _kill_group(pid):
    try:
        os.killpg(pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass


def _start(cmd, stdout, stderr, cwd=None, pass_fds=(), env=None):
    proc = subprocess.Popen(cmd, stdin=subprocess.DEVNULL, stdout=stdout, stderr=stderr, cwd=cwd,
                            start_new_session=True, pass_fds=pass_fds, env=env)
    with _active_lock:
        _active.add(proc.pid)
    return proc


def _descendants(pid):
    """Every process below pid (through /proc), children first found first."""
    children = {}
    for e in os.listdir("/proc"):
        if e.isdigit():
            try:
                with open(f"/proc/{e}/stat", "rb") as f:
                    ppid = int(f.read().rsplit(b")", 1)[1].split()[1])
            except (OSError, ValueError, IndexError):
                continue
            children.setdefault(ppid, []).append(int(e))
    out, todo = [], [pid]
    while todo:
        for c in children.get(todo.pop(), []):
            out.append(c)
            todo.append(c)
    return out


def _kill_tree(pid):
    """Kills pid's process group and every process below it, wherever its group
    (ninja puts each compiler in a group of its own)."""
    for _ in range(3):
        below = _descendants(pid)
        for p in below:
            try:
                os.kill(p, signal.SIGKILL)
            except (ProcessLookupError, PermissionError):
                pass
        _kill_group(pid)
        if not below:
            break


def _finish(proc, timeout):
    """Waits for proc (at most `timeout` s), then kills its whole process group
    (and, if it did not finish, every process below it)."""
    rc = None
    try:
        rc = proc.wait(timeout=timeout)
    except subprocess.TimeoutExpired:
        pass
    finally:
        if rc is None:  # timed out, or the grader is being stopped
            _kill_tree(proc.pid)
        _kill_group(proc.pid)  # the process on timeout, and any child it left behind
        proc.wait()
        with _active_lock:
            _active.discard(proc.pid)
    return rc


def run_capped(cmd, timeout, cap, cwd=None, keep_tail=False):
    """Runs cmd in its own process group with a wall-clock limit.

    Returns (returncode or None on timeout, captured text of stdout and stderr)."""
    proc = _start(cmd, subprocess.PIPE, subprocess.STDOUT, cwd=cwd)
    reader = _Capture(proc.stdout, cap, keep_tail)
    reader.start()
    rc = _finish(proc, timeout)
    reader.join(timeout=5)  # a grandchild that escaped the group may hold the pipe: give up
    _close_unless_busy(proc.stdout, reader)
    return rc, reader.text()


def run_collect(cmd, timeout, cap, cwd=None):
    """Runs cmd (in the folder cwd); returns (rc, stdout bytes, stderr tail bytes); rc None on
    timeout, -1 when stdout passed `cap` bytes (the process is then stopped)."""
    proc = _start(cmd, subprocess.PIPE, subprocess.PIPE, cwd=cwd)
    out, err = _Capture(proc.stdout, cap + 1), _Capture(proc.stderr, 16 * 1024, keep_tail=True)
    out.start()
    err.start()
    deadline = time.monotonic() + timeout
    while proc.poll() is None and time.monotonic() < deadline and out.total <= cap:
        time.sleep(0.01)
    too_big = out.total > cap
    rc = _finish(proc, 0 if too_big else max(0.0, deadline - time.monotonic()))
    out.join(timeout=5)
    err.join(timeout=5)
    _close_unless_busy(proc.stdout, out)
    _close_unless_busy(proc.stderr, err)
    return (-1 if too_big else rc), out.data, err.data


def _close_unless_busy(stream, reader):
    """Closes a pipe unless its reader is still blocked on it (a process that escaped
    holds the other end): closing would wait for that process; the reader, a daemon
    thread, ends when it does."""
    if not reader.is_alive():
        stream.close()


def kill_all():
    with _active_lock:
        for pid in list(_active):
            _kill_tree(pid)


SIGNAL_HINTS = {
    "SIGSEGV": "invalid memory access: an index out of range, or a matrix of the wrong size?",
    "SIGBUS": "invalid memory access",
    "SIGFPE": "arithmetic error: an integer division by zero?",
    "SIGABRT": "aborted: a failed assertion or an uncaught exception?",
    "SIGXFSZ": f"wrote more than {REPORT_FSIZE // (1024 * 1024)} MiB of output",
    "SIGXCPU": "used more than its CPU time limit",
    "SIGKILL": "killed: out of memory?",
}


def signal_name(signum):
    try:
        name = signal.Signals(signum).name
    except ValueError:
        return f"signal {signum}"
    return f"{name}: {SIGNAL_HINTS[name]}" if name in SIGNAL_HINTS else name

