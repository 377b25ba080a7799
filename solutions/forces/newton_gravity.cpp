#include "newton_gravity.h"

#include <cmath>

// TODO(F2) Newtonian gravitation between all pairs, softened by eps.
void add_newton_gravity(const wb::Mat2X& x, const wb::VecX& m, double G, double eps,
                        wb::Mat2X& f) {
  const Eigen::Index n = x.cols();
  const double eps2 = eps * eps;
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = i + 1; j < n; ++j) {
      const wb::Vec2 d = x.col(j) - x.col(i);  // from i to j
      const double s = d.squaredNorm() + eps2;
      if (s == 0.0) continue;  // coincident and unsoftened: no defined direction
      const wb::Vec2 fij = (G * m[i] * m[j] / (s * std::sqrt(s))) * d;  // on i, towards j
      f.col(i) += fij;
      f.col(j) -= fij;  // Newton's third law
    }
  }
}
