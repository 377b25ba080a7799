#include "backward_euler_spring.h"

// TODO(I1) backward Euler for one spring, solved by hand (see backward_euler_spring.h).
// Plan: 1. substitute x' = x + h v' into v' = v + (h/m)(-k (x' - c) - b v' + f_ext);
//       2. collect the v' terms: (m + h b + h^2 k) v' = m v - h k (x - c) + h f_ext;
//       3. divide to get v', then x' = x + h v' (with the NEW velocity).
void backward_euler_spring_step(double m, double k, double b, const wb::Vec2& c,
                                const wb::Vec2& f_ext, double h, wb::Vec2& x, wb::Vec2& v) {
  // ---- Replace with your code ----
  (void)m, (void)k, (void)b, (void)c, (void)f_ext, (void)h, (void)x, (void)v;
  // ---- end ----
}
