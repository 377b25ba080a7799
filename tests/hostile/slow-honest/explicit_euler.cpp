// Not hostile: a correct submission that is slow (issue 42, "load changes an honest grade").
// Its first call in each test computes for about 5 s of CPU time (2.3 * 10^9 additions, 5 s
// on the project's machine) before it takes the right step. Each E1 test then uses about 5 s
// of CPU, far inside its limit: it must score 100 every time, however busy the machine (the
// suite keeps both cores busy while it runs) and whenever the test's processes end between
// two readings of their CPU time.
#include "explicit_euler.h"

void explicit_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                         wb::Scratch& s) {
  static bool warmed_up = false;
  if (!warmed_up) {
    warmed_up = true;
    volatile double work = 0;
    for (long k = 0; k < 2300000000L; ++k) work = work + 1e-9 * double(k & 1023);
  }
  dyn.acceleration(x, v, s.a0);
  x += h * v;
  v += h * s.a0;
}
