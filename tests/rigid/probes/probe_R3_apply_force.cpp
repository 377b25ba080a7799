// Diagnosis probes of R3 (tests/common/wb_probe.h): a force through the centre (no torque), one
// off the centre, gravity; on a body that already holds a force and a torque.
#include "apply_force.h"
#include "rigid_probes.h"

// The lab's probe files compile as one unit (cmake/labs.cmake): each keeps its helpers in a
// namespace of its own.
namespace probe_R3_apply_force {

using rbprobe::Vec3;

namespace {
void force(wbprobe::Probe& P, rigid::Body b, const Vec3& F, const Vec3& p) {
  P.call("apply_force"), rbprobe::body_in(P, b), P.in("F", F), P.in("p", p);
  apply_force(b, F, p);
  rbprobe::body_out(P, b);
}
}  // namespace

WB_PROBE("R3", "push", "a body at rest at the origin pushed along x at the point (0, 1, 0)") {
  P.simple();
  rigid::Body b;
  force(P, b, Vec3(1, 0, 0), Vec3(0, 1, 0));
}
WB_PROBE("R3", "centre",
         "a force through the centre of a moving body holding a force and torque") {
  const rigid::Body b = rbprobe::body();
  force(P, b, Vec3(1.5, -0.5, 2), b.x);
}
WB_PROBE("R3", "off-centre", "a force at a point off the centre") {
  const rigid::Body b = rbprobe::body();
  force(P, b, Vec3(1.5, -0.5, 2), b.x + Vec3(0.25, 0.5, -0.75));
}
// The body at the origin, holding a force and a torque: an arm measured from the origin is
// right here, and what was held must still be kept.
WB_PROBE("R3", "origin",
         "a force off the centre of a body at the origin holding a force and torque") {
  rigid::Body b = rbprobe::body();
  b.x.setZero();
  force(P, b, Vec3(1.5, -0.5, 2), Vec3(0.25, 0.5, -0.75));
}
WB_PROBE("R3", "gravity", "apply_gravity, g = (0, -9.81, 0)") {
  rigid::Body b = rbprobe::body();
  P.call("apply_gravity"), rbprobe::body_in(P, b), P.in("g", Vec3(0, -9.81, 0));
  apply_gravity(b, Vec3(0, -9.81, 0));
  rbprobe::body_out(P, b);
}

}  // namespace probe_R3_apply_force
