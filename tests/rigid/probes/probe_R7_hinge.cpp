// Diagnosis probes of R7 (tests/common/wb_probe.h): apply_hinge and apply_revolute on a body
// in the world frame's axes (q = 1) and turned away from them, without drift and with drift
// (the anchor off, the axis off).
#include "hinge.h"
#include "rigid_probes.h"

// The lab's probe files compile as one unit (cmake/labs.cmake): each keeps its helpers in a
// namespace of its own.
namespace probe_R7_hinge {

using rbprobe::Vec3;

namespace {
void hinge(wbprobe::Probe& P, rigid::Body b, const Vec3& r_body, const Vec3& anchor, double h,
           double beta) {
  P.call("apply_hinge"), rbprobe::body_in(P, b), P.in("r_body", r_body), P.in("anchor", anchor);
  P.in("h", h), P.in("beta", beta);
  const Vec3 Pimp = apply_hinge(b, r_body, anchor, h, beta);
  P.group("the body"), P.out("returned", Pimp), P.group("");
  rbprobe::body_out(P, b);
}
void revolute(wbprobe::Probe& P, rigid::Body b, const Vec3& r_body, const Vec3& anchor,
              const Vec3& axis_body, const Vec3& axis, double h, double beta) {
  P.call("apply_revolute"), rbprobe::body_in(P, b), P.in("r_body", r_body);
  P.in("anchor", anchor), P.in("axis_body", axis_body), P.in("axis", axis), P.in("h", h);
  P.in("beta", beta);
  const RevoluteImpulse J = apply_revolute(b, r_body, anchor, axis_body, axis, h, beta);
  P.group("the body"), P.out("returned.P", J.P), P.out("returned.M", J.M);
  P.group("");
  rbprobe::body_out(P, b);
}
const Vec3 kR(0.5, -0.25, 0.75);  // the pinned point, body frame
// The anchor where the pinned point is: no drift.
Vec3 pinned(const rigid::Body& b) { return b.x + b.q.toRotationMatrix() * kR; }
// apply_hinge and apply_revolute on copies of b0 (h = 0.05, beta = 0.2), every output in one
// group: the "turned" and "drift" probes differ only in the anchor and the axis.
void hinge_then_revolute(wbprobe::Probe& P, const rigid::Body& b0, const Vec3& anchor,
                         const Vec3& axis_body, const Vec3& axis) {
  P.call("apply_hinge, apply_revolute"), rbprobe::body_in(P, b0), P.in("r_body", kR);
  P.in("anchor", anchor), P.in("axis_body", axis_body), P.in("axis", axis), P.in("h", 0.05);
  P.in("beta", 0.2);
  rigid::Body b1 = b0, b2 = b0;
  const Vec3 Ph = apply_hinge(b1, kR, anchor, 0.05, 0.2);
  const RevoluteImpulse J = apply_revolute(b2, kR, anchor, axis_body, axis, 0.05, 0.2);
  P.group("everything");
  P.out("apply_hinge: returned", Ph), P.out("apply_hinge: b.v", b1.v);
  P.out("apply_hinge: b.omega", b1.omega), P.out("apply_revolute: returned.P", J.P);
  P.out("apply_revolute: returned.M", J.M), P.out("apply_revolute: b.v", b2.v);
  P.out("apply_revolute: b.omega", b2.omega);
}
}  // namespace

WB_PROBE("R7", "ball-simple",
         "apply_hinge: a unit body at rest at the origin pinned at (1, 0, 0), moving down") {
  P.simple();
  rigid::Body b;
  b.v = Vec3(0, -1, 0);
  hinge(P, b, Vec3(1, 0, 0), Vec3(1, 0, 0), 0.1, 0.2);
}
WB_PROBE("R7", "ball", "apply_hinge: a turned, spinning body pinned where it is (no drift)") {
  P.simple();
  const rigid::Body b = rbprobe::body();
  hinge(P, b, kR, pinned(b), 0.05, 0.2);
}
WB_PROBE("R7", "ball-drift",
         "apply_hinge: the same body, the anchor 0.1 away from the pinned point") {
  P.simple();
  const rigid::Body b = rbprobe::body();
  hinge(P, b, kR, pinned(b) + Vec3(0.06, -0.08, 0), 0.05, 0.2);
}
WB_PROBE("R7", "revolute",
         "apply_revolute: a turned, spinning body, its axis along the hinge, no drift") {
  P.simple();
  const rigid::Body b = rbprobe::body();
  const Vec3 axis_body(0, 0, 1);
  const Vec3 axis = b.q.toRotationMatrix() * axis_body;
  revolute(P, b, kR, pinned(b), axis_body, axis, 0.05, 0.2);
}
WB_PROBE("R7", "revolute-drift",
         "apply_revolute: the body's axis 0.1 rad off the hinge axis, the anchor off too") {
  P.simple();
  const rigid::Body b = rbprobe::body();
  const Vec3 axis_body(0, 0, 1);
  const Vec3 axis = rbprobe::turn(0.1, Vec3(1, 0, 0)) * (b.q.toRotationMatrix() * axis_body);
  revolute(P, b, kR, pinned(b) + Vec3(0.06, -0.08, 0), axis_body, axis.normalized(), 0.05, 0.2);
}
// The parts, one probe each. Not turned (q = 1), without drift: a frame mistake (body or world)
// is right here, a mistake in the impulse (the effective mass, the torque, the angular rows)
// is not. Each function alone, its outputs apart: a wrong torque changes only b.omega, a
// wrong effective mass the impulse and everything after it; apply_revolute's angular impulse
// and b.omega together (a mistake in the angular rows changes one or both).
WB_PROBE("R7", "ball-unturned",
         "apply_hinge: the body not turned (q = 1), spinning, pinned where it is") {
  rigid::Body b = rbprobe::body();
  b.q = Eigen::Quaterniond::Identity();
  const Vec3 anchor = pinned(b);
  P.call("apply_hinge"), rbprobe::body_in(P, b), P.in("r_body", kR), P.in("anchor", anchor);
  P.in("h", 0.05), P.in("beta", 0.2);
  const Vec3 Pimp = apply_hinge(b, kR, anchor, 0.05, 0.2);
  P.out("returned", Pimp), P.out("b.v", b.v), P.out("b.omega", b.omega);
  P.group("the other fields"), P.out("b.x", b.x), P.out("b.q", b.q), P.out("b.f", b.f);
  P.out("b.tau", b.tau), P.group("");
}
WB_PROBE("R7", "revolute-unturned",
         "apply_revolute: the body not turned (q = 1), spinning, its axis along the hinge, no "
         "drift") {
  rigid::Body b = rbprobe::body();
  b.q = Eigen::Quaterniond::Identity();
  const Vec3 axis_body(0, 0, 1);
  const Vec3 anchor = pinned(b);
  P.call("apply_revolute"), rbprobe::body_in(P, b), P.in("r_body", kR), P.in("anchor", anchor);
  P.in("axis_body", axis_body), P.in("axis", axis_body), P.in("h", 0.05), P.in("beta", 0.2);
  const RevoluteImpulse J = apply_revolute(b, kR, anchor, axis_body, axis_body, 0.05, 0.2);
  P.out("returned.P", J.P), P.out("b.v", b.v);
  P.group("the angular part"), P.out("returned.M", J.M), P.out("b.omega", b.omega);
  P.group("the other fields"), P.out("b.x", b.x), P.out("b.q", b.q), P.out("b.f", b.f);
  P.out("b.tau", b.tau), P.group("");
}
// Turned, without drift, both functions, in one group: what goes wrong here and not above is a
// frame (a vector of the body frame used as a world one), in either function.
WB_PROBE("R7", "turned",
         "apply_hinge, then apply_revolute: the body turned away from the world frame, pinned "
         "where it is, its axis along the hinge") {
  const rigid::Body b0 = rbprobe::body();
  const Vec3 axis_body(0, 0, 1);
  const Vec3 axis = b0.q.toRotationMatrix() * axis_body;
  const Vec3 anchor = pinned(b0);
  hinge_then_revolute(P, b0, anchor, axis_body, axis);
}
// The drift correction, in one group: apply_hinge with the anchor off, apply_revolute with the
// anchor and the axis off.
WB_PROBE("R7", "drift",
         "apply_hinge with the anchor 0.1 off, then apply_revolute with the axis 0.1 rad off as "
         "well") {
  const rigid::Body b0 = rbprobe::body();
  const Vec3 axis_body(0, 0, 1);
  const Vec3 axis =
      (rbprobe::turn(0.1, Vec3(1, 0, 0)) * (b0.q.toRotationMatrix() * axis_body)).normalized();
  const Vec3 anchor = pinned(b0) + Vec3(0.06, -0.08, 0);
  hinge_then_revolute(P, b0, anchor, axis_body, axis);
}

}  // namespace probe_R7_hinge
