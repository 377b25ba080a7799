#!/usr/bin/env -S sh -c 'exec "${0%/*}/../../tools/lib/start-python" "$0" "$@"'
"""Bad-input regression cases: every case must end in one clear line.

Runs each case of tests/badinput/cases.json against the lab executables in
--bin and checks the run contract for bad input (docs/run-contract.md):
exit status 2 (or the case's `status`; `kill_after` S: a slow valid run,
stopped after S seconds, that must have warned (`may_finish`: or that finished, as
a skeleton's stubs do, with status 0); `stop_after` S: a run sent
SIGTERM after S seconds, which must leave no output behind; `differs_from`: the
arguments of a second run whose initial momentum must differ), exactly one line of valid UTF-8 on
stderr of at most MAX_LINE bytes naming what the case `expect`s (`stderr_lines`: the
number of lines of a run that is not refused; `lines_prefix`: what every line of
it starts with), nothing on stdout, no output
file left behind (`absent`), special files still special (`special`: made by
`fifo` with a reader, or `symlink` [name, target]), within TIME_LIMIT_S seconds
(`max_seconds`: another limit; `solution_not_stub`: on the solution side, no stub
warning and no "stub" in the summary; `max_cpu_seconds`: a limit on the CPU time it
used, which a loaded machine does not inflate) and MEMORY_LIMIT_BYTES of
address space. `budget`: a run that must stay within the limits it was given (its
--max-time and --max-memory flags) to within BUDGET_SLACK, measured on the process
(its CPU time and peak resident size, os.wait4), whether it finishes, is refused or is
stopped by its budget (docs/scenes.md, "Cost"). `stop_signal`: the signal `stop_after`
sends (default SIGTERM). `precreate`: [name, text] files made in {tmp} before the run
(a killed run's temporaries). `readonly`: files made in {tmp} with mode 0444 that the
run may not write; when the runner is root, the run starts without root's
CAP_DAC_OVERRIDE and CAP_DAC_READ_SEARCH. `{exe}` in an `expect` string is the executable's name;
`{badutf8}` in an argument is the byte 0xFF, `{name250}` and `{name300}` file
names of 250 and 300 bytes. Large
scenes (deep nesting, a 17 MiB file, a file at the 16 MiB cap, generators at
their maximum) are generated into a temporary folder, not checked in.

  tests/badinput/run_badinput.py --bin build/bin [--side solution] [-k NAME]
"""
import argparse
import ctypes
import glob
import json
import math
import os
import resource
import shutil
import signal
import stat
import subprocess
import sys
import tempfile
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
MAX_LINE = 1100  # messages are cut to 1000 bytes (kMaxMessageBytes) plus the "<exe>: error: " prefix
TIME_LIMIT_S = 20.0  # each case is refused in well under a second; this is a hang detector
# The hang detector counts the run's CPU time, not the wall clock: on a loaded machine (a nice
# 10 check beside two busy cores) a 2 s budget run took more than 20 s of wall time (the
# rehearsal of 2026-12-07). A run that is over TIME_LIMIT_S of wall time is a hang only while
# it computes nothing (less than IDLE_CPU_S of CPU in the last IDLE_WINDOW_S), and whatever it
# does after HANG_WALL_FACTOR times the limit.
IDLE_WINDOW_S, IDLE_CPU_S, HANG_WALL_FACTOR = 2.0, 0.02, 10
MEMORY_LIMIT_BYTES = 2 << 30  # a refused scene must not allocate gigabytes first
BUDGET_SLACK = 1.1  # a run stopped by its budget passes its limits by at most 10 % (issue 45)
PR_CAPBSET_DROP, CAP_DAC_OVERRIDE, CAP_DAC_READ_SEARCH = 24, 1, 2  # <linux/prctl.h>, capability.h
# libc, loaded in the parent: a preexec_fn imports and loads nothing (the readers' threads)
LIBC = ctypes.CDLL(None, use_errno=True)
# How the run contract's warnings about a stub end (docs/run-contract.md, `warnings`).
STUB_WARNING_ENDINGS = ("written yet?", "still a stub?", "still stubs?")


def generate(kind, tmp):
    """Writes the scene of a generated case; returns its path."""
    path = os.path.join(tmp, kind + ".json")
    if kind == "deep-array":  # 60,000 nested arrays (120 KB) as a force list
        text = '{"forces": ' + "[" * 60000 + "]" * 60000 + "}"
    elif kind == "deep-object":
        text = '{"a": ' * 100000 + "1" + "}" * 100000
    elif kind == "deep-top":
        text = "[" * 200000 + "]" * 200000
    elif kind == "huge-string-value":  # 15 MB value of the wrong type
        text = '{"dt": 0.1, "t_end": 1, "name": ["' + "a" * 15_000_000 + '"]}'
    elif kind == "too-large":  # 17 MiB: valid JSON, refused by its size
        text = '{"dt": 0.1' + " " * (17 << 20) + "}"
    elif kind == "many-emitters":  # 100 emitters of 5M particles in a few KB
        e = '{"count": 5000000, "min": [0, 0], "max": [1, 1], "m": 1}'
        text = '{"dt": 0.1, "t_end": 1, "emitters": [' + ", ".join([e] * 100) + "]}"
    elif kind == "boids-6000":  # boids, not newton: no O(n^2) potential to wait for
        text = json.dumps({"dt": 0.01, "t_end": 1, "forces": [{"type": "damping", "b": 1},
                                                               {"type": "boids"}],
                           "emitters": [{"count": 6000, "min": [0, 0], "max": [100, 100],
                                         "m": 1}]})
    elif kind == "emitter-200":
        text = ('{"dt": 0.01, "emitters": [{"count": 200, "min": [0, 0], "max": [1, 1], '
                '"m": 1}]}')
    elif kind == "long-key":
        text = '{"' + "k" * 100000 + '": 1}'
    elif kind == "at-size-cap":  # exactly 16 MiB: ~870,000 small objects, the last one bad
        head, tail = '{"dt": 0.1, "t_end": 0, "particles": [', '{"x": [0, 0], "m": -1}]}'
        item = '{"x": [0, 0], "m": 1},'
        count = ((16 << 20) - len(head) - len(tail)) // len(item)
        pad = (16 << 20) - len(head) - len(tail) - count * len(item)
        text = head + item * count + " " * pad + tail
        assert len(text) == 16 << 20
    elif kind == "rope-max":  # the rope generator at its maximum
        text = json.dumps({"dt": 1e-3, "t_end": 0, "rope": {"start": [0, 0], "end": [1000, 0],
                                                             "beads": 1000000, "m": 0.01,
                                                             "k": 100},
                           "forces": [{"type": "gravity", "g": [0, -9.81]}]})
    elif kind == "cloth-max":  # the cloth generator at its maximum: 1000 x 1000
        text = json.dumps({"dt": 1e-3, "t_end": 0, "cloth": {
            "origin": [0, 0], "rows": 1000, "cols": 1000, "spacing": 0.01, "m": 0.001, "k": 10,
            "k_bend": 1}, "forces": [{"type": "gravity", "g": [0, -9.81]}]})
    elif kind == "cloth-300":  # the 300 x 300 cloth, by LDLT in natural order (its
        # fill-in makes it slow; without the newton key, CG is chosen and it is not: issue 45)
        text = json.dumps({"dt": 1e-3, "t_end": 1, "cloth": {
            "origin": [0, 0], "rows": 300, "cols": 300, "spacing": 0.01, "m": 0.001, "k": 10},
            "forces": [{"type": "gravity", "g": [0, -9.81]}], "newton": {"solver": "ldlt"}})
    elif kind == "discs-at-one-point":  # 10^5 discs emitted at one point: 5e9 pairs
        text = json.dumps({"dt": 1e-3, "t_end": 1, "contact": {}, "emitters": [
            {"count": 100000, "min": [0, 0], "max": [0, 0], "m": 1, "radius": 0.1}]})
    elif kind == "particles-x-planes":  # 10^6 particles x 100 planes x 20 passes
        planes = [{"point": [0, -k], "normal": [0, 1]} for k in range(100)]
        text = json.dumps({"dt": 1e-3, "t_end": 10, "contact": {"iterations": 20},
                           "planes": planes, "emitters": [
                               {"count": 1000000, "min": [0, 0], "max": [1000, 1000],
                                "m": 1}]})
    elif kind == "bodies-x-planes":  # 1000 boxes x 20000 planes: 1.6e8 point tests
        bodies = [{"shape": "box", "size": [1, 1, 1], "m": 1, "x": [2 * k, 0, 5]}
                  for k in range(1000)]
        planes = [{"point": [0, 0, -k], "normal": [0, 0, 1]} for k in range(20000)]
        text = json.dumps({"dt": 1e-3, "t_end": 1, "bodies": bodies, "planes": planes})
    elif kind == "newline-in-file-name":
        path = os.path.join(tmp, "bad\nname.json")
        text = '{"dt": 0.1, "dt": 0.2}'
    elif kind == "newline-name-slow":  # a valid scene that warns (the cost model) first
        path = os.path.join(tmp, "slow\nname.json")
        text = json.dumps({"dt": 1e-6, "t_end": 100, "emitters": [
            {"count": 200, "min": [0, 0], "max": [1, 1], "m": 1}]})
    elif kind == "newline-name-unconverged":  # Newton fails every step: one warning at the end
        path = os.path.join(tmp, "rope\nname.json")
        with open(os.path.join(HERE, "scenes", "newton-unconverged.json"), encoding="utf-8") as f:
            text = f.read()
    elif kind == "collisions-iterations-1000":  # 20 000 discs, 1000 solver iterations per step
        text = json.dumps({"dt": 2e-3, "t_end": 10, "contact": {"iterations": 1000},
                           "planes": [{"point": [0, 0], "normal": [0, 1]}],
                           "emitters": [{"count": 20000, "seed": 1, "min": [-3, 0.05],
                                         "max": [3, 3], "m": 1e-3, "radius": 0.01}],
                           "forces": [{"type": "gravity", "g": [0, -9.81]}]})
    elif kind == "rigid-iterations-1000":  # 200 boxes resting, 1000 contact iterations per step
        bodies = [{"shape": "box", "size": [1, 1, 1], "m": 1, "x": [2 * k, 0, 0.5]}
                  for k in range(200)]
        text = json.dumps({"dt": 1e-3, "t_end": 100, "bodies": bodies, "contact": {"iterations": 1000},
                           "planes": [{"point": [0, 0, 0], "normal": [0, 0, 1]}],
                           "forces": [{"type": "gravity", "g": [0, 0, -9.81]}]})
    elif kind == "curl-obstacles":  # 20 000 obstacles x 200 000 particles
        obstacles = [{"center": [k % 200, k // 200], "radius": 0.1} for k in range(20000)]
        text = json.dumps({"dt": 0.01, "t_end": 10, "emitters": [
            {"count": 200000, "min": [0, 0], "max": [200, 100], "m": 1}], "forces": [
            {"type": "curl-noise", "b": 1, "amplitude": 1, "scale": 1, "seed": 1,
             "obstacles": obstacles}]})
    elif kind == "discs-converge":  # 30 000 discs on a circle, all at its centre at step 2
        n, R, h = 30000, 1000.0, 0.01
        parts = []
        for k in range(n):
            a = 2 * 3.141592653589793 * k / n
            x, y = R * math.cos(a), R * math.sin(a)
            parts.append({"x": [x, y], "v": [-x / (2 * h), -y / (2 * h)], "m": 1, "radius": 0.01})
        text = json.dumps({"dt": h, "t_end": 1, "contact": {}, "particles": parts})
    elif kind == "giant-disc-among-1e5":  # issue 45: cells 4 radii wide hold every disc
        parts = [{"x": [0, 0], "m": 1, "radius": 1e9}]
        text = json.dumps({"dt": 1e-3, "t_end": 1, "contact": {}, "particles": parts,
                           "emitters": [{"count": 100000, "seed": 3, "min": [-100, -100],
                                         "max": [100, 100], "m": 1, "radius": 0.01}]})
    elif kind == "discs-on-2000-planes":  # issue 45: 2000 identical planes, 1000 iterations
        planes = [{"point": [0, 0], "normal": [0, 1]}] * 2000
        text = json.dumps({"dt": 1e-3, "t_end": 10, "planes": planes,
                           "contact": {"solver": "accumulated", "iterations": 1000},
                           "forces": [{"type": "gravity", "g": [0, -9.81]}],
                           "emitters": [{"count": 2000, "seed": 1, "min": [-50, 0.05],
                                         "max": [50, 0.06], "m": 1, "radius": 0.05}]})
    elif kind in ("rope-long-springs", "rope-long-springs-ldlt"):  # issue 45: fill-in
        n = 5000
        springs = [{"type": "spring", "i": i, "j": n - 1 - i, "k": 1}
                   for i in range(0, 5000, 10)]
        doc = {"dt": 1 / 60, "t_end": 10, "rope": {"start": [0, 0], "end": [50, 0],
                                                   "beads": n, "m": 0.01, "k": 100},
               "forces": springs + [{"type": "gravity", "g": [0, -9.81]}]}
        if kind.endswith("-ldlt"):
            doc["newton"] = {"solver": "ldlt"}
        text = json.dumps(doc)
    elif kind == "cloth-300-cg-tight":  # issue 45: CG to 1e-14, 300 x 300
        text = json.dumps({"dt": 1 / 60, "t_end": 10, "cloth": {
            "origin": [0, 0], "rows": 300, "cols": 300, "spacing": 0.01, "m": 0.001,
            "k": 1000}, "forces": [{"type": "gravity", "g": [0, -9.81]}],
            "newton": {"solver": "cg", "cg_tol": 1e-14}})
    elif kind == "cloth-100-no-newton":  # issue 45: the lab's default solver by pattern
        text = json.dumps({"dt": 1 / 60, "t_end": 1, "cloth": {
            "origin": [0, 0], "rows": 100, "cols": 100, "spacing": 0.05, "m": 0.01,
            "k": 1e4, "k_bend": 100}, "forces": [{"type": "gravity", "g": [0, -9.81]}]})
    elif kind == "rigid-380000-point-forces":  # issue 45: force terms the model undercounts
        f = '{"type":"force","body":0,"F":[1e-6,0,0]}'
        text = ('{"dt":0.001,"t_end":100,"bodies":[{"shape":"sphere","radius":1,"m":1}],'
                '"forces":[' + ",".join([f] * 380000) + "]}")
    elif kind == "damping-400000":  # issue 45: 400 000 damping terms on one particle
        f = '{"type":"damping","b":1e-9}'
        text = ('{"dt":0.001,"t_end":100,"particles":[{"x":[0,0],"v":[1,0],"m":1}],'
                '"forces":[' + ",".join([f] * 400000) + "]}")
    elif kind == "sweep-1e5-terms":  # issue 45: a sweep whose every step pays 10^5 terms
        f = '{"type":"gravity","g":[0,-1e-6]}'
        text = ('{"dt":0.01,"t_end":1,"particles":[{"x":[0,0],"v":[1,0],"m":1}],'
                '"forces":[' + ",".join([f] * 100000) + "]}")
    elif kind == "dt-long-zeros":  # issue 45: 1 and 100 001 zeros, e-100002: dt = 0.1
        text = ('{"t_end": 1, "particles": [{"x": [0, 0], "m": 1}], "dt": 1'
                + "0" * 100001 + "e-100002}")
    else:
        raise SystemExit(f"run_badinput.py: unknown generator '{kind}'")
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)
    return path


def summary_state(stdout):
    """The summary line's momentum (which the emitters' seeds decide)."""
    lines = stdout.decode("utf-8", "replace").strip().splitlines()
    return json.loads(lines[-1]).get("momentum0") if lines else None


def limit_memory():
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT_BYTES, MEMORY_LIMIT_BYTES))


def without_dac_override():
    """preexec_fn of a `readonly` case run by root: the run keeps root's user (it must still
    reach the repository, which may be root's own, as /root/workbook on a fresh machine) but
    loses the two capabilities that let root write a file of mode 0444 (dropped from the
    bounding set before exec: the program starts without them)."""
    limit_memory()
    for cap in (CAP_DAC_OVERRIDE, CAP_DAC_READ_SEARCH):
        if LIBC.prctl(PR_CAPBSET_DROP, cap, 0, 0, 0) != 0:
            raise OSError(ctypes.get_errno(), "prctl(PR_CAPBSET_DROP)")


def cpu_seconds(pid):
    """The CPU time of process pid and of its waited-for children so far (/proc/pid/stat), or
    None once it is gone."""
    try:
        with open(f"/proc/{pid}/stat", encoding="ascii") as f:
            fields = f.read().rsplit(")", 1)[1].split()
    except (OSError, IndexError):
        return None
    return sum(int(x) for x in fields[11:15]) / os.sysconf("SC_CLK_TCK")


def communicate(proc, timeout, by_cpu=False):
    """proc.communicate(timeout), and the child's own resource usage (os.wait4): its CPU
    time and peak resident size, which RUSAGE_CHILDREN cannot give one child at a time.
    by_cpu: `timeout` is a hang detector (see IDLE_WINDOW_S): past it, the run times out once
    it has used `timeout` seconds of CPU, or computed nothing for IDLE_WINDOW_S, or reached
    HANG_WALL_FACTOR times `timeout` of wall time."""
    # The readers are the process's own, started once: a second call (after a timeout,
    # the process killed or signalled) keeps what the first read.
    if not hasattr(proc, "wb_readers"):
        proc.wb_got = {}

        def drain(name, pipe):
            proc.wb_got[name] = pipe.read()

        proc.wb_readers = [threading.Thread(target=drain, args=(k, p), daemon=True)
                           for k, p in (("out", proc.stdout), ("err", proc.stderr))]
        for t in proc.wb_readers:
            t.start()
    got, readers = proc.wb_got, proc.wb_readers
    start = time.monotonic()
    deadline = start + timeout
    seen = []  # (wall, cpu) of the last IDLE_WINDOW_S, by_cpu only
    while True:
        pid, status, usage = os.wait4(proc.pid, os.WNOHANG)
        if pid:
            break
        now = time.monotonic()
        if by_cpu:
            cpu = cpu_seconds(proc.pid)
            if cpu is not None:
                seen = [(w, c) for w, c in seen if w >= now - IDLE_WINDOW_S] + [(now, cpu)]
            idle = (cpu is not None and now - seen[0][0] >= IDLE_WINDOW_S * 0.9 and
                    cpu - seen[0][1] < IDLE_CPU_S)
            if now > deadline and (idle or (cpu or 0) > timeout or
                                   now > start + HANG_WALL_FACTOR * timeout):
                raise subprocess.TimeoutExpired(proc.args, timeout)
        elif now > deadline:
            raise subprocess.TimeoutExpired(proc.args, timeout)
        time.sleep(0.01)
    proc.returncode = os.waitstatus_to_exitcode(status)
    for t in readers:
        t.join()
    return got.get("out", b""), got.get("err", b""), usage


def flag_value(argv, flag):
    """The number after `flag` in argv, or None."""
    if flag in argv[:-1]:
        try:
            return float(argv[argv.index(flag) + 1])
        except ValueError:
            return None
    return None


def run_case(case, args):
    """Returns a list of problems (empty: the case passed)."""
    suffix = "" if args.side == "student" else "-" + args.side
    exe = os.path.join(args.bin, case["lab"] + suffix)
    if not os.path.exists(exe):
        return None  # lab not built
    tmp = tempfile.mkdtemp(prefix="wb-badinput-")
    try:
        scene = generate(case["generate"], tmp) if "generate" in case else ""
        subst = {"{scene}": scene, "{scenes}": os.path.join(HERE, "scenes"), "{tmp}": tmp,
                 "{repo}": REPO, "{badutf8}": "\udcff", "{name250}": "n" * 246 + ".csv",
                 "{name300}": "n" * 296 + ".csv"}
        argv = [exe]
        for a in case["args"]:
            for k, v in subst.items():
                a = a.replace(k, v)
            argv.append(a)
        # Special files the run writes to: a symbolic link (to /dev/null, say)
        # and FIFOs, each with a reader that drains it.
        readers = []
        if "symlink" in case:
            os.symlink(case["symlink"][1], os.path.join(tmp, case["symlink"][0]))
        for name in case.get("fifo", []):
            path = os.path.join(tmp, name)
            os.mkfifo(path)
            got = []
            t = threading.Thread(target=lambda p=path, g=got: g.append(open(p, "rb").read()),
                                 daemon=True)
            t.start()
            readers.append((name, t, got))
        for name, text in case.get("precreate", []):
            with open(os.path.join(tmp, name), "w", encoding="utf-8") as f:
                f.write(text)
        preexec = None if args.no_memory_limit else limit_memory
        for name in case.get("readonly", []):
            path = os.path.join(tmp, name)
            with open(path, "w", encoding="utf-8") as f:
                f.write("kept\n")
            os.chmod(path, 0o444)
            if os.geteuid() == 0:  # root may write anything: not without these capabilities
                preexec = without_dac_override
        start = time.monotonic()
        cpu_before = resource.getrusage(resource.RUSAGE_CHILDREN)
        # A valid but slow run ("kill_after": S) must warn before it starts: it
        # is stopped after S seconds and its stderr checked. A run stopped by
        # SIGTERM ("stop_after": S) must leave no temporary file behind.
        kill_after = case.get("kill_after")
        stop_after = case.get("stop_after")
        limit = case.get("max_seconds", TIME_LIMIT_S) * args.time_scale
        proc = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                preexec_fn=preexec)
        usage = None
        try:
            out, err_bytes, usage = communicate(proc, kill_after or stop_after or limit,
                                                by_cpu=not (kill_after or stop_after))
            code = proc.returncode
            if kill_after and case.get("may_finish") and code == 0:
                code = "killed"  # a skeleton's stub does no work: it may finish in time
            elif kill_after or stop_after:
                return [f"finished within {kill_after or stop_after} s, expected a run long "
                        "enough to stop"]
        except subprocess.TimeoutExpired:
            if not (kill_after or stop_after):
                proc.kill()
                proc.communicate()
                return [f"took more than {limit} s (and was computing nothing, or used that much "
                        f"CPU, or ran {HANG_WALL_FACTOR} times as long)"]
            if stop_after:
                proc.send_signal(getattr(signal, case.get("stop_signal", "SIGTERM")))
            else:
                proc.kill()
            out, err_bytes, usage = communicate(proc, limit)
            code = "stopped" if stop_after else "killed"
        p = subprocess.CompletedProcess(argv, code, out, err_bytes)
        for _, t, _ in readers:
            t.join(timeout=5)
        wall = time.monotonic() - start
        cpu_after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (cpu_after.ru_utime - cpu_before.ru_utime) + (cpu_after.ru_stime - cpu_before.ru_stime)
        problems = []
        if usage is not None:  # this child's own, not every child's since the last case
            cpu = usage.ru_utime + usage.ru_stime
        if "max_cpu_seconds" in case and cpu > case["max_cpu_seconds"] * args.time_scale:
            problems.append(f"used {cpu:.1f} s of CPU, expected at most {case['max_cpu_seconds']}")
        if case.get("budget") and usage is not None:
            max_time, max_mib = flag_value(argv, "--max-time"), flag_value(argv, "--max-memory")
            rss_mib = usage.ru_maxrss / 1024
            if max_time and cpu > BUDGET_SLACK * max_time * args.time_scale:
                problems.append(f"used {cpu:.2f} s of CPU, more than {BUDGET_SLACK} x its "
                                f"--max-time {max_time:g}")
            if max_mib and not args.no_memory_limit and rss_mib > BUDGET_SLACK * max_mib:
                problems.append(f"held {rss_mib:.0f} MiB, more than {BUDGET_SLACK} x its "
                                f"--max-memory {max_mib:g}")
        status = case.get("status", "stopped" if stop_after else "killed" if kill_after else 2)
        if p.returncode != status:
            problems.append(f"exit status {p.returncode}, expected {status}")
        try:
            err = p.stderr.decode("utf-8")
        except UnicodeDecodeError as e:
            problems.append(f"stderr is not valid UTF-8 ({e})")
            err = p.stderr.decode("utf-8", "replace")
        lines = err.split("\n")
        if status == 2:
            said = lines[:-1]
            if case.get("budget"):  # an accepted run may warn before it starts, then stop
                said = [ln for ln in said if not ln.startswith(os.path.basename(exe) + ": warning: ")]
            if len(said) != 1 or lines[-1] != "":
                problems.append(f"stderr has {len(said)} lines (besides warnings before the "
                                f"run), expected exactly one" if case.get("budget") else
                                f"stderr has {len(lines) - 1} lines, expected exactly one")
            longest = max(len(ln.encode("utf-8")) + 1 for ln in lines)
            if longest > MAX_LINE:
                problems.append(f"stderr has a line of {longest} bytes, expected at most {MAX_LINE}")
            if p.stdout:
                problems.append("stdout is not empty")
            if "\r" in err:
                problems.append("stderr holds a carriage return")
        elif "stderr_lines" in case:
            # A skeleton's runs also warn that a step looks like a stub: not counted.
            counted = [ln for ln in lines[:-1] if not ln.endswith(STUB_WARNING_ENDINGS)]
            if len(counted) != case["stderr_lines"]:
                problems.append(f"stderr has {len(counted)} lines (besides stub warnings), "
                                f"expected {case['stderr_lines']}")
        if case.get("solution_not_stub") and args.side == "solution":
            # A run the solution does right is never called a stub (a scene at rest,
            # one moved only by its collision phase, a body held still by a hinge).
            stubs = [ln for ln in lines[:-1] if ln.endswith(STUB_WARNING_ENDINGS)]
            if stubs or b'"stub":true' in p.stdout:
                problems.append("the solution's run is called a stub: "
                                + (stubs[0][:200] if stubs else "\"stub\":true in the summary"))
        if "lines_prefix" in case:
            prefix = case["lines_prefix"].replace("{exe}", os.path.basename(exe))
            for ln in lines[:-1]:
                if not ln.startswith(prefix):
                    problems.append(f"stderr line {ln[:80]!r} does not start with {prefix!r}")
        for want in case.get("expect", []):
            want = want.replace("{exe}", os.path.basename(exe))
            if want not in err:
                problems.append(f"stderr lacks {want!r}")
        out = p.stdout.decode("utf-8", "replace")
        for want in case.get("stdout", []):
            if want not in out:
                problems.append(f"stdout lacks {want!r}")
        if "differs_from" in case:  # another run whose summary must differ (seeds)
            other = [exe] + [a.replace("{scenes}", subst["{scenes}"]) for a in case["differs_from"]]
            q = subprocess.run(other, capture_output=True, timeout=limit)
            if q.returncode != 0 or summary_state(q.stdout) == summary_state(p.stdout):
                problems.append("gives the same summary as " + " ".join(case["differs_from"]))
        for name in case.get("absent", []):
            left = [f for f in os.listdir(tmp) if f.startswith(name)]
            if left:
                problems.append(f"left output files behind: {left}")
        for name in case.get("special", []):
            mode = os.lstat(os.path.join(tmp, name)).st_mode
            if stat.S_ISREG(mode):
                problems.append(f"{name} was replaced by a regular file")
            left = [f for f in os.listdir(tmp) if f.startswith(name + ".tmp")]
            if left:
                problems.append(f"left temporary files behind: {left}")
        for name, _, got in readers:
            data = got[0] if got else b""
            if not data.startswith(case.get("fifo_starts", "").encode()):
                problems.append(f"the reader of {name} got {data[:40]!r}")
        for name in case.get("readonly", []):
            with open(os.path.join(tmp, name), encoding="utf-8") as f:
                if f.read() != "kept\n":
                    problems.append(f"{name}, a file the run may not write, was replaced")
        if args.verbose or problems:
            rss = f", {usage.ru_maxrss / 1024:.0f} MiB" if usage is not None else ""
            print(f"    ({wall:.2f} s, {cpu:.2f} s CPU{rss}) stderr: {err.strip()[:300]!r}")
        return problems
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def every_lab(cases):
    """The cases with "lab": "*" once for every lab folder (labs/<lab>/, a new lab's too), named
    <name>@<lab>, with {first_scene} its first default scene; the others as they are."""
    labs = sorted(d for d in os.listdir(os.path.join(REPO, "labs"))
                  if os.path.isdir(os.path.join(REPO, "labs", d)))
    out = []
    for case in cases:
        if case["lab"] != "*":
            out.append(case)
            continue
        for lab in labs:
            scenes = sorted(glob.glob(os.path.join(REPO, "scenes", lab, "*.json")))
            first = scenes[0] if scenes else os.path.join(REPO, "scenes", lab, "none.json")
            out.append(dict(case, name=f"{case['name']}@{lab}", lab=lab,
                            args=[a.replace("{first_scene}", first) for a in case["args"]],
                            expect=[e.replace("{lab}", lab) for e in case.get("expect", [])]))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default=os.path.join(REPO, "build", "bin"),
                    help="folder of the lab executables (default: build/bin)")
    ap.add_argument("--side", default="solution", choices=["solution", "student"],
                    help="which executables (default: solution; bad input is refused before "
                         "any student function runs, so both sides must pass)")
    ap.add_argument("-k", dest="only", help="run only the cases whose name contains this")
    ap.add_argument("--no-memory-limit", action="store_true",
                    help="do not limit the address space (needed under AddressSanitizer)")
    ap.add_argument("--time-scale", type=float, default=1.0,
                    help="multiply the time limit (sanitizer builds run 10-50 times slower)")
    ap.add_argument("-v", "--verbose", action="store_true", help="print every message")
    args = ap.parse_args()
    with open(os.path.join(HERE, "cases.json"), encoding="utf-8") as f:
        cases = every_lab(json.load(f)["cases"])
    failed = ran = 0
    for case in cases:
        if args.only and args.only not in case["name"]:
            continue
        problems = run_case(case, args)
        if problems is None:
            print(f"skip {case['name']} ({case['lab']} not built)")
            continue
        ran += 1
        print(("ok   " if not problems else "FAIL ") + f"{case['class']}/{case['name']}")
        for pr in problems:
            print("    " + pr)
        failed += bool(problems)
    print(f"badinput: {ran - failed} of {ran} cases passed")
    if ran == 0:  # a pack without the forces, euler or midpoint labs
        print("badinput: no case ran: none of their lab executables is in " + args.bin)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
