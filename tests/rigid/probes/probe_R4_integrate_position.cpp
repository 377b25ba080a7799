// Diagnosis probes of R4 (tests/common/wb_probe.h): a body that does not spin, one that spins
// while turned away from the world frame, a large turn in one step, a slow spin.
#include "integrate_position.h"
#include "rigid_probes.h"

// The lab's probe files compile as one unit (cmake/labs.cmake): each keeps its helpers in a
// namespace of its own.
namespace probe_R4_integrate_position {

using rbprobe::Vec3;

namespace {
void run(wbprobe::Probe& P, rigid::Body b, double h) {
  P.call("integrate_position"), rbprobe::body_in(P, b), P.in("h", h);
  P.tol(1e-9, 1e-12);
  integrate_position(b, h);
  rbprobe::body_out(P, b);
  P.out("|q|", b.q.norm());
}
}  // namespace

WB_PROBE("R4", "spin-z", "a body at the origin spinning at 1 rad/s about z, h = 0.5") {
  P.simple();
  rigid::Body b;
  b.omega = Vec3(0, 0, 1);
  run(P, b, 0.5);
}
WB_PROBE("R4", "no-spin", "a turned body moving without spinning, h = 0.1") {
  rigid::Body b = rbprobe::body();
  b.omega.setZero();
  run(P, b, 0.1);
}
WB_PROBE("R4", "spin", "a turned body spinning about a tilted axis, h = 0.1") {
  run(P, rbprobe::body(), 0.1);
}
WB_PROBE("R4", "large-turn", "a turned body spinning at 6 rad/s, h = 0.25: 1.5 rad in one step") {
  rigid::Body b = rbprobe::body();
  b.omega = Vec3(2, -4, 4);
  run(P, b, 0.25);
}
WB_PROBE("R4", "slow-spin", "a turned body spinning at 1e-9 rad/s about x, h = 1") {
  rigid::Body b = rbprobe::body();
  b.omega = Vec3(1e-9, 0, 0);
  run(P, b, 1.0);
}
WB_PROBE("R4", "unnormalised", "a turned body whose q has drifted to |q| = 1.01, spinning") {
  rigid::Body b = rbprobe::body();
  b.q.coeffs() *= 1.01;
  run(P, b, 0.1);
}

}  // namespace probe_R4_integrate_position
