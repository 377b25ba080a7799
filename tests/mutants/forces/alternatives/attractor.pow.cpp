// Correct alternative: |d|^3 as pow(|d|^2, 1.5), the magnitude and direction
// computed separately.
#include "attractor.h"

#include <cmath>

void add_attractor(const wb::Mat2X& x, const wb::VecX& m, const wb::Vec2& center, double GM,
                   wb::Mat2X& f) {
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    const wb::Vec2 to_center = center - x.col(i);
    const double r2 = to_center.squaredNorm();
    if (r2 <= 0) continue;
    const double magnitude = GM * m(i) / r2;             // GM m / r^2
    f.col(i) += magnitude * to_center / std::sqrt(r2);  // along the unit vector to the centre
  }
}
