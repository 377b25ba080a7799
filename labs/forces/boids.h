// TODO(F7) boids: steering as a proxy force. Handout: handouts/forces.md#f7. Tests: [F7].
#pragma once
#include "wb/types.h"

struct BoidRule {
  double weight = 0.0;  // strength (1/s^2 for separation/cohesion, 1/s for alignment)
  double radius =
      0.0;  // neighbour radius (m): j is a neighbour of i when 0 < |x_j - x_i| < radius
};

struct BoidsParams {
  BoidRule separation;     // steer away from close neighbours
  BoidRule alignment;      // match the neighbours' mean velocity
  BoidRule cohesion;       // steer towards the neighbours' centre
  double goal_weight = 0;  // strength of the pull to the goal (m/s^2)
  wb::Vec2 goal{0, 0};     // where the flock heads (m); unused when goal_weight == 0
};

// Adds the boids steering force f_i += m_i s_i, with s_i the sum of four terms.
// N_r(i) is the set of neighbours j != i with 0 < |x_j - x_i| < r:
//
//   separation  w_s * sum_{j in N_s(i)} (x_i - x_j) / |x_i - x_j|^2
//   alignment   w_a * (mean_{j in N_a(i)} v_j - v_i)      (0 if N_a(i) is empty)
//   cohesion    w_c * (mean_{j in N_c(i)} x_j - x_i)      (0 if N_c(i) is empty)
//   goal        w_g * (goal - x_i) / |goal - x_i|         (0 at the goal)
//
// Inputs:
//   x, v  2 x n positions (m) and velocities (m/s)
//   m     n masses (kg)
//   p     the rules' weights and radii
// Outputs:
//   f     2 x n forces (N); add, do not overwrite
void add_boids(const wb::Mat2X& x, const wb::Mat2X& v, const wb::VecX& m, const BoidsParams& p,
               wb::Mat2X& f);
