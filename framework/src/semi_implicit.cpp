// The provided semi-implicit Euler step (wb/semi_implicit.h).
#include "wb/semi_implicit.h"

namespace wb {

void semi_implicit_euler_step(const Dynamics& dyn, double h, Mat2X& x, Mat2X& v, Scratch& s) {
  dyn.acceleration(x, v, s.a0);
  v += h * s.a0;
  x += h * v;
}

Integrator semi_implicit_euler_integrator() {
  return {"symplectic-euler", semi_implicit_euler_step, 1, 1,
          "semi-implicit Euler, provided: velocities first, then positions"};
}

}  // namespace wb
