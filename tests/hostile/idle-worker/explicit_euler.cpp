// Hostile: idles in every call (a blocking read on its own pipe; sleep() is denied by seccomp).
#include <unistd.h>

#include "explicit_euler.h"

void explicit_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                         wb::Scratch& s) {
  (void)dyn, (void)h, (void)x, (void)v, (void)s;
  usleep(2000000);  // denied: returns at once
  char c;
  for (int fd = 3; fd < 16; ++fd) {
    if (read(fd, &c, 1) >= 0) break;  // the request pipe: blocks
  }
}
