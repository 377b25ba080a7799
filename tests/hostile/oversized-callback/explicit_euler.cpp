// Hostile: calls the test's Dynamics with arrays of 6000 particles whatever the system has,
// so that a test's callback that indexes its own per-particle arrays by the columns of x
// reads and writes past them in the trusted test process (issue 29: "sizes chosen by the
// worker"). Then takes a correct step.
#include "explicit_euler.h"

void explicit_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                         wb::Scratch& s) {
  wb::Mat2X big = wb::Mat2X::Constant(2, 6000, 1.0), a(2, 6000);
  dyn.acceleration(big, big, a);
  dyn.acceleration(x, v, s.a0);
  x += h * v;
  v += h * s.a0;
}
