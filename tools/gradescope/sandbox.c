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
#include <sys/mman.h>
#include <sys/mount.h>
#include <sys/sendfile.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <termios.h>
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

// The seccomp filter is an ALLOW list: a call that is not below fails with ENOSYS (a glibc
// that tries a newer call first then falls back to an older one, which is below or fails the
// same way). Every call below returns without waiting for anything but its own pipes and
// the CPU: nothing sleeps, nothing waits a while, nothing touches a file, lock, memory or
// signal another process can see (docs/grading.md, "The sandbox, in layers").
static void allow_rule(scmp_filter_ctx ctx, const char* name, unsigned n,
                       const struct scmp_arg_cmp* cmp) {
  int nr = seccomp_syscall_resolve_name(name);
  if (nr == __NR_SCMP_ERROR) return;  // not a call of this architecture
  if (seccomp_rule_add_array(ctx, SCMP_ACT_ALLOW, nr, n, cmp) != 0) fail(name);
}

static void allow(scmp_filter_ctx ctx, const char* name) { allow_rule(ctx, name, 0, NULL); }

// Allowed when argument `arg` is one of `values` (one rule each).
static void allow_values(scmp_filter_ctx ctx, const char* name, unsigned arg,
                         const long* values, size_t n) {
  for (size_t i = 0; i < n; ++i) {
    struct scmp_arg_cmp cmp = {arg, SCMP_CMP_EQ, (scmp_datum_t)values[i], 0};
    allow_rule(ctx, name, 1, &cmp);
  }
}

// Refused with `err` (instead of ENOSYS) when argument `arg` has every bit of `bits` set.
static void refuse_bits(scmp_filter_ctx ctx, const char* name, unsigned arg, unsigned long bits,
                        int err) {
  int nr = seccomp_syscall_resolve_name(name);
  if (nr == __NR_SCMP_ERROR) return;
  struct scmp_arg_cmp cmp = {arg, SCMP_CMP_MASKED_EQ, bits, bits};
  if (seccomp_rule_add_array(ctx, SCMP_ACT_ERRNO(err), nr, 1, &cmp) != 0) fail(name);
}

static void install_seccomp(const char* exec_path, char* const* exec_argv) {
  if (prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) != 0) fail("no_new_privs");
  scmp_filter_ctx ctx = seccomp_init(SCMP_ACT_ERRNO(ENOSYS));
  if (!ctx) fail("seccomp_init");
  // Starting (the loader, libc's start-up), memory, clocks, its own identity and usage,
  // ending. None of these waits (getrandom only before the kernel's pool is ready at boot).
  const char* plain[] = {"brk", "mmap", "munmap", "mremap", "mprotect", "arch_prctl",
                         "set_tid_address", "set_robust_list", "rseq", "restart_syscall",
                         "rt_sigaction", "rt_sigprocmask", "rt_sigreturn", "sigaltstack",
                         "clock_gettime", "clock_getres", "gettimeofday", "time", "getpid",
                         "gettid", "getppid", "getuid", "geteuid", "getgid", "getegid",
                         "getresuid", "getresgid", "getgroups", "uname", "getrlimit",
                         "getrusage", "times", "sched_getaffinity", "sched_yield", "getrandom",
                         "exit", "exit_group",
                         // Its pipes, standard streams and the read-only files of its view:
                         // a pipe waits for the other end only; the files are its own copies.
                         "read", "readv", "pread64", "write", "writev", "close", "lseek", "fstat",
                         "newfstatat", "stat", "lstat", "statx", "access", "faccessat",
                         "faccessat2", "readlink", "readlinkat", "getcwd", "getdents64"};
  for (size_t i = 0; i < sizeof plain / sizeof *plain; ++i) allow(ctx, plain[i]);
  // Reading its limits, not setting them (prlimit64 with no new limit).
  struct scmp_arg_cmp no_new_limit = {2, SCMP_CMP_EQ, 0, 0};
  allow_rule(ctx, "prlimit64", 1, &no_new_limit);
  // Files open read-only: any write, create, truncate or append flag is refused (EACCES);
  // O_TMPFILE includes O_DIRECTORY, so it is refused by its own bit.
  const unsigned long write_flags = O_WRONLY | O_RDWR | O_CREAT | O_TRUNC | O_APPEND | 020000000;
  struct scmp_arg_cmp ro_open = {1, SCMP_CMP_MASKED_EQ, write_flags, 0};
  struct scmp_arg_cmp ro_openat = {2, SCMP_CMP_MASKED_EQ, write_flags, 0};
  allow_rule(ctx, "open", 1, &ro_open);
  allow_rule(ctx, "openat", 1, &ro_openat);
  const unsigned long each_flag[] = {O_WRONLY, O_RDWR, O_CREAT, O_TRUNC, O_APPEND, 020000000};
  for (size_t i = 0; i < sizeof each_flag / sizeof *each_flag; ++i) {
    refuse_bits(ctx, "open", 1, each_flag[i], EACCES);
    refuse_bits(ctx, "openat", 2, each_flag[i], EACCES);
  }
  // fcntl: descriptor flags and duplicates only; no record or open-file-description locks
  // (F_GETLK/F_SETLK/F_SETLKW/F_OFD_*: a lock is seen by whoever opens the same file), no
  // leases, notifications or signal-driven I/O.
  const long fcntl_cmds[] = {F_DUPFD, F_GETFD, F_SETFD, F_GETFL, F_SETFL, F_DUPFD_CLOEXEC};
  allow_values(ctx, "fcntl", 1, fcntl_cmds, sizeof fcntl_cmds / sizeof *fcntl_cmds);
  // ioctl: isatty() only.
  const long ioctl_cmds[] = {TCGETS};
  allow_values(ctx, "ioctl", 1, ioctl_cmds, 1);
  // madvise: the advice malloc gives; not MADV_PAGEOUT/COLD (a page put out and read back
  // waits for the disk) nor the POPULATE ones (which may read a file).
  const long advice[] = {MADV_NORMAL, MADV_RANDOM, MADV_SEQUENTIAL, MADV_DONTNEED, MADV_FREE,
                         MADV_HUGEPAGE, MADV_NOHUGEPAGE, MADV_DONTDUMP, MADV_DODUMP};
  allow_values(ctx, "madvise", 2, advice, sizeof advice / sizeof *advice);
  // futex: wakes only. A wait could only wait for good in a process with one thread, and
  // a futex in a shared mapping is seen by every process that maps the same file.
  const long futex_ops[] = {FUTEX_WAKE, FUTEX_WAKE_PRIVATE};
  allow_values(ctx, "futex", 1, futex_ops, sizeof futex_ops / sizeof *futex_ops);
  // Signals to itself only (abort(), and a crash handler that raises the signal again), and
  // none that stops it (SIGSTOP, SIGTSTP, SIGTTIN, SIGTTOU: a stopped process waits for good).
  const long own_signals[] = {SIGHUP, SIGINT, SIGQUIT, SIGILL, SIGTRAP, SIGABRT, SIGBUS, SIGFPE,
                              SIGKILL, SIGUSR1, SIGSEGV, SIGUSR2, SIGPIPE, SIGTERM, SIGXCPU,
                              SIGXFSZ, SIGSYS};
  pid_t self = getpid();
  for (size_t i = 0; i < sizeof own_signals / sizeof *own_signals; ++i) {
    struct scmp_arg_cmp to_self[2] = {{0, SCMP_CMP_EQ, (scmp_datum_t)self, 0},
                                      {1, SCMP_CMP_EQ, (scmp_datum_t)own_signals[i], 0}};
    allow_rule(ctx, "kill", 2, to_self);
    allow_rule(ctx, "tkill", 2, to_self);
    struct scmp_arg_cmp to_self_tg[3] = {{0, SCMP_CMP_EQ, (scmp_datum_t)self, 0},
                                         {1, SCMP_CMP_EQ, (scmp_datum_t)self, 0},
                                         {2, SCMP_CMP_EQ, (scmp_datum_t)own_signals[i], 0}};
    allow_rule(ctx, "tgkill", 3, to_self_tg);
  }
  // Exec only this once: the filter admits execve of exactly these path and argv pointers,
  // which exist in this process only until the exec replaces it (whatever a later exec
  // could run would still be inside this filter).
  struct scmp_arg_cmp this_exec[2] = {{0, SCMP_CMP_EQ, (scmp_datum_t)(uintptr_t)exec_path, 0},
                                      {1, SCMP_CMP_EQ, (scmp_datum_t)(uintptr_t)exec_argv, 0}};
  allow_rule(ctx, "execve", 2, this_exec);
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

// Copies `from` into a new file `to` (in the view's tmpfs), readable and, if it was,
// executable (the loader must be: the kernel opens it to run it), writable by no one: the
// view's files are its own inodes, in memory, shared with no other process (a lock, a
// notification, a page read from the disk or not: nothing done to one copy reaches another).
static void copy_file(const char* from, const char* to) {
  int in = open(from, O_RDONLY | O_CLOEXEC);
  struct stat st;
  if (in < 0 || fstat(in, &st) != 0) fail(from);
  int out = open(to, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0700);
  if (out < 0) fail("create (view)");
  for (;;) {
    ssize_t n = sendfile(out, in, NULL, 1 << 30);
    if (n == 0) break;
    if (n < 0) {
      if (errno == EINTR) continue;
      fail("copy (view)");
    }
  }
  if (fchmod(out, (st.st_mode & 0555) | 0444) != 0) fail("chmod (view)");
  close(in);
  close(out);
}

// The size of the tmpfs that holds the view's files: their sizes rounded up to pages, and
// room for the folders.
static unsigned long long view_size(const char** files, int n, const char* program) {
  unsigned long long total = 1 << 20;
  struct stat st;
  for (int k = 0; k <= n; ++k) {
    const char* f = k < n ? files[k] : program;
    if (stat(f, &st) != 0) fail(f);
    total += ((unsigned long long)st.st_size + 4095) / 4096 * 4096 + 4096;
  }
  return total;
}

// In the namespace's init (process 1 of the new PID namespace, in its own mount namespace):
// nothing mounted here reaches the host. Without a view, /proc becomes this namespace's own,
// showing only the processes of the test's own user (hidepid) and no system-wide files where
// the kernel allows it (subset=pid). With a view, the root becomes a tmpfs holding only
// copies of the view's files, each at its own path, and of the program at /<its name>
// (*exec_path, so no host folder's name reaches it); no /proc.
static void private_mounts(const char* root, const char** files, int n, const char* program,
                           const char** exec_path) {
  if (mount(NULL, "/", NULL, MS_REC | MS_PRIVATE, NULL) != 0) fail("mount (private)");
  if (!root) {
    const unsigned long flags = MS_NOSUID | MS_NODEV | MS_NOEXEC;
    if (mount("proc", "/proc", "proc", flags, "hidepid=invisible,subset=pid") != 0 &&
        mount("proc", "/proc", "proc", flags, "hidepid=2") != 0)
      fail("mount /proc");
    return;
  }
  char opts[64];
  snprintf(opts, sizeof opts, "size=%llu,mode=0755", view_size(files, n, program));
  if (mount("wb-view", root, "tmpfs", MS_NOSUID | MS_NODEV, opts) != 0)
    fail("mount tmpfs (view)");
  char path[4096];
  for (int k = 0; k < n; ++k) {
    if (snprintf(path, sizeof path, "%s%s", root, files[k]) >= (int)sizeof path) {
      errno = ENAMETOOLONG;
      fail("view path");
    }
    if (access(path, F_OK) == 0) continue;  // listed twice
    make_parents(path);
    copy_file(files[k], path);
  }
  static char inside[512];
  const char* name = strrchr(program, '/') ? strrchr(program, '/') + 1 : program;
  if (snprintf(inside, sizeof inside, "/%s", name) >= (int)sizeof inside ||
      snprintf(path, sizeof path, "%s%s", root, inside) >= (int)sizeof path) {
    errno = ENAMETOOLONG;
    fail("view path");
  }
  copy_file(program, path);
  *exec_path = inside;
  // The old root goes: pivot_root puts it under the new one, and it is then detached.
  if (snprintf(path, sizeof path, "%s/old-root", root) >= (int)sizeof path) fail("view path");
  if (mkdir(path, 0700) != 0) fail("mkdir (view)");
  if (syscall(SYS_pivot_root, root, path) != 0) fail("pivot_root (view)");
  if (chdir("/") != 0) fail("chdir (view)");
  if (umount2("/old-root", MNT_DETACH) != 0) fail("umount old root (view)");
  if (rmdir("/old-root") != 0) fail("rmdir (view)");
  if (mount(NULL, "/", NULL, MS_REMOUNT | MS_RDONLY | MS_NOSUID | MS_NODEV, NULL) != 0)
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
  if ((n_view > 0 && !view_root) || ((view_root || use_proc) && !use_ns)) {
    fprintf(stderr, "wb-sandbox: --view needs --view-root; it and --proc need --ns\n");
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
  if (use_proc || view_root) {
    const char* exec_path = child_argv[0];
    private_mounts(view_root, view, n_view, child_argv[0], &exec_path);
    child_argv[0] = (char*)exec_path;
  }
  pid_t test = fork();
  if (test < 0) fail("fork");
  if (test == 0) {
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (as) limit(RLIMIT_AS, as, "RLIMIT_AS");
    if (fsize) limit(RLIMIT_FSIZE, fsize, "RLIMIT_FSIZE");
    if (cpu) {  // SIGXCPU at the limit (the grader names it), SIGKILL a second later
      struct rlimit r = {(rlim_t)cpu, (rlim_t)cpu + 1};
      if (setrlimit(RLIMIT_CPU, &r) != 0) fail("RLIMIT_CPU");
    }
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
  // The init's own command line and environment (the launcher's flags, folders, the grader's
  // variables) are wiped: /proc/1/cmdline shows nothing of them (the test has its own copy).
  for (char** a = argv; *a; ++a) memset(*a, 0, strlen(*a));
  for (char** e = environ; e && *e; ++e) memset(*e, 0, strlen(*e));
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
