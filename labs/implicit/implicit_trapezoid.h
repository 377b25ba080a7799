// TODO(I5) implicit trapezoid step of a spring network. Handout:
// handouts/implicit.md#i5. Tests: [I5].
#pragma once
#include "backward_euler.h"

// One step of the implicit trapezoid rule: the average of the slopes at both
// ends of the step, the end being unknown:
//
//   x' = x + h/2 (v + v')
//   v' = v + h/(2M) ( f(x, v) + f(x', v') ) + (h/M) f_ext
//
// It splits into half an explicit Euler step and half a backward Euler step:
//
//   x~ = x + h/2 v,   v~ = v + h/(2M) ( f(x, v) + f_ext )     (explicit, known)
//   x' = x~ + h/2 v', v' = v~ + h/(2M) ( f(x', v') + f_ext )  (backward Euler, h/2)
//
// so the second half is backward_euler_step (I4) from (x~, v~) with step h/2,
// with this network's workspace (the pattern does not depend on the step size).
// On a linear spring the step keeps the energy exactly, for every h.
// Second order in h. Pinned particles never move.
//
// Inputs:
//   net    the springs, masses, drag and pinned particles (n particles)
//   f_ext  the other forces (2 x n, N), taken at the start of the step
//   h      step size (s), > 0
//   opt    passed to the backward Euler half step
// Outputs:
//   x, v   2 x n positions (m) and velocities (m/s): advanced in place
//   ws     this network's workspace (backward_euler.h), passed to the half step
//   returns the Newton report of the backward Euler half step
NewtonReport implicit_trapezoid_step(const SpringNetwork& net, const wb::Mat2X& f_ext, double h,
                                     const NewtonOptions& opt, wb::Mat2X& x, wb::Mat2X& v,
                                     NewtonWorkspace& ws);
