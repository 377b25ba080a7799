"""The launcher's seccomp allow list and the worker's view (tools/gradescope/sandbox.c), tried
directly with a small C program: guards against a call that waits without the CPU, a lock or a
signal to another process getting through (issue 42: membarrier slept 10 s per test; POSIX
record locks on the shared worker binary passed between concurrent tests), and against the
view sharing a file with another test or showing the grader's paths."""
import os
import shutil
import subprocess

import pytest

from grader.sandbox import SANDBOX_SOURCE, elf_closure

PROBE = r"""
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <linux/futex.h>
#include <linux/membarrier.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/file.h>
#include <sys/inotify.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <time.h>
#include <unistd.h>
static void show(const char* what, long r) { printf("%s %s\n", what, r < 0 ? strerrorname_np(errno) : "ok"); }
int main(int argc, char** argv) {
  (void)argc;
  int fd = open(argv[0], O_RDONLY);
  show("open-read", fd);
  show("open-write", open(argv[0], O_WRONLY));
  show("membarrier", syscall(SYS_membarrier, MEMBARRIER_CMD_GLOBAL, 0, 0));
  show("sync", syscall(SYS_sync));
  show("fsync", fsync(fd));
  struct flock l = {.l_type = F_RDLCK, .l_whence = SEEK_SET, .l_start = 0, .l_len = 1};
  show("fcntl-setlk", fcntl(fd, F_SETLK, &l));
  show("fcntl-getlk", fcntl(fd, F_GETLK, &l));
  show("fcntl-getfd", fcntl(fd, F_GETFD));
  show("flock", flock(fd, LOCK_SH | LOCK_NB));
  show("inotify", inotify_init1(0));
  struct timespec ts = {0, 1000};
  show("nanosleep", nanosleep(&ts, NULL));
  int word = 0;
  show("futex-wait", syscall(SYS_futex, &word, FUTEX_WAIT_PRIVATE, 0, NULL, NULL, 0));
  show("futex-wake", syscall(SYS_futex, &word, FUTEX_WAKE_PRIVATE, 1, NULL, NULL, 0));
  show("kill-stop-self", kill(getpid(), SIGSTOP));
  show("kill-init", kill(1, SIGTERM));
  show("kill-self-0-probe", kill(getpid(), 0));
  void* p = mmap(NULL, 4096, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  show("madvise-dontneed", madvise(p, 4096, MADV_DONTNEED));
  show("madvise-pageout", madvise(p, 4096, 21));
  show("mincore", mincore(p, 4096, (unsigned char[1]){0}));
  show("setpriority", syscall(SYS_setpriority, 0, 0, 19));
  show("fork", fork());
  show("proc", open("/proc/1/cmdline", O_RDONLY));
  struct stat st;
  show("fstat", fstat(fd, &st));
  printf("name %s\ninode %lu %lu\n", argv[0], (unsigned long)st.st_dev, (unsigned long)st.st_ino);
  return 0;
}
"""


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    if not shutil.which("gcc"):
        pytest.skip("no gcc")
    d = tmp_path_factory.mktemp("filter")
    os.chmod(d, 0o755)
    launcher, probe = str(d / "wb-sandbox"), str(d / "probe")
    for cmd in (["gcc", "-O2", "-o", launcher, SANDBOX_SOURCE, "-lseccomp"],
                ["gcc", "-O2", "-o", probe, "-x", "c", "-"]):
        r = subprocess.run(cmd, input=PROBE.encode(), capture_output=True)
        if r.returncode != 0:
            pytest.skip(f"cannot build ({r.stderr.decode()[-200:]})")
    return d, launcher, probe


def _run(launcher, flags, probe):
    r, w = os.pipe()
    out = subprocess.run([launcher, "--status-fd", str(w)] + flags + ["--", probe],
                         pass_fds=(w,), capture_output=True, timeout=60)
    os.close(w)
    status = os.read(r, 4096).decode()
    os.close(r)
    assert status.strip() == "exit 0", status + out.stderr.decode()
    return dict(line.split(" ", 1) for line in out.stdout.decode().splitlines())


def test_calls_outside_the_allow_list_are_refused(built):
    """Defect: a deny list let through calls that block without the CPU (membarrier, sync),
    locks and notifications another test could see, and stopping itself for good."""
    _, launcher, probe = built
    got = _run(launcher, ["--seccomp"], probe)
    for call in ("membarrier", "sync", "fsync", "fcntl-setlk", "fcntl-getlk", "flock", "inotify",
                 "nanosleep", "futex-wait", "madvise-pageout", "mincore", "setpriority", "fork"):
        assert got[call] == "ENOSYS", call
    assert got["open-write"] == "EACCES"
    assert got["kill-stop-self"] == "ENOSYS" and got["kill-init"] == "ENOSYS"
    for call in ("open-read", "fcntl-getfd", "futex-wake", "madvise-dontneed", "fstat"):
        assert got[call] == "ok", call  # what a worker needs still works


@pytest.mark.skipif(os.geteuid() != 0, reason="namespaces need root")
def test_the_view_is_a_copy_with_no_proc_and_no_host_path(built):
    """Defect: every worker had the same binary bound into its view (one inode: locks on it
    passed between tests), saw its folder on the host in its argv, and read its namespace
    init's command line (the launcher's flags and folders) in /proc."""
    d, launcher, probe = built
    root = d / "view"
    root.mkdir(exist_ok=True)
    flags = ["--seccomp", "--ns", "--view-root", str(root)] + [
        x for f in elf_closure(probe) for x in ("--view", f)] + ["--uid", str(1 << 20)]
    got = _run(launcher, flags, probe)
    host = os.stat(probe)
    assert got["name"] == "/probe"
    assert got["inode"] != f"{host.st_dev} {host.st_ino}"
    assert got["proc"] == "ENOENT"
