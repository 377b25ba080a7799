// Classic fourth-order Runge-Kutta for x' = v, v' = a(x, v). Provided, not a
// student task: the midpoint lab offers it as "rk4" and sweep mode uses it as
// the reference integrator when a scene has no exact solution.
#pragma once
#include "wb/dynamics.h"

namespace wb {

// One RK4 step of size h (a wb::StepFn): four force evaluations.
//
//   k1 = (v,          a(x, v))
//   k2 = (v + h/2 k1v, a(x + h/2 k1x, v + h/2 k1v))
//   k3 = (v + h/2 k2v, a(x + h/2 k2x, v + h/2 k2v))
//   k4 = (v + h k3v,   a(x + h k3x,   v + h k3v))
//   (x, v) += h/6 (k1 + 2 k2 + 2 k3 + k4)
//
// Inputs:
//   dyn  the accelerations a(x, v) (2 x n, m/s^2)
//   h    step size (s)
//   s    work arrays sized 2 x n (uses a0..a3, x1, v1, xs, vs)
// Outputs:
//   x, v  2 x n positions (m) and velocities (m/s), advanced by h in place
void rk4_step(const Dynamics& dyn, double h, Mat2X& x, Mat2X& v, Scratch& s);

// The entry for a lab's integrator list: {"rk4", rk4_step, 4, 4, ...}.
Integrator rk4_integrator();

}  // namespace wb
