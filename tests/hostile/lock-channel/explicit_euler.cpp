// Hostile: test cases talk to each other (issue 42, "test cases share nothing"). Two tests run
// at once; each worker advertises itself on files every worker can open (its own binary, the C
// library, the loader's cache) with a POSIX record lock (fcntl F_SETLK), an open file
// description lock (F_OFD_SETLK) and flock(LOCK_SH), and looks for another worker's with
// F_GETLK, F_OFD_GETLK and flock(LOCK_EX | LOCK_NB). It takes the right step only once it has
// heard another worker: a channel between tests makes the E1 tests pass (an honest grader
// gives 50, the E2 tests' points), and it says which channel worked where the results show it.
#include <errno.h>
#include <fcntl.h>
#include <sys/file.h>
#include <time.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstring>

#include "explicit_euler.h"

namespace {
double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

const char* heard_through() {
  const char* files[] = {program_invocation_name, "/lib/x86_64-linux-gnu/libc.so.6",
                         "/etc/ld.so.cache"};
  int mine[3], probe[3];
  for (int k = 0; k < 3; ++k) {
    mine[k] = open(files[k], O_RDONLY | O_CLOEXEC);
    probe[k] = open(files[k], O_RDONLY | O_CLOEXEC);
  }
  // This worker's own byte (the stack's random address): another worker's lock is elsewhere.
  const off_t byte = 16 + off_t(reinterpret_cast<std::uintptr_t>(&mine) >> 4) % 1000000;
  const double until = cpu_seconds() + 1.5;  // another test starts within this much
  while (cpu_seconds() < until) {
    for (int k = 0; k < 3; ++k) {
      if (mine[k] < 0 || probe[k] < 0) continue;
      // Another process's record lock (F_GETLK never reports the caller's own record locks;
      // it does report its open file description locks, as l_pid -1).
      struct flock q {};
      q.l_type = F_WRLCK, q.l_whence = SEEK_SET, q.l_start = 0, q.l_len = 0;
      if (fcntl(probe[k], F_GETLK, &q) == 0 && q.l_type != F_UNLCK && q.l_pid != -1)
        return "fcntl F_GETLK";
      // An OFD lock on another byte than this worker's own.
      struct flock o {};
      o.l_type = F_WRLCK, o.l_whence = SEEK_SET, o.l_start = 0, o.l_len = 0, o.l_pid = 0;
      if (fcntl(probe[k], F_OFD_GETLK, &o) == 0 && o.l_type != F_UNLCK && o.l_start != byte)
        return "fcntl F_OFD_GETLK";
      // Another's flock (this worker's own is dropped before asking).
      flock(mine[k], LOCK_UN);
      if (flock(probe[k], LOCK_EX | LOCK_NB) != 0 && errno == EWOULDBLOCK) return "flock";
      flock(probe[k], LOCK_UN);
      // Advertise: a record lock and an OFD lock on its byte, a shared flock.
      struct flock r {};
      r.l_type = F_RDLCK, r.l_whence = SEEK_SET, r.l_start = byte, r.l_len = 1;
      fcntl(mine[k], F_SETLK, &r);
      r.l_pid = 0;
      fcntl(mine[k], F_OFD_SETLK, &r);
      flock(mine[k], LOCK_SH);
    }
  }
  return nullptr;
}
}  // namespace

void explicit_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                         wb::Scratch& s) {
  static const char* channel = nullptr;
  static bool asked = false;
  if (!asked) {
    asked = true;
    channel = heard_through();
    char line[200];
    const int n = std::snprintf(line, sizeof line, "lock-channel: %s\n",
                                channel ? channel : "no other test heard");
    if (n > 0 && write(2, line, std::size_t(n)) < 0) {
    }
  }
  if (!channel) return;  // no step: E1 fails
  dyn.acceleration(x, v, s.a0);
  x += h * v;
  v += h * s.a0;
}
