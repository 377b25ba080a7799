#include "uniform_gravity.h"

// TODO(F1) uniform gravity: f_i += m_i g for every particle i.
void add_uniform_gravity(const wb::VecX& m, const wb::Vec2& g, wb::Mat2X& f) {
  // ---- Replace with your code ----
  (void)m, (void)g, (void)f;
  // ---- end ----
}
