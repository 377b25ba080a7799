// TODO(F1) uniform gravity. Handout: handouts/forces.md#f1. Tests: [F1].
#pragma once
#include "wb/types.h"

// Adds the uniform gravity force m_i g to every particle.
//
// Inputs:
//   m  n masses (kg), all > 0
//   g  gravitational acceleration (m/s^2), e.g. (0, -9.81)
// Outputs:
//   f  2 x n forces (N); add to each column, do not overwrite or resize
void add_uniform_gravity(const wb::VecX& m, const wb::Vec2& g, wb::Mat2X& f);
