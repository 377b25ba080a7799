// Graded tests for TODO(R6), contact impulses against a plane
// (labs/rigid/plane_contact.cpp). Expected values: Newton's restitution law at
// the contact point, conservation of angular momentum about the point where an
// impulse acts, the classic 5/7 rolling speed of a sphere, Coulomb's bound.
#include <cmath>
#include <vector>

#include "plane_contact.h"
#include "rigid_test_helpers.h"

// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace test_R6_plane_contact {

using namespace rigidtest;

namespace {

// One impulse: a few products of numbers ~1-10.
constexpr double kImpulseTol = 1e-12;

const Vec3 kUp(0, 0, 1);

Vec3 point_velocity(const Body& b, const Vec3& p) { return b.v + b.omega.cross(p - b.x); }

// A tilted box above the floor, its lowest corner p touching it.
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

}  // namespace

TEST_CASE("R6 normal impulse: the contact point leaves at -e times its approach speed",
          "[rigid][R6][5pts]") {
  for (double e : {0.0, 0.4, 1.0}) {
    INFO("restitution e = " << e);
    Vec3 p;
    Body b = tilted_box(p);
    const double vn = point_velocity(b, p).dot(kUp);
    REQUIRE(vn < 0);  // the corner approaches the floor
    const Vec3 mv0 = b.m * b.v;
    const double jn = contact_impulse(b, p, kUp, e, 0.0);
    require_near(point_velocity(b, p).dot(kUp), -e * vn, kImpulseTol,
                 "Newton's law: normal velocity of the contact point after = -e * before");
    require_near(jn, (b.m * b.v - mv0).dot(kUp), kImpulseTol,
                 "the returned jn is the change of momentum along n");
  }
  // The same corner moving away from the floor: no impulse.
  Vec3 p;
  Body b = tilted_box(p);
  b.v = -b.v;
  b.omega = -b.omega;
  const Body before = b;
  require_near(contact_impulse(b, p, kUp, 0.5, 0.5), 0.0, 0.0,
               "a separating point gets no impulse");
  require_near(b.v, before.v, 0.0, "separating: v unchanged");
  require_near(b.omega, before.omega, 0.0, "separating: omega unchanged");
}

TEST_CASE("R6 frictionless impulse: angular momentum about the contact point is conserved",
          "[rigid][R6][4pts]") {
  // An impulse J at p changes m v by J and I omega by (p - x) x J: the angular
  // momentum about p, I omega + (x - p) x m v, does not change; without friction
  // J is along n, so the tangential momentum does not change either.
  Vec3 p;
  Body b = tilted_box(p);
  const Vec3 L0 = momentum_about(b, p), mv0 = b.m * b.v;
  contact_impulse(b, p, kUp, 0.3, 0.0);
  require_near(momentum_about(b, p), L0, kImpulseTol,
               "angular momentum about the contact point I omega + (x - p) x m v");
  const Vec3 dmv = b.m * b.v - mv0;
  require_near(Vec3(dmv.x(), dmv.y(), 0.0), Vec3::Zero(), kImpulseTol,
               "no friction: momentum changes only along the normal");
  INFO("the impulse changed m v along the normal (up) by " << dmv.z()
                                                           << ", expected > 0: a contact only "
                                                              "pushes, along +n (a sign error?)");
  REQUIRE(dmv.z() > 0);
}

TEST_CASE("R6 friction: a sliding sphere rolls at 5/7 of its speed or loses mu jn / m",
          "[rigid][R6][4pts]") {
  // A sphere (I = 2/5 m r^2) lands with tangential speed u and no spin. The normal
  // impulse is jn = (1 + e) m |vn| (r is along n: no turning). Sticking needs
  // jt = u / (1/m + r^2 / I) = 2/7 m u, leaving v = 5/7 u and a rolling contact;
  // when mu jn is smaller, the sphere slides and loses mu jn / m of its speed.
  const double m = 2.0, r = 0.5, u = 3.0, vn = -2.0, e = 0.5;
  const double jn = (1 + e) * m * -vn;
  const Vec3 I = Vec3::Constant(0.4 * m * r * r);
  {
    Body s = make_body(m, I, quat(1, 0, 0, 0), Vec3::Zero(), Vec3(0, 0, r), Vec3(u, 0, vn));
    const Vec3 p(0, 0, 0);
    require_near(contact_impulse(s, p, kUp, e, 1.0), jn, kImpulseTol, "jn = (1 + e) m |vn|");
    require_near(s.v, Vec3(5.0 / 7.0 * u, 0.0, -e * vn), kImpulseTol,
                 "mu = 1 is enough to stick: v = 5/7 u along the floor, -e vn up");
    require_near(point_velocity(s, p), Vec3(0.0, 0.0, -e * vn), kImpulseTol,
                 "sticking: the contact point no longer slides");
  }
  {
    const double mu = 0.1;
    Body s = make_body(m, I, quat(1, 0, 0, 0), Vec3::Zero(), Vec3(0, 0, r), Vec3(u, 0, vn));
    contact_impulse(s, Vec3(0, 0, 0), kUp, e, mu);
    require_near(s.v, Vec3(u - mu * jn / m, 0.0, -e * vn), kImpulseTol,
                 "mu = 0.1: Coulomb's bound |jt| <= mu jn, the sphere slides on");
  }
}

TEST_CASE("R6 resolve: a penetrating body is pushed out by its deepest point",
          "[rigid][R6][2pts]") {
  // A box 1 m high, 0.25 m into the floor and already moving up: no impulse, but
  // the deepest corner comes back to the plane.
  const Vec3 size(2.0, 1.5, 1.0);
  Body b = make_body(1.0, Vec3(1, 2, 3), quat(1, 0, 0, 0), Vec3::Zero(), Vec3(0, 0, 0.25),
                     Vec3(0.0, 0.0, 1.0));
  resolve_plane_contact(b, corners(b, size), Vec3::Zero(), kUp, 0.5, 0.5);
  require_near(b.x, Vec3(0, 0, 0.5), kImpulseTol, "x moves up by the deepest penetration 0.25 m");
  require_near(b.v, Vec3(0, 0, 1), 0.0, "a separating body keeps its velocity");
}

TEST_CASE("R6 resolve: a box landing flat with e = 0 stops without sinking through the floor",
          "[rigid][R6][3pts]") {
  // Dropped flat from 1 m above its resting height: it hits at ~4.4 m/s and, with
  // e = 0, stays. Between two detections it can go at most h |v| into the floor.
  const Vec3 size(1.0, 2.0, 0.5);
  const double h = 1e-3, g = 9.81, rest = 0.25, v_hit = std::sqrt(2 * g * 1.0);
  Body b = make_body(2.0, Vec3(2.0 / 12 * 4.25, 2.0 / 12 * 1.25, 2.0 / 12 * 5.0),
                     quat(1, 0, 0, 0), Vec3::Zero(), Vec3(0, 0, rest + 1.0));
  double lowest = b.x.z();
  for (int k = 0; k < 2000; ++k) {  // 2 s
    b.v += h * Vec3(0, 0, -g);
    resolve_plane_contact(b, corners(b, size), Vec3::Zero(), kUp, 0.0, 0.5);
    ref_position(b, h);
    lowest = std::min(lowest, b.x.z());
  }
  // Resting, the box stays within the contact slop above the plane (or one step of
  // free fall g h^2 below it); one-shot sequential impulses (no accumulated
  // impulses, handout) leave a residual motion far below one step of gravity g h.
  require_near(b.x.z(), rest + 0.5 * kContactSlop, 0.5 * kContactSlop + g * h * h,
               "resting height: half the box's 0.5 m height, within the contact slop");
  INFO("lowest centre height " << lowest << ", allowed " << rest - 1.01 * h * v_hit);
  REQUIRE(lowest >= rest - 1.01 * h * v_hit);
  require_near(b.v, Vec3::Zero(), 0.1 * g * h, "at rest: the velocity is gone (e = 0)");
  require_near(b.omega, Vec3::Zero(), 0.1 * g * h / 0.25, "at rest: no spin (it landed flat)");
}

}  // namespace test_R6_plane_contact
