// TODO(F4) viscous damping. Handout: handouts/forces.md#f4. Tests: [F4].
#pragma once
#include "wb/types.h"

// Adds the viscous drag  f_i += -b v_i  (the same b for every particle).
//
// Inputs:
//   v  2 x n velocities (m/s)
//   b  drag coefficient (kg/s), >= 0
// Outputs:
//   f  2 x n forces (N); add, do not overwrite
void add_damping(const wb::Mat2X& v, double b, wb::Mat2X& f);
