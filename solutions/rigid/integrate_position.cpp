#include "integrate_position.h"

// TODO(R4) move the centre with the new velocity and turn the body by |omega| h
// about omega (see integrate_position.h).
void integrate_position(rigid::Body& b, double h) {
  b.x += h * b.v;
  const double speed = b.omega.norm();  // rad/s
  if (speed > 0.0) {
    const Eigen::Quaterniond dq(Eigen::AngleAxisd(speed * h, b.omega / speed));
    b.q = dq * b.q;  // omega is in the world frame: turn after the current orientation
  }
  b.q.normalize();
}
