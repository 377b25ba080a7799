// TODO(R4) advance the position and the orientation. Handout: handouts/rigid.md#r4. Tests: [R4].
#pragma once
#include "rigid_body.h"

// The second half of a semi-implicit Euler step, run after the velocities
// (integrate_velocity_*) and the impulses of the step have been applied:
//
//   x_{n+1} = x_n + h v_{n+1}
//   q_{n+1} = dq q_n,   dq = the rotation of angle |omega| h about omega / |omega|
//             (the exponential map exp(h [omega]x); omega is in the WORLD frame,
//              so dq multiplies on the LEFT), then renormalised to |q| = 1
//
// so that R = q.toRotationMatrix() stays a rotation however many steps are taken.
// When omega = 0 there is no axis: q stays as it is (and must not become NaN).
//
// Inputs:
//   b.v, b.omega  the new linear (m/s) and angular (rad/s) velocity, world frame
//   h             step size (s), > 0
// Outputs:
//   b.x, b.q      advanced in place; nothing else changes
void integrate_position(rigid::Body& b, double h);
