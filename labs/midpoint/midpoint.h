// TODO(M1) midpoint method. Handout: handouts/midpoint.md#m1. Tests: [M1].
#pragma once
#include "wb/dynamics.h"

// One step of the midpoint method, as in the lecture. The state is
// X = (x, v) and its time derivative is f(X) = (v, a(x, v)):
//
//   X_mid = X + (h/2) f(X)        half an Euler step     (1st force evaluation)
//   X'    = X + h f(X_mid)        a full step FROM X, with the slope at X_mid
//                                                        (2nd force evaluation)
//
// written out for particles:
//
//   a_0   = a(x, v)
//   x_mid = x + (h/2) v           v_mid = v + (h/2) a_0
//   a_mid = a(x_mid, v_mid)
//   x'    = x + h v_mid           v'    = v + h a_mid
//
// Second order: the error after a fixed time T shrinks like h^2.
//
// Inputs:
//   dyn  the accelerations: dyn.acceleration(x, v, a) fills a (2 x n, m/s^2);
//        each call is one force evaluation (counted by dyn.evals()): call it
//        exactly twice per step
//   h    step size (s), > 0
//   s    work arrays, already sized 2 x n (s.a0, s.a1 for accelerations, s.x1,
//        s.v1 for the midpoint state), so that a step allocates nothing;
//        contents on entry are undefined
// Outputs:
//   x    2 x n positions (m), column i is particle i: advanced in place
//   v    2 x n velocities (m/s): advanced in place
void midpoint_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v, wb::Scratch& s);
