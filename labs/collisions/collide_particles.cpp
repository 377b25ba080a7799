#include "collide_particles.h"

// TODO(C2) particle-particle response (see collide_particles.h).
// Plan: 1. d = x1 - x2, dist = |d|; overlap s = r1 + r2 - dist; s < 0: return 0;
//       2. the normal n = d / dist, or (0, 1) when dist == 0;
//       3. v_n = (v1 - v2).n; if v_n < 0: J = -(1 + e) v_n / (1/m1 + 1/m2),
//          v1 += (J / m1) n, v2 -= (J / m2) n;
//       4. separate by s, shared in proportion to 1/m so that the centre of
//          mass stays put;
//       5. return J (0 if no impulse).
double collide_particles(double m1, double r1, double m2, double r2, double restitution,
                         wb::Vec2& x1, wb::Vec2& v1, wb::Vec2& x2, wb::Vec2& v2) {
  // ---- Replace with your code ----
  (void)m1, (void)r1, (void)m2, (void)r2, (void)restitution;
  (void)x1, (void)v1, (void)x2, (void)v2;
  return 0.0;
  // ---- end ----
}
