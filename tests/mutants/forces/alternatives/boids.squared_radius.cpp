// Correct alternative: squared-distance radius checks (inclusive at the radius:
// the header's strict < only matters exactly on the boundary), one pass per rule.
#include "boids.h"

void add_boids(const wb::Mat2X& x, const wb::Mat2X& v, const wb::VecX& m, const BoidsParams& p,
               wb::Mat2X& f) {
  const Eigen::Index n = x.cols();
  const double rs2 = p.separation.radius * p.separation.radius;
  const double ra2 = p.alignment.radius * p.alignment.radius;
  const double rc2 = p.cohesion.radius * p.cohesion.radius;
  for (Eigen::Index i = 0; i < n; ++i) {
    wb::Vec2 acc = wb::Vec2::Zero();
    // separation
    for (Eigen::Index j = 0; j < n; ++j) {
      const wb::Vec2 d = x.col(i) - x.col(j);
      const double r2 = d.squaredNorm();
      if (j != i && r2 > 0 && r2 <= rs2) acc += p.separation.weight * d / r2;
    }
    // alignment
    wb::Vec2 vm = wb::Vec2::Zero();
    double count = 0;
    for (Eigen::Index j = 0; j < n; ++j) {
      const double r2 = (x.col(i) - x.col(j)).squaredNorm();
      if (j != i && r2 > 0 && r2 <= ra2) vm += v.col(j), count += 1;
    }
    if (count > 0) acc += p.alignment.weight * (vm / count - v.col(i));
    // cohesion
    wb::Vec2 xm = wb::Vec2::Zero();
    count = 0;
    for (Eigen::Index j = 0; j < n; ++j) {
      const double r2 = (x.col(i) - x.col(j)).squaredNorm();
      if (j != i && r2 > 0 && r2 <= rc2) xm += x.col(j), count += 1;
    }
    if (count > 0) acc += p.cohesion.weight * (xm / count - x.col(i));
    // goal
    const wb::Vec2 g = p.goal - x.col(i);
    if (g.squaredNorm() > 0) acc += p.goal_weight * g.normalized();
    f.col(i) += m[i] * acc;
  }
}
