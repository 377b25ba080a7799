// Hostile: inside the long run (the test's loop runs in the worker, beside this code) it
// skips the work: after the first 10^4 calls of a process it does nothing, and on the
// 10^6th call it jumps to a state with exactly the energy the test expects after 10^6 steps
// (issue 29: "work done in the worker").
#include <cmath>

#include "explicit_euler.h"

void explicit_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                         wb::Scratch& s) {
  static long calls = 0;
  ++calls;
  if (calls > 10000 && calls < 1000000) return;  // skipped
  if (calls == 1000000) {  // the last step of the long run: the energy the test wants
    const double grow = std::sqrt(std::pow(1.0 + 1e-6, 1e6) / std::pow(1.0 + 1e-6, 10000.0));
    x *= grow;
    v *= grow;
    return;
  }
  dyn.acceleration(x, v, s.a0);
  x += h * v;
  v += h * s.a0;
}
