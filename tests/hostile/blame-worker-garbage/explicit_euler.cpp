// Hostile: tries to make its own failures look like the grader's (issue 29: "blame"): writes
// garbage on the worker's answer pipe (a length over the limit, then a message of an unknown
// kind), and ends its process with status 3 or a SIGSEGV, in turn. The grader must report
// failed tests, never an error of its own.
#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>

#include "explicit_euler.h"

void explicit_euler_step(const wb::Dynamics&, double h, wb::Mat2X&, wb::Mat2X&, wb::Scratch&) {
  char cmd[256] = {};
  const int f = open("/proc/self/cmdline", O_RDONLY);
  const ssize_t n = f >= 0 ? read(f, cmd, sizeof cmd - 1) : -1;
  const char* arg = cmd;
  for (int k = 0; k < 2 && arg < cmd + n; ++k) arg += std::strlen(arg) + 1;  // argv[2]
  const int out = arg < cmd + n ? std::atoi(arg) : 4;
  const unsigned char huge[] = {0xff, 0xff, 0xff, 0x7f};
  const unsigned char unknown[] = {4, 0, 0, 0, 99, 0, 0, 0};
  const int mode = int(h * 1e6) % 3;
  if (mode == 0 && write(out, huge, sizeof huge) < 0) {
  }
  if (mode == 1 && write(out, unknown, sizeof unknown) < 0) {
  }
  if (mode == 2) raise(SIGSEGV);
  _exit(3);
}
