// Diagnosis probes of R6 (tests/common/wb_probe.h): prepare_contact of a corner of a turned,
// spinning body (above and below the threshold, leaving), warm_start_contact, one
// solve_contact from a closing contact, from stored totals to take back, with friction at its
// bound and within it, and solve_plane_contacts with stored totals and from nothing.
#include <vector>

#include "plane_contact.h"
#include "rigid_probes.h"

// The lab's probe files compile as one unit (cmake/labs.cmake): each keeps its helpers in a
// namespace of its own.
namespace probe_R6_plane_contact {

using rbprobe::Mat3;
using rbprobe::Vec3;

namespace {
const Vec3 kN(0, 1, 0);
void contact_in(wbprobe::Probe& P, const Contact& c) {
  P.in("c.p", c.p), P.in("c.Pn", c.Pn), P.in("c.Pt", c.Pt), P.in("c.r", c.r), P.in("c.K", c.K);
  P.in("c.mass_n", c.mass_n), P.in("c.bias", c.bias);
}
// With bias_apart (prepare_contact's probes), the restitution target is an output of its own:
// a mistake in when the contact bounces is not taken for one of the effective mass.
void contact_out(wbprobe::Probe& P, const Contact& c, bool bias_apart = false) {
  P.group("the contact");
  P.out("c.Pn", c.Pn), P.out("c.Pt", c.Pt), P.out("c.r", c.r), P.out("c.K", c.K);
  P.out("c.mass_n", c.mass_n);
  if (!bias_apart) P.out("c.bias", c.bias);
  P.group("");
  if (bias_apart) P.out("c.bias", c.bias);
}
// A body falling onto the floor y = 0, a corner of it touching at p.
rigid::Body falling() {
  rigid::Body b = rbprobe::body();
  b.x = Vec3(0.5, 0.6, -0.25), b.v = Vec3(0.8, -2.0, 0.3), b.f.setZero(), b.tau.setZero();
  return b;
}
Contact corner(double Pn, const Vec3& Pt) {
  Contact c;
  c.p = Vec3(0.2, 0, 0.1), c.Pn = Pn, c.Pt = Pt;
  return c;
}
// A prepared contact, its r, K and mass_n from the formulas of plane_contact.h (inputs of
// warm_start_contact and solve_contact: computed here, so that a mistake in prepare_contact
// does not show in the probes of the others), its bias given.
Contact prepared(const rigid::Body& b, double bias, Contact c) {
  const Mat3 R = b.q.toRotationMatrix();
  const Mat3 I_inv = R * b.I_body.diagonal().cwiseInverse().asDiagonal() * R.transpose();
  c.r = c.p - b.x;
  c.K = Mat3::Identity() / b.m - rigid::skew(c.r) * I_inv * rigid::skew(c.r);
  c.mass_n = 1.0 / kN.dot(c.K * kN);
  c.bias = bias;
  return c;
}
void prepare(wbprobe::Probe& P, const rigid::Body& b, double e, double threshold, Contact c) {
  P.call("prepare_contact"), rbprobe::body_in(P, b), P.in("n", kN), P.in("e", e);
  P.in("threshold", threshold), contact_in(P, c);
  prepare_contact(b, kN, e, threshold, c);
  contact_out(P, c, true);
}
void solve(wbprobe::Probe& P, rigid::Body b, Contact c, double mu) {
  P.call("solve_contact"), rbprobe::body_in(P, b), contact_in(P, c), P.in("n", kN);
  P.in("mu", mu);
  const double dPn = solve_contact(b, c, kN, mu);
  P.out("returned", dPn), contact_out(P, c), rbprobe::body_out(P, b);
}
}  // namespace

WB_PROBE("R6", "prepare-cube",
         "prepare_contact: a unit cube of mass 1 falling flat at 2 m/s, its corner on the floor, "
         "e = 0.5") {
  P.simple();
  rigid::Body b;
  b.I_body = Vec3(1.0 / 6, 1.0 / 6, 1.0 / 6).asDiagonal();
  b.x = Vec3(0, 0.5, 0), b.v = Vec3(0, -2, 0);
  Contact c;
  c.p = Vec3(0.5, 0, 0.5);
  prepare(P, b, 0.5, 0.1, c);
}
// The effective mass and the restitution target.
WB_PROBE("R6", "prepare",
         "prepare_contact: a turned, spinning body falling at 2 m/s onto the floor, e = 0.6, "
         "threshold 1") {
  prepare(P, falling(), 0.6, 1.0, corner(0.7, Vec3(0.1, 0, -0.05)));
}
WB_PROBE("R6", "prepare-slow",
         "prepare_contact: the same body, threshold 5 (above its approach speed): no bounce") {
  P.simple();
  prepare(P, falling(), 0.6, 5.0, corner(0.7, Vec3(0.1, 0, -0.05)));
}
WB_PROBE(
    "R6", "prepare-leaving",
    "prepare_contact: the same body leaving the floor at 0.5 m/s, not spinning, threshold 1") {
  P.simple();
  rigid::Body b = falling();
  b.v = Vec3(0.8, 0.5, 0.3), b.omega.setZero();
  prepare(P, b, 0.6, 1.0, corner(0.7, Vec3(0.1, 0, -0.05)));
}
// The restitution target, its three cases in one output: approaching faster than the threshold
// (a bounce), slower (resting), leaving. A mistake in which case applies shows here and in no
// effective mass.
WB_PROBE("R6", "prepare-targets",
         "prepare_contact: the body not spinning, its point approaching at 2 m/s, at 0.5 m/s, "
         "leaving at 0.5 m/s; e = 0.6, threshold 1") {
  rigid::Body b = falling();
  b.omega.setZero();
  P.call("prepare_contact (3 times)"), rbprobe::body_in(P, b), P.in("n", kN), P.in("e", 0.6);
  P.in("threshold", 1.0);
  const Vec3 vy(-2.0, -0.5, 0.5);
  P.in("b.v.y (each call)", vy);
  Vec3 bias = Vec3::Zero();
  for (int i = 0; i < 3; ++i) {
    b.v.y() = vy(i);
    Contact c = corner(0.7, Vec3(0.1, 0, -0.05));
    prepare_contact(b, kN, 0.6, 1.0, c);
    bias(i) = c.bias;
  }
  P.out("c.bias (each call)", bias);
}
// Warm starting.
WB_PROBE("R6", "warm-start", "warm_start_contact: stored totals Pn = 0.7, Pt = (0.1, 0, -0.05)") {
  P.simple();
  rigid::Body b = falling();
  const Contact c = prepared(b, 1.2, corner(0.7, Vec3(0.1, 0, -0.05)));
  P.call("warm_start_contact"), rbprobe::body_in(P, b), contact_in(P, c), P.in("n", kN);
  warm_start_contact(b, c, kN);
  rbprobe::body_out(P, b);
}
// One iteration.
// mu = 0.1: the friction reaches its bound (any impulse along the sliding gives the same).
WB_PROBE("R6", "solve-closing", "solve_contact: closing, nothing stored, mu = 0.1") {
  const rigid::Body b = falling();
  solve(P, b, prepared(b, 1.2, corner(0, Vec3::Zero())), 0.1);
}
WB_PROBE("R6", "solve-take-back",
         "solve_contact: separating slowly with Pn = 0.5 stored: partly taken back") {
  rigid::Body b = falling();
  b.v = Vec3(0, 0.2, 0), b.omega.setZero();
  solve(P, b, prepared(b, 0, corner(0.5, Vec3::Zero())), 0);
}
// The point right below the centre: the normal impulse does not change the sliding, the
// friction impulse not the normal velocity; the order of the two steps shows only through the
// bound. Sliding fast along x with friction stored against it: the friction ends on its bound
// mu Pn (the new total), whatever impulse along the sliding took it there.
WB_PROBE("R6", "solve-friction",
         "solve_contact: the point right below the centre sliding at 3 m/s along x, approaching "
         "at 0.1 m/s, Pn = 0.5 and Pt = (-0.1, 0, 0) stored, mu = 0.2") {
  rigid::Body b = falling();
  b.v = Vec3(3.0, -0.1, 0.0), b.omega.setZero();
  Contact c = corner(0.5, Vec3(-0.1, 0, 0));
  c.p = Vec3(b.x.x(), 0, b.x.z());
  solve(P, b, prepared(b, 0, c), 0.2);
}
// The same point sliding fast along a diagonal of the plane, nothing stored: the friction ends
// on its bound, the disc of radius mu Pn, against the sliding; the normal velocity after the
// normal step is 0 (no target), so a sliding that keeps a normal part is right here and a bound
// taken on each component (a square, not the disc) is not.
WB_PROBE("R6", "solve-friction-diagonal",
         "solve_contact: the point right below the centre sliding at (2, 0, -1.5) m/s, "
         "approaching at 0.1 m/s, Pn = 0.5 stored, mu = 0.2") {
  rigid::Body b = falling();
  b.v = Vec3(2.0, -0.1, -1.5), b.omega.setZero();
  Contact c = corner(0.5, Vec3::Zero());
  c.p = Vec3(b.x.x(), 0, b.x.z());
  solve(P, b, prepared(b, 0, c), 0.2);
}
// The same point sliding slowly: the friction stops the sliding within its bound. A detail: a
// wrong mass along the sliding and a bound applied when it should not be both show here alone.
WB_PROBE("R6", "solve-sticking",
         "solve_contact: the point right below the centre sliding slowly (0.2, 0, 0.1) m/s, "
         "approaching at 0.5 m/s, Pn = 1 stored, mu = 0.8") {
  P.simple();
  rigid::Body b = falling();
  b.v = Vec3(0.2, -0.5, 0.1), b.omega.setZero();
  Contact c = corner(1.0, Vec3::Zero());
  c.p = Vec3(b.x.x(), 0, b.x.z());
  solve(P, b, prepared(b, 0, c), 0.8);
}
// The whole solver on two corners.
WB_PROBE("R6", "solve-plane",
         "solve_plane_contacts: two corners, stored totals, e = 0.6, mu = 0.5, 8 iterations") {
  rigid::Body b = falling();
  std::vector<Contact> cs = {corner(0.3, Vec3(0.05, 0, 0)), corner(0.2, Vec3::Zero())};
  cs[1].p = Vec3(0.9, 0, -0.6);
  P.call("solve_plane_contacts"), rbprobe::body_in(P, b), P.in("n", kN), P.in("e", 0.6);
  P.in("threshold", 1.0), P.in("mu", 0.5), P.in("iterations", 8);
  P.in("contacts[0].p", cs[0].p), P.in("contacts[0].Pn", cs[0].Pn),
      P.in("contacts[0].Pt", cs[0].Pt);
  P.in("contacts[1].p", cs[1].p), P.in("contacts[1].Pn", cs[1].Pn),
      P.in("contacts[1].Pt", cs[1].Pt);
  const double total = solve_plane_contacts(b, cs, kN, 0.6, 1.0, 0.5, 8);
  P.out("returned", total), rbprobe::body_out(P, b);
  if (cs.size() == 2) P.out("contacts[0].Pn", cs[0].Pn), P.out("contacts[1].Pn", cs[1].Pn);
}
// Nothing stored and one pass: the warm start does nothing here, every pass counts.
WB_PROBE("R6", "solve-plane-once",
         "solve_plane_contacts: two corners, nothing stored, e = 0.6, mu = 0.5, 1 iteration") {
  rigid::Body b = falling();
  std::vector<Contact> cs = {corner(0, Vec3::Zero()), corner(0, Vec3::Zero())};
  cs[1].p = Vec3(0.9, 0, -0.6);
  P.call("solve_plane_contacts"), rbprobe::body_in(P, b), P.in("n", kN), P.in("e", 0.6);
  P.in("threshold", 1.0), P.in("mu", 0.5), P.in("iterations", 1);
  P.in("contacts[0].p", cs[0].p), P.in("contacts[1].p", cs[1].p);
  const double total = solve_plane_contacts(b, cs, kN, 0.6, 1.0, 0.5, 1);
  P.group("everything");  // what one pass gives, in turn: one contact's Pn may stay 0
  P.out("returned", total), P.out("b.x", b.x), P.out("b.v", b.v), P.out("b.q", b.q);
  P.out("b.omega", b.omega), P.out("b.f", b.f), P.out("b.tau", b.tau);
  if (cs.size() == 2) P.out("contacts[0].Pn", cs[0].Pn), P.out("contacts[1].Pn", cs[1].Pn);
}

}  // namespace probe_R6_plane_contact
