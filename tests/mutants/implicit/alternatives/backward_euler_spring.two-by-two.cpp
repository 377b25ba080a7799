#include <Eigen/Dense>

#include "backward_euler_spring.h"

// Alternative I1: the two equations of each coordinate as one 2 x 2 linear solve,
//   [ 1         -h       ] [x']   [ x                       ]
//   [ h k / m   1 + hb/m ] [v'] = [ v + h (k c + f_ext) / m ]
void backward_euler_spring_step(double m, double k, double b, const wb::Vec2& c,
                                const wb::Vec2& f_ext, double h, wb::Vec2& x, wb::Vec2& v) {
  Eigen::Matrix2d A;
  A << 1.0, -h, h * k / m, 1.0 + h * b / m;
  const Eigen::PartialPivLU<Eigen::Matrix2d> lu(A);
  for (int d = 0; d < 2; ++d) {
    const Eigen::Vector2d s =
        lu.solve(Eigen::Vector2d(x[d], v[d] + h * (k * c[d] + f_ext[d]) / m));
    x[d] = s[0];
    v[d] = s[1];
  }
}
