// Diagnosis probes of R5 (tests/common/wb_probe.h): the linear part alone (no spin, no torque),
// the torque alone (no spin), the gyroscopic term alone (spinning, no torque) on a body turned
// away from the world frame; for the explicit and the implicit update.
#include "integrate_velocity.h"
#include "rigid_probes.h"

// The lab's probe files compile as one unit (cmake/labs.cmake): each keeps its helpers in a
// namespace of its own.
namespace probe_R5_integrate_velocity {

using rbprobe::Vec3;

namespace {
using Step = void (*)(rigid::Body&, double);
void run(wbprobe::Probe& P, Step fn, const char* name, rigid::Body b, double h) {
  P.call(name), rbprobe::body_in(P, b), P.in("h", h);
  fn(b, h);
  rbprobe::body_out(P, b);
}
rigid::Body linear() {
  rigid::Body b = rbprobe::body();
  b.omega.setZero(), b.tau.setZero();
  return b;
}
rigid::Body torque() {
  rigid::Body b = rbprobe::body();
  b.omega.setZero(), b.f.setZero();
  return b;
}
rigid::Body gyro() {
  rigid::Body b = rbprobe::body();
  b.tau.setZero(), b.f.setZero();
  return b;
}
}  // namespace

WB_PROBE("R5", "fall",
         "integrate_velocity_explicit: a body of mass 2 at rest, f = (0, -19.6, 0), h = 0.1") {
  P.simple();
  rigid::Body b;
  b.m = 2, b.f = Vec3(0, -19.6, 0);
  run(P, &integrate_velocity_explicit, "integrate_velocity_explicit", b, 0.1);
}
WB_PROBE("R5", "explicit-linear", "integrate_velocity_explicit: force only, no spin, no torque") {
  P.simple();
  run(P, &integrate_velocity_explicit, "integrate_velocity_explicit", linear(), 0.1);
}
WB_PROBE("R5", "explicit-torque",
         "integrate_velocity_explicit: torque only, no spin, turned body") {
  P.simple();
  run(P, &integrate_velocity_explicit, "integrate_velocity_explicit", torque(), 0.1);
}
// The linear part, both updates in one group: a force, no spin, no torque.
WB_PROBE("R5", "linear",
         "integrate_velocity_explicit, then integrate_velocity_implicit: a force, no spin, no "
         "torque") {
  const rigid::Body b0 = linear();
  rigid::Body a = b0, b = b0;
  P.call("integrate_velocity_explicit, integrate_velocity_implicit"), rbprobe::body_in(P, b0);
  P.in("h", 0.1);
  integrate_velocity_explicit(a, 0.1);
  integrate_velocity_implicit(b, 0.1);
  P.group("both bodies");
  P.out("explicit: b.v", a.v), P.out("explicit: b.omega", a.omega), P.out("explicit: b.f", a.f);
  P.out("explicit: b.tau", a.tau), P.out("implicit: b.v", b.v),
      P.out("implicit: b.omega", b.omega);
  P.out("implicit: b.f", b.f), P.out("implicit: b.tau", b.tau);
}
WB_PROBE("R5", "explicit-gyro", "integrate_velocity_explicit: spinning, no torque, turned body") {
  run(P, &integrate_velocity_explicit, "integrate_velocity_explicit", gyro(), 0.1);
}
WB_PROBE("R5", "implicit-linear", "integrate_velocity_implicit: force only, no spin, no torque") {
  P.simple();
  run(P, &integrate_velocity_implicit, "integrate_velocity_implicit", linear(), 0.1);
}
WB_PROBE("R5", "implicit-torque",
         "integrate_velocity_implicit: torque only, no spin, turned body") {
  P.simple();
  run(P, &integrate_velocity_implicit, "integrate_velocity_implicit", torque(), 0.1);
}
WB_PROBE("R5", "implicit-gyro", "integrate_velocity_implicit: spinning, no torque, turned body") {
  run(P, &integrate_velocity_implicit, "integrate_velocity_implicit", gyro(), 0.1);
}

}  // namespace probe_R5_integrate_velocity
