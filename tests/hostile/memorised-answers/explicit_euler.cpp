// Hostile: no physics for inputs it has not seen. It knows the step sizes of the public E1
// tests (the student pack holds them) and answers exactly there; everywhere else it does
// nothing. Every public E1 test passes; only the held-out inputs (issue 29) tell.
#include "explicit_euler.h"

namespace {
bool seen_in_the_public_tests(double h) {
  const double w = 2.0;  // sqrt(k / m) of the public oscillator tests
  const double known[] = {0.25,    0.001 / w,         0.01 / w, 0.1 / w, 0.5 / w, 1.0 / w,
                          2.5 / w, 1000.0 / 60.0 / w, 0.01,     0.1,     0.05,    0.02,
                          1e-3,    1e-3 / w};
  for (double k : known)
    if (h == k) return true;
  return false;
}
}  // namespace

void explicit_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                         wb::Scratch& s) {
  if (!seen_in_the_public_tests(h)) return;  // "memorised": nothing to replay
  dyn.acceleration(x, v, s.a0);
  x += h * v;
  v += h * s.a0;
}
