// Graded tests for C1, particle-plane response (labs/collisions/collide_plane.cpp).
// Expected values: the impulse law v' = v - (1 + e)(v.n) n for the normal part,
// the tangential part unchanged, the gap closed to 0, and the rebound height
// e^2 H of a ball dropped from H (energy (1/2) m v^2 scales by e^2 at the bounce).
#include <cmath>

#include "collide_plane.h"
#include "collisions_params.h"
#include "heldout.h"
#include "test_helpers.h"

// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace test_C1_collide_plane {

namespace {

using wb::Vec2;
using wbtest::require_near;

constexpr double kRound = 1e-13;  // a few ulps of O(1) quantities: the law is exact

// The public tests' scenarios, each a function of its parameters: the public test runs it with
// the published ones (wbtest::Params()), the held-out test with drawn ones in the same format
// (tests/common/params.h, collisions_params.h): short decimals within a fifth or so of the
// published values, the tilted normal among short-decimal unit vectors, each case kept on its
// side of every boundary it is about (touching and the threshold stay exact: an axis-aligned
// plane, binary fractions).

// A plane through p with the unit normal n ((0.6, 0.8) in the public tests: exact in binary up
// to the rounding of 0.6 and 0.8) and its tangent t.
struct Plane {
  Vec2 p, n, t;
  explicit Plane(const wbtest::Params& q)
      : p(q.num(0.3, 0.1, 0.5), q.num(-0.2, -0.4, 0.0)),
        n(collisionstest::short_unit(q, Vec2(0.6, 0.8))),
        t(wb::perp(n)) {}
  // The point at gap d and tangential offset s from the plane, for radius r.
  Vec2 at_gap(double d, double s, double r) const { return p + (r + d) * n + s * t; }
};

void tilted(const wbtest::Params& q) {
  const Plane k(q);
  const double r = q.num(0.1, 0.08, 0.12), m = q.num(2.5, 2.0, 3.0), e = q.num(0.5, 0.3, 0.7);
  const double d = q.num(-0.02, -0.03, -0.01), s = q.num(0.7, 0.5, 0.9);
  const double speed = q.num(1.5, 1.2, 1.8), slide = q.num(0.9, 0.7, 1.1);
  Vec2 x = k.at_gap(d, s, r);
  Vec2 v = -speed * k.n + slide * k.t;
  const double j = collide_plane(k.p, k.n, r, m, e, 0.0, x, v);
  INFO("plane through " << wbtest::str(k.p) << " normal " << wbtest::str(k.n) << ", r = " << r
                        << ", m = " << m << ", e = " << e);
  require_near(v, Vec2(e * speed * k.n + slide * k.t), kRound,
               "velocity after: normal part -e v.n, tangential part unchanged");
  require_near(x, k.at_gap(0.0, s, r), kRound,
               "position after: moved out along n until the gap (x - p).n - r is 0");
  require_near(j, (1 + e) * m * speed, kRound, "returned impulse j = -(1 + e) m v.n");
}

void impulse_and_momentum(const wbtest::Params& q) {
  const Plane k(q);
  const double r = q.num(0.05, 0.04, 0.06), e = q.num(0.8, 0.6, 0.9);
  const double speed = q.num(2.0, 1.5, 2.5), slide = q.num(-0.4, -0.6, -0.2);
  for (double m : {q.num(0.5, 0.4, 0.6), q.num(4.0, 3.0, 5.0)}) {
    Vec2 x = k.at_gap(q.num(-0.001, -0.002, -0.0005), q.num(-0.3, -0.4, -0.2), r);
    const Vec2 v0 = -speed * k.n + slide * k.t;
    Vec2 v = v0;
    const double j = collide_plane(k.p, k.n, r, m, e, 0.0, x, v);
    INFO("mass " << m << ", normal " << wbtest::str(k.n));
    require_near(j, (1 + e) * m * speed, kRound * m, "j = -(1 + e) m v.n (positive, in N s)");
    require_near(Vec2(m * (v - v0)), Vec2(j * k.n), kRound * m,
                 "momentum change m (v' - v) = j n: the impulse acts along +n only");
  }
}

void receding(const wbtest::Params& q) {
  const Plane k(q);
  const double r = q.num(0.2, 0.15, 0.25), m = q.num(1.5, 1.2, 1.8), s = q.num(0.25, 0.1, 0.4);
  Vec2 x = k.at_gap(q.num(-0.05, -0.08, -0.02), s, r);
  const Vec2 v0 = q.num(0.3, 0.2, 0.4) * k.n + q.num(1.1, 0.9, 1.3) * k.t;  // moving away
  Vec2 v = v0;
  const double j = collide_plane(k.p, k.n, r, m, q.num(0.9, 0.7, 1.0), 0.0, x, v);
  require_near(v, v0, kRound,
               "a receding particle keeps its velocity (no impulse pulls it back)");
  require_near(j, 0.0, kRound, "returned impulse of a receding particle");
  require_near(x, k.at_gap(0.0, s, r), kRound, "it is still moved out of the plane");
}

// An axis-aligned plane through a point on halves, a radius on quarters: a centre at exactly
// r from the plane is exact in binary (held-out: the axis, its sign, the point and r drawn).
// Halves, not eighths: the point is (0, 0) in every public call, one digit each, and 0.375
// told the held-out calls apart by their digits (tools/adversary --inputs).
struct AxisPlane {
  Vec2 p, n, t;
  explicit AxisPlane(const wbtest::Params& q)
      : p(double(q.count(0, -1, 1)) / 2.0, double(q.count(0, -1, 1)) / 2.0),
        n(collisionstest::short_unit(q, Vec2(0, 1), true)),
        t(wb::perp(n)) {}
  // A centre at gap d along n and offset s along t, each coordinate as a public test writes it.
  Vec2 at(double d, double s, double r) const {
    const Vec2 x = p + (r + d) * n + s * t;
    return Vec2(collisionstest::decimal6(x.x()), collisionstest::decimal6(x.y()));
  }
  // The same with the velocity's normal and tangential parts.
  Vec2 vel(double vn, double vt) const { return vn * n + vt * t; }
};

void clear_and_touching(const wbtest::Params& q) {
  const AxisPlane k(q);
  const double r = double(q.count(1, 1, 3)) / 4.0, m = q.num(2.0, 1.6, 2.4);  // 0.25
  // t = perp(n) = (-1, 0) in the public test: the offset -0.4 puts the centre at x = 0.4.
  const double s = q.num(-0.4, -0.6, -0.2), vt = q.num(-0.5, -0.7, -0.3);
  const double speed = q.num(3.0, 2.5, 3.5);
  {
    // Gaps of 0.01 to 0.04: the centre's coordinate r + gap keeps the public 0.26's two digits.
    const Vec2 x0 = k.at(q.num(0.01, 0.01, 0.04), s, r), v0 = k.vel(-speed, vt);
    Vec2 x = x0, v = v0;  // gap about 0.01 > 0, approaching: not yet in contact
    const double j = collide_plane(k.p, k.n, r, m, 1.0, 0.0, x, v);
    INFO("plane through " << wbtest::str(k.p) << " normal " << wbtest::str(k.n) << ", r = " << r
                          << ", x = " << wbtest::str(x0));
    require_near(x, x0, 0.0, "position of a particle not in contact");
    require_near(v, v0, 0.0, "velocity of a particle not in contact");
    require_near(j, 0.0, 0.0, "impulse on a particle not in contact");
  }
  Vec2 x = k.at(0.0, s, r), v = k.vel(-speed, vt);  // gap exactly 0 (all values exact in binary)
  INFO("plane through " << wbtest::str(k.p) << " normal " << wbtest::str(k.n) << ", r = " << r
                        << ", x = " << wbtest::str(x) << " (touching exactly)");
  const double j = collide_plane(k.p, k.n, r, m, 1.0, 0.0, x, v);
  require_near(v, k.vel(speed, vt), kRound,
               "touching (gap 0) and approaching: it bounces, e = 1");
  require_near(j, 2 * m * speed, kRound, "j = -(1 + e) m v.n = 2 m |v.n|");
}

// A ball resting on the floor under gravity, semi-implicit Euler: gravity adds g h of approach
// each step, below rest_speed, so every contact is resting: the ball must neither bounce
// (jitter) nor gain energy. Held-out: 560 steps, as many calls as the held-out rebound makes
// (about 1.7 s / h): tools/adversary --inputs samples 300 calls of each public test, so the
// resting run and the rebound weigh the same among the public calls, and must among the
// held-out ones (with 300 steps the resting run's 3 kg told them apart by the largest number).
void resting(const wbtest::Params& q) {
  const AxisPlane k(q);
  const double r = q.num(0.1, 0.08, 0.12), m = q.num(3.0, 2.5, 3.5), e = q.num(0.9, 0.7, 1.0),
               rest = q.num(0.05, 0.04, 0.06);
  {
    const double slow = q.num(0.03, 0.02, 0.035), fast = q.num(0.5, 0.4, 0.6);
    const double vt = q.num(-0.2, -0.3, -0.1), d = q.num(-0.001, -0.002, -0.0005);
    Vec2 x = k.at(d, 0.0, r), v = k.vel(-slow, vt);  // slower than rest_speed: e = 0
    const double j = collide_plane(k.p, k.n, r, m, e, rest, x, v);
    require_near(v, k.vel(0.0, vt), kRound, "approach slower than rest_speed: e = 0, v.n = 0");
    require_near(j, m * slow, kRound,
                 "a resting contact still returns its impulse j = -(1 + 0) m v.n = m |v.n|");
    Vec2 x2 = k.at(d, 0.0, r), v2 = k.vel(-fast, vt);  // faster: bounces with e
    collide_plane(k.p, k.n, r, m, e, rest, x2, v2);
    require_near(v2, k.vel(e * fast, vt), kRound,
                 "approach faster than rest_speed: v.n = e |v.n|");
  }
  {
    // At the threshold: -v.n = rest_speed exactly is not below it (bounces with e);
    // just below it rests. A tangential speed of 2 m/s (above rest_speed) and the
    // momentum m |v.n| (also above) do not enter the decision.
    const double slow = q.num(0.5, 0.4, 0.6), below = collisionstest::decimal6(slow - 0.001);
    const double vt = q.num(-2.0, -2.5, -1.5), d = q.num(-0.01, -0.02, -0.005);
    Vec2 x = k.at(d, 0.0, r), v = k.vel(-slow, vt);
    double j = collide_plane(k.p, k.n, r, m, e, slow, x, v);
    INFO("rest_speed " << slow << ", normal " << wbtest::str(k.n));
    require_near(v, k.vel(e * slow, vt), kRound,
                 "approach speed equal to rest_speed: not resting, rebounds with e");
    require_near(j, (1 + e) * m * slow, kRound, "j = -(1 + e) m v.n at the threshold");
    x = k.at(d, 0.0, r);
    v = k.vel(-below, vt);
    j = collide_plane(k.p, k.n, r, m, e, slow, x, v);
    require_near(v, k.vel(0.0, vt), kRound,
                 "approach speed 0.001 below rest_speed (compare the normal speed "
                 "-v.n, not |v| or m |v.n|): resting, e = 0");
    require_near(j, m * below, kRound, "resting: j = -m v.n");
  }
  // The run keeps the published mass and step, held-out too: 3 kg is the largest number of
  // its calls, and g h = 0.00981 their velocity's format (a drawn h makes g h a short decimal
  // now and then): either drawn would set the held-out calls apart. The plane, the radius, e,
  // rest_speed and the start are drawn; the mass is tried by every other scenario.
  const double g = 9.81, h = 1e-3, m_run = 3.0;
  Vec2 x = k.at(0.0, q.num(-0.3, -0.5, -0.1), r), v(0.0, 0.0);
  const double x0n = (x - k.p).dot(k.n);
  double highest = x0n, fastest = 0;
  const long steps = q.steps(100000, 560);
  for (long i = 0; i < steps; ++i) {
    v -= g * h * k.n;
    x += h * v;
    collide_plane(k.p, k.n, r, m_run, e, rest, x, v);
    highest = wbtest::worst_of(highest, (x - k.p).dot(k.n));
    fastest = wbtest::worst_of(fastest, v.norm());
  }
  constexpr double kRestTol = 1e-12;  // rounding of x -= d n at a height of 0.1 m
  require_near(highest, r, kRestTol, "highest centre over the run: resting, never above r");
  require_near((x - k.p).dot(k.n), r, kRestTol, "final height: still resting on the floor");
  require_near(fastest, 0.0, kRestTol, "largest speed after a step's contact: 0 (no jitter)");
}

// A ball dropped from H rebounds to e^2 H. Held-out: H, the ball, e and a step 20 to 40 times
// the published one (the share of calls the public test's 10^4 have), the tolerance with it.
void rebound(const wbtest::Params& q) {
  const AxisPlane k(q);
  const double r = q.num(0.05, 0.04, 0.06), m = q.num(0.7, 0.5, 0.9), g = 9.81,
               h = q.num(1e-4, 2e-3, 4e-3), H = q.num(1.0, 0.8, 1.2);
  for (double e : {1.0, q.num(0.7, 0.5, 0.9)}) {
    Vec2 x = k.at(H, 0.0, r), v(0.0, 0.0);
    bool bounced = false;
    double apex = 0, t = 0;
    while (t < 3.0) {  // drop (0.45 s), bounce, rise to the apex (<= 0.45 s)
      v -= g * h * k.n;
      x += h * v;
      t += h;
      if (collide_plane(k.p, k.n, r, m, e, 0.0, x, v) > 0) bounced = true;
      if (bounced) apex = wbtest::worst_of(apex, (x - k.p).dot(k.n) - r);
      if (bounced && v.dot(k.n) < 0) break;  // past the apex
    }
    INFO("restitution " << e << ", H = " << H << ", h = " << h);
    REQUIRE(bounced);
    // Step-size error: semi-implicit Euler loses g^2 h^2 / 2 of specific energy
    // per step (g h T / 2 in height over the time T flown); the contact is found
    // up to |v| h deep, and the apex is sampled within |v| h: each bounded by
    // v_max h with v_max = sqrt(2 g H).
    const double tol = h * (g * t / 2 + 2 * std::sqrt(2 * g * H));
    require_near(apex, e * e * H, tol, "rebound height e^2 H (kinetic energy scales by e^2)");
  }
}

// Fast particles tunnel: the centre can be on the solid side, (x - p).n < 0.
// The gap d = (x - p).n - r is then below -r, and the same law applies.
void deep(const wbtest::Params& q) {
  const Plane k(q);
  const double depth = q.num(0.35, 0.25, 0.45), s = q.num(0.4, 0.2, 0.6);
  for (double r : {q.num(0.1, 0.08, 0.12), 0.0}) {
    const double m = q.num(1.5, 1.2, 1.8), e = q.num(0.5, 0.3, 0.7);
    const double speed = q.num(2.0, 1.5, 2.5), slide = q.num(0.3, 0.2, 0.4);
    Vec2 x = k.at_gap(-depth - r, s, r);  // centre `depth` below the plane
    Vec2 v = -speed * k.n + slide * k.t;
    const double j = collide_plane(k.p, k.n, r, m, e, 0.0, x, v);
    INFO("radius " << r << ", centre " << depth << " below the plane, normal "
                   << wbtest::str(k.n));
    require_near(x, k.at_gap(0.0, s, r), kRound,
                 "moved out along +n until it just touches: x - d n with d = (x - p).n - r < -r");
    require_near(v, Vec2(e * speed * k.n + slide * k.t), kRound,
                 "normal velocity -e v.n after, tangential kept");
    require_near(j, (1 + e) * m * speed, kRound, "j = -(1 + e) m v.n");
    // Receding but still deep: pushed out along +n, no impulse.
    x = k.at_gap(-depth - r, s, r);
    const double away = q.num(0.5, 0.3, 0.7);
    v = away * k.n;
    require_near(collide_plane(k.p, k.n, r, m, e, 0.0, x, v), 0.0, kRound,
                 "impulse on a receding particle below the plane");
    require_near(x, k.at_gap(0.0, s, r), kRound, "a receding deep particle is moved out too");
    require_near(v, Vec2(away * k.n), kRound, "a receding deep particle keeps its velocity");
  }
}

}  // namespace

TEST_CASE(
    "C1 collide_plane: tilted plane reverses the normal velocity times e and keeps the "
    "tangential one",
    "[collisions][C1][4pts]") {
  tilted(wbtest::Params());
}

TEST_CASE(
    "C1 collide_plane: the impulse j = -(1 + e) m v.n is positive and changes the "
    "momentum by j n",
    "[collisions][C1][2pts]") {
  impulse_and_momentum(wbtest::Params());
}

TEST_CASE("C1 collide_plane: a receding particle is moved out but gets no impulse",
          "[collisions][C1][3pts]") {
  receding(wbtest::Params());
}

TEST_CASE(
    "C1 collide_plane: a particle clear of the plane is left alone and touching counts "
    "as contact",
    "[collisions][C1][3pts]") {
  clear_and_touching(wbtest::Params());
}

TEST_CASE(
    "C1 collide_plane: below rest_speed the contact is resting and a ball on a floor "
    "stays put for 10^5 steps",
    "[collisions][C1][3pts]") {
  resting(wbtest::Params());
}

TEST_CASE("C1 collide_plane: the rebound height of a dropped ball is e^2 times the drop height",
          "[collisions][C1][3pts]") {
  rebound(wbtest::Params());
}

TEST_CASE(
    "C1 collide_plane: a centre below the plane deeper than the radius is pushed out and "
    "bounces",
    "[collisions][C1][3pts]") {
  deep(wbtest::Params());
}

TEST_CASE("C1 held-out: random planes and particles in and out of contact follow the header",
          "[collisions][C1][held-out][4pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("C1")) {
    INFO(g.replay());
    const wbtest::Params q(g);
    tilted(q);
    impulse_and_momentum(q);
    receding(q);
    clear_and_touching(q);
    resting(q);
    rebound(q);
    deep(q);
    // Then the held-out test's own draws, in the public tests' format (short decimals, the
    // tilted normals among short-decimal unit vectors):
    // Every situation in every draw, with random values: the gap (touching exactly,
    // penetrating, the centre below the plane, clear) times the normal motion (approaching
    // fast, approaching slower than rest_speed, at exactly rest_speed, receding). A plane is
    // axis-aligned with short binary fractions where a boundary must be exact (touching, an
    // approach speed of exactly rest_speed), tilted at random otherwise.
    for (int gap_kind = 0; gap_kind < 4; ++gap_kind) {
      for (int motion = 0; motion < 4; ++motion) {
        const bool exact = gap_kind == 0 || motion == 2 || g.coin();
        const Vec2 n = exact ? (g.coin() ? Vec2(0, g.sign()) : Vec2(g.sign(), 0))
                             : collisionstest::short_unit(q, Vec2(0.6, 0.8));
        const Vec2 t(-n.y(), n.x());
        const Vec2 p = exact ? Vec2(g.integer(-8, 8) / 8.0, g.integer(-8, 8) / 8.0)
                             : Vec2(q.num(0.0, -2.0, 2.0), q.num(0.0, -2.0, 2.0));
        const double r = exact ? g.integer(1, 8) / 8.0 : q.num(0.5, 0.05, 1.0);
        // A mass away from 1 and a restitution away from 0, so that forgetting either shows.
        const double m = g.coin() ? q.num(0.5, 0.1, 0.8) : q.num(2.0, 1.25, 5.0);
        const double e = q.num(0.5, 0.2, 1.0);
        const double rest_speed = g.integer(1, 8) / 8.0;
        const double gap = gap_kind == 0   ? 0.0
                           : gap_kind == 1 ? -g.uniform(0.1, 0.9) * r
                           : gap_kind == 2 ? -(1.0 + g.uniform(0.2, 1.0)) * r
                                           : g.uniform(0.1, 0.5) * r;
        const Vec2 x0 =
            p + (r + gap) * n + (exact ? g.integer(-16, 16) / 8.0 : q.num(0.0, -2.0, 2.0)) * t;
        const double vn = motion == 0 ? -q.num(3.0, 1.5, 5.0)
                          : motion == 1
                              ? -wbtest::Params::short_decimal(rest_speed * g.uniform(0.2, 0.95))
                          : motion == 2 ? -rest_speed
                                        : q.num(1.0, 0.2, 2.0);
        // A sliding speed above rest_speed: the resting test must read -v.n, not |v|.
        const Vec2 v0 =
            vn * n + g.sign() * (exact ? g.integer(10, 24) / 8.0 : q.num(2.0, 1.25, 3.0)) * t;
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
