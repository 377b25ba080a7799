// TODO(R2) the inertia tensor in the world frame, its inverse, and the parallel
// axis theorem. Handout: handouts/rigid.md#r2. Tests: [R2].
#pragma once
#include "rigid_body.h"

// A body turned by the rotation R (body -> world) has, in the world frame,
//
//   I     = R I_body R^T
//   I^-1  = R I_body^-1 R^T      (R^-1 = R^T: no general 3x3 inversion needed;
//                                 I_body is diagonal, so I_body^-1 is 1 / each entry)
//
// About a point P that is not the centre of mass, with d = x - P:
//
//   I_P = I + m (|d|^2 E - d d^T)      (the parallel axis theorem)
//
// Inputs:
//   R       3x3 rotation matrix, body -> world (orthonormal, det 1)
//   I_body  3x3 diagonal inertia about the centre, body frame (kg m^2), entries > 0
//   I       3x3 inertia about the centre of mass, any frame (kg m^2)
//   m       mass (kg);  d  the centre of mass minus the point P (m)
// Outputs: 3x3 tensors, (kg m^2) or (1 / (kg m^2)) for the inverse
rigid::Mat3 world_inertia(const rigid::Mat3& R, const rigid::Mat3& I_body);
rigid::Mat3 world_inverse_inertia(const rigid::Mat3& R, const rigid::Mat3& I_body);
rigid::Mat3 parallel_axis(const rigid::Mat3& I, double m, const rigid::Vec3& d);
