// Diagnosis probes of R6 (tests/common/wb_probe.h): prepare_contact of a corner of a turned,
// spinning body (above and below the threshold), warm_start_contact, one solve_contact from a
// closing contact, from stored totals to take back, with friction on stored totals, and
// solve_plane_contacts.
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
  prepare(P, falling(), 0.6, 5.0, corner(0.7, Vec3(0.1, 0, -0.05)));
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
WB_PROBE("R6", "solve-closing", "solve_contact: closing, nothing stored, mu = 0.5") {
  const rigid::Body b = falling();
  solve(P, b, prepared(b, 1.2, corner(0, Vec3::Zero())), 0.5);
}
WB_PROBE("R6", "solve-take-back",
         "solve_contact: separating slowly with Pn = 0.5 stored: partly taken back") {
  rigid::Body b = falling();
  b.v = Vec3(0, 0.2, 0), b.omega.setZero();
  solve(P, b, prepared(b, 0, corner(0.5, Vec3::Zero())), 0);
}
WB_PROBE("R6", "solve-friction",
         "solve_contact: sliding fast with Pn = 0.5 and Pt = (0.1, 0, -0.05) stored, mu = 0.4") {
  rigid::Body b = falling();
  b.v = Vec3(3.0, -0.1, 1.0);
  solve(P, b, prepared(b, 0, corner(0.5, Vec3(0.1, 0, -0.05))), 0.4);
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

}  // namespace probe_R6_plane_contact
