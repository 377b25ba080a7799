// TODO(R3) forces and torques on a rigid body. Handout: handouts/rigid.md#r3. Tests: [R3].
#pragma once
#include "rigid_body.h"

// A force F applied at a world point p pushes the centre of mass as if it acted
// there, and turns the body about its centre of mass:
//
//   f   += F
//   tau += (p - x) x F          (zero when the line of action passes through x)
//
// Gravity acts at the centre of mass: f += m g, no torque.
//
// Inputs:
//   F  force (N), world frame;  p  the point where it acts (m), world frame
//   g  gravitational acceleration (m/s^2), world frame
// Outputs:
//   b.f, b.tau  ADDED to (other forces may already be there); nothing else changes
void apply_force(rigid::Body& b, const rigid::Vec3& F, const rigid::Vec3& p);
void apply_gravity(rigid::Body& b, const rigid::Vec3& g);
