// TODO(R7) a hinge: a body pinned to the world at one point. Handout:
// handouts/rigid.md#r7. Tests: [R7].
#pragma once
#include "rigid_body.h"

// The body's point r_body (body frame, relative to the centre) must stay at the
// world point `anchor`. Each step, after the velocities and before the
// positions are advanced, an impulse P at that point makes its velocity
//
//   v_p' = v' + omega' x r = -(beta / h) C          (r = R r_body, C = x + r - anchor)
//
// i.e. zero plus a correction that removes the fraction beta of the position
// drift C per step (Baumgarte), so the drift stays bounded. With
// v' = v + P / m and omega' = omega + I^-1 (r x P) (I^-1 world, R2):
//
//   K P = -(v + omega x r + (beta / h) C),   K = E / m - [r]x I^-1 [r]x
//
// K is the 3x3 "effective mass" inverse (symmetric positive definite): solve it.
//
// Inputs:
//   b       the body;  r_body  the pinned point, body frame (m);  anchor  world (m)
//   h       step size (s), > 0;  beta  drift correction in [0, 1]
// Outputs:
//   b.v, b.omega  changed by the impulse P; returns P (N s), world frame
rigid::Vec3 apply_hinge(rigid::Body& b, const rigid::Vec3& r_body, const rigid::Vec3& anchor,
                        double h, double beta);
