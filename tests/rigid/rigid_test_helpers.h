// Helpers for the rigid lab's graded tests: bodies, a reference free motion
// written independently of the student's files, and 3D comparisons.
#pragma once
#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>
#include <string>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include "heldout.h"
#include "params.h"
#include "rigid_body.h"
#include "test_helpers.h"

namespace rigidtest {

using rigid::Body;
using rigid::Mat3;
using rigid::Vec3;

inline std::string str(const Vec3& v) { return wbtest::text(v); }

// Every component of a 3-vector: |got - expected| <= abs_tol + rel_tol |.|.
inline void require_near(const Vec3& got, const Vec3& expected, double abs_tol,
                         const std::string& what, double rel_tol = 0.0) {
  INFO(what << "\n  expected " << str(expected) << "\n  got      " << str(got) << "\n  tolerance "
            << wbtest::num(abs_tol) << " + " << wbtest::num(rel_tol) << " * |value|");
  for (int i = 0; i < 3; ++i) REQUIRE(wbtest::near(got[i], expected[i], abs_tol, rel_tol));
}

inline void require_near(const Mat3& got, const Mat3& expected, double abs_tol,
                         const std::string& what) {
  INFO(what << "\n  expected " << wbtest::text(expected) << "\n  got      " << wbtest::text(got)
            << "\n  tolerance " << wbtest::num(abs_tol) << " on every entry");
  REQUIRE(wbtest::max_abs_diff(got, expected) <= abs_tol);  // NaN anywhere fails
}

using wbtest::require_near;

// A unit quaternion from [w, x, y, z] (normalised).
inline Eigen::Quaterniond quat(double w, double x, double y, double z) {
  return Eigen::Quaterniond(w, x, y, z).normalized();
}

// The shortest rotation taking the direction of a to that of b: about a x b by the angle
// between them (half a turn about a perpendicular axis when they are opposite). Written out:
// Eigen's FromTwoVectors instantiates a whole SVD, a third of these tests' compile time.
inline Eigen::Quaterniond rotation_from_to(const Vec3& a, const Vec3& b) {
  const Vec3 u = a.normalized(), w = b.normalized();
  Vec3 axis = u.cross(w);
  const double s = axis.norm(), c = u.dot(w);
  if (s > 1e-12) return Eigen::Quaterniond(Eigen::AngleAxisd(std::atan2(s, c), axis / s));
  if (c > 0) return Eigen::Quaterniond::Identity();
  axis = std::abs(u.x()) < 0.9 ? u.cross(Vec3::UnitX()) : u.cross(Vec3::UnitY());
  return Eigen::Quaterniond(Eigen::AngleAxisd(M_PI, axis.normalized()));
}

inline Body make_body(double m, const Vec3& I_principal, const Eigen::Quaterniond& q,
                      const Vec3& omega, const Vec3& x = Vec3::Zero(),
                      const Vec3& v = Vec3::Zero()) {
  Body b;
  b.m = m;
  b.I_body = I_principal.asDiagonal();
  b.q = q;
  b.omega = omega;
  b.x = x;
  b.v = v;
  return b;
}

inline Mat3 rot(const Body& b) { return b.q.toRotationMatrix(); }

// The world inertia tensor, written here as sum over principal axes I_k a_k a_k^T
// (a_k = the body's k-th axis in the world): another way than R I R^T.
inline Mat3 inertia(const Body& b) {
  const Mat3 R = rot(b);
  Mat3 I = Mat3::Zero();
  for (int k = 0; k < 3; ++k) I += b.I_body(k, k) * R.col(k) * R.col(k).transpose();
  return I;
}
inline Mat3 inverse_inertia(const Body& b) {
  const Mat3 R = rot(b);
  Mat3 I = Mat3::Zero();
  for (int k = 0; k < 3; ++k) I += R.col(k) * R.col(k).transpose() / b.I_body(k, k);
  return I;
}

// Rotational kinetic energy and the spin angular momentum about the centre.
inline double spin_energy(const Body& b) { return 0.5 * b.omega.dot(inertia(b) * b.omega); }
inline Vec3 spin_momentum(const Body& b) { return inertia(b) * b.omega; }
// Angular velocity in the body frame.
inline Vec3 body_omega(const Body& b) { return rot(b).transpose() * b.omega; }
// Angular momentum about a point P: I omega + (x - P) x m v.
inline Vec3 momentum_about(const Body& b, const Vec3& P) {
  return spin_momentum(b) + (b.x - P).cross(b.m * b.v);
}

// Reference position update (the test's own): x += h v, q turned by h |omega|
// about omega with the half-angle formula, renormalised.
inline void ref_position(Body& b, double h) {
  b.x += h * b.v;
  const double a = b.omega.norm() * h;
  if (a > 0) {
    const Vec3 axis = b.omega.normalized() * std::sin(0.5 * a);
    const Eigen::Quaterniond dq(std::cos(0.5 * a), axis.x(), axis.y(), axis.z());
    b.q = (dq * b.q).normalized();
  }
}

using VelocityStep = std::function<void(Body&, double)>;

// A torque-free step: the velocity update under test, then the reference
// position update (so that a velocity test does not depend on R4).
inline void free_step(Body& b, double h, const VelocityStep& velocity) {
  b.f.setZero();
  b.tau.setZero();
  velocity(b, h);
  ref_position(b, h);
}

// A random body the student has never seen (held-out checks, tests/common/heldout.h): mass,
// principal moments (each smaller than the sum of the others, as for a real solid),
// orientation, position and velocities, forces and torques already accumulated. Every number
// is a short decimal, as the public tests write theirs (the orientation: a quaternion of short
// decimals, normalised, as quat() makes the public ones), so that its digits do not tell a
// held-out call from a public one (issue 42, item 3; tests/common/params.h).
inline Body random_body(wbtest::HeldOut& g) {
  const auto d = [&g](double lo, double hi) {
    return wbtest::Params::short_decimal(g.uniform(lo, hi));
  };
  const auto v3 = [&d](double lo, double hi) { return Vec3(d(lo, hi), d(lo, hi), d(lo, hi)); };
  Body b;
  b.m = d(0.2, 5.0);
  Vec3 I;
  do {
    I = v3(0.1, 3.0);
  } while (2 * std::max({I.x(), I.y(), I.z()}) >= I.sum());
  b.I_body = I.asDiagonal();
  b.q = quat(d(-1, 1), d(-1, 1), d(-1, 1), d(-1, 1));
  b.x = v3(-2, 2);
  b.v = v3(-2, 2);
  b.omega = v3(-3, 3);
  b.f = v3(-5, 5);
  b.tau = v3(-5, 5);
  return b;
}

// A published vector in a scenario of the public tests (tests/common/params.h): as published
// in the public test, each entry drawn in the held-out one, a short decimal within half of it
// either side (within 0.5 of a published 0).
inline Vec3 num3(const wbtest::Params& p, const Vec3& published) {
  Vec3 v;
  for (int i = 0; i < 3; ++i) {
    const double x = published[i], w = x == 0 ? 0.5 : 0.5 * std::abs(x);
    v[i] = p.num(x, x - w, x + w);
  }
  return v;
}

// A published orientation quat(w, x, y, z): each component drawn within 0.2 of it (held-out).
inline Eigen::Quaterniond quat_near(const wbtest::Params& p, double w, double x, double y,
                                    double z) {
  return quat(p.num(w, w - 0.2, w + 0.2), p.num(x, x - 0.2, x + 0.2), p.num(y, y - 0.2, y + 0.2),
              p.num(z, z - 0.2, z + 0.2));
}

// Every field of a body against the expected one (tolerance relative to the sizes).
inline void require_body(const Body& got, const Body& e, double tol, const std::string& what) {
  require_near(got.x, e.x, tol * (1 + e.x.norm()), what + ": x");
  require_near(got.v, e.v, tol * (1 + e.v.norm()), what + ": v");
  require_near(got.omega, e.omega, tol * (1 + e.omega.norm()), what + ": omega");
  require_near(got.f, e.f, tol * (1 + e.f.norm()), what + ": f");
  require_near(got.tau, e.tau, tol * (1 + e.tau.norm()), what + ": tau");
  require_near(Vec3(got.q.vec()), Vec3(e.q.vec()), tol, what + ": q (x, y, z)");
  require_near(got.q.w(), e.q.w(), tol, what + ": q (w)");
  require_near(got.m, e.m, 0.0, what + ": m (unchanged)");
  require_near(got.I_body, e.I_body, 0.0, what + ": I_body (unchanged)");
}

}  // namespace rigidtest
