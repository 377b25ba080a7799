// TODO(I1) backward Euler for one spring, solved by hand. Handout:
// handouts/implicit.md#i1. Tests: [I1].
#pragma once
#include "wb/types.h"

// One backward Euler step of a particle on a linear spring (rest length 0)
// to a fixed anchor c, with a viscous drag b and a constant force f_ext:
//
//   x' = x + h v'
//   v' = v + (h/m) ( -k (x' - c) - b v' + f_ext )
//
// The forces are taken at the END of the step (x', v'), which are unknown.
// The spring is linear, so substituting the first line into the second gives
// one linear equation in v', solved in closed form (no iteration):
//
//   (m + h b + h^2 k) v' = m v - h k (x - c) + h f_ext,   then x' = x + h v'.
//
// On an undamped spring (b = 0, f_ext = 0) the energy 1/2 m |v|^2 + 1/2 k |x - c|^2
// is multiplied by exactly 1 / (1 + (h w)^2) per step, w = sqrt(k / m): the step
// is stable for every h, and damps.
//
// Inputs:
//   m      mass (kg), > 0
//   k      stiffness (N/m), >= 0
//   b      drag (N s/m), >= 0
//   c      the anchor (m)
//   f_ext  other forces, held constant over the step (N)
//   h      step size (s), > 0
// Outputs:
//   x      position (m): advanced in place
//   v      velocity (m/s): advanced in place
void backward_euler_spring_step(double m, double k, double b, const wb::Vec2& c,
                                const wb::Vec2& f_ext, double h, wb::Vec2& x, wb::Vec2& v);
