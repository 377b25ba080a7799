// Diagnosis probes of C5 (tests/common/wb_probe.h): prepare_contact (a pair and a plane, above
// and below the threshold), warm_start_contact, and solve_contact: once from a closing contact,
// from stored totals that must be taken back and with friction within its bound; twice on one
// contact (the normal total added to, then partly taken back) with friction at its bound.
#include "contact_solver.h"
#include "wb_probe.h"

// The lab's probe files compile as one unit (cmake/labs.cmake): each keeps its helpers in a
// namespace of its own.
namespace probe_C5_contact_solver {

using wbprobe::cols;
using wbprobe::vec;

namespace {
using wb::Vec2;
void contact_in(wbprobe::Probe& P, const Contact& c) {
  P.in("c.a", c.a), P.in("c.b", c.b), P.in("c.n", c.n), P.in("c.mu", c.mu), P.in("c.Pn", c.Pn);
  P.in("c.Pt", c.Pt), P.in("c.mass_n", c.mass_n), P.in("c.bias", c.bias);
}
void contact_out(wbprobe::Probe& P, const Contact& c) {
  P.out("c.Pn", c.Pn), P.out("c.Pt", c.Pt), P.out("c.mass_n", c.mass_n), P.out("c.bias", c.bias);
}
Contact contact(int a, int b, Vec2 n, double mu, double Pn, double Pt, double mass_n,
                double bias) {
  Contact c;
  c.a = a, c.b = b, c.n = n, c.mu = mu, c.Pn = Pn, c.Pt = Pt, c.mass_n = mass_n, c.bias = bias;
  return c;
}
void prepare(wbprobe::Probe& P, const wb::VecX& w, const wb::Mat2X& v, double e, double threshold,
             Contact c) {
  P.call("prepare_contact");
  P.in("w", w), P.in("v", v), P.in("e", e), P.in("threshold", threshold), contact_in(P, c);
  prepare_contact(w, v, e, threshold, c);
  contact_out(P, c);
}
void warm(wbprobe::Probe& P, const wb::VecX& w, const Contact& c, wb::Mat2X v) {
  P.call("warm_start_contact");
  P.in("w", w), contact_in(P, c), P.in("v", v);
  warm_start_contact(w, c, v);
  P.out("v", v);
}
// What solve_contact returned and left. The normal step's outputs apart from the friction's: a
// mistake in the friction bound never changes the normal total (the friction acts along the
// tangent), one in the accumulated normal total changes both (the bound follows the total).
void solve_out(wbprobe::Probe& P, const char* returned, double dPn, const Contact& c,
               const wb::Mat2X& v) {
  P.group("the normal total");
  P.out(returned, dPn), P.out("c.Pn", c.Pn);
  P.group("the friction total and v");
  P.out("c.Pt", c.Pt), P.out("v", v);
  P.group("the normal total");
  P.out("c.mass_n", c.mass_n), P.out("c.bias", c.bias);
  P.group("");
}
void solve(wbprobe::Probe& P, const wb::VecX& w, Contact c, wb::Mat2X v) {
  P.call("solve_contact");
  P.in("w", w), contact_in(P, c), P.in("v", v);
  const double dPn = solve_contact(w, c, v);
  solve_out(P, "returned", dPn, c, v);
}
// Two iterations on one contact, the velocities changed between them by `push` on particle 0
// (what another contact would do): what the second leaves.
void solve_twice(wbprobe::Probe& P, const wb::VecX& w, Contact c, wb::Mat2X v, const Vec2& push) {
  P.call("solve_contact (2 times)");
  P.in("w", w), contact_in(P, c), P.in("v", v), P.in("dv of particle 0 between the calls", push);
  solve_contact(w, c, v);
  if (v.cols() > 0) v.col(0) += push;
  const double dPn = solve_contact(w, c, v);
  solve_out(P, "returned (2nd call)", dPn, c, v);
}
const Vec2 kN(0.6, 0.8);
const wb::VecX kW = vec({2.0 / 3, 2.0});  // masses 1.5 and 0.5
// Particle 0 above particle 1 along kN, closing at 1.5 m/s, sliding along perp(kN).
const wb::Mat2X kV = cols({{-0.9, -1.2}, {0.3, 0.4}});
}  // namespace

WB_PROBE("C5", "prepare-floor",
         "prepare_contact: a particle of mass 1 hitting a floor at 2 m/s, e = 0.5") {
  P.simple();
  prepare(P, vec({1}), cols({{0, -2}}), 0.5, 0.1, contact(0, -1, Vec2(0, 1), 0, 0, 0, 0, 0));
}
// The effective mass and the restitution target.
WB_PROBE(
    "C5", "prepare-pair",
    "prepare_contact: a pair of masses 1.5 and 0.5 closing at 1.5 m/s, e = 0.6, threshold 1") {
  prepare(P, kW, kV, 0.6, 1.0, contact(0, 1, kN, 0.4, 0.7, 0.1, 0, 0));
}
WB_PROBE("C5", "prepare-plane",
         "prepare_contact: particle 1 (mass 0.5) on a plane, closing at 1.5 m/s, e = 0.6") {
  prepare(P, kW, cols({{0, 0}, {-0.9, -1.2}}), 0.6, 1.0, contact(1, -1, kN, 0.4, 0.7, 0.1, 0, 0));
}
WB_PROBE("C5", "prepare-slow",
         "prepare_contact: the pair closing at 1.5 m/s, below the threshold 2: no bounce") {
  P.simple();
  prepare(P, kW, kV, 0.6, 2.0, contact(0, 1, kN, 0.4, 0.7, 0.1, 0, 0));
}
WB_PROBE("C5", "prepare-leaving",
         "prepare_contact: the pair separating at 0.5 m/s, threshold 1: no push back") {
  P.simple();
  prepare(P, kW, cols({{0.3, 0.4}, {0, 0}}), 0.6, 1.0, contact(0, 1, kN, 0.4, 0.7, 0.1, 0, 0));
}
// The restitution target, its three cases in one output: closing faster than the threshold (a
// bounce), slower (resting), separating. A mistake in which case applies shows here and in no
// effective mass.
WB_PROBE(
    "C5", "prepare-targets",
    "prepare_contact: the pair closing at 1.5 m/s, closing at 0.5 m/s, separating at 0.5 m/s; "
    "e = 0.6, threshold 1") {
  P.call("prepare_contact (3 times)");
  const double un[3] = {-1.5, -0.5, 0.5};
  Eigen::Vector3d bias = Eigen::Vector3d::Zero();
  wb::Mat2X v = kV;
  for (int i = 0; i < 3; ++i) {
    v.col(0) = un[i] * kN, v.col(1).setZero();
    if (i == 0) P.in("w", kW), P.in("e", 0.6), P.in("threshold", 1.0);
    P.in(i == 0 ? "v (1st call)" : i == 1 ? "v (2nd call)" : "v (3rd call)", v);
    Contact c = contact(0, 1, kN, 0.4, 0.7, 0.1, 0, 0);
    prepare_contact(kW, v, 0.6, 1.0, c);
    bias(i) = c.bias;
  }
  P.out("c.bias (each call)", bias);
}
// Warm starting: the stored totals applied again.
WB_PROBE("C5", "warm-start",
         "warm_start_contact: the pair with stored totals Pn = 0.7, Pt = 0.1") {
  warm(P, kW, contact(0, 1, kN, 0.4, 0.7, 0.1, 0.375, 0.9), kV);
}
// One iteration from a closing contact with nothing stored.
WB_PROBE("C5", "solve-closing",
         "solve_contact: the pair closing at 1.5 m/s, nothing stored, mu = 0.4") {
  solve(P, kW, contact(0, 1, kN, 0.4, 0, 0, 0.375, 0.9), kV);
}
// Stored totals larger than needed: the total is taken back, and stays >= 0. A detail: the
// friction probe below takes a total partly back.
WB_PROBE("C5", "solve-take-back",
         "solve_contact: the pair separating at 0.5 m/s with Pn = 0.3 stored") {
  P.simple();
  solve(P, kW, contact(0, 1, kN, 0, 0.3, 0, 0.375, 0), cols({{0.2, 0.2}, {-0.1, -0.2}}));
}
// Friction on stored totals: the bound is mu times the normal total of this iteration, on the
// friction total; the sliding fast along +perp(n), so that the friction total is negative and
// at its bound (any mass along the sliding gives the same total). Two iterations on one
// contact: the pair closing at 0.2 m/s adds to the stored normal total (0.5 to 0.575), then
// particle 0 is pushed apart (as another contact would) and the total is partly taken back (to
// 0.425). Every mistake of the accumulated total then shows in the normal total as a wrong
// value (a total never taken back, one that forgot what was stored), and every mistake of the
// bound in the friction total (the bound follows the total, call after call).
WB_PROBE("C5", "solve-friction",
         "solve_contact twice: the pair closing at 0.2 m/s and sliding fast with Pn = 0.5 and "
         "Pt = -0.15 stored, mu = 0.4; then particle 0 pushed apart at 0.4 m/s") {
  const Contact c = contact(0, 1, kN, 0.4, 0.5, -0.15, 0.375, 0);
  const wb::Mat2X v = cols({{-1.82, 1.74}, {0.3, 0.4}});
  const Vec2 push = 0.4 * kN;
  solve_twice(P, kW, c, v, push);
}
// Sliding slowly: the friction stops the sliding within its bound. A detail: a wrong mass
// along the sliding and a bound applied when it should not be both show here alone.
WB_PROBE("C5", "solve-sticking",
         "solve_contact: the pair closing at 1 m/s and sliding at 0.2 m/s, Pn = 1 stored, "
         "mu = 1") {
  P.simple();
  solve(P, kW, contact(0, 1, kN, 1.0, 1.0, 0, 0.375, 0), cols({{-0.44, -0.92}, {0, 0}}));
}

}  // namespace probe_C5_contact_solver
