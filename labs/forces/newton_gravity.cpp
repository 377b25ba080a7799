#include "newton_gravity.h"

// TODO(F2) Newtonian gravitation between all pairs, softened by eps.
// Plan: 1. loop over pairs i < j;  2. d = x_j - x_i, s = |d|^2 + eps^2, skip s == 0;
//       3. the pair force G m_i m_j d / s^(3/2) pulls i towards j and j towards i.
void add_newton_gravity(const wb::Mat2X& x, const wb::VecX& m, double G, double eps,
                        wb::Mat2X& f) {
  // ---- Replace with your code ----
  (void)x, (void)m, (void)G, (void)eps, (void)f;
  // ---- end ----
}
