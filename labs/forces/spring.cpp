#include "spring.h"

// TODO(F5) spring-damper: the force on end i (see spring.h for the formula).
// Plan: 1. d = x_i - x_j and L = |d|; return zero when L == 0;
//       2. u = d / L;  3. spring term k (L - rest);  4. damper term kd (v_i - v_j) . u;
//       5. return -(spring + damper) u.
wb::Vec2 spring_force(const wb::Vec2& xi, const wb::Vec2& xj, const wb::Vec2& vi,
                      const wb::Vec2& vj, double k, double rest, double kd) {
  // ---- Replace with your code ----
  (void)xi, (void)xj, (void)vi, (void)vj, (void)k, (void)rest, (void)kd;
  return wb::Vec2::Zero();
  // ---- end ----
}
