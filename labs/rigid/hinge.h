// TODO(R7) joints to the world: a point (ball) joint, and a revolute hinge that also
// keeps a body axis along a world axis. Handout: handouts/rigid.md#r7. Tests: [R7].
#pragma once
#include "rigid_body.h"

// ---- The point (ball) joint: apply_hinge -----------------------------------------
// The body's point r_body (body frame, relative to the centre) must stay at the
// world point `anchor`; the body may turn about any axis through it. Each step,
// after the velocities and before the positions are advanced, an impulse P at that
// point makes its velocity
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
// Returns P (N s), world frame.
rigid::Vec3 apply_hinge(rigid::Body& b, const rigid::Vec3& r_body, const rigid::Vec3& anchor,
                        double h, double beta);

// ---- The revolute hinge: apply_revolute -----------------------------------------
//
//          axis a (world, unit)              a door: the body turns about a only
//             |
//          anchor ----+                      u = R axis_body: the body's axis, world;
//             |       |  body                it must stay along a
//             |   x   |
//             |       |
//             +-------+
//
// Five velocity rows, solved together:
//   3 point rows    v + omega x r                          = -(beta / h) C      (as above)
//   2 angular rows  b1 . omega,  b2 . omega                 = -(beta / h) C_a
// with (b1, b2) = tangent_basis(a) (rigid_body.h), B = [b1 b2] (3x2), and the angular
// drift C_a = B^T (a x u) (2 numbers, zero when u is along a; to first order its
// rate is B^T omega, so the rows' Jacobian is B^T).
//
// The impulse: P (3, at the point) and the angular impulse M = B mu (mu: 2 numbers,
// so M is perpendicular to a: the hinge never brakes the turning about a):
//   v' = v + P / m,   omega' = omega + I^-1 (r x P + B mu)
//
// Putting these into the rows gives the 5x5 system K lambda = rhs, lambda = (P, mu):
//
//       | E/m - [r]x I^-1 [r]x     -[r]x I^-1 B |           | -(v + omega x r) - (beta/h) C |
//   K = |                                        |,  rhs =  |                               |
//       | B^T I^-1 [r]x              B^T I^-1 B |           | -B^T omega - (beta/h) C_a     |
//
// (the Jacobian J of the rows times diag(E/m, I^-1) times J^T, with [r]x^T = -[r]x:
// K is symmetric positive definite.) Solve it with Eigen (a
// 5x5 fixed-size matrix and .ldlt().solve(rhs)), apply P and M as above.
//
// Inputs:
//   b          the body;  r_body  the pinned point, body frame (m);  anchor  world (m)
//   axis_body  the body's hinge axis, body frame (unit);  axis  the hinge axis a, world (unit)
//   h          step size (s), > 0;  beta  drift correction in [0, 1]
// Outputs:
//   b.v, b.omega  changed by the impulse; returns P (N s) and M (N m s), world frame
struct RevoluteImpulse {
  rigid::Vec3 P = rigid::Vec3::Zero();  // linear impulse at the pinned point (N s)
  rigid::Vec3 M = rigid::Vec3::Zero();  // angular impulse, perpendicular to a (N m s)
};
RevoluteImpulse apply_revolute(rigid::Body& b, const rigid::Vec3& r_body,
                               const rigid::Vec3& anchor, const rigid::Vec3& axis_body,
                               const rigid::Vec3& axis, double h, double beta);
