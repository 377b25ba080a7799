// The long runs of the euler tests (euler_kernels.h).
#include "euler_kernels.h"

#include <algorithm>
#include <limits>

#include "explicit_euler.h"
#include "symplectic_euler.h"

void euler_oscillator_run(int method, double w, double h, long n, long sample, wb::Mat2X& x,
                          wb::Mat2X& v, double& e_min, double& e_max) {
  const wb::StepFn step = method == 0 ? explicit_euler_step : symplectic_euler_step;
  const wb::LambdaDynamics dyn(
      [w](const wb::Mat2X& xx, const wb::Mat2X&, wb::Mat2X& a) { a = -(w * w) * xx; });
  wb::Scratch s;
  s.resize(x.cols());
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  for (long k = 0; k < n; ++k) {
    for (wb::Mat2X* m : {&s.a0, &s.a1, &s.a2, &s.a3, &s.x1, &s.v1, &s.xs, &s.vs})
      m->setConstant(nan);
    step(dyn, h, x, v, s);
    if (sample > 0 && k % sample == 0) {
      const double e = 0.5 * v.squaredNorm() + 0.5 * w * w * x.squaredNorm();
      e_min = std::min(e_min, e);
      e_max = std::max(e_max, e);
    }
  }
}
