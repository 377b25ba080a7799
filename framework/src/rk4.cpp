// Classic RK4 on the first-order system (x, v)' = (v, a(x, v)).
#include "wb/rk4.h"

namespace wb {

// The position slopes are velocities, so they need no arrays of their own:
// k2x = v + h/2 a0, k3x = v + h/2 a1, k4x = v + h a2, and
//   k1x + 2 k2x + 2 k3x + k4x = 6 v + h (a0 + a1 + a2).
// Each stage's point and the final combination are then one pass each over
// the arrays they read (the update moves 512 bytes per particle, where
// running sums of the slopes moved 736; docs/benchmarks.md).
void rk4_step(const Dynamics& dyn, double h, Mat2X& x, Mat2X& v, Scratch& s) {
  const double h2 = 0.5 * h, hh4 = 0.25 * h * h, hh2 = 0.5 * h * h;

  // Stage 1 at the start: k1 = (v, a0).
  dyn.acceleration(x, v, s.a0);

  // Stage 2 at the half step along k1: k2 = (v + h/2 a0, a1).
  s.x1 = x + h2 * v;
  s.v1 = v + h2 * s.a0;
  dyn.acceleration(s.x1, s.v1, s.a1);

  // Stage 3 at the half step along k2: x + h/2 k2x = x + h/2 v + h^2/4 a0.
  s.x1 = x + h2 * v + hh4 * s.a0;
  s.v1 = v + h2 * s.a1;
  dyn.acceleration(s.x1, s.v1, s.a2);

  // Stage 4 at the full step along k3: x + h k3x = x + h v + h^2/2 a1.
  s.x1 = x + h * v + hh2 * s.a1;
  s.v1 = v + h * s.a2;
  dyn.acceleration(s.x1, s.v1, s.a3);

  // Combine: x += h/6 (6 v + h (a0 + a1 + a2)), v += h/6 (a0 + 2 a1 + 2 a2 + a3).
  x += h * v + (h * h / 6.0) * (s.a0 + s.a1 + s.a2);
  v += (h / 6.0) * (s.a0 + 2.0 * s.a1 + 2.0 * s.a2 + s.a3);
}

Integrator rk4_integrator() {
  return {"rk4", rk4_step, 4, 4, "classic Runge-Kutta 4, provided (the sweep's reference)"};
}

}  // namespace wb
