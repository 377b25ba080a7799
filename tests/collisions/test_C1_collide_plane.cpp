// Graded tests for C1, particle-plane response (labs/collisions/collide_plane.cpp).
// Expected values: the impulse law v' = v - (1 + e)(v.n) n for the normal part,
// the tangential part unchanged, the gap closed to 0, and the rebound height
// e^2 H of a ball dropped from H (energy (1/2) m v^2 scales by e^2 at the bounce).
#include <cmath>

#include "collide_plane.h"
#include "heldout.h"
#include "test_helpers.h"

// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace test_C1_collide_plane {

namespace {

using wb::Vec2;
using wbtest::require_near;

constexpr double kRound = 1e-13;  // a few ulps of O(1) quantities: the law is exact

// A plane through p with the unit normal n = (0.6, 0.8) (exact in binary up to
// rounding of 0.6 and 0.8) and its tangent t.
const Vec2 kP(0.3, -0.2);
const Vec2 kN(0.6, 0.8);
const Vec2 kT(-0.8, 0.6);

// The point at gap d and tangential offset s from the plane, for radius r.
Vec2 at_gap(double d, double s, double r) { return kP + (r + d) * kN + s * kT; }

}  // namespace

TEST_CASE(
    "C1 collide_plane: tilted plane reverses the normal velocity times e and keeps the "
    "tangential one",
    "[collisions][C1][4pts]") {
  const double r = 0.1, m = 2.5, e = 0.5;
  Vec2 x = at_gap(-0.02, 0.7, r);
  Vec2 v = -1.5 * kN + 0.9 * kT;
  const double j = collide_plane(kP, kN, r, m, e, 0.0, x, v);
  require_near(v, Vec2(0.75 * kN + 0.9 * kT), kRound,
               "velocity after: normal part -e v.n = 0.75, tangential part unchanged 0.9");
  require_near(x, at_gap(0.0, 0.7, r), kRound,
               "position after: moved out along n until the gap (x - p).n - r is 0");
  require_near(j, (1 + e) * m * 1.5, kRound, "returned impulse j = -(1 + e) m v.n");
}

TEST_CASE(
    "C1 collide_plane: the impulse j = -(1 + e) m v.n is positive and changes the "
    "momentum by j n",
    "[collisions][C1][2pts]") {
  const double r = 0.05, e = 0.8;
  for (double m : {0.5, 4.0}) {
    Vec2 x = at_gap(-0.001, -0.3, r);
    const Vec2 v0 = -2.0 * kN - 0.4 * kT;
    Vec2 v = v0;
    const double j = collide_plane(kP, kN, r, m, e, 0.0, x, v);
    INFO("mass " << m);
    require_near(j, (1 + e) * m * 2.0, kRound * m, "j = -(1 + e) m v.n (positive, in N s)");
    require_near(Vec2(m * (v - v0)), Vec2(j * kN), kRound * m,
                 "momentum change m (v' - v) = j n: the impulse acts along +n only");
  }
}

TEST_CASE("C1 collide_plane: a receding particle is moved out but gets no impulse",
          "[collisions][C1][3pts]") {
  const double r = 0.2, m = 1.5;
  Vec2 x = at_gap(-0.05, 0.25, r);
  const Vec2 v0 = 0.3 * kN + 1.1 * kT;  // moving away from the plane
  Vec2 v = v0;
  const double j = collide_plane(kP, kN, r, m, 0.9, 0.0, x, v);
  require_near(v, v0, kRound,
               "a receding particle keeps its velocity (no impulse pulls it back)");
  require_near(j, 0.0, kRound, "returned impulse of a receding particle");
  require_near(x, at_gap(0.0, 0.25, r), kRound, "it is still moved out of the plane");
}

TEST_CASE(
    "C1 collide_plane: a particle clear of the plane is left alone and touching counts "
    "as contact",
    "[collisions][C1][3pts]") {
  const Vec2 p(0, 0), n(0, 1);
  const double r = 0.25, m = 2.0;
  {
    Vec2 x(0.4, 0.26), v(0.5, -3.0);  // gap 0.01 > 0, approaching: not yet in contact
    const double j = collide_plane(p, n, r, m, 1.0, 0.0, x, v);
    require_near(x, Vec2(0.4, 0.26), 0.0, "position of a particle not in contact");
    require_near(v, Vec2(0.5, -3.0), 0.0, "velocity of a particle not in contact");
    require_near(j, 0.0, 0.0, "impulse on a particle not in contact");
  }
  Vec2 x(0.4, 0.25), v(0.5, -3.0);  // gap exactly 0 (all values exact in binary)
  const double j = collide_plane(p, n, r, m, 1.0, 0.0, x, v);
  require_near(v, Vec2(0.5, 3.0), kRound, "touching (gap 0) and approaching: it bounces, e = 1");
  require_near(j, 12.0, kRound, "j = -(1 + e) m v.n = 2 * 2 * 3");
}

TEST_CASE(
    "C1 collide_plane: below rest_speed the contact is resting and a ball on a floor "
    "stays put for 10^5 steps",
    "[collisions][C1][3pts]") {
  const Vec2 p(0, 0), n(0, 1);
  const double r = 0.1, m = 3.0, e = 0.9, rest = 0.05;
  {
    Vec2 x(0.0, 0.099), v(0.2, -0.03);  // slower than rest_speed: e = 0
    const double j = collide_plane(p, n, r, m, e, rest, x, v);
    require_near(v, Vec2(0.2, 0.0), kRound, "approach at 0.03 m/s < rest_speed: e = 0, v.n = 0");
    require_near(j, 3.0 * 0.03, kRound,
                 "a resting contact still returns its impulse j = -(1 + 0) m v.n = m 0.03");
    Vec2 x2(0.0, 0.099), v2(0.2, -0.5);  // faster: bounces with e
    collide_plane(p, n, r, m, e, rest, x2, v2);
    require_near(v2, Vec2(0.2, 0.45), kRound, "approach at 0.5 m/s > rest_speed: v.n = e 0.5");
  }
  {
    // At the threshold: -v.n = rest_speed exactly is not below it (bounces with e);
    // just below it rests. A tangential speed of 2 m/s (above rest_speed) and the
    // momentum m |v.n| = 1.5 (also above) do not enter the decision.
    const double slow = 0.5;
    Vec2 x(0.0, 0.09), v(2.0, -0.5);
    double j = collide_plane(p, n, r, m, e, slow, x, v);
    require_near(v, Vec2(2.0, 0.45), kRound,
                 "approach speed equal to rest_speed 0.5: not resting, rebounds with e = 0.9");
    require_near(j, 1.9 * 3.0 * 0.5, kRound, "j = -(1 + e) m v.n at the threshold");
    x = Vec2(0.0, 0.09);
    v = Vec2(2.0, -0.499);
    j = collide_plane(p, n, r, m, e, slow, x, v);
    require_near(v, Vec2(2.0, 0.0), kRound,
                 "approach speed 0.499 just below rest_speed 0.5 (compare the normal speed "
                 "-v.n, not |v| or m |v.n|): resting, e = 0");
    require_near(j, 3.0 * 0.499, kRound, "resting: j = -m v.n");
  }
  // A ball resting on the floor under gravity, semi-implicit Euler: gravity
  // adds g h = 0.00981 m/s of approach each step, below rest_speed, so every
  // contact is resting: the ball must neither bounce (jitter) nor gain energy.
  const double g = 9.81, h = 1e-3;
  Vec2 x(0.3, r), v(0.0, 0.0);
  double highest = x.y(), fastest = 0;
  for (int k = 0; k < 100000; ++k) {
    v.y() -= g * h;
    x += h * v;
    collide_plane(p, n, r, m, e, rest, x, v);
    highest = wbtest::worst_of(highest, x.y());
    fastest = wbtest::worst_of(fastest, v.norm());
  }
  constexpr double kRestTol = 1e-12;  // rounding of x -= d n at a height of 0.1 m
  require_near(highest, r, kRestTol, "highest centre over 10^5 steps: resting, never above r");
  require_near(x.y(), r, kRestTol, "final height: still resting on the floor");
  require_near(fastest, 0.0, kRestTol, "largest speed after a step's contact: 0 (no jitter)");
}

TEST_CASE("C1 collide_plane: the rebound height of a dropped ball is e^2 times the drop height",
          "[collisions][C1][3pts]") {
  const Vec2 p(0, 0), n(0, 1);
  const double r = 0.05, m = 0.7, g = 9.81, h = 1e-4, H = 1.0;
  for (double e : {1.0, 0.7}) {
    Vec2 x(0.0, r + H), v(0.0, 0.0);
    bool bounced = false;
    double apex = 0, t = 0;
    while (t < 3.0) {  // drop (0.45 s), bounce, rise to the apex (<= 0.45 s)
      v.y() -= g * h;
      x += h * v;
      t += h;
      if (collide_plane(p, n, r, m, e, 0.0, x, v) > 0) bounced = true;
      if (bounced) apex = wbtest::worst_of(apex, x.y() - r);
      if (bounced && v.y() < 0) break;  // past the apex
    }
    INFO("restitution " << e);
    REQUIRE(bounced);
    // Step-size error: semi-implicit Euler loses g^2 h^2 / 2 of specific energy
    // per step (g h T / 2 in height over the time T flown); the contact is found
    // up to |v| h deep, and the apex is sampled within |v| h: each bounded by
    // v_max h with v_max = sqrt(2 g H).
    const double tol = h * (g * t / 2 + 2 * std::sqrt(2 * g * H));
    require_near(apex, e * e * H, tol, "rebound height e^2 H (kinetic energy scales by e^2)");
  }
}

TEST_CASE(
    "C1 collide_plane: a centre below the plane deeper than the radius is pushed out and "
    "bounces",
    "[collisions][C1][3pts]") {
  // Fast particles tunnel: the centre can be on the solid side, (x - p).n < 0.
  // The gap d = (x - p).n - r is then below -r, and the same law applies.
  for (double r : {0.1, 0.0}) {
    const double m = 1.5, e = 0.5;
    Vec2 x = at_gap(-0.35 - r, 0.4, r);  // centre 0.35 m below the plane
    Vec2 v = -2.0 * kN + 0.3 * kT;
    const double j = collide_plane(kP, kN, r, m, e, 0.0, x, v);
    INFO("radius " << r << ", centre 0.35 below the plane");
    require_near(x, at_gap(0.0, 0.4, r), kRound,
                 "moved out along +n until it just touches: x - d n with d = (x - p).n - r < -r");
    require_near(v, Vec2(1.0 * kN + 0.3 * kT), kRound,
                 "normal velocity -e v.n = 1.0 after, tangential kept");
    require_near(j, (1 + e) * m * 2.0, kRound, "j = -(1 + e) m v.n");
    // Receding but still deep: pushed out along +n, no impulse.
    x = at_gap(-0.35 - r, 0.4, r);
    v = 0.5 * kN;
    require_near(collide_plane(kP, kN, r, m, e, 0.0, x, v), 0.0, kRound,
                 "impulse on a receding particle below the plane");
    require_near(x, at_gap(0.0, 0.4, r), kRound, "a receding deep particle is moved out too");
    require_near(v, Vec2(0.5 * kN), kRound, "a receding deep particle keeps its velocity");
  }
}

TEST_CASE("C1 held-out: random planes and particles in and out of contact follow the header",
          "[collisions][C1][held-out][4pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("C1")) {
    INFO(g.replay());
    // Every situation in every draw, with random values: the gap (touching exactly,
    // penetrating, the centre below the plane, clear) times the normal motion (approaching
    // fast, approaching slower than rest_speed, at exactly rest_speed, receding). A plane is
    // axis-aligned with short binary fractions where a boundary must be exact (touching, an
    // approach speed of exactly rest_speed), tilted at random otherwise.
    for (int gap_kind = 0; gap_kind < 4; ++gap_kind) {
      for (int motion = 0; motion < 4; ++motion) {
        const bool exact = gap_kind == 0 || motion == 2 || g.coin();
        const Vec2 n = exact ? (g.coin() ? Vec2(0, g.sign()) : Vec2(g.sign(), 0)) : g.unit2();
        const Vec2 t(-n.y(), n.x());
        const Vec2 p =
            exact ? Vec2(g.integer(-8, 8) / 8.0, g.integer(-8, 8) / 8.0) : Vec2(g.vec2(-2, 2));
        const double r = exact ? g.integer(1, 8) / 8.0 : g.uniform(0.05, 1.0);
        // A mass away from 1 and a restitution away from 0, so that forgetting either shows.
        const double m = g.coin() ? g.uniform(0.1, 0.8) : g.uniform(1.25, 5.0);
        const double e = g.uniform(0.2, 1.0);
        const double rest_speed = g.integer(1, 8) / 8.0;
        const double gap = gap_kind == 0   ? 0.0
                           : gap_kind == 1 ? -g.uniform(0.1, 0.9) * r
                           : gap_kind == 2 ? -(1.0 + g.uniform(0.2, 1.0)) * r
                                           : g.uniform(0.1, 0.5) * r;
        const Vec2 x0 =
            p + (r + gap) * n + (exact ? g.integer(-16, 16) / 8.0 : g.uniform(-2, 2)) * t;
        const double vn = motion == 0   ? -g.uniform(1.5, 5.0)
                          : motion == 1 ? -rest_speed * g.uniform(0.2, 0.95)
                          : motion == 2 ? -rest_speed
                                        : g.uniform(0.2, 2.0);
        // A sliding speed above rest_speed: the resting test must read -v.n, not |v|.
        const Vec2 v0 =
            vn * n + g.sign() * (exact ? g.integer(10, 24) / 8.0 : g.uniform(1.25, 3.0)) * t;
        Vec2 xe = x0, ve = v0;
        double je = 0;
        const double d = (x0 - p).dot(n) - r, vne = v0.dot(n);
        if (d <= 0) {
          if (vne < 0) {
            const double ee = -vne < rest_speed ? 0.0 : e;
            je = -(1 + ee) * m * vne;
            ve = v0 + (je / m) * n;
          }
          xe = x0 - d * n;
        }
        Vec2 x = x0, v = v0;
        const double j = collide_plane(p, n, r, m, e, rest_speed, x, v);
        INFO("plane through " << wbtest::str(p) << " normal " << wbtest::str(n) << ", r = " << r
                              << ", m = " << m << ", e = " << e << ", rest_speed = " << rest_speed
                              << "; x = " << wbtest::str(x0) << " (gap " << d
                              << "), v = " << wbtest::str(v0) << " (v.n = " << vne << ")");
        const double scale = 1.0 + x0.norm() + v0.norm();
        wbtest::require_near(j, je, 1e-12 * (1.0 + m * std::abs(vne)),
                             "the impulse j = -(1 + e) m v.n when in contact and approaching, "
                             "e = 0 when -v.n < rest_speed, else 0");
        wbtest::require_near(v, ve, 1e-12 * scale, "v + (j / m) n");
        wbtest::require_near(x, xe, 1e-12 * scale, "in contact: moved out along n to just touch");
      }
    }
  }
}

}  // namespace test_C1_collide_plane
