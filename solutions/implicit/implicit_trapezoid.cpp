#include "implicit_trapezoid.h"

#include "network_forces.h"

// TODO(I5) implicit trapezoid step of a spring network (see implicit_trapezoid.h).
NewtonReport implicit_trapezoid_step(const SpringNetwork& net, const wb::Mat2X& f_ext, double h,
                                     const NewtonOptions& opt, wb::Mat2X& x, wb::Mat2X& v,
                                     NewtonWorkspace& ws) {
  // Pinned particles never move.
  for (Eigen::Index p = 0; p < net.n(); ++p)
    if (net.is_pinned(p)) v.col(p).setZero();
  // Half an explicit Euler step with the forces at the start.
  wb::Mat2X f;
  network_forces(net, x, v, f);
  const wb::Mat2X a = (f + f_ext) * net.m.cwiseInverse().asDiagonal();
  x += (0.5 * h) * v;
  v += (0.5 * h) * a;  // (pinned particles: backward_euler_step zeroes v again)
  // Half a backward Euler step from there (it pins the pinned particles again).
  return backward_euler_step(net, f_ext, 0.5 * h, opt, x, v, ws);
}
