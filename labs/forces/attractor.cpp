#include "attractor.h"

// TODO(F3) attractor: f_i += -GM m_i d_i / |d_i|^3 with d_i = x_i - center.
void add_attractor(const wb::Mat2X& x, const wb::VecX& m, const wb::Vec2& center, double GM,
                   wb::Mat2X& f) {
  // ---- Replace with your code ----
  (void)x, (void)m, (void)center, (void)GM, (void)f;
  // ---- end ----
}
