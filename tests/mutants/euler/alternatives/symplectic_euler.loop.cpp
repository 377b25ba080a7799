#include "symplectic_euler.h"

// Correct, written component by component.
void symplectic_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                           wb::Scratch& s) {
  dyn.acceleration(x, v, s.a0);
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    for (int d = 0; d < 2; ++d) {
      v(d, i) += h * s.a0(d, i);
      x(d, i) += h * v(d, i);
    }
  }
}
