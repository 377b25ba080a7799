// TODO(F2) Newtonian gravitation between all pairs. Handout: handouts/forces.md#f2. Tests: [F2].
#pragma once
#include "wb/types.h"

// Adds the softened gravitational pull of every particle j on every particle i:
//
//   f_i += sum_{j != i} G m_i m_j (x_j - x_i) / (|x_j - x_i|^2 + eps^2)^(3/2)
//
// the force of the potential  V = - sum_{i<j} G m_i m_j / sqrt(r_ij^2 + eps^2).
// A pair with |x_j - x_i|^2 + eps^2 == 0 (coincident, no softening) adds nothing.
//
// Inputs:
//   x    2 x n positions (m)
//   m    n masses (kg)
//   G    gravitational constant (N m^2 / kg^2), >= 0
//   eps  softening length (m), >= 0
// Outputs:
//   f    2 x n forces (N); add, do not overwrite
void add_newton_gravity(const wb::Mat2X& x, const wb::VecX& m, double G, double eps,
                        wb::Mat2X& f);
