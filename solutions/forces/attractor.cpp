#include "attractor.h"

// TODO(F3) attractor: f_i += -GM m_i d_i / |d_i|^3 with d_i = x_i - center.
void add_attractor(const wb::Mat2X& x, const wb::VecX& m, const wb::Vec2& center, double GM,
                   wb::Mat2X& f) {
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    const wb::Vec2 d = x.col(i) - center;
    const double r = d.norm();
    if (r == 0.0) continue;  // at the centre: no direction
    f.col(i) -= (GM * m[i] / (r * r * r)) * d;
  }
}
