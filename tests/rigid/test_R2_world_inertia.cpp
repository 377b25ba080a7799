// Graded tests for TODO(R2), world-frame inertia, its inverse and the parallel axis
// theorem (labs/rigid/world_inertia.cpp). Expected values: the body's principal
// axes are the tensor's eigenvectors, energy is the same in every frame, and
// the integral of the box about its corner.
#include <cmath>

#include "rigid_test_helpers.h"
#include "world_inertia.h"

// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace test_R2_world_inertia {

using namespace rigidtest;

namespace {

// A few products of 3x3 matrices of entries ~1-10: ~10 ulps.
constexpr double kAlgebraTol = 1e-12;
// Gauss-Legendre with 2 points per axis integrates polynomials of degree <= 3
// exactly: only rounding is left.
constexpr double kExactQuadTol = 1e-12;

const Mat3 kR = quat(0.8, -0.3, 0.4, 0.2).toRotationMatrix();
const Vec3 kI(0.5, 2.0, 7.0);  // principal moments (kg m^2), all different

}  // namespace

TEST_CASE(
    "R2 world inertia: principal axes turned by R are eigenvectors and energy is frame-free",
    "[rigid][R2][3pts]") {
  const Mat3 I = world_inertia(kR, kI.asDiagonal());
  for (int k = 0; k < 3; ++k) {
    const Vec3 axis = kR.col(k);  // the body's k-th axis in the world
    require_near(Vec3(I * axis), Vec3(kI[k] * axis), kAlgebraTol,
                 "I (R e_k) = I_k (R e_k): the body's principal axis k, turned with it, keeps "
                 "its moment I_k (axis " +
                     std::to_string(k) + ")");
  }
  const Vec3 w(0.3, -1.2, 2.5);  // world frame
  const Vec3 wb = kR.transpose() * w;
  require_near(0.5 * w.dot(I * w), 0.5 * wb.dot(kI.asDiagonal() * wb), kAlgebraTol,
               "1/2 w.I w (world) = 1/2 w_b.I_body w_b (body): kinetic energy does not depend "
               "on the frame",
               kAlgebraTol);
}

TEST_CASE("R2 world inverse inertia: I^-1 (I w) gives w back", "[rigid][R2][4pts]") {
  const Mat3 I_inv = world_inverse_inertia(kR, kI.asDiagonal());
  const Mat3 I = kR * kI.asDiagonal() * kR.transpose();
  require_near(Mat3(I_inv * I), Mat3::Identity(), kAlgebraTol,
               "I^-1 I = E for I = R diag(0.5, 2, 7) R^T");
  require_near(Mat3(I_inv - I_inv.transpose()), Mat3::Zero(), kAlgebraTol, "I^-1 is symmetric");
}

TEST_CASE("R2 parallel axis: a box about its corner equals the integral over the box",
          "[rigid][R2][3pts]") {
  const double m = 2.0;
  const Vec3 size(1.0, 3.0, 2.0);
  const Mat3 I_c = (m / 12.0 * Vec3(13.0, 5.0, 10.0)).asDiagonal();  // textbook box tensor
  // Integral of rho (|r|^2 E - r r^T) with r measured from the corner (0, 0, 0) of
  // the box [0, a] x [0, b] x [0, c], by 2-point Gauss-Legendre (exact here).
  const double g = 0.5 / std::sqrt(3.0);
  Mat3 expected = Mat3::Zero();
  for (int i = 0; i < 8; ++i) {
    const Vec3 u(i & 1 ? 0.5 + g : 0.5 - g, i & 2 ? 0.5 + g : 0.5 - g, i & 4 ? 0.5 + g : 0.5 - g);
    const Vec3 r = u.cwiseProduct(size);
    expected += m / 8.0 * (r.squaredNorm() * Mat3::Identity() - r * r.transpose());
  }
  const Vec3 d = size / 2;  // centre of mass minus the corner
  require_near(parallel_axis(I_c, m, d), expected, kExactQuadTol * expected.norm(),
               "I_corner = I_c + m (|d|^2 E - d d^T) for a 1 x 3 x 2 m box of 2 kg");
}

TEST_CASE(
    "R2 held-out: random rotations and offsets give R I R^T and its inverse and the parallel "
    "axis",
    "[rigid][R2][held-out][2pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("R2")) {
    INFO(g.replay());
    for (int s = 0; s < 5; ++s) {
      const Body b = rigidtest::random_body(g);
      const Mat3 R = rot(b), I = b.I_body;
      const Vec3 d = g.vec3(-2, 2);
      INFO("R =\n"
           << R << "\nI_body diagonal " << I.diagonal().transpose() << ", m = " << b.m
           << ", d = " << rigidtest::str(d));
      const double scale = I.diagonal().sum();
      rigidtest::require_near(world_inertia(R, I), Mat3(R * I * R.transpose()), 1e-13 * scale,
                              "I = R I_body R^T");
      rigidtest::require_near(world_inverse_inertia(R, I),
                              Mat3(R * I.diagonal().cwiseInverse().asDiagonal() * R.transpose()),
                              1e-13 * I.diagonal().cwiseInverse().sum(),
                              "I^-1 = R I_body^-1 R^T");
      const Mat3 Iw = R * I * R.transpose();
      rigidtest::require_near(
          parallel_axis(Iw, b.m, d),
          Mat3(Iw + b.m * (d.squaredNorm() * Mat3::Identity() - d * d.transpose())),
          1e-13 * (scale + b.m * d.squaredNorm()), "I_P = I + m (|d|^2 E - d d^T)");
    }
  }
}

}  // namespace test_R2_world_inertia
