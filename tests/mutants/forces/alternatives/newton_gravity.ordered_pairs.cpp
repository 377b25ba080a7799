// Correct alternative: every ordered pair (i, j != i), each force added only to i
// (so every pair is visited twice), and coincident unsoftened pairs skipped with
// a small threshold instead of an exact == 0 test.
#include "newton_gravity.h"

#include <cmath>

void add_newton_gravity(const wb::Mat2X& x, const wb::VecX& m, double G, double eps,
                        wb::Mat2X& f) {
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    wb::Vec2 fi = wb::Vec2::Zero();
    for (Eigen::Index j = 0; j < x.cols(); ++j) {
      if (j == i) continue;
      const wb::Vec2 d = x.col(j) - x.col(i);
      const double s = d.squaredNorm() + eps * eps;
      if (s < 1e-300) continue;
      fi += m[j] * d / std::pow(s, 1.5);
    }
    f.col(i) += G * m[i] * fi;
  }
}
