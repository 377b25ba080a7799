// Fixed-size Eigen typedefs shared by every lab.
#pragma once
#if defined(WB_HARDENED) && !defined(WB_HARDENED_INCLUDED)
#error \
    "a hardened build (WB_HARDENED) must include wb/hardened.h before anything (cmake/labs.cmake)"
#endif
#include <Eigen/Core>

namespace wb {
using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat2 = Eigen::Matrix2d;
using Mat3 = Eigen::Matrix3d;
using VecX = Eigen::VectorXd;
using MatX = Eigen::MatrixXd;
// n particles in 2D: column i is particle i.
using Mat2X = Eigen::Matrix<double, 2, Eigen::Dynamic>;

// The 2D cross product (z component of the 3D one) and the perpendicular.
inline double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
inline Vec2 perp(const Vec2& a) { return Vec2(-a.y(), a.x()); }  // a rotated by +90 degrees
}  // namespace wb
