#include "midpoint.h"

// A correct variant: the two updates written particle by particle with Vec2
// temporaries; the forces are still evaluated once per stage for all particles.
void midpoint_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                   wb::Scratch& s) {
  dyn.acceleration(x, v, s.a0);
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    s.x1.col(i) = x.col(i) + 0.5 * h * v.col(i);
    s.v1.col(i) = v.col(i) + 0.5 * h * s.a0.col(i);
  }
  dyn.acceleration(s.x1, s.v1, s.a1);
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    const wb::Vec2 vmid = s.v1.col(i), amid = s.a1.col(i);
    x.col(i) += h * vmid;
    v.col(i) += h * amid;
  }
}
