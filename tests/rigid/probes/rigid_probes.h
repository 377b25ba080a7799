// Shared by the rigid lab's probes (tests/common/wb_probe.h): a body as inputs and outputs.
#pragma once
#include <cmath>

#include "rigid_body.h"
#include "wb_probe.h"

namespace rbprobe {

using rigid::Mat3;
using rigid::Vec3;

inline Eigen::Quaterniond turn(double angle, const Vec3& axis) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis.normalized()));
}

// A box-like body of mass 2 with a generic inertia, turned away from the world frame, moving
// and spinning, holding some force and torque.
inline rigid::Body body() {
  rigid::Body b;
  b.m = 2.0;
  b.I_body = Vec3(0.5, 1.25, 2.0).asDiagonal();
  b.x = Vec3(0.5, 1.0, -0.25);
  b.v = Vec3(0.3, -0.2, 0.1);
  b.q = turn(0.7, Vec3(1, 2, 2));
  b.omega = Vec3(0.4, -1.1, 0.8);
  b.f = Vec3(0.5, -19.6, 0.25);
  b.tau = Vec3(0.2, 0.1, -0.3);
  return b;
}

inline void body_in(wbprobe::Probe& P, const rigid::Body& b) {
  P.in("b.m", b.m), P.in("b.I_body", b.I_body), P.in("b.x", b.x), P.in("b.v", b.v);
  P.in("b.q", b.q), P.in("b.omega", b.omega), P.in("b.f", b.f), P.in("b.tau", b.tau);
}
// Every field that a function may change: shown apart, wrong together (one part's mistakes
// change some fields, another's others).
inline void body_out(wbprobe::Probe& P, const rigid::Body& b) {
  P.group("the body");
  P.out("b.x", b.x), P.out("b.v", b.v), P.out("b.q", b.q), P.out("b.omega", b.omega);
  P.out("b.f", b.f), P.out("b.tau", b.tau);
  P.group("");
}

}  // namespace rbprobe
