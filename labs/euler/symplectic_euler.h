// TODO(E2) semi-implicit (symplectic) Euler step. Handout: handouts/euler.md#e2. Tests: [E2].
#pragma once
#include "wb/dynamics.h"

// One semi-implicit Euler step of size h, the lecture's "first try": the
// velocity first, then the position with the NEW velocity,
//
//   a_n     = a(x_n, v_n)          (one force evaluation)
//   v_{n+1} = v_n + h a_n
//   x_{n+1} = x_n + h v_{n+1}      (the NEW velocity)
//
// Inputs:
//   dyn  the accelerations: dyn.acceleration(x, v, a) fills a (2 x n, m/s^2);
//        each call is one force evaluation (counted by dyn.evals())
//   h    step size (s), > 0
//   s    work arrays, already sized 2 x n (use s.a0 for the acceleration, so
//        that a step allocates nothing); contents on entry are undefined
// Outputs:
//   x    2 x n positions (m), column i is particle i: advanced in place
//   v    2 x n velocities (m/s): advanced in place
void symplectic_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                           wb::Scratch& s);
