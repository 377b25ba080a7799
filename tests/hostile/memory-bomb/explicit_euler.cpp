#include "explicit_euler.h"
#include <vector>
void explicit_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                         wb::Scratch& s) {
  (void)dyn, (void)h, (void)x, (void)v, (void)s;
  std::vector<double> big(std::size_t(1) << 31, 1.0);
  x(0, 0) += big[big.size() - 1] * 0.0;
}
