"""The sandbox around every process that runs code built from a submission (tools/gradescope/
sandbox.c): seccomp, namespaces, another user, limits, as this machine allows.

Trust: this is the wall around student code."""
import hashlib
import math
import os
import re
import secrets
import shutil
import subprocess
import threading

from .common import Defect, REPORT_CAP, REPORT_FSIZE, OUTPUT_CAP, TEST_ADDRESS_SPACE, TEST_CPU
from .procs import _Capture, _close_unless_busy, _finish, _start

# ------------------------------------------------------------------ the sandbox

SANDBOX_SOURCE = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "gradescope",
                              "sandbox.c")
BUILD_UID = 60999  # the build (compiler, assembler, linker) runs as this user when root
BUILD_ADDRESS_SPACE = 4 * 1024 * 1024 * 1024  # RLIMIT_AS of each compiler process
BUILD_FSIZE = 512 * 1024 * 1024  # largest file a build may write (the precompiled headers: 100 MB)
BUILD_CPU = 900  # s, RLIMIT_CPU of each build process
# Test processes run as users drawn at random from this range, never two at once with the same
# one: a process cannot guess the other's user from its own (tools/gradescope/hostile knows the
# range, to find what a test user left behind).
TEST_UID_RANGE = (1 << 20, 1 << 30)
LAYER_TEXT = {
    "seccomp": "seccomp allow list: the calls a test needs, none that waits for anything but its "
               "own pipes (no sleeping, locks, processes, threads, exec, signals to others, "
               "sockets); files read-only",
    "namespaces": "own PID, mount, network and IPC namespaces: everything the test started ends "
                  "with it",
    "proc": "its own /proc: no other process is visible (their command lines, environments)",
    "view": "the worker's file system holds its own copies of its binary and libraries only "
            "(no sources, build tree, tests or solutions, no /proc, no file another test sees)",
    "user": "unprivileged user, a random one for each process (cannot write the grader's files "
            "or signal it)",
    "rlimits": "limits: memory (address space), file size, CPU time, no core files",
}


class Sandbox:
    """The layers around each test process that this machine can give (see
    tools/gradescope/sandbox.c). `layers` lists the active ones, in order."""

    def __init__(self, root, say):
        self.launcher, self.layers, self.missing = None, [], {}
        self._uids, self._uid_lock = set(), threading.Lock()
        self.view_root = os.path.join(root, "view")  # an empty folder: the worker's tmpfs root
        self._libraries = {}
        self.layers.append("rlimits")
        try:
            self.launcher = self._compile(root)
        except Exception as e:  # no compiler or no libseccomp: the limits alone
            self.launcher = None
            reason = str(e).strip().splitlines()[-1:] or ["unknown"]
            for layer in ("seccomp", "namespaces", "proc", "view", "user"):
                self.missing[layer] = f"the launcher could not be built: {reason[0]}"
            return
        if not os.path.isdir(self.view_root):
            os.mkdir(self.view_root, 0o755)
        true = shutil.which("true") or "/bin/true"
        wanted = {"seccomp": ["--seccomp"], "namespaces": ["--ns"], "proc": ["--ns", "--proc"],
                  "view": ["--ns"] + self._view_flags(true),
                  "user": ["--uid", str(TEST_UID_RANGE[0])]}
        disabled = set(os.environ.get("WB_SANDBOX_DISABLE", "").replace(",", " ").split())
        for layer, flags in wanted.items():
            if layer in disabled:  # to see what the other layers hold alone
                self.missing[layer] = "disabled by WB_SANDBOX_DISABLE"
                continue
            if layer in ("proc", "view") and "namespaces" not in self.layers:
                self.missing[layer] = "needs the namespaces layer"
                continue
            ok, why = self._probe(flags)
            if ok:
                self.layers.append(layer)
            else:
                self.missing[layer] = why
        ok, why = self._probe(self.flags(0, view=true))
        if not ok:  # each works alone but not together: keep the safest single one
            raise Defect(f"the sandbox layers {', '.join(self.layers)} do not work together: {why}")

    def _compile(self, root):
        if not os.path.isfile(SANDBOX_SOURCE):
            raise RuntimeError("tools/gradescope/sandbox.c is not in this copy of the project")
        with open(SANDBOX_SOURCE, "rb") as f:
            src = f.read()
        exe = os.path.join(root, "wb-sandbox-" + hashlib.sha256(src).hexdigest()[:16])
        if not os.path.isfile(exe):
            tmp = exe + ".tmp"
            out = subprocess.run(["gcc", "-O2", "-o", tmp, SANDBOX_SOURCE, "-lseccomp"],
                                 stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                                 stderr=subprocess.STDOUT, timeout=120)
            if out.returncode != 0:
                raise RuntimeError(out.stdout.decode("utf-8", "replace"))
            os.chmod(tmp, 0o755)
            os.replace(tmp, exe)
        return exe

    def _probe(self, flags):
        true = shutil.which("true") or "/bin/true"
        r, w = os.pipe()
        try:
            proc = subprocess.run([self.launcher, "--status-fd", str(w)] + flags + ["--", true],
                                  stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                  stderr=subprocess.PIPE, pass_fds=(w,), timeout=30, cwd="/")
            os.close(w)
            w = -1
            status = os.read(r, 4096).decode("utf-8", "replace").strip()
        except (OSError, subprocess.SubprocessError) as e:
            return False, str(e)
        finally:
            os.close(r)
            if w >= 0:
                os.close(w)
        if proc.returncode == 0 and status == "exit 0":
            return True, ""
        return False, status.split("\n")[0].removeprefix("error ") or \
            proc.stderr.decode("utf-8", "replace").strip()

    def next_uid(self):
        """A user no running test process has, drawn at random (released by release_uid)."""
        with self._uid_lock:
            while True:
                uid = TEST_UID_RANGE[0] + secrets.randbelow(TEST_UID_RANGE[1] - TEST_UID_RANGE[0])
                if uid not in self._uids:
                    self._uids.add(uid)
                    return uid

    def release_uid(self, uid):
        with self._uid_lock:
            self._uids.discard(uid)

    def libraries(self, binary):
        """The files a dynamically linked binary needs to start: its interpreter, the shared
        libraries it and they need (DT_NEEDED, resolved as the loader would: RUNPATH, then
        ldconfig's cache, then the default folders) and the loader's cache. Read with readelf
        (the binary never runs); cached per binary path and version."""
        st = os.stat(binary)
        key = (binary, st.st_ino, st.st_size, st.st_mtime_ns)
        if key not in self._libraries:
            self._libraries[key] = elf_closure(binary)
        return self._libraries[key]

    def _view_flags(self, binary):
        """The view of a process running `binary`: the launcher copies the binary itself to
        /<its name> and these libraries to their own paths."""
        return ["--view-root", self.view_root] + [
            x for f in self.libraries(binary) for x in ("--view", f)]

    def flags(self, uid, view=None):
        """The launcher's flags of the active layers; `view`: the binary whose file system view
        the process gets (when that layer is active)."""
        f = []
        if "seccomp" in self.layers:
            f.append("--seccomp")
        if "namespaces" in self.layers:
            f.append("--ns")
            if "proc" in self.layers:
                f.append("--proc")
            if view and "view" in self.layers:
                f += self._view_flags(view)
        if "user" in self.layers:
            f += ["--uid", str(uid or TEST_UID_RANGE[0])]
        return f

    def describe(self):
        lines = [f"  active: {LAYER_TEXT[l]}" for l in self.layers]
        lines += [f"  NOT active: {LAYER_TEXT[l].split(':')[0].split(' (')[0]} ({why})"
                  for l, why in self.missing.items()]
        return "\n".join(lines)

    def build_command(self, cmd, cwd, as_user=True):
        """The launcher's layers for a build (the compiler, assembler and linker): limits
        (BUILD_* in common.py), and when root another user (BUILD_UID, which owns only the
        build folder) in its own PID and network namespaces; no seccomp (compilers start
        processes). None without a launcher."""
        if self.launcher is None:
            return None
        f = []
        if "namespaces" in self.layers:
            f.append("--ns")
        if "user" in self.layers and as_user:
            f += ["--uid", str(BUILD_UID)]
        return [self.launcher] + f + ["--as", str(BUILD_ADDRESS_SPACE), "--fsize", str(BUILD_FSIZE),
                                      "--cpu", str(BUILD_CPU), "--nofile", "1024", "--cwd", cwd,
                                      "--"] + cmd

    def start(self, cmd, cwd, pass_fds=(), env=(), stdout_cap=REPORT_CAP + 1,
              stderr_cap=OUTPUT_CAP, wrapped=None, keep_tail=False, view=False, cpu=None):
        """Starts one process in the sandbox (its standard output and error captured, capped,
        read in linear time); `pass_fds` are inherited, `env` lists "NAME=VALUE"s added to
        its clean environment (at most 4); `view`: the process sees only its binary and
        libraries (the worker); `cpu`: its CPU time limit, s (the kernel's RLIMIT_CPU: SIGXCPU
        a second after it, SIGKILL a second later; TEST_CPU if None). Returns a Running;
        Running.finish() waits for it."""
        rlimit_cpu = TEST_CPU if cpu is None else math.ceil(cpu) + 1
        if self.launcher is None:  # no launcher: the limits through prlimit, if present
            wrapped = (["prlimit", f"--fsize={REPORT_FSIZE}", f"--as={TEST_ADDRESS_SPACE}",
                        f"--cpu={rlimit_cpu}:{rlimit_cpu + 1}", "--core=0", "--"]
                       if shutil.which("prlimit") else [])
            if not wrapped and "rlimits" in self.layers:
                self.layers.remove("rlimits")
                self.missing["rlimits"] = "prlimit is not installed"
            clean = {"PATH": "/usr/bin:/bin", "LANG": "C.UTF-8"}
            for e in env:
                clean[e.split("=", 1)[0]] = e.split("=", 1)[1]
            proc = _start(wrapped + cmd, subprocess.PIPE, subprocess.PIPE, cwd=cwd,
                          pass_fds=pass_fds, env=clean)
            status_r = None
        else:
            status_r, status_w = os.pipe()
            os.set_inheritable(status_w, True)
            uid = None
            if wrapped:  # a prepared launcher command (build_command)
                full = [wrapped[0], "--status-fd", str(status_w)] + wrapped[1:]
            else:
                uid = self.next_uid()
                full = [self.launcher, "--status-fd", str(status_w)] + \
                    self.flags(uid, cmd[0] if view else None) + [
                    "--as", str(TEST_ADDRESS_SPACE), "--fsize", str(REPORT_FSIZE), "--cpu",
                    str(rlimit_cpu), "--cwd", cwd] + [x for e in env for x in ("--env", e)] + \
                    ["--"] + cmd
            try:
                proc = _start(full, subprocess.PIPE, subprocess.PIPE, cwd=cwd,
                              pass_fds=(status_w,) + tuple(pass_fds))
            except BaseException:
                if uid is not None:
                    self.release_uid(uid)
                raise
            finally:
                os.close(status_w)
            running = Running(proc, status_r, stdout_cap, stderr_cap, keep_tail)
            running.release = (lambda: self.release_uid(uid)) if uid is not None else None
            return running
        return Running(proc, status_r, stdout_cap, stderr_cap, keep_tail)

    def run(self, cmd, timeout, cwd):
        """Runs one process. Returns (status, stdout bytes or None if over the cap, stderr
        text) where status is ("exit", N), ("signal", N), ("timeout", None) or ("error", message)."""
        return self.start(cmd, cwd).finish(timeout)


class Running:
    """One sandboxed process under way."""

    def __init__(self, proc, status_r, stdout_cap, stderr_cap, keep_tail=False):
        self.proc, self.status_r, self.cap = proc, status_r, stdout_cap - 1
        self.release = None  # frees the process's user once it has ended
        self.report = _Capture(proc.stdout, stdout_cap, keep_tail)
        self.output = _Capture(proc.stderr, stderr_cap, keep_tail)
        self.report.start()
        self.output.start()

    def finish(self, timeout):
        proc = self.proc
        rc = _finish(proc, timeout)
        # Nothing the process started can still hold the pipes (no children with the
        # seccomp filter, the namespace ends with its init, the group was killed):
        # a reader still blocked after that gives up, and what it has is all that counts.
        self.report.join(timeout=5)
        self.output.join(timeout=5)
        _close_unless_busy(proc.stdout, self.report)
        _close_unless_busy(proc.stderr, self.output)
        status = None
        if self.status_r is not None:
            with os.fdopen(self.status_r, "rb") as f:
                line = f.read(4096).decode("utf-8", "replace").strip().split("\n")[0]
            m = re.fullmatch(r"(exit|signal) (\d+)", line)
            if line.startswith("error "):
                status = ("error", line[6:])
            elif m:
                status = (m.group(1), int(m.group(2)))
        if self.release and rc is not None:  # ended: its namespace and every process in it too
            self.release()
        if rc is None:
            status = ("timeout", None)
        elif status is None:  # without the launcher, or it was killed
            status = ("exit", rc) if rc >= 0 else ("signal", -rc)
        data = self.report.data if self.report.total <= self.cap else None
        return status, data, self.output.text()


# ------------------------------------------------------------ a binary's libraries

def _readelf(args, path):
    out = subprocess.run(["readelf", "-W"] + args + [path], stdin=subprocess.DEVNULL,
                         stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, timeout=60)
    return out.stdout.decode("utf-8", "replace")


_LDCONFIG = None


def _ldconfig():
    """{library name: path} of the loader's cache for this machine's word size."""
    global _LDCONFIG
    if _LDCONFIG is None:
        _LDCONFIG = {}
        try:
            out = subprocess.run(["ldconfig", "-p"], stdin=subprocess.DEVNULL,
                                 stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                                 timeout=60).stdout.decode("utf-8", "replace")
        except (OSError, subprocess.SubprocessError):
            out = ""
        for line in out.splitlines():
            m = re.match(r"\s*(\S+) \((.*)\) => (\S+)$", line)
            if m and ("x86-64" in m.group(2) or "64bit" in m.group(2) or "x86" not in m.group(2)):
                _LDCONFIG.setdefault(m.group(1), m.group(3))
    return _LDCONFIG


DEFAULT_LIB_DIRS = ["/lib/x86_64-linux-gnu", "/usr/lib/x86_64-linux-gnu", "/lib64", "/usr/lib64",
                    "/lib", "/usr/lib", "/usr/local/lib"]


def elf_closure(binary):
    """The interpreter, the shared libraries (transitively) and /etc/ld.so.cache a binary needs
    (readelf only: the binary is never run). Raises Defect when a library cannot be found."""
    files, todo, seen = [], [binary], set()
    interp = re.search(r"\[Requesting program interpreter: ([^\]]+)\]", _readelf(["-l"], binary))
    if interp:
        files.append(interp.group(1))
    while todo:
        path = todo.pop()
        dyn = _readelf(["-d"], path)
        runpath = [d for m in re.finditer(r"\((?:RUNPATH|RPATH)\).*\[(.*)\]", dyn)
                   for d in m.group(1).split(":") if d.startswith("/")]
        for name in re.findall(r"\(NEEDED\).*\[(.*)\]", dyn):
            if name in seen:
                continue
            seen.add(name)
            found = next((os.path.join(d, name) for d in runpath
                          if os.path.isfile(os.path.join(d, name))), None) or \
                _ldconfig().get(name) or next((os.path.join(d, name) for d in DEFAULT_LIB_DIRS
                                               if os.path.isfile(os.path.join(d, name))), None)
            if not found:
                raise Defect(f"{binary} needs {name}, which the loader would not find")
            files.append(found)
            todo.append(found)
    if os.path.isfile("/etc/ld.so.cache"):
        files.append("/etc/ld.so.cache")
    # A path that is a symbolic link (/lib64/ld-linux-x86-64.so.2) is bound with its target's
    # content at the link's own path: the loader opens the paths it resolved, nothing else.
    return sorted(set(files))
