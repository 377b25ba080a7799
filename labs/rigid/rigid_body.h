// The state of one rigid body in 3D, shared by every task of the rigid lab
// (no task here: nothing to write in this file).
//
// A particle's state is (x, v); a rigid body's is (x, v, R, omega) plus the
// force and torque accumulated during the current step:
//
//          body frame                 world frame
//     ^ z                         p = x + R r   (a point r fixed in the body)
//     |   +------+
//     |  /|     /|                v_p = v + omega x (p - x)
//     | +------+ |
//     | | +----|-+    R = q.toRotationMatrix() maps body -> world
//     | |/ . x |/
//     | +------+      L = m x.cross(v) + I omega,  I = R I_body R^T
//     +------------> x
#pragma once
#include <cmath>

#include <Eigen/Geometry>

#include "wb/types.h"

namespace rigid {

using wb::Mat2;
using wb::Mat3;
using wb::Vec2;
using wb::Vec3;

struct Body {
  double m = 1.0;                                         // mass (kg), > 0
  Mat3 I_body = Mat3::Identity();                         // inertia about x, body frame (kg m^2)
  Vec3 x = Vec3::Zero();                                  // centre of mass, world (m)
  Vec3 v = Vec3::Zero();                                  // its velocity, world (m/s)
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();  // orientation body -> world, unit
  Vec3 omega = Vec3::Zero();                              // angular velocity, world (rad/s)
  Vec3 f = Vec3::Zero();                                  // force accumulated this step (N)
  Vec3 tau = Vec3::Zero();  // torque about x accumulated this step, world (N m)
};

// The cross-product matrix: skew(a) * b == a.cross(b).
inline Mat3 skew(const Vec3& a) {
  Mat3 s;
  s << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return s;
}

// Two unit vectors t1, t2 that make (t1, t2, n) a right-handed orthonormal frame,
// for a unit n: the same n always gives the same t1, t2 (contacts and hinges keep
// impulses along them from one step to the next).
inline void tangent_basis(const Vec3& n, Vec3& t1, Vec3& t2) {
  // Start from the world axis least aligned with n (far from parallel to it).
  const Vec3 a = std::abs(n.x()) < 0.57 ? Vec3::UnitX() : Vec3::UnitY();
  t1 = a.cross(n).normalized();
  t2 = n.cross(t1);
}

}  // namespace rigid
