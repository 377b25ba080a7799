#include "boids.h"

// TODO(F7) boids: separation, alignment, cohesion and the goal, as a force m_i s_i.
void add_boids(const wb::Mat2X& x, const wb::Mat2X& v, const wb::VecX& m, const BoidsParams& p,
               wb::Mat2X& f) {
  const Eigen::Index n = x.cols();
  for (Eigen::Index i = 0; i < n; ++i) {
    wb::Vec2 sep = wb::Vec2::Zero(), vsum = wb::Vec2::Zero(), xsum = wb::Vec2::Zero();
    int n_align = 0, n_cohere = 0;
    for (Eigen::Index j = 0; j < n; ++j) {
      if (j == i) continue;
      const wb::Vec2 d = x.col(i) - x.col(j);  // from j to i
      const double r = d.norm();
      if (r == 0.0) continue;  // coincident boids have no direction
      if (r < p.separation.radius) sep += d / (r * r);
      if (r < p.alignment.radius) vsum += v.col(j), ++n_align;
      if (r < p.cohesion.radius) xsum += x.col(j), ++n_cohere;
    }
    wb::Vec2 s = p.separation.weight * sep;
    if (n_align > 0) s += p.alignment.weight * (vsum / n_align - v.col(i));
    if (n_cohere > 0) s += p.cohesion.weight * (xsum / n_cohere - x.col(i));
    const wb::Vec2 to_goal = p.goal - x.col(i);
    const double dist = to_goal.norm();
    if (p.goal_weight != 0.0 && dist > 0.0) s += p.goal_weight * to_goal / dist;
    f.col(i) += m[i] * s;
  }
}
