// Correct alternative: a plain loop over the particles.
#include "uniform_gravity.h"

void add_uniform_gravity(const wb::VecX& m, const wb::Vec2& g, wb::Mat2X& f) {
  for (Eigen::Index i = 0; i < m.size(); ++i) {
    f(0, i) += m(i) * g(0);
    f(1, i) += m(i) * g(1);
  }
}
