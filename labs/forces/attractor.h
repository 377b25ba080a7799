// TODO(F3) attractor: gravity towards a point. Handout: handouts/forces.md#f3. Tests: [F3].
#pragma once
#include "wb/types.h"

// Adds the pull of a fixed point mass at `center` (the "spherical earth"):
//
//   f_i += -GM m_i d_i / |d_i|^3,   d_i = x_i - center
//
// the force of the potential V = - sum_i GM m_i / |d_i|.
// A particle exactly at the centre (|d_i| == 0) gets no force.
//
// Inputs:
//   x       2 x n positions (m)
//   m       n masses (kg)
//   center  the attracting point (m)
//   GM      its gravitational parameter (m^3/s^2), >= 0
// Outputs:
//   f       2 x n forces (N); add, do not overwrite
void add_attractor(const wb::Mat2X& x, const wb::VecX& m, const wb::Vec2& center, double GM,
                   wb::Mat2X& f);
