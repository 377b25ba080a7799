#include "collide_plane.h"

// TODO(C1) particle-plane response (see collide_plane.h).
// Plan: 1. the gap d = (x - p).n - r; no contact (d > 0): return 0;
//       2. the normal velocity v_n = v.n; if approaching (v_n < 0): pick e
//          (0 below rest_speed), j = -(1 + e) m v_n, v += (j / m) n;
//       3. move the particle out: x -= d n;
//       4. return j (0 if no impulse).
double collide_plane(const wb::Vec2& p, const wb::Vec2& n, double r, double m, double restitution,
                     double rest_speed, wb::Vec2& x, wb::Vec2& v) {
  // ---- Replace with your code ----
  (void)p, (void)n, (void)r, (void)m, (void)restitution, (void)rest_speed, (void)x, (void)v;
  return 0.0;
  // ---- end ----
}
