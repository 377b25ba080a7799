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
  P.group("the body"), P.out("|q|", b.q.norm()), P.group("");
}
}  // namespace

WB_PROBE("R4", "spin-z", "a body at the origin spinning at 1 rad/s about z, h = 0.5") {
  P.simple();
  rigid::Body b;
  b.omega = Vec3(0, 0, 1);
  run(P, b, 0.5);
}
WB_PROBE("R4", "no-spin", "a turned body moving without spinning, h = 0.1") {
  P.simple();
  rigid::Body b = rbprobe::body();
  b.omega.setZero();
  run(P, b, 0.1);
}
WB_PROBE("R4", "spin", "a turned body spinning about a tilted axis, h = 0.1") {
  P.simple();
  run(P, rbprobe::body(), 0.1);
}
WB_PROBE("R4", "large-turn", "a turned body spinning at 6 rad/s, h = 0.25: 1.5 rad in one step") {
  P.simple();
  rigid::Body b = rbprobe::body();
  b.omega = Vec3(2, -4, 4);
  run(P, b, 0.25);
}
WB_PROBE("R4", "slow-spin", "a turned body spinning at 1e-9 rad/s about x, h = 1") {
  P.simple();
  rigid::Body b = rbprobe::body();
  b.omega = Vec3(1e-9, 0, 0);
  run(P, b, 1.0);
}
WB_PROBE("R4", "unnormalised", "a turned body whose q has drifted to |q| = 1.01, spinning") {
  P.simple();
  rigid::Body b = rbprobe::body();
  b.q.coeffs() *= 1.01;
  run(P, b, 0.1);
}

// The orientation update: a turned body spinning about a tilted axis whose q has drifted to
// |q| = 1.01.
WB_PROBE("R4", "orientation",
         "a turned body spinning at 1.4 rad/s about a tilted axis, |q| = 1.01, h = 0.1") {
  rigid::Body b = rbprobe::body();
  b.q.coeffs() *= 1.01;
  run(P, b, 0.1);
}
// The zero-spin guard: a body that does not spin and one that spins at 1e-9 rad/s, together.
WB_PROBE("R4", "zero-spin",
         "two turned bodies, one not spinning, one spinning at 1e-9 rad/s about x, h = 1") {
  rigid::Body a = rbprobe::body(), b = rbprobe::body();
  a.omega.setZero();
  b.omega = Vec3(1e-9, 0, 0);
  P.call("integrate_position (twice)"), rbprobe::body_in(P, a), P.in("second b.omega", b.omega);
  P.in("h", 1.0);
  P.tol(1e-9, 1e-12);
  integrate_position(a, 1.0);
  integrate_position(b, 1.0);
  P.group("both bodies");
  P.out("first b.x", a.x), P.out("first b.q", a.q), P.out("second b.x", b.x),
      P.out("second b.q", b.q);
}

}  // namespace probe_R4_integrate_position
