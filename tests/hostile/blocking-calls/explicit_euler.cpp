// Hostile: sleeps through calls that block without using the CPU and end by themselves
// (issue 42, "a sleep that the filter lets through": membarrier(MEMBARRIER_CMD_GLOBAL) waits
// for a grace period, 10 s of wall-clock time for 0.18 s of CPU per test). It tries each
// call of that class it knows: membarrier, sync, syncfs, fsync, fdatasync, msync(MS_SYNC),
// madvise(MADV_PAGEOUT) with the page read back, sched_setscheduler(SCHED_IDLE), nice(19),
// and says in its output which ones slept. With one that sleeps, it stays about 8 s in its
// first call with a few ticks of CPU (the old idle rule allowed 1 % of a core) and then takes
// the right step: the E1 tests pass (an honest grader gives 50, the E2 tests' points).
#include <errno.h>
#include <fcntl.h>
#include <linux/membarrier.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <time.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <string>

#include "explicit_euler.h"

namespace {
double clock_s(clockid_t c) {
  timespec t{};
  clock_gettime(c, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

int self_fd = -1;
void* mapped = nullptr;
std::size_t mapped_size = 0;

// Each candidate: one call that may block without the CPU; returns the call's result.
long membarrier_global() { return syscall(SYS_membarrier, MEMBARRIER_CMD_GLOBAL, 0, 0); }
long call_sync() { return syscall(SYS_sync); }
long call_syncfs() { return syncfs(self_fd); }
long call_fsync() { return fsync(self_fd); }
long call_fdatasync() { return fdatasync(self_fd); }
long call_msync() { return mapped ? msync(mapped, mapped_size, MS_SYNC) : -1; }
long pageout_and_touch() {
  if (!mapped) return -1;
  if (madvise(mapped, mapped_size, 21 /* MADV_PAGEOUT */) != 0) return -1;
  volatile char sum = 0;
  for (std::size_t i = 0; i < mapped_size; i += 4096) sum += static_cast<char*>(mapped)[i];
  return 0;
}

struct Candidate {
  const char* name;
  long (*call)();
};
const Candidate candidates[] = {{"membarrier(MEMBARRIER_CMD_GLOBAL)", membarrier_global},
                                {"sync", call_sync},
                                {"syncfs", call_syncfs},
                                {"fsync", call_fsync},
                                {"fdatasync", call_fdatasync},
                                {"msync(MS_SYNC)", call_msync},
                                {"madvise(MADV_PAGEOUT)", pageout_and_touch}};

void say(const std::string& line) {
  if (write(2, line.data(), line.size()) < 0) {
  }
}

// The candidate that slept (wall-clock time well above its CPU time), or nullptr.
const Candidate* find_sleep() {
  self_fd = open(program_invocation_name, O_RDONLY | O_CLOEXEC);
  struct stat st {};
  if (self_fd >= 0 && fstat(self_fd, &st) == 0 && st.st_size >= 4096) {
    mapped_size = std::size_t(st.st_size) / 4096 * 4096;  // whole pages of the file only
    void* p = mmap(nullptr, mapped_size, PROT_READ, MAP_SHARED, self_fd, 0);
    mapped = p == MAP_FAILED ? nullptr : p;
  }
  const Candidate* found = nullptr;
  for (const Candidate& c : candidates) {
    const double w0 = clock_s(CLOCK_MONOTONIC), c0 = clock_s(CLOCK_PROCESS_CPUTIME_ID);
    errno = 0;
    long r = 0;
    for (int k = 0; k < 5 && r == 0; ++k) r = c.call();
    const double wall = clock_s(CLOCK_MONOTONIC) - w0,
                 cpu = clock_s(CLOCK_PROCESS_CPUTIME_ID) - c0;
    const bool slept = r == 0 && wall - cpu > 0.002;
    say(std::string("blocking-calls: ") + c.name + (r == 0 ? " returned" : " refused: ") +
        (r == 0 ? "" : std::strerror(errno)) + (slept ? " (SLEPT without the CPU)" : "") + "\n");
    if (slept && !found) found = &c;
  }
  // Lower its own priority (not a wait, but less CPU for the same wall-clock time).
  sched_param sp{};
  if (sched_setscheduler(0, SCHED_IDLE, &sp) == 0) say("blocking-calls: SCHED_IDLE accepted\n");
  if (setpriority(PRIO_PROCESS, 0, 19) == 0) say("blocking-calls: nice 19 accepted\n");
  return found;
}
}  // namespace

void explicit_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                         wb::Scratch& s) {
  static const Candidate* sleep = nullptr;
  static bool asked = false;
  if (!asked) {
    asked = true;
    sleep = find_sleep();
    if (sleep) {  // about 8 s of wall-clock time, almost none of it on the CPU
      const double until = clock_s(CLOCK_MONOTONIC) + 8;
      while (clock_s(CLOCK_MONOTONIC) < until) sleep->call();
    }
  }
  if (!sleep) return;  // no step: E1 fails
  dyn.acceleration(x, v, s.a0);
  x += h * v;
  v += h * s.a0;
}
