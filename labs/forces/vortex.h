// TODO(F8) vortex field: drag towards a swirling flow. Handout: handouts/forces.md#f8. Tests:
// [F8].
#pragma once
#include "wb/types.h"

struct VortexParams {
  wb::Vec2 center{0, 0};  // the vortex axis (m)
  double omega = 1.0;     // angular speed of the core (rad/s); > 0 turns counter-clockwise
  double core = 1.0;      // core radius R (m), > 0
  double drag = 1.0;      // coupling c to the flow (kg/s), >= 0
};

// The flow is a Rankine vortex around `center`: with d = x - center, r = |d|,
// perp(d) = (-d_y, d_x),
//
//   u(x) = omega * perp(d)               for r <= R   (turns like a solid disc)
//   u(x) = omega * R^2 * perp(d) / r^2   for r >  R   (speed falls off as 1/r)
//
// and each particle is dragged towards the flow:  f_i += c (u(x_i) - v_i).
//
// Inputs:
//   x, v  2 x n positions (m) and velocities (m/s)
//   p     the vortex
// Outputs:
//   f     2 x n forces (N); add, do not overwrite
void add_vortex(const wb::Mat2X& x, const wb::Mat2X& v, const VortexParams& p, wb::Mat2X& f);

// The flow velocity u(x) above, at one point (m/s). add_vortex uses it.
wb::Vec2 vortex_flow(const wb::Vec2& x, const VortexParams& p);
