// TODO(R5) advance the linear and angular velocity, with the gyroscopic term
// taken explicitly or implicitly. Handout: handouts/rigid.md#r5. Tests: [R5].
#pragma once
#include "rigid_body.h"

// The first half of a semi-implicit Euler step, from the force b.f and torque
// b.tau accumulated for this step. Linear part (both variants):
//
//   v_{n+1} = v_n + h f / m
//
// Angular part: Euler's equation I omega' = tau - omega x (I omega), with
// I = R I_body R^T and R = b.q.toRotationMatrix() (see world_inertia.h).
//
// explicit: the gyroscopic term at the old omega (it gains energy: handout):
//   omega_{n+1} = omega_n + h I^-1 (tau - omega_n x (I omega_n))
//
// implicit: in the body frame w = R^T omega, the gyroscopic equation
//   I_body (w' - w) + h w' x (I_body w') = 0
// solved by ONE Newton step from w' = w:
//   J  = I_body + h ([w]x I_body - [I_body w]x)      ([a]x b = a x b)
//   w' = w - J^-1 (h w x (I_body w))
// then back to the world frame, and the torque added explicitly:
//   omega_{n+1} = R w' + h I^-1 tau
//
// Inputs:
//   b.m, b.I_body, b.q, b.f (N), b.tau (N m, world), b.v, b.omega;  h  step (s), > 0
// Outputs:
//   b.v, b.omega  advanced in place; x, q, f, tau unchanged
void integrate_velocity_explicit(rigid::Body& b, double h);
void integrate_velocity_implicit(rigid::Body& b, double h);
