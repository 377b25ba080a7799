// TODO(M2) trapezoid method. Handout: handouts/midpoint.md#m2. Tests: [M2].
#pragma once
#include "wb/dynamics.h"

// One step of the trapezoid method, as in the lecture. The state is
// X = (x, v) and its time derivative is f(X) = (v, a(x, v)):
//
//   X_a = X + h f(X)              a full Euler step      (1st force evaluation)
//   X_b = X + h f(X_a)            a full step FROM X (not from X_a), with the
//                                 slope at X_a          (2nd force evaluation)
//   X'  = (X_a + X_b) / 2         their average
//
// which is the same as X' = X + (h/2) (f(X) + f(X_a)): the average of the
// slopes at both ends of the Euler step. Written out for particles:
//
//   a_0 = a(x, v)
//   x_a = x + h v                 v_a = v + h a_0
//   a_a = a(x_a, v_a)
//   x_b = x + h v_a               v_b = v + h a_a
//   x'  = (x_a + x_b) / 2         v'  = (v_a + v_b) / 2
//
// Second order, like the midpoint method, but a different method: the two
// agree on linear forces and differ on nonlinear ones.
//
// Inputs:
//   dyn  the accelerations: dyn.acceleration(x, v, a) fills a (2 x n, m/s^2);
//        each call is one force evaluation (counted by dyn.evals()): call it
//        exactly twice per step
//   h    step size (s), > 0
//   s    work arrays, already sized 2 x n (s.a0, s.a1 for accelerations, s.x1,
//        s.v1 for X_a), so that a step allocates nothing; contents on entry
//        are undefined
// Outputs:
//   x    2 x n positions (m), column i is particle i: advanced in place
//   v    2 x n velocities (m/s): advanced in place
void trapezoid_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                    wb::Scratch& s);
