// Classic RK4 on the first-order system (x, v)' = (v, a(x, v)).
#include "wb/rk4.h"

namespace wb {

void rk4_step(const Dynamics& dyn, double h, Mat2X& x, Mat2X& v, Scratch& s) {
  // Stage 1 at the start: k1 = (v, a0).
  dyn.acceleration(x, v, s.a0);
  s.xs = v;     // running sum of the position slopes k1x + 2 k2x + 2 k3x + k4x
  s.vs = s.a0;  // running sum of the velocity slopes

  // Stage 2 at the half step along k1: k2 = (v1, a1).
  s.x1 = x + (0.5 * h) * v;
  s.v1 = v + (0.5 * h) * s.a0;
  dyn.acceleration(s.x1, s.v1, s.a1);
  s.xs += 2.0 * s.v1;
  s.vs += 2.0 * s.a1;

  // Stage 3 at the half step along k2: k3 = (v1, a2). x1 uses k2x = v1 before v1 changes.
  s.x1 = x + (0.5 * h) * s.v1;
  s.v1 = v + (0.5 * h) * s.a1;
  dyn.acceleration(s.x1, s.v1, s.a2);
  s.xs += 2.0 * s.v1;
  s.vs += 2.0 * s.a2;

  // Stage 4 at the full step along k3: k4 = (v1, a3).
  s.x1 = x + h * s.v1;
  s.v1 = v + h * s.a2;
  dyn.acceleration(s.x1, s.v1, s.a3);
  s.xs += s.v1;
  s.vs += s.a3;

  // Combine.
  x += (h / 6.0) * s.xs;
  v += (h / 6.0) * s.vs;
}

Integrator rk4_integrator() {
  return {"rk4", rk4_step, 4, 4, "classic Runge-Kutta 4, provided (the sweep's reference)"};
}

}  // namespace wb
