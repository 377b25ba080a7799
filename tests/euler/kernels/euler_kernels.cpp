// The long runs of the euler tests (euler_kernels.h).
#include "euler_kernels.h"

#include <limits>

#include "explicit_euler.h"
#include "symplectic_euler.h"

void euler_oscillator_run(int method, double w, double h, long n, long every, wb::Mat2X& x,
                          wb::Mat2X& v, wb::Mat2X& xs, wb::Mat2X& vs) {
  const wb::StepFn step = method == 0 ? explicit_euler_step : symplectic_euler_step;
  const wb::LambdaDynamics dyn(
      [w](const wb::Mat2X& xx, const wb::Mat2X&, wb::Mat2X& a) { a = -(w * w) * xx; });
  wb::Scratch s;
  s.resize(x.cols());
  const Eigen::Index p = x.cols();
  const long checkpoints = every > 0 ? n / every + 1 : 1;
  xs.resize(2, checkpoints * p);
  vs.resize(2, checkpoints * p);
  xs.leftCols(p) = x;
  vs.leftCols(p) = v;
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  for (long k = 1; k <= n; ++k) {
    for (wb::Mat2X* m : {&s.a0, &s.a1, &s.a2, &s.a3, &s.x1, &s.v1, &s.xs, &s.vs})
      m->setConstant(nan);
    step(dyn, h, x, v, s);
    if (every > 0 && k % every == 0) {
      xs.middleCols((k / every) * p, p) = x;
      vs.middleCols((k / every) * p, p) = v;
    }
  }
}
