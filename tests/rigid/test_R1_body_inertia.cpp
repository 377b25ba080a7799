// Graded tests for TODO(R1), body-frame inertia tensors (labs/rigid/body_inertia.cpp).
// Expected values: the integral I = rho * integral of (|r|^2 E - r r^T) dV over the
// solid, evaluated here by quadrature (never the closed forms of the header).
#include <cmath>

#include "body_inertia.h"
#include "rigid_test_helpers.h"

// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace test_R1_body_inertia {

using namespace rigidtest;

namespace {

// Midpoint rule with n cells per coordinate: error ~ (1/n)^2 of a smooth integrand;
// n = 80 leaves < 1e-3 relative on every entry.
constexpr int kCells = 80;
constexpr double kQuadratureTol = 1e-3;

// rho * integral of (|r|^2 E - r r^T) over a solid given in coordinates u in
// [lo, hi]^3 (per axis) by r(u) and the volume element |det dr/du|(u).
Mat3 integrate(const std::function<Vec3(const Vec3&)>& r,
               const std::function<double(const Vec3&)>& jac, const Vec3& lo, const Vec3& hi,
               double rho) {
  Mat3 I = Mat3::Zero();
  const Vec3 du = (hi - lo) / kCells;
  for (int i = 0; i < kCells; ++i) {
    for (int j = 0; j < kCells; ++j) {
      for (int k = 0; k < kCells; ++k) {
        const Vec3 u = lo + Vec3((i + 0.5) * du.x(), (j + 0.5) * du.y(), (k + 0.5) * du.z());
        const Vec3 p = r(u);
        I += jac(u) * (p.squaredNorm() * Mat3::Identity() - p * p.transpose());
      }
    }
  }
  return rho * du.prod() * I;
}

void require_tensor(const Mat3& got, const Mat3& expected, const std::string& what) {
  require_near(got, expected, kQuadratureTol * expected.norm(), what);
}

}  // namespace

TEST_CASE("R1 box: inertia equals the integral over the box with edges a b c",
          "[rigid][R1][3pts]") {
  const double m = 3.0;
  const Vec3 size(1.0, 2.0, 4.0);
  const Mat3 expected =
      integrate([](const Vec3& u) { return u; }, [](const Vec3&) { return 1.0; }, -size / 2,
                size / 2, m / size.prod());
  require_tensor(box_inertia(m, size), expected,
                 "box 1 x 2 x 4 m of 3 kg: I = rho * integral of (r^2 E - r r^T) dV");
}

TEST_CASE("R1 sphere: inertia equals the integral over the ball", "[rigid][R1][4pts]") {
  const double m = 2.0, R = 0.7;
  // Spherical coordinates u = (r, theta, phi), dV = r^2 sin(theta).
  const Mat3 expected = integrate(
      [](const Vec3& u) {
        return Vec3(u[0] * std::sin(u[1]) * std::cos(u[2]),
                    u[0] * std::sin(u[1]) * std::sin(u[2]), u[0] * std::cos(u[1]));
      },
      [](const Vec3& u) { return u[0] * u[0] * std::sin(u[1]); }, Vec3(0, 0, 0),
      Vec3(R, M_PI, 2 * M_PI), m / (4.0 / 3.0 * M_PI * R * R * R));
  require_tensor(sphere_inertia(m, R), expected,
                 "ball of radius 0.7 m and 2 kg: I = rho * integral of (r^2 E - r r^T) dV");
}

TEST_CASE("R1 cylinder: inertia equals the integral over the cylinder along z",
          "[rigid][R1][3pts]") {
  const double m = 5.0, R = 0.4, L = 3.0;
  // Cylindrical coordinates u = (s, phi, z), dV = s.
  const Mat3 expected = integrate(
      [](const Vec3& u) { return Vec3(u[0] * std::cos(u[1]), u[0] * std::sin(u[1]), u[2]); },
      [](const Vec3& u) { return u[0]; }, Vec3(0, 0, -L / 2), Vec3(R, 2 * M_PI, L / 2),
      m / (M_PI * R * R * L));
  require_tensor(cylinder_inertia(m, R, L), expected,
                 "cylinder r = 0.4 m, length 3 m along z, 5 kg: I = rho * integral of "
                 "(r^2 E - r r^T) dV");
}

TEST_CASE("R1 held-out: random boxes spheres and cylinders have the header's moments",
          "[rigid][R1][held-out][2pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("R1")) {
    INFO(g.replay());
    for (int s = 0; s < 5; ++s) {
      const double m = g.uniform(0.1, 10.0), a = g.uniform(0.1, 3.0), b = g.uniform(0.1, 3.0),
                   c = g.uniform(0.1, 3.0);
      INFO("m = " << m << ", box edges " << a << " " << b << " " << c << ", sphere radius " << a
                  << ", cylinder radius " << a << " and length " << b);
      rigidtest::require_near(
          box_inertia(m, Vec3(a, b, c)),
          Mat3(Vec3(m / 12 * (b * b + c * c), m / 12 * (a * a + c * c), m / 12 * (a * a + b * b))
                   .asDiagonal()),
          1e-13 * m * (a * a + b * b + c * c),
          "box: m/12 (b^2 + c^2), m/12 (a^2 + c^2), m/12 (a^2 + b^2)");
      rigidtest::require_near(sphere_inertia(m, a), Mat3((0.4 * m * a * a) * Mat3::Identity()),
                              1e-13 * m * a * a, "sphere: 2/5 m r^2 on every axis");
      const double Ixy = m / 12 * (3 * a * a + b * b);
      rigidtest::require_near(
          cylinder_inertia(m, a, b), Mat3(Vec3(Ixy, Ixy, 0.5 * m * a * a).asDiagonal()),
          1e-13 * m * (a * a + b * b),
          "cylinder along z: m/12 (3 r^2 + L^2) about x and y, m r^2/2 about z");
    }
  }
}

}  // namespace test_R1_body_inertia
