// TODO(C2) particle-particle response. Handout: handouts/collisions.md#c2. Tests: [C2].
#pragma once
#include "wb/types.h"

// Two discs (masses m1, m2 > 0, radii r1, r2 >= 0) in contact exchange an
// impulse along the line of centres:
//
//        ( 1 ) <-- n -- ( 2 )      n points from particle 2 to particle 1
//
//   dist = |x1 - x2|,   overlap s = r1 + r2 - dist    (contact when s >= 0)
//   n    = (x1 - x2) / dist,  or n = (0, 1) when dist == 0 (coincident centres:
//          the documented fallback, so that nothing divides by zero)
//   v_n  = (v1 - v2).n        relative normal velocity, < 0 when approaching
//
// Response, only when in contact (s >= 0):
//   1. if v_n < 0 (approaching), the impulse J n with
//        J  = -(1 + e) v_n / (1/m1 + 1/m2)        (N s, > 0)
//        v1 = v1 + (J / m1) n,   v2 = v2 - (J / m2) n
//      (equal and opposite: the total momentum is unchanged). Receding
//      particles (v_n >= 0) get no impulse.
//   2. separated along n so that they just touch, without moving the centre
//      of mass (m1 x1 + m2 x2 unchanged):
//        x1 = x1 + s (1/m1) / (1/m1 + 1/m2) n,   x2 = x2 - s (1/m2) / (1/m1 + 1/m2) n
//
// Inputs:
//   m1, r1, m2, r2  masses (kg) and radii (m)
//   restitution     e in [0, 1]
// Outputs:
//   x1, v1, x2, v2  positions (m) and velocities (m/s), changed in place
// Returns J, the impulse magnitude applied (N s), 0 when none.
double collide_particles(double m1, double r1, double m2, double r2, double restitution,
                         wb::Vec2& x1, wb::Vec2& v1, wb::Vec2& x2, wb::Vec2& v2);
