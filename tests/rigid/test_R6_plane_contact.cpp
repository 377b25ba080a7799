// Graded tests for TODO(R6), contact with a plane by accumulated, warm-started
// impulses (labs/rigid/plane_contact.cpp). Expected values: the velocity change of a
// point per unit impulse (the test's own K), Newton's restitution law above the
// threshold, the totals' bounds (Pn >= 0, |Pt| <= mu Pn) and what they imply
// (an impulse taken back when a contact is over-pushed), Coulomb's sliding
// acceleration g (sin - mu cos) on a slope, rest on a floor to rounding.
#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>
#include <vector>

#include "params.h"
#include "plane_contact.h"
#include "rigid_test_helpers.h"

// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace test_R6_plane_contact {

using namespace rigidtest;

namespace {

// One impulse or one 3x3 product: a few operations on numbers ~0.1-10.
constexpr double kImpulseTol = 1e-12;
constexpr double kG = 9.81;

const Vec3 kUp(0, 0, 1);

Vec3 point_velocity(const Body& b, const Vec3& p) { return b.v + b.omega.cross(p - b.x); }

// The test's own impulse: J at the world point p.
void impulse_at(Body& b, const Vec3& p, const Vec3& J) {
  b.v += J / b.m;
  b.omega += inverse_inertia(b) * (p - b.x).cross(J);
}

// A tilted, spinning box and its lowest corner p, approaching the floor.
Body tilted_box(Vec3& p) {
  Body b = make_body(3.0, Vec3(0.5, 1.25, 1.5), quat(0.9, 0.25, -0.3, 0.1), Vec3(0.7, -1.2, 0.4),
                     Vec3(0.2, -0.1, 1.0), Vec3(0.5, 0.25, -2.0));
  p = b.x + rot(b) * Vec3(-0.5, 0.5, -0.5);
  return b;
}

// The 8 corners of a box of full edges `size`, world frame.
std::vector<Vec3> corners(const Body& b, const Vec3& size) {
  std::vector<Vec3> c;
  for (int k = 0; k < 8; ++k) {
    const Vec3 s(k & 1 ? 0.5 : -0.5, k & 2 ? 0.5 : -0.5, k & 4 ? 0.5 : -0.5);
    c.push_back(b.x + rot(b) * s.cwiseProduct(size));
  }
  return c;
}

Contact contact_at(const Vec3& p, double Pn = 0, const Vec3& Pt = Vec3::Zero()) {
  Contact c;
  c.p = p;
  c.Pn = Pn;
  c.Pt = Pt;
  return c;
}

namespace heldout_R6 {
// The header's contact solver, written by the test (plane_contact.h).
struct Ref {
  Vec3 p, r;
  Mat3 K;
  double mass_n = 0, bias = 0, Pn = 0;
  Vec3 Pt = Vec3::Zero();
};
Mat3 contact_K(const Body& b, const Vec3& r) {
  const Mat3 R = rot(b);
  const Mat3 Iinv = R * b.I_body.diagonal().cwiseInverse().asDiagonal() * R.transpose();
  return Mat3::Identity() / b.m - rigid::skew(r) * Iinv * rigid::skew(r);
}
void apply(Body& b, const Vec3& r, const Vec3& J) {
  const Mat3 R = rot(b);
  const Mat3 Iinv = R * b.I_body.diagonal().cwiseInverse().asDiagonal() * R.transpose();
  b.v += J / b.m;
  b.omega += Iinv * r.cross(J);
}
void prepare(const Body& b, const Vec3& n, double e, double threshold, Ref& c) {
  c.r = c.p - b.x;
  c.K = contact_K(b, c.r);
  c.mass_n = 1 / n.dot(c.K * n);
  const double un = (b.v + b.omega.cross(c.r)).dot(n);
  c.bias = un > 0 ? -un : (-un > threshold ? -e * un : 0.0);  // leaving: aim at -un
}
double solve(Body& b, Ref& c, const Vec3& n, double mu) {
  const double un = (b.v + b.omega.cross(c.r)).dot(n);
  const double Pn1 = std::max(c.Pn + c.mass_n * (c.bias - un), 0.0), added = Pn1 - c.Pn;
  apply(b, c.r, added * n);
  c.Pn = Pn1;
  const Vec3 u = b.v + b.omega.cross(c.r), ut = u - u.dot(n) * n;
  if (ut.norm() > 0) {
    const Vec3 d = ut / ut.norm();
    Vec3 Pt1 = c.Pt - ut.norm() / d.dot(c.K * d) * d;
    if (Pt1.norm() > mu * c.Pn) Pt1 *= mu * c.Pn / Pt1.norm();
    apply(b, c.r, Pt1 - c.Pt);
    c.Pt = Pt1;
  }
  return added;
}

// solve_plane_contacts of the header on the contacts `refs` (p, Pn, Pt set): prepare each,
// warm start each, `iterations` passes of solve in order; returns the sum of the Pn.
double solve_all(Body& b, std::vector<Ref>& refs, const Vec3& n, double e, double threshold,
                 double mu, int iterations) {
  for (auto& r : refs) prepare(b, n, e, threshold, r);
  for (auto& r : refs) apply(b, r.p - b.x, r.Pn * n + r.Pt);
  for (int it = 0; it < iterations; ++it)
    for (auto& r : refs) solve(b, r, n, mu);
  double total = 0;
  for (const auto& r : refs) total += r.Pn;
  return total;
}

// The lab's solve_plane_contacts on `cs`, checked against solve_all from the same inputs (the
// vector that comes back is hostile: its size is checked before it is indexed).
double check_all(Body& b, std::vector<Contact>& cs, const Vec3& n, double e, double threshold,
                 double mu, int iterations) {
  const Body b0 = b;
  std::vector<Ref> refs(cs.size());
  for (std::size_t i = 0; i < cs.size(); ++i) {
    refs[i].p = cs[i].p;
    refs[i].Pn = cs[i].Pn;
    refs[i].Pt = cs[i].Pt;
  }
  Body e_b = b0;
  const double want = solve_all(e_b, refs, n, e, threshold, mu, iterations);
  INFO(refs.size() << " contacts, n = " << str(n) << ", e = " << e
                   << ", threshold = " << threshold << ", mu = " << mu << ", " << iterations
                   << " iterations; body m = " << b0.m << ", x = " << str(b0.x)
                   << ", v = " << str(b0.v) << ", omega = " << str(b0.omega));
  const double total = solve_plane_contacts(b, cs, n, e, threshold, mu, iterations);
  {
    INFO("solve_plane_contacts returned " << cs.size() << " contacts, expected " << refs.size()
                                          << " (it updates their totals, it never adds or "
                                             "drops one)");
    REQUIRE(cs.size() == refs.size());
  }
  wbtest::require_near(total, want, 1e-11, "solve_plane_contacts returns the sum of the Pn",
                       1e-10);
  for (std::size_t i = 0; i < refs.size(); ++i) {
    INFO("contact " << i);
    wbtest::require_near(cs[i].Pn, refs[i].Pn, 1e-11, "its Pn total", 1e-10);
    rigidtest::require_near(cs[i].Pt, refs[i].Pt, 1e-11, "its Pt total", 1e-10);
  }
  rigidtest::require_body(b, e_b, 1e-10, "the body after prepare, warm start and the passes");
  return total;
}
}  // namespace heldout_R6

// A box of edges `size` (mass m) resting flat on a plane of normal n through the
// origin, its body z along n; its four lower corners are the contacts.
Body box_on_plane(double m, const Vec3& size, const Vec3& n, const Eigen::Quaterniond& spin) {
  const Eigen::Quaterniond q = rotation_from_to(kUp, n) * spin;
  const Vec3 I(m / 12 * (size.y() * size.y() + size.z() * size.z()),
               m / 12 * (size.x() * size.x() + size.z() * size.z()),
               m / 12 * (size.x() * size.x() + size.y() * size.y()));
  return make_body(m, I, q, Vec3::Zero(), 0.5 * size.z() * n);
}

// Steps a box on a plane: gravity, the student's solve_plane_contacts on the four
// lower corners with their totals kept from step to step, the reference position
// update. Returns the sum of the normal totals of the last step. `how`: the lab's solver
// (public), the lab's solver checked call by call against the header's (held-out), or the
// header's written here (held-out: the steps before the checked ones).
enum class Solver { lab, checked, reference };
double run_on_plane(Body& b, const Vec3& size, const Vec3& n, double mu, double h, long steps,
                    std::vector<Contact>& kept, Solver how = Solver::lab, int iterations = 10) {
  double total = 0;
  for (long k = 0; k < steps; ++k) {
    b.v += h * Vec3(0, 0, -kG);
    // The four lower corners, from the body the lab's code returned last step: a body of the
    // worker's choosing may have any number of "lower" corners, so they are counted before
    // they are stored (never kept[j++] past its end).
    std::vector<Vec3> lower;
    for (const Vec3& p : corners(b, size)) {
      if (wbtest::finite((p - b.x).dot(n)) < 0) lower.push_back(p);
    }
    {
      INFO("step " << k << ": the box must have 4 corners below its centre along n, got "
                   << lower.size() << " (the body the contacts returned: x = " << str(b.x)
                   << ", q = " << b.q.coeffs().transpose() << ")");
      REQUIRE(lower.size() == 4);
    }
    // Each step hands the contacts in as a caller starts them: the point and the totals kept from
    // the last step, what prepare_contact sets (r, K, mass_n, bias) at zero. Kept instead, the
    // contacts' K would be every call's largest number, the same to the last bit at every step of
    // a run and moved a bit by a drawn friction: it would tell a public call from a held-out one
    // (tools/adversary --inputs). solve_plane_contacts prepares every contact it is given.
    for (std::size_t j = 0; j < 4; ++j) {
      const double Pn = kept[j].Pn;
      const Vec3 Pt = kept[j].Pt;
      kept[j] = contact_at(lower[j], Pn, Pt);
    }
    if (how == Solver::reference) {
      std::vector<heldout_R6::Ref> refs(4);
      for (std::size_t j = 0; j < 4; ++j) {
        refs[j].p = kept[j].p;
        refs[j].Pn = kept[j].Pn;
        refs[j].Pt = kept[j].Pt;
      }
      total = heldout_R6::solve_all(b, refs, n, 0.0, 0.05, mu, iterations);
      for (std::size_t j = 0; j < 4; ++j) {  // the totals kept for the next step
        kept[j].Pn = refs[j].Pn;
        kept[j].Pt = refs[j].Pt;
      }
    } else if (how == Solver::checked) {
      total = heldout_R6::check_all(b, kept, n, 0.0, 0.05, mu, iterations);
    } else {
      total = solve_plane_contacts(b, kept, n, 0.0, 0.05, mu, iterations);
    }
    {  // the vector comes back from the lab's code: its size is checked before it is indexed
      INFO("solve_plane_contacts returned "
           << kept.size()
           << " contacts, it was given 4 (it "
              "updates their totals, it never adds or drops one)");
      REQUIRE(kept.size() == 4);
    }
    // Rounding noise flushed (|v|, |omega| components below kFlush set to 0): a box at rest keeps
    // motions of ~1e-19 whose exact zeros come and go with the run's every bit, so that a public
    // run (its published friction) and a held-out one (a drawn friction) would settle into
    // different patterns of zeros and tell their calls apart (tools/adversary --inputs). The
    // flush is a thousandth of the rest tolerance: a creeping solver leaves far more.
    constexpr double kFlush = 1e-15;
    for (int i = 0; i < 3; ++i) {
      if (std::abs(b.v[i]) < kFlush) b.v[i] = 0;
      if (std::abs(b.omega[i]) < kFlush) b.omega[i] = 0;
    }
    ref_position(b, h);
  }
  return total;
}
double run_on_plane(Body& b, const Vec3& size, const Vec3& n, double mu, double h, long steps) {
  std::vector<Contact> kept(4);
  return run_on_plane(b, size, n, mu, h, steps, kept);
}

// The runs of the public tests below (a box resting on the floor, a box on a slope) are
// functions of their parameters: the public test runs each with the published ones
// (wbtest::Params()), the held-out test with drawn ones in the same format
// (tests/common/params.h: short decimals within half of the published value either side unless
// said). The public runs check laws over thousands of steps; the held-out ones take 80 steps of
// the same run (the runs are nine tenths of the public calls as tools/adversary --inputs samples
// them, and must be of the held-out ones too) after a drawn number taken by the header's solver
// written here, and check every call against it (heldout_R6::check_all). The geometry (the
// boxes, their turn, the slope, their masses) stays as published, and so does the step: the
// largest number of every call of a run is the box's mass (run_on_plane hands the contacts in
// unprepared), the same at every step, and a drawn one would tell the calls apart. The friction
// and the point of the run are drawn.
void resting_box(const wbtest::Params& p) {
  // Four corners on the floor, 10 iterations per step, totals kept between steps.
  // After a few steps each corner carries a quarter of the weight, m g h / 4 per step,
  // and nothing moves. Without accumulated totals or without the warm start the
  // iterations start from zero each step and leave a residual motion (the creep of
  // the one-shot passes, handout) far above this bound.
  constexpr double kRestTol = 1e-12;  // m/s, rad/s: rounding of ~10^3 steps of g h
  const Vec3 size(1.0, 0.6, 0.4);
  const double m = 2.0, h = 1e-3, mu = p.num(0.5, 0.25, 0.75);
  Body b = box_on_plane(m, size, kUp, Eigen::Quaterniond(Eigen::AngleAxisd(0.3, kUp)));
  const Vec3 x0 = b.x;
  std::vector<Contact> kept(4);
  if (p.held_out()) {
    run_on_plane(b, size, kUp, mu, h, p.count(0, 1, 60), kept, Solver::reference);
    run_on_plane(b, size, kUp, mu, h, 80, kept, Solver::checked);
    return;
  }
  const double total = run_on_plane(b, size, kUp, mu, h, 1000, kept);
  require_near(total, m * kG * h, 0.0, "sum of Pn = m g h: the floor holds the weight", 1e-9);
  require_near(b.v, Vec3::Zero(), kRestTol, "at rest: v = 0 after 1000 steps");
  require_near(b.omega, Vec3::Zero(), kRestTol, "at rest: omega = 0");
  require_near(b.x, x0, 1e-9, "the box has not crept from where it was set down");
}

void slope(const wbtest::Params& p) {
  // A 30 degree slope whose fall line is along neither world axis, and a box turned
  // about the normal: the friction must oppose the slip in whatever direction it is.
  // Held-out: static mu 0.65 to 0.9 (above tan 30 = 0.577), sliding mu 0.15 to 0.45.
  const double theta = M_PI / 6, h = 1e-3, fall_angle = 0.7;
  const Vec3 fall = Vec3(std::cos(fall_angle), std::sin(fall_angle), 0);  // horizontal, downhill
  const Vec3 n = (std::cos(theta) * kUp + std::sin(theta) * fall).normalized();
  const Vec3 down = (Vec3(0, 0, -1) - Vec3(0, 0, -1).dot(n) * n).normalized();
  const Vec3 size(0.4, 0.4, 0.2);
  const auto spin = Eigen::Quaterniond(Eigen::AngleAxisd(0.4, kUp));
  const double mu_static = p.num(0.7, 0.65, 0.9), mu = p.num(0.3, 0.15, 0.45);
  if (p.held_out()) {  // the static run, then the sliding one: 64 and 16 checked steps
    for (const auto& [friction, steps] : {std::pair{mu_static, 64L}, std::pair{mu, 16L}}) {
      Body b = box_on_plane(1.0, size, n, spin);
      std::vector<Contact> kept(4);
      run_on_plane(b, size, n, friction, h, p.count(0, 1, 100), kept, Solver::reference);
      run_on_plane(b, size, n, friction, h, steps, kept, Solver::checked);
    }
    return;
  }
  {
    Body b = box_on_plane(1.0, size, n, spin);
    run_on_plane(b, size, n, mu_static, h, 200);
    const Vec3 x1 = b.x;
    run_on_plane(b, size, n, mu_static, h, 2000);
    require_near((b.x - x1).dot(down), 0.0, 1e-9,
                 "mu = 0.7 > tan 30 = 0.58: held still over 2 s (static friction)");
  }
  {
    const double T = 0.5;
    Body b = box_on_plane(1.0, size, n, spin);
    run_on_plane(b, size, n, mu, h, long(T / h));
    const double a = kG * (std::sin(theta) - mu * std::cos(theta));
    require_near(b.v.dot(down), a * T, 0.0,
                 "mu = 0.3 < tan 30: speed along the fall line a T, a = g (sin - mu cos)", 1e-6);
    require_near((b.v - b.v.dot(down) * down).norm(), 0.0, 1e-9,
                 "it slides straight down the fall line (friction opposes the slip)");
  }
}

}  // namespace

TEST_CASE("R6 prepare: effective mass along n and the restitution target above the threshold",
          "[rigid][R6][2pts]") {
  Vec3 p;
  const Body b0 = tilted_box(p);
  const double vn = point_velocity(b0, p).dot(kUp);  // -2.4: approaching
  INFO("the test's own set-up: the corner approaches the floor, u.n = " << vn);
  REQUIRE(wbtest::finite(vn) < 0);
  // The test's own K: the velocity change of p per unit impulse along each axis.
  Mat3 K;
  for (int k = 0; k < 3; ++k) {
    Body probe = b0;
    impulse_at(probe, p, Vec3::Unit(k));
    K.col(k) = point_velocity(probe, p) - point_velocity(b0, p);
  }
  for (double e : {0.0, 0.5}) {
    // Both sides of the threshold, close to it: a closing speed just above bounces,
    // just below does not (resting).
    for (double factor : {0.99, 1.01}) {
      const double threshold = -vn * factor;
      const bool bounces = factor < 1;
      INFO("e = " << e << ", closing speed " << -vn << ", threshold " << threshold);
      Body b = b0;
      Contact c = contact_at(p, 1.5, Vec3(0.25, -0.5, 0));
      prepare_contact(b, kUp, e, threshold, c);
      require_near(c.r, p - b0.x, kImpulseTol, "r = p - x");
      require_near(c.K, K, kImpulseTol, "K: velocity change of p per unit impulse at p");
      require_near(c.mass_n, 1.0 / kUp.dot(K * kUp), 0.0,
                   "mass_n = 1 / (n^T K n), the effective mass along n", kImpulseTol);
      require_near(c.bias, bounces ? -e * vn : 0.0, kImpulseTol,
                   bounces ? "above the threshold the contact aims at -e vn"
                           : "below the threshold the contact does not bounce: bias 0");
      require_near(c.Pn, 1.5, 0.0, "prepare leaves the stored Pn as it is");
      require_near(c.Pt, Vec3(0.25, -0.5, 0), 0.0, "prepare leaves the stored Pt as it is");
      require_near(b.v, b0.v, 0.0, "prepare applies nothing: v unchanged");
      require_near(b.omega, b0.omega, 0.0, "prepare applies nothing: omega unchanged");
    }
  }
  // A tilted plane: the effective mass along ITS normal, 1 / (n^T K n) (not one entry of K,
  // which is the same only for n = z), and the approach speed along it.
  {
    const Vec3 n(0.36, -0.48, 0.8);  // unit
    const double vt = point_velocity(b0, p).dot(n);
    INFO("plane normal " << str(n) << ", u.n = " << vt << ", threshold 0.1, e = 0.5");
    Body b = b0;
    Contact c = contact_at(p);
    prepare_contact(b, n, 0.5, 0.1, c);
    require_near(c.mass_n, 1.0 / n.dot(K * n), 0.0,
                 "mass_n = 1 / (n^T K n) along the plane's own normal", kImpulseTol);
    require_near(c.bias, vt > 0 ? -vt : (-vt > 0.1 ? -0.5 * vt : 0.0), kImpulseTol,
                 "the bias from the normal velocity along this n");
  }
  // The same corner LEAVING the floor: on both sides of the threshold and for any e the
  // target is -u.n (another contact may turn it back, never faster than it leaves: with a
  // target of 0 the solver would add (1/2) Pn u.n of energy when it does).
  for (double e : {0.0, 0.5}) {
    for (double factor : {0.99, 1.01}) {
      Body b = b0;
      b.v = -b0.v;
      b.omega = -b0.omega;  // u.n = -vn: separating
      const double threshold = -vn * factor;
      INFO("separating at " << -vn << " m/s, threshold " << threshold << ", e = " << e);
      Contact c = contact_at(p);
      prepare_contact(b, kUp, e, threshold, c);
      require_near(c.bias, vn, kImpulseTol,
                   "a point moving away from the plane aims at -u.n: it may be turned back at "
                   "most as fast as it leaves, whatever e and the threshold");
    }
  }
}

TEST_CASE("R6 warm start: the stored totals are applied at the point with their own sign",
          "[rigid][R6][2pts]") {
  Vec3 p;
  const Body b0 = tilted_box(p);
  Contact c = contact_at(p, 2.0, Vec3(0.3, -0.4, 0.0));
  Body b = b0;
  prepare_contact(b, kUp, 0.0, 0.0, c);
  warm_start_contact(b, c, kUp);
  Body expected = b0;
  impulse_at(expected, p, 2.0 * kUp + Vec3(0.3, -0.4, 0.0));
  require_near(b.v, expected.v, kImpulseTol,
               "v += (Pn n + Pt) / m: the totals of the last step, pushing out of the plane");
  require_near(b.omega, expected.omega, kImpulseTol, "omega += I^-1 (r x (Pn n + Pt))");
  require_near(c.Pn, 2.0, 0.0, "warm starting keeps the totals (they are already applied)");
}

TEST_CASE("R6 one iteration: the normal impulse is a clamped total that can be taken back",
          "[rigid][R6][2pts]") {
  // A point moving INTO the plane with nothing stored: the iteration adds the impulse
  // that makes u.n = bias, and returns it.
  Vec3 p;
  for (double e : {0.0, 0.6}) {
    INFO("e = " << e << ", threshold 0.1 m/s, below the closing speed");
    Body b = tilted_box(p);
    const double vn = point_velocity(b, p).dot(kUp);
    Contact c = contact_at(p);
    prepare_contact(b, kUp, e, 0.1, c);
    const Vec3 mv0 = b.m * b.v;
    const double added = solve_contact(b, c, kUp, 0.0);
    require_near(point_velocity(b, p).dot(kUp), -e * vn, kImpulseTol,
                 "after one iteration u.n = bias = -e vn (Newton's restitution law)");
    require_near(c.Pn, (b.m * b.v - mv0).dot(kUp), kImpulseTol,
                 "the total Pn is the momentum the contact gave along n");
    require_near(added, c.Pn, kImpulseTol, "returned: the impulse this iteration added");
  }
  // The same point after a warm start that pushed too hard: it now leaves the plane.
  // The total comes down (a NEGATIVE increment), to exactly u.n = 0, while it stays
  // >= 0. Clamping each iteration's increment to >= 0 instead would leave it moving
  // away; forgetting the total would push once more.
  for (double stored : {6.0, 0.5}) {
    INFO("stored Pn = " << stored);
    Body b = tilted_box(p);
    b.v.z() = -0.05;  // approaching slowly
    b.omega.setZero();
    Contact c = contact_at(p, stored);
    prepare_contact(b, kUp, 0.0, 10.0, c);
    warm_start_contact(b, c, kUp);
    const double un = point_velocity(b, p).dot(kUp);
    REQUIRE(wbtest::finite(un) > 0);               // over-pushed
    const double needed = stored - c.mass_n * un;  // the total that gives u.n = 0
    const Body before = b;
    const double added = solve_contact(b, c, kUp, 0.0);
    if (needed > 0) {
      require_near(c.Pn, needed, kImpulseTol, "total Pn + mass_n (bias - u.n): above 0, kept");
      require_near(point_velocity(b, p).dot(kUp), 0.0, kImpulseTol,
                   "taking back part of the total stops the point: u.n = 0");
    } else {
      require_near(c.Pn, 0.0, 0.0, "the total would go below 0: clamped to 0 (never pulls)");
      require_near(point_velocity(b, p).dot(kUp), un - stored / c.mass_n, kImpulseTol,
                   "the whole stored impulse taken back, no more: the point leaves");
      REQUIRE(wbtest::finite(point_velocity(b, p).dot(kUp)) > 0);
    }
    require_near(added, c.Pn - stored, kImpulseTol, "returned: new total minus old total");
    require_near(Vec3(b.m * (b.v - before.v)), Vec3(added * kUp), kImpulseTol,
                 "the body receives exactly the change of the total, along n");
  }
}

TEST_CASE("R6 friction: the bound is mu times the accumulated normal total and opposes the slip",
          "[rigid][R6][2pts]") {
  // A sphere (r along -n: no turning from the normal impulse) sliding along x.
  const double m = 2.0, R = 0.5, I = 0.4 * m * R * R;
  const Vec3 p(0, 0, 0);
  auto sphere = [&](const Vec3& v) {
    return make_body(m, Vec3::Constant(I), quat(1, 0, 0, 0), Vec3::Zero(), Vec3(0, 0, R), v);
  };
  // Sticking needs |Pt| = 2/7 m u (the 5/7 rolling speed).
  const double u = 3.0, stick = 2.0 / 7.0 * m * u;
  // 1. Pn stored large from earlier iterations; this iteration adds almost nothing
  //    along n. The bound mu * 10 = 5 N s is enough to stick; the increment's own
  //    mu * dPn is not.
  {
    Body s = sphere(Vec3(u, 0, -0.001));
    Contact c = contact_at(p, 10.0);
    prepare_contact(s, kUp, 0.0, 1.0, c);
    solve_contact(s, c, kUp, 0.5);
    require_near(point_velocity(s, p), Vec3::Zero(), kImpulseTol,
                 "mu Pn (the total, 5 N s) > 2/7 m u: the point stops sliding");
    require_near(c.Pt, Vec3(-stick, 0, 0), kImpulseTol, "Pt = -2/7 m u, against the slip");
  }
  // 2. The cone's boundary, both sides: mu Pn just above and just below 2/7 m u.
  for (double f : {1.02, 0.98}) {
    const double Pn = 4.0, mu = f * stick / Pn;
    INFO("mu Pn / (2/7 m u) = " << f);
    Body s = sphere(Vec3(u, 0, 0));
    Contact c = contact_at(p, Pn);
    prepare_contact(s, kUp, 0.0, 1.0, c);
    solve_contact(s, c, kUp, mu);
    const double jt = std::min(stick, mu * Pn);
    require_near(c.Pt, Vec3(-jt, 0, 0), kImpulseTol, "|Pt| = min(2/7 m u, mu Pn)");
    require_near(s.v.x(), u - jt / m, kImpulseTol, "v.x loses |Pt| / m");
  }
  // 3. A stored friction total the slip has reversed: the total is corrected, and its
  //    direction ends against the new slip (x), clamped to mu Pn as a total.
  {
    Body s = sphere(Vec3(u, 0.5, 0));
    Contact c = contact_at(p, 1.0, Vec3(0.0, 0.4, 0));  // stored pushing along +y
    prepare_contact(s, kUp, 0.0, 1.0, c);
    solve_contact(s, c, kUp, 0.3);
    INFO("friction total Pt = " << str(c.Pt) << ", expected |Pt| <= mu Pn = 0.3");
    REQUIRE(wbtest::finite(c.Pt.norm()) <= 0.3 * 1.0 * (1 + 1e-12));
    require_near(c.Pt.norm(), 0.3, kImpulseTol, "sliding: |Pt| = mu Pn exactly");
    require_near(c.Pt.z(), 0.0, kImpulseTol, "Pt lies in the plane");
  }
  // 4. Degenerate cases the header names: no slip, mu = 0, Pn = 0: no NaN, no friction.
  for (const auto& [v, mu, Pn] :
       {std::tuple{Vec3(0, 0, 0), 0.5, 1.0}, std::tuple{Vec3(u, 0, 0), 0.0, 1.0},
        std::tuple{Vec3(u, 0, 0.5), 0.5, 0.0}}) {
    INFO("v = " << str(v) << ", mu = " << mu << ", stored Pn = " << Pn);
    Body s = sphere(v);
    Contact c = contact_at(p, Pn);
    prepare_contact(s, kUp, 0.0, 1.0, c);
    solve_contact(s, c, kUp, mu);
    REQUIRE(s.v.allFinite());
    REQUIRE(s.omega.allFinite());
    require_near(c.Pt, Vec3::Zero(), 0.0, "no slip, mu = 0 or no normal total: Pt stays 0");
    require_near(s.v.x(), v.x(), kImpulseTol, "no friction: v.x unchanged");
  }
}

TEST_CASE("R6 friction with restitution: the slip is the point's velocity in the plane",
          "[rigid][R6][1pts]") {
  // A sphere (r along -n: the normal impulse does not turn it) hitting the floor at 2 m/s
  // while sliding at 3 m/s, e = 0.5. After step 1 the point moves AWAY at e * 2 = 1 m/s:
  // the slip is only the part in the plane, ut = u - (u.n) n, and the friction impulse
  // lies in the plane, leaving u.n = 1 m/s. mu = 0.5, Pn = 6 N s: the cone does not bind,
  // so the point stops sliding (Pt = -2/7 m ut: the 5/7 rolling speed).
  const double m = 2.0, R = 0.5, I = 0.4 * m * R * R;
  const Vec3 p(0, 0, 0);
  for (const Vec3& slide : {Vec3(3, 0, 0), Vec3(1.8, -2.4, 0)}) {
    INFO("sliding at " << str(slide) << ", approaching at 2 m/s, e = 0.5, mu = 0.5");
    Body s = make_body(m, Vec3::Constant(I), quat(1, 0, 0, 0), Vec3::Zero(), Vec3(0, 0, R),
                       slide + Vec3(0, 0, -2));
    Contact c = contact_at(p);
    prepare_contact(s, kUp, 0.5, 0.1, c);
    solve_contact(s, c, kUp, 0.5);
    require_near(c.Pn, (1 + 0.5) * 2.0 * m, kImpulseTol, "Pn = (1 + e) m |vn| (r along n)");
    require_near(c.Pt, Vec3(-2.0 / 7.0 * m * slide), kImpulseTol,
                 "Pt = -2/7 m ut with ut the slip IN THE PLANE, u - (u.n) n");
    require_near(point_velocity(s, p), Vec3(0, 0, 0.5 * 2.0), kImpulseTol,
                 "the point stops sliding and still leaves at -e vn = 1 m/s: friction acts "
                 "only in the plane");
  }
}

TEST_CASE("R6 friction: the bound is the normal total of this iteration", "[rigid][R6][2pts]") {
  // Step 1 (normal) comes before step 2 (friction), and step 2's bound is mu times the
  // total step 1 just made. A sphere sliding at 3 m/s along x, mu = 0.1: the cone binds
  // (mu Pn < 2/7 m u = 1.71 N s), so |Pt| = mu Pn tells which Pn was used.
  const double m = 2.0, R = 0.5, I = 0.4 * m * R * R;
  const Vec3 p(0, 0, 0);
  struct Case {
    double vz, stored, Pn;
    const char* why;
  };
  const Case cases[] = {
      {-1.0, 0.0, 2.0, "nothing stored, approaching at 1 m/s: this iteration makes Pn = 2"},
      {1.0, 10.0, 6.0,
       "10 N s stored, leaving at 1 m/s (target -u.n = -1): this iteration takes Pn down to 6"},
  };
  for (const Case& k : cases) {
    INFO(k.why);
    Body s = make_body(m, Vec3::Constant(I), quat(1, 0, 0, 0), Vec3::Zero(), Vec3(0, 0, R),
                       Vec3(3, 0, k.vz));
    Contact c = contact_at(p, k.stored);
    prepare_contact(s, kUp, 0.0, 1.5, c);
    solve_contact(s, c, kUp, 0.1);
    require_near(c.Pn, k.Pn, kImpulseTol, "the normal total after step 1");
    require_near(c.Pt, Vec3(-0.1 * k.Pn, 0, 0), kImpulseTol,
                 "|Pt| = mu Pn with the NEW normal total of step 1 (step 1 before step 2), "
                 "not the total the iteration started with");
    require_near(s.v.x(), 3.0 - 0.1 * k.Pn / m, kImpulseTol, "v.x = 3 - mu Pn / m");
  }
}

TEST_CASE("R6 together: one pass over the contacts in order per iteration", "[rigid][R6][1pts]") {
  // solve_plane_contacts = prepare and warm start each contact, then `iterations` passes
  // of solve_contact over the contacts in order. The test's own pass (mu = 0): for each
  // contact, lambda = (bias - u.n) / (n^T K n), the total clamped at 0, its change applied
  // at the point. One contact and one pass: u.n = -e vn exactly (Newton's law).
  Vec3 p;
  const Body b0 = tilted_box(p);
  const double vn = point_velocity(b0, p).dot(kUp);
  {
    Body b = b0;
    std::vector<Contact> cs = {contact_at(p)};
    const double total = solve_plane_contacts(b, cs, kUp, 0.6, 0.1, 0.0, 1);
    require_near(point_velocity(b, p).dot(kUp), -0.6 * vn, kImpulseTol,
                 "one contact, iterations = 1: after its one pass u.n = -e vn");
    require_near(total, cs[0].Pn, kImpulseTol, "returns the sum of the contacts' Pn");
  }
  // Two corners, their totals stored from a last step: every pass changes what the other
  // corner needs, so 1, 2 and 3 passes end in three different states.
  const Vec3 q = b0.x + rot(b0) * Vec3(0.5, -0.5, -0.5);
  const double e = 0.3, threshold = 0.1;
  for (int iterations : {1, 2, 3}) {
    INFO("two contacts, stored Pn 0.2 and 0.4 N s, e = 0.3, iterations = " << iterations);
    Body b = b0;
    std::vector<Contact> cs = {contact_at(p, 0.2), contact_at(q, 0.4)};
    solve_plane_contacts(b, cs, kUp, e, threshold, 0.0, iterations);
    // The test's own passes.
    Body r = b0;
    const Vec3 pts[2] = {p, q};
    double Pn[2] = {0.2, 0.4}, bias[2], mass[2];
    for (int k = 0; k < 2; ++k) {
      Mat3 K;
      for (int a = 0; a < 3; ++a) {
        Body probe = b0;
        impulse_at(probe, pts[k], Vec3::Unit(a));
        K.col(a) = point_velocity(probe, pts[k]) - point_velocity(b0, pts[k]);
      }
      mass[k] = 1.0 / kUp.dot(K * kUp);
      const double u = point_velocity(b0, pts[k]).dot(kUp);
      bias[k] = u > 0 ? -u : (-u > threshold ? -e * u : 0.0);
    }
    for (int k = 0; k < 2; ++k) impulse_at(r, pts[k], Pn[k] * kUp);  // warm start
    for (int it = 0; it < iterations; ++it) {
      for (int k = 0; k < 2; ++k) {
        const double lambda = mass[k] * (bias[k] - point_velocity(r, pts[k]).dot(kUp));
        const double next = std::max(Pn[k] + lambda, 0.0);
        impulse_at(r, pts[k], (next - Pn[k]) * kUp);
        Pn[k] = next;
      }
    }
    require_near(b.v, r.v, kImpulseTol, "v after `iterations` passes over both contacts");
    require_near(b.omega, r.omega, kImpulseTol, "omega after `iterations` passes");
    require_near(cs[0].Pn, Pn[0], kImpulseTol, "contact 0's total after the passes");
    require_near(cs[1].Pn, Pn[1], kImpulseTol, "contact 1's total after the passes");
  }
}

TEST_CASE("R6 together and warm-started: a box on the floor rests to rounding",
          "[rigid][R6][2pts]") {
  resting_box(wbtest::Params());
}

TEST_CASE("R6 slope: static friction holds when mu > tan theta and else a = g (sin - mu cos)",
          "[rigid][R6][1pts]") {
  slope(wbtest::Params());
}

// The public runs again, their parameters drawn from the held-out seed in the public tests'
// format, a few steps of each, every call checked against the header's solver; then the header's
// steps one at a time on random bodies and contacts, among them the cases a mistake needs
// (resting, leaving, bouncing, stored totals).
TEST_CASE("R6 held-out: random bodies and contacts are solved as the header says",
          "[rigid][R6][held-out][3pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("R6")) {
    INFO(g.replay());
    const wbtest::Params p(g);
    resting_box(p);
    slope(p);
    for (int s = 0; s < 4; ++s) {
      // A state in the middle of a run, as the public runs' calls have it: the body's motion
      // is not in short decimals (random_body's are), the coefficients are.
      Body b0 = rigidtest::random_body(g);
      b0.x = g.vec3(-2, 2);
      b0.v = g.vec3(-2, 2);
      b0.omega = g.vec3(-3, 3);
      const Vec3 n = g.unit3();
      const auto d = [](double x) { return wbtest::Params::short_decimal(x); };
      const double e = d(s == 2 ? g.uniform(0.3, 1.0) : g.uniform(0.0, 1.0)),
                   threshold = d(g.uniform(0.0, 1.0)), mu = d(g.uniform(0.0, 1.2));
      // The body moving into the plane (or slowly along it), 1 to 4 contact points.
      b0.v -= (b0.v.dot(n) + g.uniform(-0.5, 3.0)) * n;
      if (s == 0) {  // every point closing slower than the threshold: resting, no bounce
        b0.omega.setZero();
        b0.v += (-threshold * g.uniform(0.1, 0.9) - b0.v.dot(n)) * n;
      } else if (s == 1) {  // every point leaving faster than the threshold: aims at -u.n
        b0.omega.setZero();
        b0.v += (threshold + g.uniform(0.2, 2.0) - b0.v.dot(n)) * n;
      } else if (s == 2) {   // every point closing faster than the threshold: bounces (e > 0.3),
        b0.omega.setZero();  // so u.n is not 0 when the friction acts: the slip is u's part in
        b0.v += (-threshold - g.uniform(0.5, 3.0) - b0.v.dot(n)) * n;  // the plane alone
      }
      const int k = int(g.integer(1, 4));
      std::vector<Contact> cs(static_cast<std::size_t>(k));
      std::vector<heldout_R6::Ref> refs(static_cast<std::size_t>(k));
      for (int i = 0; i < k; ++i) {
        cs[std::size_t(i)].p = b0.x + g.vec3(-1, 1);
        // Totals from the last step: none, or some (Pt in the plane within the cone); the first
        // contact always some (it is checked step by step: its warm start must show).
        if (i == 0 || g.coin()) {
          cs[std::size_t(i)].Pn = i == 0 ? g.uniform(0.2, 2.0) : g.uniform(0.0, 2.0);
          Vec3 t = g.vec3(-1, 1);
          t -= t.dot(n) * n;
          if (t.norm() > 0)
            cs[std::size_t(i)].Pt =
                t / t.norm() * g.uniform(0.0, 1.0) * mu * cs[std::size_t(i)].Pn;
        }
        refs[std::size_t(i)].p = cs[std::size_t(i)].p;
        refs[std::size_t(i)].Pn = cs[std::size_t(i)].Pn;
        refs[std::size_t(i)].Pt = cs[std::size_t(i)].Pt;
      }
      const int iterations = int(g.integer(1, 6));
      INFO(k << " contacts, n = " << rigidtest::str(n) << ", e = " << e
             << ", threshold = " << threshold << ", mu = " << mu << ", " << iterations
             << " iterations; body m = " << b0.m << ", v = " << rigidtest::str(b0.v)
             << ", omega = " << rigidtest::str(b0.omega));
      // One contact step by step: prepare, warm start, two iterations.
      {
        Body b = b0, e_b = b0;
        Contact c = cs[0];
        heldout_R6::Ref ref = refs[0];
        prepare_contact(b, n, e, threshold, c);
        heldout_R6::prepare(e_b, n, e, threshold, ref);
        rigidtest::require_near(c.r, ref.r, 1e-13, "prepare: r = p - x", 1e-13);
        rigidtest::require_near(c.K, ref.K, 1e-12 * (1 + wbtest::max_abs(ref.K)),
                                "prepare: K = E/m - [r]x I^-1 [r]x");
        wbtest::require_near(c.mass_n, ref.mass_n, 0.0, "prepare: mass_n = 1 / (n^T K n)", 1e-12);
        wbtest::require_near(c.bias, ref.bias, 1e-12,
                             "prepare: bias = -u.n leaving, -e u.n above the threshold, else 0",
                             1e-12);
        warm_start_contact(b, c, n);
        heldout_R6::apply(e_b, ref.r, ref.Pn * n + ref.Pt);
        rigidtest::require_body(b, e_b, 1e-12, "warm start: J = Pn n + Pt applied at p");
        for (int it = 0; it < 2; ++it) {
          const double got = solve_contact(b, c, n, mu);
          const double want = heldout_R6::solve(e_b, ref, n, mu);
          INFO("solve_contact, iteration " << it + 1);
          wbtest::require_near(got, want, 1e-12, "returns Pn' - Pn", 1e-11);
          wbtest::require_near(c.Pn, ref.Pn, 1e-12, "Pn' = max(Pn + mass_n (bias - u.n), 0)",
                               1e-11);
          rigidtest::require_near(c.Pt, ref.Pt, 1e-12,
                                  "Pt' = Pt - |ut| / (d^T K d) d, scaled to mu Pn at most",
                                  1e-11);
          rigidtest::require_body(b, e_b, 1e-11, "the body after the iteration's two impulses");
        }
      }
      // All of them together.
      Body b = b0, e_b = b0;
      std::vector<Contact> got = cs;
      const double total = solve_plane_contacts(b, got, n, e, threshold, mu, iterations);
      for (auto& r : refs) heldout_R6::prepare(e_b, n, e, threshold, r);
      for (auto& r : refs) heldout_R6::apply(e_b, r.p - e_b.x, r.Pn * n + r.Pt);
      for (int it = 0; it < iterations; ++it)
        for (auto& r : refs) heldout_R6::solve(e_b, r, n, mu);
      double want = 0;
      for (const auto& r : refs) want += r.Pn;
      {
        INFO("solve_plane_contacts returned " << got.size() << " contacts, expected " << k);
        REQUIRE(got.size() == std::size_t(k));
      }
      wbtest::require_near(total, want, 1e-11, "solve_plane_contacts returns the sum of the Pn",
                           1e-10);
      for (int i = 0; i < k; ++i) {
        INFO("contact " << i);
        wbtest::require_near(got[std::size_t(i)].Pn, refs[std::size_t(i)].Pn, 1e-11,
                             "its Pn total", 1e-10);
        rigidtest::require_near(got[std::size_t(i)].Pt, refs[std::size_t(i)].Pt, 1e-11,
                                "its Pt total", 1e-10);
      }
      rigidtest::require_body(b, e_b, 1e-10, "the body after prepare, warm start and the passes");
    }
  }
}

}  // namespace test_R6_plane_contact
