// Graded tests for TODO(C5), contacts by accumulated, warm-started impulses
// (labs/collisions/contact_solver.cpp). Expected values: the effective mass of two
// particles 1 / (1/m_a + 1/m_b), Newton's restitution law above the threshold,
// the totals' bounds (Pn >= 0, |Pt| <= mu Pn) and what they imply (an over-pushed
// contact takes impulse back), momentum conservation, and a column of discs that
// rests to rounding because the totals carry the weight from step to step.
#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "contact_solver.h"
#include "heldout.h"
#include "params.h"
#include "test_helpers.h"

// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace test_C5_contact_solver {

using wb::Mat2X;
using wb::Vec2;
using wb::VecX;

namespace {

constexpr double kTol = 1e-12;  // a few products of numbers ~0.1-10
constexpr double kG = 9.81;

Contact make_contact(int a, int b, const Vec2& n, double mu = 0, double Pn = 0, double Pt = 0) {
  Contact c;
  c.a = a, c.b = b, c.n = n.normalized(), c.mu = mu, c.Pn = Pn, c.Pt = Pt;
  return c;
}

void require_vec(const Vec2& got, const Vec2& expected, double tol, const std::string& what) {
  INFO(what << "\n  expected (" << expected.x() << ", " << expected.y() << ")\n  got      ("
            << got.x() << ", " << got.y() << ")\n  tolerance " << tol);
  REQUIRE(wbtest::near(got.x(), expected.x(), tol, 0.0));
  REQUIRE(wbtest::near(got.y(), expected.y(), tol, 0.0));
}

// The public tests' scenarios, each a function of its parameters: the public test runs it with
// the published ones (wbtest::Params()), the held-out test with drawn ones in the same format
// (tests/common/params.h): short decimals within a fifth or so of the published values, the
// same particle counts, each case kept on its side of every bound it is about. The normals stay
// the published ones (a contact's normal and totals are no call's argument the worker sees as a
// number list, and the cases' signs rest on them).

// Three particles: 0 and 1 a pair (masses 2 and 0.5), 2 a bystander.
VecX inverse_masses(const wbtest::Params& p) {
  return (VecX(3) << p.num(0.5, 0.4, 0.6), p.num(2.0, 1.6, 2.4), p.num(1.0, 0.8, 1.2)).finished();
}
// v0 = (1, -2), v1 = (-0.5, 1) (closing at 1.5 m/s along (0.6, 0.8)), v2 = (7, 7).
Mat2X pair_velocities(const wbtest::Params& p) {
  Mat2X v(2, 3);
  v << p.num(1.0, 0.8, 1.2), p.num(-0.5, -0.6, -0.4), p.num(7.0, 6.0, 8.0),
      p.num(-2.0, -2.4, -1.6), p.num(1.0, 0.8, 1.2), p.num(7.0, 6.0, 8.0);
  return v;
}
// One particle on a floor: its inverse mass (2 kg).
VecX floor_mass(const wbtest::Params& p) {
  return (VecX(1) << p.num(0.5, 0.45, 0.55)).finished();
}

void prepare_both_sides(const wbtest::Params& p) {
  const VecX w = inverse_masses(p);
  Mat2X v = pair_velocities(p);
  const Vec2 n = Vec2(0.6, 0.8);                   // from 1 to 0
  const double un = (v.col(0) - v.col(1)).dot(n);  // about -1.5: closing
  const double e1 = p.num(0.7, 0.5, 0.9);
  const double mu = p.num(0.4, 0.3, 0.5), Pn = p.num(1.25, 1.0, 1.5),
               Pt = p.num(-0.5, -0.6, -0.4);
  for (double e : {0.0, e1}) {
    for (double f : {0.99, 1.01}) {
      const double threshold = -un * f;
      const bool bounces = f < 1;
      INFO("pair, e = " << e << ", closing speed " << -un << ", threshold " << threshold);
      Contact c = make_contact(0, 1, n, mu, Pn, Pt);
      const Mat2X v0 = v;
      prepare_contact(w, v, e, threshold, c);
      wbtest::require_near(c.mass_n, 1.0 / (w[0] + w[1]), 0.0, "mass_n = 1 / (1/m_a + 1/m_b)",
                           kTol);
      wbtest::require_near(c.bias, bounces ? -e * un : 0.0, kTol,
                           bounces ? "above the threshold the contact aims at -e un"
                                   : "below the threshold: resting, bias 0 (no micro-bounce)");
      wbtest::require_near(c.Pn, Pn, 0.0, "prepare keeps the stored Pn");
      wbtest::require_near(c.Pt, Pt, 0.0, "prepare keeps the stored Pt");
      INFO("prepare applies no impulse");
      REQUIRE(v == v0);
    }
  }
  // The same pair separating: on both sides of the threshold and for any e, the
  // target is -un (another contact may turn it back, never faster than it leaves: with a
  // target of 0 the solver would add (1/2) Pn un of energy when it does).
  for (double e : {0.0, e1}) {
    for (double f : {0.99, 1.01}) {
      Mat2X u = -v;
      INFO("pair separating at " << -un << " m/s, e = " << e << ", threshold " << -un * f);
      Contact c = make_contact(0, 1, n);
      prepare_contact(w, u, e, -un * f, c);
      wbtest::require_near(c.bias, un, kTol,
                           "a separating contact aims at -un: it may be turned back at most as "
                           "fast as it separates, whatever e and the threshold");
    }
  }
  // A plane (b = -1): only particle a's mass, only its velocity.
  Contact c = make_contact(1, -1, Vec2(0, 1));
  prepare_contact(w, v, p.num(0.5, 0.4, 0.6), p.num(0.1, 0.05, 0.15), c);
  wbtest::require_near(c.mass_n, 1.0 / w[1], 0.0, "at a plane mass_n = m_a", kTol);
  wbtest::require_near(c.bias, -v(1, 1), kTol,
                       "particle 1 leaves the floor at about 1 m/s: a separating contact aims "
                       "at -un");
}

void warm_start(const wbtest::Params& p) {
  const VecX w = inverse_masses(p);
  Mat2X v = Mat2X::Zero(2, 3);
  const Vec2 n(0.6, 0.8), t(-0.8, 0.6);  // t = perp(n)
  const double Pn = p.num(2.0, 1.6, 2.4), Pt = p.num(0.3, 0.2, 0.4);
  Contact c = make_contact(0, 1, n, p.num(0.5, 0.4, 0.6), Pn, Pt);
  prepare_contact(w, v, 0.0, 0.0, c);
  warm_start_contact(w, c, v);
  const Vec2 J = Pn * n + Pt * t;
  require_vec(v.col(0), w[0] * J, kTol, "v_a += w_a (Pn n + Pt perp(n)): pushed away from b");
  require_vec(v.col(1), -w[1] * J, kTol, "v_b -= w_b J: equal and opposite");
  require_vec(v.col(2), Vec2::Zero(), 0.0, "a particle not in the contact is untouched");
  Mat2X u = Mat2X::Zero(2, 3);
  const double Pn2 = p.num(1.5, 1.2, 1.8), Pt2 = p.num(-0.25, -0.3, -0.2);
  Contact floor = make_contact(2, -1, Vec2(0, 1), p.num(0.5, 0.4, 0.6), Pn2, Pt2);
  prepare_contact(w, u, 0.0, 0.0, floor);
  warm_start_contact(w, floor, u);
  // perp((0, 1)) = (-1, 0): J = Pn (0, 1) + Pt (-1, 0) = (-Pt, Pn).
  require_vec(u.col(2), Vec2(-w[2] * Pt2, w[2] * Pn2), kTol,
              "at a plane only v_a changes: w_a (Pn n + Pt perp(n))");
}

void one_iteration(const wbtest::Params& p) {
  const VecX w = inverse_masses(p);
  const Vec2 n(0.6, 0.8);
  // Closing with nothing stored: the iteration makes un = bias and returns what it added;
  // the total momentum of the pair does not change.
  const double threshold = p.num(0.1, 0.05, 0.15);
  for (double e : {0.0, p.num(0.7, 0.5, 0.9)}) {
    INFO("e = " << e);
    Mat2X v = pair_velocities(p);
    v.col(2).setZero();
    const double un0 = (v.col(0) - v.col(1)).dot(n);
    const Vec2 p0 = v.col(0) / w[0] + v.col(1) / w[1];
    Contact c = make_contact(0, 1, n);
    prepare_contact(w, v, e, threshold, c);
    const double added = solve_contact(w, c, v);
    wbtest::require_near((v.col(0) - v.col(1)).dot(n), -e * un0, kTol,
                         "after one iteration un = -e un0 (Newton's restitution law)");
    wbtest::require_near(added, c.Pn, kTol, "returned: the impulse this iteration added");
    wbtest::require_near(c.Pn, (1 + e) * -un0 / (w[0] + w[1]), kTol,
                         "Pn = (1 + e) |un| / (w_a + w_b)");
    require_vec(Vec2(v.col(0) / w[0] + v.col(1) / w[1]), p0, kTol,
                "the pair's total momentum is unchanged");
  }
  // Over-pushed by a warm start: the total comes DOWN (a negative increment) to exactly
  // un = bias while it stays >= 0, or to 0 when even that is too much. Clamping the
  // increment instead, or forgetting the total, gets this wrong.
  for (const auto& [stored, vy] : {std::pair{p.num(3.0, 2.5, 3.5), p.num(-0.1, -0.15, -0.05)},
                                   std::pair{p.num(0.05, 0.03, 0.07), p.num(0.1, 0.05, 0.15)}}) {
    INFO("stored Pn = " << stored << ", particle 0 moving at " << vy << " m/s along n");
    Mat2X v(2, 3);
    v << 0.0, 0.0, 0.0, vy, 0.0, 0.0;  // particle 0 on the floor, falling or leaving
    Contact c = make_contact(0, -1, Vec2(0, 1), 0.0, stored);
    prepare_contact(w, v, 0.0, p.num(0.5, 0.4, 0.6), c);
    warm_start_contact(w, c, v);
    const double up = v(1, 0);
    REQUIRE(wbtest::finite(up) > 0);
    const double added = solve_contact(w, c, v);
    const double bias = vy > 0 ? -vy : 0.0;  // leaving: -un; falling slower than 0.4: 0
    const double needed = stored + (bias - up) / w[0];
    if (needed > 0) {
      wbtest::require_near(c.Pn, needed, kTol, "total Pn + mass_n (bias - un): above 0, kept");
      wbtest::require_near(v(1, 0), bias, kTol, "part of the total taken back: un = bias");
    } else {
      wbtest::require_near(c.Pn, 0.0, 0.0, "the total would go below 0: clamped to 0");
      wbtest::require_near(v(1, 0), up - stored * w[0], kTol,
                           "the whole stored impulse taken back, no more");
    }
    wbtest::require_near(added, c.Pn - stored, kTol, "returned: new total minus old total");
  }
}

void friction_bound(const wbtest::Params& p) {
  const VecX w = floor_mass(p);  // 2 kg
  const double m = 1.0 / w[0];
  const Vec2 up(0, 1);
  // perp((0, 1)) = (-1, 0): sliding along +x is ut = -u.x.
  // 1. A large stored Pn, an iteration that adds almost nothing along n: the bound is
  //    mu times the total (enough to stop the slide), not mu times the increment.
  {
    Mat2X v(2, 1);
    const double vx = p.num(1.0, 0.9, 1.1);
    v << vx, p.num(-0.001, -0.002, -0.0005);
    Contact c = make_contact(0, -1, up, p.num(0.5, 0.4, 0.6), p.num(10.0, 8.0, 12.0));
    prepare_contact(w, v, 0.0, p.num(1.0, 0.8, 1.2), c);
    solve_contact(w, c, v);
    require_vec(v.col(0), Vec2::Zero(), kTol, "mu Pn (5 N s) > m |ut| (2 N s): the slide stops");
    wbtest::require_near(c.Pt, m * vx, kTol, "Pt = m ut along perp(n), against the slide");
  }
  // 2. Both sides of the cone's boundary: mu Pn just above and below m |ut|.
  for (double f : {1.02, 0.98}) {
    const double Pn = p.num(4.0, 3.0, 5.0), vx = p.num(1.0, 0.9, 1.1);
    const double mu = wbtest::Params::short_decimal(f * m * vx / Pn);
    INFO("mu Pn / (m |ut|) = " << f);
    Mat2X v(2, 1);
    v << vx, 0.0;
    Contact c = make_contact(0, -1, up, mu, Pn);
    prepare_contact(w, v, 0.0, p.num(1.0, 0.8, 1.2), c);
    solve_contact(w, c, v);
    const double jt = std::min(m * vx, mu * Pn);
    wbtest::require_near(c.Pt, jt, kTol, "|Pt| = min(m |ut|, mu Pn)");
    wbtest::require_near(v(0, 0), vx - jt * w[0], kTol, "v.x loses |Pt| / m");
  }
  // 3. A stored friction total beyond what the slide needs is taken back, clamped as a
  //    total to mu Pn.
  {
    Mat2X v(2, 1);
    v << p.num(-0.25, -0.27, -0.23), 0.0;
    const double mu = p.num(0.2, 0.18, 0.22), Pn = p.num(1.0, 0.9, 1.1);
    Contact c = make_contact(0, -1, up, mu, Pn, p.num(0.9, 0.85, 0.95));  // > mu Pn
    prepare_contact(w, v, 0.0, p.num(1.0, 0.8, 1.2), c);
    solve_contact(w, c, v);
    wbtest::require_near(c.Pt, mu * Pn, kTol,
                         "the total 0.9 - m |ut| = 0.4 is clamped to mu Pn = 0.2 as a total");
  }
  // 4. The degenerate cases: no slide, mu = 0, no normal total left (the disc moves
  //    away, so the stored 1 N s is taken back to 0): no friction, and no NaN.
  const double vx1 = p.num(1.0, 0.8, 1.2), mu1 = p.num(0.5, 0.4, 0.6), Pn1 = p.num(1.0, 0.8, 1.2);
  for (const auto& [vx, mu, Pn] :
       {std::tuple{0.0, mu1, Pn1}, std::tuple{vx1, 0.0, Pn1}, std::tuple{vx1, mu1, 0.0}}) {
    INFO("v.x = " << vx << ", mu = " << mu << ", stored Pn = " << Pn);
    Mat2X v(2, 1);
    v << vx, p.num(0.5, 0.4, 0.6);  // moving away from the floor
    Contact c = make_contact(0, -1, up, mu, Pn);
    prepare_contact(w, v, 0.0, p.num(1.0, 0.8, 1.2), c);
    solve_contact(w, c, v);
    INFO("the velocities must stay finite");
    REQUIRE(v.allFinite());
    wbtest::require_near(c.Pn, 0.0, 0.0, "the disc leaves the floor: the normal total is 0");
    wbtest::require_near(c.Pt, 0.0, 0.0, "no slide, mu = 0 or Pn = 0: Pt = 0");
    wbtest::require_near(v(0, 0), vx, kTol, "no friction: v.x unchanged");
  }
}

void pair_friction(const wbtest::Params& p) {
  // Particles 0 (2 kg) and 1 (0.5 kg) touching along n, sliding past each other along
  // t = perp(n), both ways, with and without restitution. A friction total within the
  // cone stops the relative slide in one iteration: the impulse along t moves BOTH
  // particles, so it is Pt = -mass_n ut with mass_n = 1 / (w_a + w_b), as along n. With
  // one particle's mass (1 / w_a) the slide would be over-corrected 5 times: ut' = -4 ut.
  const VecX w = inverse_masses(p);
  const Vec2 n(0.6, 0.8), t(-0.8, 0.6);  // t = perp(n)
  const double mass_n = 1.0 / (w[0] + w[1]);
  const double speed = p.num(1.5, 1.2, 1.8), e1 = p.num(0.6, 0.4, 0.8);
  const double va = p.num(0.25, 0.22, 0.28), vb = p.num(0.75, 0.7, 0.8), closing = vb - va;
  for (double slide : {speed, -speed}) {
    for (double e : {0.0, e1}) {
      INFO("relative slide ut = " << slide << " m/s along perp(n), closing at " << closing
                                  << " m/s, e = " << e << ", mu = 5 (the cone does not bind)");
      Mat2X v = Mat2X::Zero(2, 3);
      v.col(0) = va * n + slide * t;  // u = v_a - v_b: un = -closing, ut = slide
      v.col(1) = vb * n;
      const Vec2 p0 = v.col(0) / w[0] + v.col(1) / w[1];
      Contact c = make_contact(0, 1, n, 5.0);
      prepare_contact(w, v, e, p.num(0.1, 0.05, 0.15), c);
      solve_contact(w, c, v);
      const Vec2 u = v.col(0) - v.col(1);
      wbtest::require_near(u.dot(n), closing * e, kTol,
                           "the normal step first: un = -e un0 (Newton's restitution law)");
      wbtest::require_near(c.Pn, (1 + e) * closing * mass_n, kTol, "Pn = (1 + e) |un| mass_n");
      wbtest::require_near(u.dot(t), 0.0, kTol,
                           "the relative slide stops: Pt = -mass_n ut with the PAIR's "
                           "mass_n = 1 / (w_a + w_b), not one particle's mass");
      wbtest::require_near(c.Pt, -slide * mass_n, kTol, "Pt = -mass_n ut, against the slide");
      require_vec(Vec2(v.col(0) / w[0] + v.col(1) / w[1]), p0, kTol,
                  "the pair's total momentum is unchanged by both impulses");
    }
  }
  // Sliding on the cone's boundary (mu Pn < mass_n |ut|): |Pt| = mu Pn, its sign against
  // the slide whichever way the slide goes.
  const double Pn = p.num(0.2, 0.15, 0.25), mu = p.num(0.5, 0.4, 0.6);
  for (double slide : {speed, -speed}) {
    INFO("relative slide ut = " << slide << " m/s, stored Pn = " << Pn << " N s, mu = " << mu);
    Mat2X v = Mat2X::Zero(2, 3);
    v.col(0) = slide * t;
    Contact c = make_contact(0, 1, n, mu, Pn);
    prepare_contact(w, v, 0.0, p.num(0.1, 0.05, 0.15), c);
    solve_contact(w, c, v);
    wbtest::require_near(c.Pt, slide > 0 ? -mu * Pn : mu * Pn, kTol,
                         "|Pt| = mu Pn, against the slide");
    wbtest::require_near((v.col(0) - v.col(1)).dot(t),
                         slide - std::copysign(mu * Pn, slide) / mass_n, kTol,
                         "the slide slows by mu Pn (w_a + w_b)");
  }
}

void friction_both_ways(const wbtest::Params& p) {
  // A 2 kg particle on a floor sliding along -x, i.e. along +perp(n) = (-1, 0): the
  // friction total must come out NEGATIVE (against the slide), bounded by -mu Pn.
  const VecX w = floor_mass(p);
  const double m = 1.0 / w[0];
  const Vec2 up(0, 1);
  struct Case {
    double vx, mu, Pn;
    const char* why;
  };
  const Case cases[] = {
      {-1.0, 0.5, 10.0, "mu Pn = 5 N s > m |ut| = 2 N s: the slide stops, Pt = -2"},
      {-1.0, 0.1, 10.0, "mu Pn = 1 N s < m |ut|: Pt = -mu Pn, v.x = -1 + 1 / 2"},
      {1.0, 0.1, 10.0, "the other way: Pt = +mu Pn, v.x = 1 - 1 / 2"},
  };
  for (const Case& k : cases) {
    // Held-out: |v.x| and Pn within 10 %, mu within 20 %: each case stays on its side.
    const double vx = p.num(k.vx, 0.9 * k.vx, 1.1 * k.vx),
                 mu = p.num(k.mu, 0.8 * k.mu, 1.2 * k.mu),
                 Pn = p.num(k.Pn, 0.9 * k.Pn, 1.1 * k.Pn);
    const double Pt = std::clamp(m * vx, -mu * Pn, mu * Pn);
    INFO("v.x = " << vx << ", mu = " << mu << ", stored Pn = " << Pn << ", m = " << m
                  << " (published: " << k.why << ")");
    Mat2X v(2, 1);
    v << vx, 0.0;
    Contact c = make_contact(0, -1, up, mu, Pn);
    prepare_contact(w, v, 0.0, p.num(1.0, 0.8, 1.2), c);
    solve_contact(w, c, v);
    wbtest::require_near(c.Pt, Pt, kTol,
                         "the friction total lies in [-mu Pn, mu Pn], against the slide");
    wbtest::require_near(v(0, 0), vx - Pt * w[0], kTol, "v.x changed by Pt perp(n) / m");
  }
}

void friction_new_normal(const wbtest::Params& p) {
  // Step 1 (normal) comes before step 2 (friction), and step 2's bound is mu times the
  // total step 1 just made. A 2 kg particle sliding at 1 m/s along +x (ut = -1), mu = 0.25.
  const VecX w = floor_mass(p);
  const Vec2 up(0, 1);
  struct Case {
    double vy, stored;
    const char* why;
  };
  const Case cases[] = {
      {-1.0, 0.0, "nothing stored, closing at 1 m/s: this iteration makes Pn = m |un| = 2"},
      {0.5, 4.0,
       "4 N s stored, leaving at 0.5 m/s (target -un = -0.5): this iteration takes Pn down to "
       "2"},
  };
  const double mu = p.num(0.25, 0.2, 0.3), threshold = p.num(2.0, 1.8, 2.2);
  for (const Case& k : cases) {
    INFO(k.why);
    const double vx = p.num(1.0, 0.9, 1.1), vy = p.num(k.vy, 0.9 * k.vy, 1.1 * k.vy),
                 stored = p.num(k.stored, 0.9 * k.stored, 1.1 * k.stored);
    // Closing slower than the threshold: target 0; leaving: target -un.
    const double Pn = stored + ((vy > 0 ? -vy : 0.0) - vy) / w[0];
    Mat2X v(2, 1);
    v << vx, vy;
    Contact c = make_contact(0, -1, up, mu, stored);
    prepare_contact(w, v, 0.0, threshold, c);
    solve_contact(w, c, v);
    wbtest::require_near(c.Pn, Pn, kTol, "the normal total after step 1");
    wbtest::require_near(c.Pt, mu * Pn, kTol,
                         "m |ut| = 2 N s > mu Pn: Pt = mu Pn with the NEW normal total (step 1 "
                         "before step 2), not the total the iteration started with");
    wbtest::require_near(v(0, 0), vx - mu * Pn * w[0], kTol, "v.x = 1 - mu Pn / m");
  }
}

// Five touching discs; each step gravity, then prepare and warm start every contact and 10
// iterations, the totals kept to the next step. The floor carries the weight of five, each
// disc-disc contact the weight of those above; nothing moves. Held-out: the column starts from
// those totals (each contact's k g h, what the public run converges to) for 60 steps, the share
// of calls the public test's 500 have; the masses and h stay the published ones: 1 kg is the
// largest number of the column's calls, and with 1 kg and g h = 0.00981 most of their velocities
// come out exactly 0 (short decimals): drawn ones, or the public run's first steps, would set the
// held-out calls apart (tools/adversary --inputs). Masses are tried by every other scenario.
void column(const wbtest::Params& p) {
  constexpr double kRestTol = 1e-12;  // m/s: rounding of ~500 steps of g h
  const int n = 5;
  const double h = 1e-3;
  const VecX w = VecX::Ones(n);
  Mat2X v = Mat2X::Zero(2, n);
  std::vector<Contact> contacts;
  contacts.push_back(make_contact(0, -1, Vec2(0, 1)));
  for (int k = 1; k < n; ++k) contacts.push_back(make_contact(k, k - 1, Vec2(0, 1)));
  if (p.held_out()) {
    for (int k = 0; k < n; ++k) contacts[std::size_t(k)].Pn = (n - k) * kG * h;
  }
  const long steps = p.steps(500, 60);
  for (long step = 0; step < steps; ++step) {
    v.row(1).array() -= kG * h;
    for (Contact& c : contacts) prepare_contact(w, v, 0.0, 0.05, c);
    for (const Contact& c : contacts) warm_start_contact(w, c, v);
    for (int it = 0; it < 10; ++it) {
      for (Contact& c : contacts) solve_contact(w, c, v);
    }
  }
  INFO("largest speed after " << steps << " steps " << v.colwise().norm().maxCoeff() << " m/s");
  REQUIRE(wbtest::max_abs(v.colwise().norm()) <= kRestTol);  // NaN fails
  double above = 0;                                          // the mass above contact k
  for (int k = n - 1; k >= 0; --k) {
    above += 1.0 / w[k];
    wbtest::require_near(contacts[std::size_t(k)].Pn, above * kG * h, 0.0,
                         "contact k carries the weight of the n - k discs above it, per step",
                         1e-9);
  }
}

}  // namespace

TEST_CASE("C5 prepare: effective mass and the restitution target on both sides of the threshold",
          "[collisions][C5][2pts]") {
  prepare_both_sides(wbtest::Params());
}

TEST_CASE("C5 warm start: the stored totals are applied again with their own sign",
          "[collisions][C5][2pts]") {
  warm_start(wbtest::Params());
}

TEST_CASE("C5 one iteration: the normal impulse is a clamped total that can be taken back",
          "[collisions][C5][3pts]") {
  one_iteration(wbtest::Params());
}

TEST_CASE("C5 friction: the bound is mu times the accumulated normal total",
          "[collisions][C5][3pts]") {
  friction_bound(wbtest::Params());
}

TEST_CASE("C5 friction between two particles: the pair's effective mass along t",
          "[collisions][C5][2pts]") {
  pair_friction(wbtest::Params());
}

TEST_CASE("C5 friction both ways: the total is clamped to -mu Pn and +mu Pn",
          "[collisions][C5][1pts]") {
  friction_both_ways(wbtest::Params());
}

TEST_CASE("C5 friction: the bound is the normal total of this iteration",
          "[collisions][C5][1pts]") {
  friction_new_normal(wbtest::Params());
}

TEST_CASE("C5 a column of five discs on a floor rests to rounding with the totals kept",
          "[collisions][C5][3pts]") {
  column(wbtest::Params());
}

TEST_CASE(
    "C5 held-out: random contacts are prepared warm-started and iterated as the header says",
    "[collisions][C5][held-out][3pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("C5")) {
    INFO(g.replay());
    const wbtest::Params p(g);
    prepare_both_sides(p);
    warm_start(p);
    one_iteration(p);
    friction_bound(p);
    pair_friction(p);
    friction_both_ways(p);
    friction_new_normal(p);
    column(p);
    // The held-out test's own draws, in the public tests' format (short decimals, 3 or 5
    // particles): 12 draws at random, then 4 situations every draw holds: separating faster than
    // the threshold (between two particles, then at a plane: the aim is -un whatever e), and
    // friction inside its bound between two particles of different masses, its total
    // positive, then negative (the pair's effective mass; the bound on both sides).
    for (int s = 0; s < 16; ++s) {
      const Eigen::Index np = Eigen::Index(p.pick({3.0, 5.0}));
      VecX w(np);
      for (Eigen::Index k = 0; k < np; ++k) w[k] = p.num(1.0, 0.1, 5.0);
      const int a = int(g.integer(0, np - 1));
      const int other = int((a + g.integer(1, np - 1)) % np);
      const int b = s == 13 || (s < 12 && s % 3 == 0) ? -1 : other;
      const double e = s == 12 || s == 13 ? p.num(0.5, 0.0, 0.8) : p.num(0.5, 0.0, 1.0);
      const double threshold = p.num(0.5, 0.0, 1.0);
      // Totals kept from the last step, some over-pushed (Pn large), some none.
      Contact c =
          make_contact(a, b, g.unit2(), s >= 14 ? p.num(1.0, 0.8, 1.2) : p.num(1.0, 0.0, 1.2),
                       s >= 14      ? p.num(2.5, 2.0, 3.0)
                       : s % 4 == 1 ? 0.0
                                    : p.num(1.0, 0.0, 3.0),
                       0.0);
      const Vec2 n = c.n, t = wb::perp(n);
      c.Pt = wbtest::Params::short_decimal(g.uniform(-1, 1) * c.mu * c.Pn);
      Mat2X v0(2, np);
      for (Eigen::Index k = 0; k < 2 * np; ++k) v0.data()[k] = p.num(0.0, -3.0, 3.0);
      const Vec2 u0 = Vec2(v0.col(a)) - (b < 0 ? Vec2(0, 0) : Vec2(v0.col(b)));
      if (s < 12 && s % 4 == 2) {  // closing slower than the threshold: resting, no bounce
        v0.col(a) += (-threshold * g.uniform(0.1, 0.9) - u0.dot(n)) * n;
      } else if (s == 12 || s == 13) {  // separating faster than the threshold
        v0.col(a) += (threshold + g.uniform(0.2, 2.0) - u0.dot(n)) * n;
      } else if (s >= 14) {  // closing fast, sliding slowly: the friction inside its bound
        if (w[a] == w[other]) w[a] *= 2;  // (kept different from the other particle's)
        // After the first iteration the friction total is -mass_n ut0 and its bound
        // mu mass_n (1 + e) |un0| (the warm start's impulses are taken back): |ut0| below
        // mu |un0| keeps it inside, of the sign of -ut0 (positive, then negative).
        const double closing = g.uniform(1.5, 3.0);
        const double slide = (s == 14 ? -1.0 : 1.0) * g.uniform(0.1, 0.5) * c.mu * closing;
        v0.col(a) += (-closing - u0.dot(n)) * n + (slide - u0.dot(t)) * t;
      }
      const double wa = w[a], wb = b < 0 ? 0.0 : w[b];
      auto rel = [&](const Mat2X& v) {
        return Vec2(v.col(a) - (b < 0 ? Vec2(0, 0) : Vec2(v.col(b))));
      };
      auto apply = [&](Mat2X& v, const Vec2& J) {
        v.col(a) += wa * J;
        if (b >= 0) v.col(b) -= wb * J;
      };
      INFO("contact of " << a << " with " << (b < 0 ? std::string("a plane") : std::to_string(b))
                         << ", n = " << wbtest::str(n) << ", mu = " << c.mu << ", w = "
                         << w.transpose() << ", v = " << v0 << ", e = " << e << ", threshold "
                         << threshold << ", totals Pn = " << c.Pn << ", Pt = " << c.Pt);
      // prepare_contact
      const double un0 = rel(v0).dot(n), mass_n = 1 / (wa + wb);
      const double bias = un0 > 0 ? -un0 : (-un0 > threshold ? -e * un0 : 0.0);
      Contact got = c;
      prepare_contact(w, v0, e, threshold, got);
      wbtest::require_near(got.mass_n, mass_n, 1e-12 * mass_n,
                           "mass_n = 1 / (w_a + w_b), w_b = 0 for a plane");
      wbtest::require_near(got.bias, bias, 1e-12 * (1 + std::abs(bias)),
                           "bias = -un when separating (un > 0), -e un when -un > threshold, "
                           "else 0");
      wbtest::require_near(got.Pn, c.Pn, 0.0, "prepare keeps Pn");
      wbtest::require_near(got.Pt, c.Pt, 0.0, "prepare keeps Pt");
      // warm_start_contact
      Mat2X v = v0, ve = v0;
      apply(ve, c.Pn * n + c.Pt * t);
      warm_start_contact(w, got, v);
      wbtest::require_near(v, ve, 1e-12,
                           "warm start: v_a += w_a J, v_b -= w_b J, J = Pn n + Pt t", 1e-12);
      // solve_contact, twice
      for (int it = 0; it < 2; ++it) {
        Contact ce = got;
        const double lambda = ce.mass_n * (ce.bias - rel(ve).dot(n));
        const double Pn1 = std::max(ce.Pn + lambda, 0.0);
        apply(ve, (Pn1 - ce.Pn) * n);
        const double Pt1 =
            std::clamp(ce.Pt - ce.mass_n * rel(ve).dot(t), -ce.mu * Pn1, ce.mu * Pn1);
        apply(ve, (Pt1 - ce.Pt) * t);
        const double added = Pn1 - ce.Pn;
        const double r = solve_contact(w, got, v);
        INFO("solve_contact, iteration " << it + 1);
        wbtest::require_near(r, added, 1e-12 * (1 + std::abs(added)), "returns Pn' - Pn");
        wbtest::require_near(got.Pn, Pn1, 1e-12 * (1 + Pn1),
                             "Pn' = max(Pn + mass_n (bias - un), 0): the TOTAL clamped");
        wbtest::require_near(
            got.Pt, Pt1, 1e-12 * (1 + std::abs(Pt1)),
            "Pt' = Pt - mass_n ut (after the normal impulse), clamped to +-mu Pn'");
        wbtest::require_near(v, ve, 1e-12, "the velocities after applying both increments",
                             1e-12);
      }
    }
  }
}

}  // namespace test_C5_contact_solver
