// Graded tests for TODO(R1), body-frame inertia tensors (labs/rigid/body_inertia.cpp).
// Expected values: the integral I = rho * integral of (|r|^2 E - r r^T) dV over the
// solid, evaluated here by quadrature (never the closed forms of the header).
#include <cmath>

#include "body_inertia.h"
#include "params.h"
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

// The scenarios of the public tests below, each a function of its parameters: the public test
// runs it with the published ones (wbtest::Params()) and checks the lab's tensor against the
// integral by quadrature; the held-out test with drawn ones, in the same format (short decimals
// within half of the published value either side, tests/common/params.h), and checks it against
// the integral's closed form to rounding (the quadrature's 512 000 cells per call would make the
// held-out test as slow as the public ones, and its 1e-3 is looser than rounding).
constexpr double kClosedFormTol = 1e-13;  // a few products of numbers ~0.1-10: rounding

void box(const wbtest::Params& p) {
  const double m = p.num(3.0, 1.5, 4.5);
  const Vec3 size(p.num(1.0, 0.5, 1.5), p.num(2.0, 1.0, 3.0), p.num(4.0, 2.0, 6.0));
  const double a = size.x(), b = size.y(), c = size.z();
  INFO("box of edges " << str(size) << " m and " << m << " kg");
  const Mat3 got = box_inertia(m, size);
  if (!p.held_out()) {
    const Mat3 expected =
        integrate([](const Vec3& u) { return u; }, [](const Vec3&) { return 1.0; }, -size / 2,
                  size / 2, m / size.prod());
    require_tensor(got, expected,
                   "box 1 x 2 x 4 m of 3 kg: I = rho * integral of (r^2 E - r r^T) dV");
    return;
  }
  rigidtest::require_near(
      got,
      Mat3(Vec3(m / 12 * (b * b + c * c), m / 12 * (a * a + c * c), m / 12 * (a * a + b * b))
               .asDiagonal()),
      kClosedFormTol * m * (a * a + b * b + c * c),
      "box: the integral is m/12 (b^2 + c^2), m/12 (a^2 + c^2), m/12 (a^2 + b^2)");
}

void sphere(const wbtest::Params& p) {
  const double m = p.num(2.0, 1.0, 3.0), R = p.num(0.7, 0.35, 1.05);
  INFO("ball of radius " << R << " m and " << m << " kg");
  const Mat3 got = sphere_inertia(m, R);
  if (!p.held_out()) {
    // Spherical coordinates u = (r, theta, phi), dV = r^2 sin(theta).
    const Mat3 expected = integrate(
        [](const Vec3& u) {
          return Vec3(u[0] * std::sin(u[1]) * std::cos(u[2]),
                      u[0] * std::sin(u[1]) * std::sin(u[2]), u[0] * std::cos(u[1]));
        },
        [](const Vec3& u) { return u[0] * u[0] * std::sin(u[1]); }, Vec3(0, 0, 0),
        Vec3(R, M_PI, 2 * M_PI), m / (4.0 / 3.0 * M_PI * R * R * R));
    require_tensor(got, expected,
                   "ball of radius 0.7 m and 2 kg: I = rho * integral of (r^2 E - r r^T) dV");
    return;
  }
  rigidtest::require_near(got, Mat3((0.4 * m * R * R) * Mat3::Identity()),
                          kClosedFormTol * m * R * R,
                          "ball: the integral is 2/5 m r^2 on every axis");
}

void cylinder(const wbtest::Params& p) {
  const double m = p.num(5.0, 2.5, 7.5), R = p.num(0.4, 0.2, 0.6), L = p.num(3.0, 1.5, 4.5);
  INFO("cylinder of radius " << R << " m, length " << L << " m along z, " << m << " kg");
  const Mat3 got = cylinder_inertia(m, R, L);
  if (!p.held_out()) {
    // Cylindrical coordinates u = (s, phi, z), dV = s.
    const Mat3 expected = integrate(
        [](const Vec3& u) { return Vec3(u[0] * std::cos(u[1]), u[0] * std::sin(u[1]), u[2]); },
        [](const Vec3& u) { return u[0]; }, Vec3(0, 0, -L / 2), Vec3(R, 2 * M_PI, L / 2),
        m / (M_PI * R * R * L));
    require_tensor(got, expected,
                   "cylinder r = 0.4 m, length 3 m along z, 5 kg: I = rho * integral of "
                   "(r^2 E - r r^T) dV");
    return;
  }
  const double Ixy = m / 12 * (3 * R * R + L * L);
  rigidtest::require_near(
      got, Mat3(Vec3(Ixy, Ixy, 0.5 * m * R * R).asDiagonal()),
      kClosedFormTol * m * (R * R + L * L),
      "cylinder along z: the integral is m/12 (3 r^2 + L^2) about x and y, m r^2/2 about z");
}

}  // namespace

TEST_CASE("R1 box: inertia equals the integral over the box with edges a b c",
          "[rigid][R1][3pts]") {
  box(wbtest::Params());
}

TEST_CASE("R1 sphere: inertia equals the integral over the ball", "[rigid][R1][4pts]") {
  sphere(wbtest::Params());
}

TEST_CASE("R1 cylinder: inertia equals the integral over the cylinder along z",
          "[rigid][R1][3pts]") {
  cylinder(wbtest::Params());
}

// The public scenarios again, their parameters drawn from the held-out seed in the public tests'
// format (short decimals of the published magnitudes), each as often as the others (one call
// each in the public tests), five draws of each: no call tells the public tests from this one
// (tools/adversary --inputs).
TEST_CASE("R1 held-out: random boxes spheres and cylinders have the header's moments",
          "[rigid][R1][held-out][2pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("R1")) {
    INFO(g.replay());
    const wbtest::Params p(g);
    for (int s = 0; s < 5; ++s) {
      box(p);
      sphere(p);
      cylinder(p);
    }
  }
}

}  // namespace test_R1_body_inertia
