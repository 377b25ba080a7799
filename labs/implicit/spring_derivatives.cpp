#include "spring_derivatives.h"

// TODO(I2) the spring's force and derivatives (see spring_derivatives.h).
// Plan: 1. d = x_i - x_j, L = |d|; if L == 0: f = 0, K = -k I, D = 0, return;
//       2. u = d / L and P = u u^T;
//       3. f = -(k (L - rest) + kd (v_i - v_j) . u) u;
//       4. across = 1 - rest / L, clamped at 0 when `definite`;
//          K = -k (P + across (I - P));
//       5. D = -kd P.
void spring_derivatives(const wb::Vec2& xi, const wb::Vec2& xj, const wb::Vec2& vi,
                        const wb::Vec2& vj, double k, double rest, double kd, bool definite,
                        wb::Vec2& f, wb::Mat2& K, wb::Mat2& D) {
  // ---- Replace with your code ----
  (void)xi, (void)xj, (void)vi, (void)vj, (void)k, (void)rest, (void)kd, (void)definite;
  f.setZero();
  K.setZero();
  D.setZero();
  // ---- end ----
}
