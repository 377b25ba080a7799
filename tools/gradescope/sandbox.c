// wb-sandbox: runs one graded test process inside the layers tools/grade asks for.
//
//   wb-sandbox --status-fd N [--ns [--proc]] [--uid U] [--seccomp] [--as B] [--fsize B]
//              [--cpu S] [--nofile N] [--cwd DIR] [--env NAME=VALUE]...
//              [--view-root DIR --view FILE...] -- PROGRAM ARGS...
//
// Layers (each one is set up or the launcher fails with status 125 and says
// why on the status descriptor: a layer asked for is never silently missing):
//   --ns       new PID, mount, network, IPC and UTS namespaces: the test is
//              process 2 of its own PID namespace under a tiny init (process 1)
//              that reports its status; when the test ends the init exits and
//              the kernel kills everything left in the namespace. No network.
//   --proc     (with --ns) /proc is the namespace's own (its two processes,
//              nothing of the host's: no other process's command line or
//              environment). Needs mount (a container may refuse it: then this
//              layer alone is missing).
//   --view-root DIR --view FILE...  (with --ns) the test sees a file system
//              that holds the FILEs only, each at its own path, read-only: an
//              empty tmpfs mounted on DIR (in the test's mount namespace only)
//              becomes its root; the working folder is /. For the worker: its
//              binary, its shared libraries and the loader, nothing else (no
//              sources, no build tree, no tests, no solutions).
//   --uid U    runs the test as user and group U (no supplementary groups),
//              so it cannot write what the grader (root) owns, nor signal it.
//   --seccomp  a seccomp filter (after no_new_privs): no fork, vfork, clone
//              (so no threads and no children), no exec after the first, no
//              signals except to itself, no ptrace, no sockets, no namespaces
//              or mounts, no io_uring, no sleeping or timers (nanosleep, poll,
//              select, alarm..., and every wait with a timeout: futex waits with
//              one, rt_sigtimedwait, semtimedop, mq_timed*, io_getevents), and
//              files open read-only: every call that creates, writes, renames,
//              removes or changes a file fails.
//   rlimits    always: address space (--as), largest file (--fsize), CPU
//              seconds (--cpu), no core files, 64 open files (--nofile).
// The test always gets a clean environment (PATH, LANG, HOME, and the --env ones, at most 4).
// The status descriptor receives one line when the test has ended:
// "exit N", "signal N", or "error MESSAGE" (the launcher could not start it).
// It is closed (close-on-exec) in the test process itself.
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <grp.h>
#include <sched.h>
#include <seccomp.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <linux/futex.h>
#include <sys/mount.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

static int status_fd = -1;

static void report(const char* fmt, ...) {
  char buf[512];
  va_list ap;
  va_start(ap, fmt);
  int n = vsnprintf(buf, sizeof buf - 1, fmt, ap);
  va_end(ap);
  if (n < 0) return;
  if (n > (int)sizeof buf - 2) n = sizeof buf - 2;
  buf[n++] = '\n';
  if (status_fd >= 0 && write(status_fd, buf, (size_t)n) < 0) {
    // nothing more can be said
  }
}

static void fail(const char* what) {
  report("error %s: %s", what, strerror(errno));
  _exit(125);
}

static void limit(int resource, unsigned long long value, const char* what) {
  struct rlimit r = {(rlim_t)value, (rlim_t)value};
  if (setrlimit(resource, &r) != 0) fail(what);
}

// Adds "fail with errno" for one syscall (unconditionally, or when arg `arg`
// has every bit of `bits` set). Unknown syscalls on this architecture are skipped.
static void deny(scmp_filter_ctx ctx, const char* name, int err) {
  int nr = seccomp_syscall_resolve_name(name);
  if (nr == __NR_SCMP_ERROR) return;
  if (seccomp_rule_add(ctx, SCMP_ACT_ERRNO(err), nr, 0) != 0) fail(name);
}

static void deny_bits(scmp_filter_ctx ctx, const char* name, unsigned arg, unsigned long bits) {
  int nr = seccomp_syscall_resolve_name(name);
  if (nr == __NR_SCMP_ERROR) return;
  struct scmp_arg_cmp cmp = {arg, SCMP_CMP_MASKED_EQ, bits, bits};
  if (seccomp_rule_add_array(ctx, SCMP_ACT_ERRNO(EACCES), nr, 1, &cmp) != 0) fail(name);
}

static void deny_unless_self(scmp_filter_ctx ctx, const char* name, pid_t self) {
  int nr = seccomp_syscall_resolve_name(name);
  if (nr == __NR_SCMP_ERROR) return;
  struct scmp_arg_cmp cmp = {0, SCMP_CMP_NE, (scmp_datum_t)self, 0};
  if (seccomp_rule_add_array(ctx, SCMP_ACT_ERRNO(EPERM), nr, 1, &cmp) != 0) fail(name);
}

static void install_seccomp(const char* exec_path, char* const* exec_argv) {
  if (prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) != 0) fail("no_new_privs");
  scmp_filter_ctx ctx = seccomp_init(SCMP_ACT_ALLOW);
  if (!ctx) fail("seccomp_init");
  // No new processes or threads.
  const char* no_processes[] = {"fork", "vfork", "clone", "setsid", "setpgid", "ptrace",
                                "process_vm_readv", "process_vm_writev", "pidfd_open",
                                "pidfd_getfd", "pidfd_send_signal", "rt_sigqueueinfo",
                                "rt_tgsigqueueinfo", "unshare", "setns", "mount", "umount2",
                                "pivot_root", "chroot", "move_mount", "open_tree", "fsopen",
                                "fsmount", "bpf", "perf_event_open", "userfaultfd", "keyctl",
                                "add_key", "request_key", "io_uring_setup", "io_uring_enter",
                                "io_uring_register", "memfd_create", "memfd_secret",
                                "personality", "seccomp", "kcmp", "setuid", "setgid",
                                "setreuid", "setregid", "setresuid", "setresgid", "setgroups",
                                "reboot", "kexec_load", "init_module", "finit_module",
                                "delete_module", "swapon", "swapoff", "sethostname",
                                "setdomainname", "acct", "quotactl", "name_to_handle_at",
                                "open_by_handle_at", "fanotify_init", "mknod", "mknodat"};
  for (size_t i = 0; i < sizeof no_processes / sizeof *no_processes; ++i)
    deny(ctx, no_processes[i], EPERM);
  deny(ctx, "clone3", ENOSYS);  // glibc then tries clone, refused above
  // No sleeping: a test that idles would otherwise hold its time slot without using the CPU
  // (waiting on a pipe, which the worker does between calls, is still allowed).
  const char* no_sleeping[] = {"nanosleep", "clock_nanosleep", "pause", "alarm", "setitimer",
                               "timer_create", "timerfd_create", "select", "pselect6", "poll",
                               "ppoll", "epoll_create", "epoll_create1", "epoll_wait",
                               "epoll_pwait", "epoll_pwait2"};
  for (size_t i = 0; i < sizeof no_sleeping / sizeof *no_sleeping; ++i)
    deny(ctx, no_sleeping[i], EPERM);
  // Nor any other wait that ends by itself after a while: with no timer and no other process
  // of its own, a process that blocks then blocks for good, and the grader's idle rule stops it.
  const char* no_timed_waits[] = {"rt_sigtimedwait", "semtimedop", "mq_timedreceive",
                                  "mq_timedsend", "io_getevents", "io_pgetevents", "futex_waitv",
                                  "timer_settime", "timerfd_settime"};
  for (size_t i = 0; i < sizeof no_timed_waits / sizeof *no_timed_waits; ++i)
    deny(ctx, no_timed_waits[i], EPERM);
  // futex: the waits that take a timeout (argument 3) may not have one (glibc's own locks
  // wait without one, and a single-threaded process never waits on them anyway).
  const int futex_waits[] = {FUTEX_WAIT, FUTEX_LOCK_PI, FUTEX_WAIT_BITSET, FUTEX_WAIT_REQUEUE_PI,
                             13 /* FUTEX_LOCK_PI2 */};
  for (size_t i = 0; i < sizeof futex_waits / sizeof *futex_waits; ++i) {
    struct scmp_arg_cmp cmp[2] = {{1, SCMP_CMP_MASKED_EQ, 0x7f, (scmp_datum_t)futex_waits[i]},
                                  {3, SCMP_CMP_NE, 0, 0}};
    if (seccomp_rule_add_array(ctx, SCMP_ACT_ERRNO(EPERM), SCMP_SYS(futex), 2, cmp) != 0)
      fail("futex");
  }
  // No network.
  const char* no_network[] = {"socket", "socketpair", "connect", "bind", "listen", "accept",
                              "accept4"};
  for (size_t i = 0; i < sizeof no_network / sizeof *no_network; ++i)
    deny(ctx, no_network[i], EPERM);
  // Signals only to itself (abort() and Catch's crash handler re-raise).
  pid_t self = getpid();
  deny_unless_self(ctx, "kill", self);
  deny_unless_self(ctx, "tkill", self);
  deny_unless_self(ctx, "tgkill", self);
  // Exec only this once: the filter admits execve of exactly these path and
  // argv pointers, which exist in this process only until the exec replaces
  // it (whatever a later exec could run would still be inside this filter).
  int nr = seccomp_syscall_resolve_name("execve");
  struct scmp_arg_cmp path_cmp = {0, SCMP_CMP_NE, (scmp_datum_t)(uintptr_t)exec_path, 0};
  struct scmp_arg_cmp argv_cmp = {1, SCMP_CMP_NE, (scmp_datum_t)(uintptr_t)exec_argv, 0};
  if (seccomp_rule_add_array(ctx, SCMP_ACT_ERRNO(EPERM), nr, 1, &path_cmp) != 0 ||
      seccomp_rule_add_array(ctx, SCMP_ACT_ERRNO(EPERM), nr, 1, &argv_cmp) != 0)
    fail("execve");
  deny(ctx, "execveat", EPERM);
  // Files: read-only. Opening with any write, create, truncate or append
  // flag fails, and so does every call that changes the file system.
  const unsigned long write_flags[] = {O_WRONLY, O_RDWR, O_CREAT, O_TRUNC, O_APPEND,
                                       020000000 /* __O_TMPFILE */};
  for (size_t i = 0; i < sizeof write_flags / sizeof *write_flags; ++i) {
    deny_bits(ctx, "open", 1, write_flags[i]);
    deny_bits(ctx, "openat", 2, write_flags[i]);
  }
  const char* no_changes[] = {"openat2", "creat", "unlink", "unlinkat", "rename", "renameat",
                              "renameat2", "link", "linkat", "symlink", "symlinkat", "mkdir",
                              "mkdirat", "rmdir", "truncate", "chmod", "fchmod", "fchmodat",
                              "fchmodat2", "chown", "fchown", "lchown", "fchownat", "utime",
                              "utimes", "utimensat", "futimesat", "setxattr", "lsetxattr",
                              "fsetxattr", "removexattr", "lremovexattr", "fremovexattr",
                              "fallocate", "splice", "tee", "vmsplice", "copy_file_range",
                              "sendfile"};
  for (size_t i = 0; i < sizeof no_changes / sizeof *no_changes; ++i)
    deny(ctx, no_changes[i], EACCES);
  if (seccomp_load(ctx) != 0) fail("seccomp_load");
  seccomp_release(ctx);
}

// Creates every missing folder of `path` (absolute) below the current root.
static void make_parents(const char* path) {
  char buf[4096];
  if (strlen(path) >= sizeof buf) {
    errno = ENAMETOOLONG;
    fail("view path");
  }
  strcpy(buf, path);
  for (char* p = buf + 1; *p; ++p) {
    if (*p != '/') continue;
    *p = 0;
    if (mkdir(buf, 0755) != 0 && errno != EEXIST) fail("mkdir (view)");
    *p = '/';
  }
}

static void bind_read_only(const char* from, const char* to) {
  if (mount(from, to, NULL, MS_BIND, NULL) != 0) fail(from);
  if (mount(NULL, to, NULL, MS_BIND | MS_REMOUNT | MS_RDONLY | MS_NOSUID | MS_NODEV, NULL) != 0)
    fail("remount read-only (view)");
}

// In the namespace's init (process 1 of the new PID namespace, in its own mount namespace):
// nothing mounted here reaches the host; /proc becomes this namespace's own; with a view, the
// root becomes a tmpfs holding only the view's files, each bound read-only at its own path.
static void private_mounts(const char* root, const char** files, int n) {
  if (mount(NULL, "/", NULL, MS_REC | MS_PRIVATE, NULL) != 0) fail("mount (private)");
  if (!root) {
    if (mount("proc", "/proc", "proc", MS_NOSUID | MS_NODEV | MS_NOEXEC, NULL) != 0)
      fail("mount /proc");
    return;
  }
  if (mount("wb-view", root, "tmpfs", MS_NOSUID | MS_NODEV, "size=1m,mode=0755") != 0)
    fail("mount tmpfs (view)");
  char path[4096];
  for (int k = 0; k < n; ++k) {
    if (snprintf(path, sizeof path, "%s%s", root, files[k]) >= (int)sizeof path) {
      errno = ENAMETOOLONG;
      fail("view path");
    }
    make_parents(path);
    int fd = open(path, O_WRONLY | O_CREAT | O_CLOEXEC, 0755);
    if (fd < 0) fail("create (view)");
    close(fd);
    bind_read_only(files[k], path);
  }
  if (snprintf(path, sizeof path, "%s/proc", root) >= (int)sizeof path) fail("view path");
  if (mkdir(path, 0555) != 0 && errno != EEXIST) fail("mkdir /proc (view)");
  if (mount("proc", path, "proc", MS_NOSUID | MS_NODEV | MS_NOEXEC, NULL) != 0)
    fail("mount /proc (view)");
  // The old root goes: pivot_root puts it under the new one, and it is then detached.
  if (snprintf(path, sizeof path, "%s/old-root", root) >= (int)sizeof path) fail("view path");
  if (mkdir(path, 0700) != 0) fail("mkdir (view)");
  if (syscall(SYS_pivot_root, root, path) != 0) fail("pivot_root (view)");
  if (chdir("/") != 0) fail("chdir (view)");
  if (umount2("/old-root", MNT_DETACH) != 0) fail("umount old root (view)");
  if (rmdir("/old-root") != 0) fail("rmdir (view)");
  if (mount(NULL, "/", NULL, MS_BIND | MS_REMOUNT | MS_RDONLY | MS_NOSUID | MS_NODEV, NULL) != 0 &&
      mount(NULL, "/", NULL, MS_REMOUNT | MS_RDONLY | MS_NOSUID | MS_NODEV, NULL) != 0)
    fail("remount / read-only (view)");
}

int main(int argc, char** argv) {
  int use_ns = 0, use_seccomp = 0, use_proc = 0;
  long uid = -1;
  unsigned long long as = 0, fsize = 0, cpu = 0, nofile = 64;
  const char* cwd = NULL;
  enum { kMaxEnv = 4, kMaxView = 64 };
  char* extra_env[kMaxEnv] = {NULL};
  int n_env = 0;
  const char* view_root = NULL;
  const char* view[kMaxView];
  int n_view = 0;
  int i = 1;
  for (; i < argc; ++i) {
    const char* a = argv[i];
    if (!strcmp(a, "--")) {
      ++i;
      break;
    } else if (!strcmp(a, "--ns")) {
      use_ns = 1;
    } else if (!strcmp(a, "--proc")) {
      use_proc = 1;
    } else if (!strcmp(a, "--seccomp")) {
      use_seccomp = 1;
    } else if (i + 1 < argc && !strcmp(a, "--status-fd")) {
      status_fd = atoi(argv[++i]);
    } else if (i + 1 < argc && !strcmp(a, "--uid")) {
      uid = atol(argv[++i]);
    } else if (i + 1 < argc && !strcmp(a, "--as")) {
      as = strtoull(argv[++i], NULL, 10);
    } else if (i + 1 < argc && !strcmp(a, "--fsize")) {
      fsize = strtoull(argv[++i], NULL, 10);
    } else if (i + 1 < argc && !strcmp(a, "--cpu")) {
      cpu = strtoull(argv[++i], NULL, 10);
    } else if (i + 1 < argc && !strcmp(a, "--nofile")) {
      nofile = strtoull(argv[++i], NULL, 10);
    } else if (i + 1 < argc && !strcmp(a, "--cwd")) {
      cwd = argv[++i];
    } else if (i + 1 < argc && !strcmp(a, "--env") && strchr(argv[i + 1], '=') &&
               n_env < kMaxEnv) {
      extra_env[n_env++] = argv[++i];
    } else if (i + 1 < argc && !strcmp(a, "--view-root") && argv[i + 1][0] == '/') {
      view_root = argv[++i];
    } else if (i + 1 < argc && !strcmp(a, "--view") && argv[i + 1][0] == '/' && n_view < kMaxView) {
      view[n_view++] = argv[++i];
    } else {
      fprintf(stderr, "wb-sandbox: unknown argument '%s'\n", a);
      return 125;
    }
  }
  if (i >= argc) {
    fprintf(stderr, "usage: wb-sandbox --status-fd N [--ns] [--uid U] [--seccomp] [--as B] "
                    "[--fsize B] [--cpu S] [--nofile N] [--cwd DIR] [--env NAME=VALUE]... [--proc] "
                    "[--view-root DIR --view FILE...] -- PROGRAM ARGS...\n");
    return 125;
  }
  if ((view_root != NULL) != (n_view > 0) || ((view_root || use_proc) && !use_ns)) {
    fprintf(stderr, "wb-sandbox: --view-root and --view go together; they and --proc need --ns\n");
    return 125;
  }
  if (status_fd >= 0) fcntl(status_fd, F_SETFD, FD_CLOEXEC);
  // If the grader dies (even by SIGKILL), so does the launcher, its init, and
  // with it the namespace and the test: nothing runs on unwatched.
  pid_t grader = getppid();
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (getppid() != grader) return 125;
  char** child_argv = argv + i;

  if (use_ns &&
      unshare(CLONE_NEWPID | CLONE_NEWNS | CLONE_NEWNET | CLONE_NEWIPC | CLONE_NEWUTS) != 0)
    fail("unshare (namespaces)");
  pid_t init = fork();
  if (init < 0) fail("fork");
  if (init > 0) {  // the launcher: waits for the namespace's init, then ends
    int st;
    while (waitpid(init, &st, 0) < 0 && errno == EINTR) {
    }
    return WIFEXITED(st) ? WEXITSTATUS(st) : 125;
  }
  // The init of the namespace (or, without --ns, a plain reaper).
  prctl(PR_SET_PDEATHSIG, SIGKILL);  // the grader killed the launcher: end everything
  if (use_proc || view_root) private_mounts(view_root, view, n_view);
  pid_t test = fork();
  if (test < 0) fail("fork");
  if (test == 0) {
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (as) limit(RLIMIT_AS, as, "RLIMIT_AS");
    if (fsize) limit(RLIMIT_FSIZE, fsize, "RLIMIT_FSIZE");
    if (cpu) limit(RLIMIT_CPU, cpu, "RLIMIT_CPU");
    limit(RLIMIT_CORE, 0, "RLIMIT_CORE");
    limit(RLIMIT_NOFILE, nofile, "RLIMIT_NOFILE");
    if (view_root) {
      if (chdir("/") != 0) fail("chdir /");
    } else if (cwd && chdir(cwd) != 0) {
      fail("chdir");
    }
    if (uid >= 0) {
      if (setgroups(0, NULL) != 0) fail("setgroups");
      if (setresgid((gid_t)uid, (gid_t)uid, (gid_t)uid) != 0) fail("setresgid");
      if (setresuid((uid_t)uid, (uid_t)uid, (uid_t)uid) != 0) fail("setresuid");
      if (getuid() != (uid_t)uid || geteuid() != (uid_t)uid) {
        errno = EPERM;
        fail("setresuid (still privileged)");
      }
    }
    if (use_seccomp) install_seccomp(child_argv[0], child_argv);
    // A clean environment: nothing of the grader's (tokens, paths) reaches the test.
    char* env[4 + kMaxEnv] = {"PATH=/usr/bin:/bin", "LANG=C.UTF-8", "HOME=/nonexistent"};
    for (int k = 0; k < n_env; ++k) env[3 + k] = extra_env[k];
    execve(child_argv[0], child_argv, env);
    fail("exec");
  }
  int st;
  while (waitpid(test, &st, 0) < 0) {
    if (errno != EINTR) fail("waitpid");
  }
  if (WIFEXITED(st))
    report("exit %d", WEXITSTATUS(st));
  else if (WIFSIGNALED(st))
    report("signal %d", WTERMSIG(st));
  else
    report("error unknown wait status %d", st);
  _exit(0);  // as the namespace's init: the kernel now kills whatever the test left
}
