#include "explicit_euler.h"

// Correct, written component by component: every particle and coordinate
// moves with its own old velocity.
void explicit_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                         wb::Scratch& s) {
  dyn.acceleration(x, v, s.a0);
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    for (int d = 0; d < 2; ++d) {
      const double v_old = v(d, i);
      v(d, i) = v_old + h * s.a0(d, i);
      x(d, i) = x(d, i) + h * v_old;
    }
  }
}
