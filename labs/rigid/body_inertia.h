// TODO(R1) body-frame inertia tensors. Handout: handouts/rigid.md#r1. Tests: [R1].
#pragma once
#include "rigid_body.h"

// The inertia tensor of a solid of uniform density about its centre of mass,
// in its own body frame (principal axes along x, y, z, so the tensor is diagonal):
//
//   I = integral over the solid of rho (|r|^2 E - r r^T) dV      (E: the 3x3 identity)
//
// Inputs:
//   m       mass (kg), > 0
//   size    box: full edge lengths (a, b, c) along body x, y, z (m), each > 0
//   radius  sphere or cylinder radius (m), > 0
//   length  cylinder length along body z (m), > 0
// Outputs: the 3x3 tensor (kg m^2), diagonal:
//   box       m/12 (b^2 + c^2),  m/12 (a^2 + c^2),  m/12 (a^2 + b^2)
//   sphere    2/5 m r^2 on every axis
//   cylinder  m/12 (3 r^2 + L^2) about x and y,  m r^2 / 2 about its axis z
rigid::Mat3 box_inertia(double m, const rigid::Vec3& size);
rigid::Mat3 sphere_inertia(double m, double radius);
rigid::Mat3 cylinder_inertia(double m, double radius, double length);
