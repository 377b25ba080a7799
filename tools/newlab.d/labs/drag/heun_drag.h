// TODO(D1) Heun's step. Handout: handouts/drag.md#d1. Tests: [D1].
#pragma once
#include "wb/dynamics.h"

// One step of Heun's method (the explicit trapezoid rule) of size h:
//
//   a0 = a(x, v)                        (first force evaluation)
//   x1 = x + h v,  v1 = v + h a0        (an explicit Euler predictor)
//   a1 = a(x1, v1)                      (second force evaluation)
//   x' = x + h/2 (v + v1)
//   v' = v + h/2 (a0 + a1)
//
// Inputs:
//   dyn  the accelerations: dyn.acceleration(x, v, a) fills a (2 x n, m/s^2);
//        each call is one force evaluation (counted by dyn.evals())
//   h    step size (s), > 0
//   s    work arrays, already sized 2 x n (s.a0, s.a1, s.x1, s.v1); contents on
//        entry are undefined
// Outputs:
//   x    2 x n positions (m), column i is particle i: advanced in place
//   v    2 x n velocities (m/s): advanced in place
void heun_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v, wb::Scratch& s);
