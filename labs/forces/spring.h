// TODO(F5) spring-damper. Handout: handouts/forces.md#f5. Tests: [F5].
#pragma once
#include "wb/types.h"

// The force on end i of a damped spring between ends i and j:
//
//   d = x_i - x_j,  L = |d|,  u = d / L
//   f_i = -( k (L - rest) + kd (v_i - v_j) . u ) u        (and f_j = -f_i)
//
// the spring part is the force of V = 1/2 k (L - rest)^2; the damper acts only
// along the spring. When L == 0 the direction u is undefined: return (0, 0).
// A spring to a fixed anchor is the same call with x_j = anchor, v_j = 0.
//
// Inputs:
//   xi, xj  end positions (m)
//   vi, vj  end velocities (m/s)
//   k       stiffness (N/m), >= 0
//   rest    rest length (m), >= 0
//   kd      damping along the spring (N s/m), >= 0
// Returns:
//   the force on end i (N)
wb::Vec2 spring_force(const wb::Vec2& xi, const wb::Vec2& xj, const wb::Vec2& vi,
                      const wb::Vec2& vj, double k, double rest, double kd);
