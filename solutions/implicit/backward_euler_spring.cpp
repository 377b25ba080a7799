#include "backward_euler_spring.h"

// TODO(I1) backward Euler for one spring, solved by hand (see backward_euler_spring.h).
void backward_euler_spring_step(double m, double k, double b, const wb::Vec2& c,
                                const wb::Vec2& f_ext, double h, wb::Vec2& x, wb::Vec2& v) {
  // The one linear equation in v' (substitute x' = x + h v' into the force).
  const double lhs = m + h * b + h * h * k;
  const wb::Vec2 rhs = m * v - h * k * (x - c) + h * f_ext;
  // New velocity, then the position with it.
  v = rhs / lhs;
  x += h * v;
}
