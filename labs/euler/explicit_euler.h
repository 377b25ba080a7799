// TODO(E1) explicit (forward) Euler step. Handout: handouts/euler.md#e1. Tests: [E1].
#pragma once
#include "wb/dynamics.h"

// One explicit Euler step of size h, as in the lecture: both updates use the
// state at the START of the step,
//
//   a_n     = a(x_n, v_n)          (one force evaluation)
//   x_{n+1} = x_n + h v_n          (the OLD velocity)
//   v_{n+1} = v_n + h a_n
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
void explicit_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                         wb::Scratch& s);
