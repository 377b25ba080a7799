"""The time one test's processes took, as the kernel counts it: CPU time (every process the test
ran, ended ones included) and the time they spent waiting for a core. Limits and the idle rule
read these, never the wall clock alone, so that a verdict does not change with the machine's
load (docs/grading.md, "Time").

Trust: reads /proc of the grader's own children (numbers the kernel keeps; nothing the
processes write)."""
import os

HZ = os.sysconf("SC_CLK_TCK")


def _stat(pid):
    """(parent pid, own CPU s, CPU s of the children it reaped) of one process, or None."""
    try:
        with open(f"/proc/{pid}/stat", "rb") as f:
            fields = f.read().rsplit(b")", 1)[1].split()
        return (int(fields[1]), (int(fields[11]) + int(fields[12])) / HZ,
                (int(fields[13]) + int(fields[14])) / HZ)
    except (OSError, ValueError, IndexError):
        return None


def _schedstat(pid):
    """(CPU s, s spent runnable waiting for a core) of one process's main thread from
    /proc/<pid>/schedstat (CONFIG_SCHED_INFO), or None."""
    try:
        with open(f"/proc/{pid}/schedstat", "rb") as f:
            ran, waited = f.read().split()[:2]
        return int(ran) / 1e9, int(waited) / 1e9
    except (OSError, ValueError):
        return None


def _children(pid):
    """The pids whose parent is pid: /proc/<pid>/task/<tid>/children (CONFIG_PROC_CHILDREN), or
    a scan of /proc where the kernel does not have it."""
    out = []
    try:
        tids = os.listdir(f"/proc/{pid}/task")
    except OSError:
        return out
    for tid in tids:
        try:
            with open(f"/proc/{pid}/task/{tid}/children", "rb") as f:
                out += [int(c) for c in f.read().split()]
        except FileNotFoundError:
            return _scan_children(pid)
        except (OSError, ValueError):
            pass
    return out


def _scan_children(pid):
    out = []
    for e in os.listdir("/proc"):
        if e.isdigit():
            st = _stat(e)
            if st and st[0] == pid:
                out.append(int(e))
    return out


class PairClock:
    """The CPU time and the waiting time of the processes of one test: the trees under `roots`
    (the launchers the grader started and has not reaped yet).

    CPU: each process's own user and system time, plus the time of the children it reaped
    (cutime, cstime: the kernel adds an ended child's whole time, its own reaped children's
    included, to its parent's when the parent reaps it). Every process that ever ran in a tree
    is therefore counted exactly once, whether it still runs, has ended or was reaped, as long
    as the root is not reaped (the grader reaps it only after the last reading). Parents are
    read before their children, so a process reaped between two readings can only be missed
    for that reading, never counted twice; the totals never decrease.

    Waiting: the time the processes spent runnable but not running (schedstat's run_delay),
    the last value seen of each process (0 without CONFIG_SCHED_INFO). CPU plus waiting is the
    time the test wanted a core: it grows at the rate of the wall clock while the test computes
    however busy the machine is, and stays put while it is blocked (sleeping, waiting on a
    pipe)."""

    def __init__(self, roots):
        self.roots = list(roots)
        self.cpu = 0.0  # s of CPU time, every process of the test
        self._waited = {}  # pid: s spent waiting for a core (last seen)

    @property
    def waited(self):
        return sum(self._waited.values())

    @property
    def wanted(self):
        """CPU plus waiting for a core: the time the test was not blocked."""
        return self.cpu + self.waited

    def sample(self):
        """Reads the kernel's counts now; returns (cpu, wanted) in seconds."""
        total, todo, seen = 0.0, list(self.roots), set()
        while todo:
            pid = todo.pop(0)
            if pid in seen:
                continue
            seen.add(pid)
            st = _stat(pid)  # the parent first: then its children
            if st is None:
                continue
            total += st[1] + st[2]
            sched = _schedstat(pid)
            if sched is not None:
                self._waited[pid] = max(self._waited.get(pid, 0.0), sched[1])
            todo += _children(pid)
        self.cpu = max(self.cpu, total)
        return self.cpu, self.wanted
