// TODO(C1) particle-plane response. Handout: handouts/collisions.md#c1. Tests: [C1].
#pragma once
#include "wb/types.h"

// One particle (a disc of radius r, mass m) against a plane through the point
// p with UNIT normal n. The free side is where (x - p).n > 0:
//
//          n ^         free side
//            |   ( x )  <- disc of radius r, velocity v
//   ---------p----------- plane
//            solid side
//
//   d   = (x - p).n - r        gap (m): d <= 0 is contact (touching or penetrating)
//   v_n = v.n                  normal velocity (m/s): v_n < 0 is approaching
//
// Response, only when d <= 0:
//   1. if v_n < 0 (approaching), an impulse along +n:
//        e = 0            when -v_n < rest_speed (resting contact: no micro-bounce)
//        e = restitution  otherwise
//        j = -(1 + e) m v_n        (N s; > 0, so the minus sign is not optional)
//        v = v + (j / m) n         (the tangential velocity is unchanged)
//      A receding particle (v_n >= 0) gets no impulse.
//   2. moved out along n so that it just touches:  x = x - d n
//
// Inputs:
//   p, n         plane point (m) and unit normal
//   r, m         radius (m, >= 0) and mass (kg, > 0)
//   restitution  e in [0, 1]: the normal velocity after is -e times the one before
//   rest_speed   approach speeds below this (m/s, >= 0) are treated as resting
// Outputs:
//   x, v         position (m) and velocity (m/s), changed in place as above
// Returns j, the impulse magnitude applied (N s), 0 when none.
double collide_plane(const wb::Vec2& p, const wb::Vec2& n, double r, double m, double restitution,
                     double rest_speed, wb::Vec2& x, wb::Vec2& v);
