// Graded tests for TODO(R2), world-frame inertia, its inverse and the parallel axis
// theorem (labs/rigid/world_inertia.cpp). Expected values: the body's principal
// axes are the tensor's eigenvectors, energy is the same in every frame, and
// the integral of the box about its corner.
#include <cmath>

#include "params.h"
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

// The scenarios of the public tests below, each a function of its parameters: the public test
// runs it with the published ones (wbtest::Params()), the held-out test with drawn ones in the
// same format (tests/common/params.h): the rotation from a quaternion of short decimals (each
// within 0.2 of the published one), the moments, offsets and masses short decimals within half
// of the published value either side (the moments stay distinct: 0.25-0.75, 1-3, 3.5-10.5).
struct Published {
  Mat3 R;
  Vec3 I;  // principal moments (kg m^2), all different
  explicit Published(const wbtest::Params& p)
      : R(quat(p.num(0.8, 0.6, 1.0), p.num(-0.3, -0.5, -0.1), p.num(0.4, 0.2, 0.6),
               p.num(0.2, 0.0, 0.4))
              .toRotationMatrix()),
        I(p.num(0.5, 0.25, 0.75), p.num(2.0, 1.0, 3.0), p.num(7.0, 3.5, 10.5)) {}
};

void principal_axes(const wbtest::Params& p) {
  const Published k(p);
  INFO("R =\n" << k.R << "\nI_body diagonal " << str(k.I));
  const Mat3 I = world_inertia(k.R, k.I.asDiagonal());
  for (int a = 0; a < 3; ++a) {
    const Vec3 axis = k.R.col(a);  // the body's a-th axis in the world
    require_near(Vec3(I * axis), Vec3(k.I[a] * axis), kAlgebraTol,
                 "I (R e_k) = I_k (R e_k): the body's principal axis k, turned with it, keeps "
                 "its moment I_k (axis " +
                     std::to_string(a) + ")");
  }
  const Vec3 w(p.num(0.3, 0.15, 0.45), p.num(-1.2, -1.8, -0.6), p.num(2.5, 1.25, 3.75));  // world
  const Vec3 wb = k.R.transpose() * w;
  require_near(0.5 * w.dot(I * w), 0.5 * wb.dot(k.I.asDiagonal() * wb), kAlgebraTol,
               "1/2 w.I w (world) = 1/2 w_b.I_body w_b (body): kinetic energy does not depend "
               "on the frame",
               kAlgebraTol);
}

void inverse(const wbtest::Params& p) {
  const Published k(p);
  INFO("R =\n" << k.R << "\nI_body diagonal " << str(k.I));
  const Mat3 I_inv = world_inverse_inertia(k.R, k.I.asDiagonal());
  const Mat3 I = k.R * k.I.asDiagonal() * k.R.transpose();
  require_near(Mat3(I_inv * I), Mat3::Identity(), kAlgebraTol,
               "I^-1 I = E for I = R diag(I_body) R^T");
  require_near(Mat3(I_inv - I_inv.transpose()), Mat3::Zero(), kAlgebraTol, "I^-1 is symmetric");
}

void box_corner(const wbtest::Params& p) {
  const double m = p.num(2.0, 1.0, 3.0);
  const Vec3 size(p.num(1.0, 0.5, 1.5), p.num(3.0, 1.5, 4.5), p.num(2.0, 1.0, 3.0));
  const double a2 = size.x() * size.x(), b2 = size.y() * size.y(), c2 = size.z() * size.z();
  const Mat3 I_c = (m / 12.0 * Vec3(b2 + c2, a2 + c2, a2 + b2)).asDiagonal();  // textbook box
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
  INFO("a box of edges " << str(size) << " m and " << m << " kg, about its corner");
  require_near(parallel_axis(I_c, m, d), expected, kExactQuadTol * expected.norm(),
               "I_corner = I_c + m (|d|^2 E - d d^T) for a box about its corner");
}

}  // namespace

TEST_CASE(
    "R2 world inertia: principal axes turned by R are eigenvectors and energy is frame-free",
    "[rigid][R2][3pts]") {
  principal_axes(wbtest::Params());
}

TEST_CASE("R2 world inverse inertia: I^-1 (I w) gives w back", "[rigid][R2][4pts]") {
  inverse(wbtest::Params());
}

TEST_CASE("R2 parallel axis: a box about its corner equals the integral over the box",
          "[rigid][R2][3pts]") {
  box_corner(wbtest::Params());
}

// The public scenarios again, their parameters drawn from the held-out seed in the public tests'
// format (one call each in the public tests, so each as often here), then the header's formulas
// on random bodies (short decimals too: rigidtest::random_body) and offsets.
TEST_CASE(
    "R2 held-out: random rotations and offsets give R I R^T and its inverse and the parallel "
    "axis",
    "[rigid][R2][held-out][2pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("R2")) {
    INFO(g.replay());
    const wbtest::Params p(g);
    for (int s = 0; s < 3; ++s) {
      principal_axes(p);
      inverse(p);
      box_corner(p);
    }
    for (int s = 0; s < 3; ++s) {
      const Body b = rigidtest::random_body(g);
      const Mat3 R = rot(b), I = b.I_body;
      const Vec3 d(p.num(0, -2, 2), p.num(0, -2, 2), p.num(0, -2, 2));
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
      // About the body's own axes (I_body, short decimals as the public test's box tensor is
      // written): the theorem adds the same m (|d|^2 E - d d^T) to any tensor.
      rigidtest::require_near(
          parallel_axis(I, b.m, d),
          Mat3(I + b.m * (d.squaredNorm() * Mat3::Identity() - d * d.transpose())),
          1e-13 * (scale + b.m * d.squaredNorm()), "I_P = I + m (|d|^2 E - d d^T)");
    }
  }
}

}  // namespace test_R2_world_inertia
