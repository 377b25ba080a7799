// Graded tests for I2, the spring's force and derivatives
// (labs/implicit/spring_derivatives.cpp). Expected values: the force formula,
// and central finite differences of it.
#include "implicit_checks.h"
#include "spring_derivatives.h"

// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace test_I2_spring_derivatives {

namespace {
using wb::Mat2;
using wb::Vec2;

// Central differences with step 1e-5 m on O(1) lengths: truncation error
// ~ delta^2 |f'''| ~ 1e-10 k, rounding ~ 1e-16 |f| / delta ~ 1e-11 k; 1e-7 k
// leaves a wide margin and is still 1e-7 of the blocks' size.
constexpr double kDelta = 1e-5;
constexpr double kFdTol = 1e-7;
constexpr double kRelTol = 1e-12;  // a closed form evaluated two ways: rounding only

const Vec2 xi(0.4, 1.3), xj(-0.5, 0.6), vi(0.7, -0.2), vj(-0.3, 0.9);
const double k = 30.0, kd = 2.5;

void require_mat(const Mat2& got, const Mat2& expected, double tol, const std::string& what) {
  INFO(what << "\n  expected\n" << expected << "\n  got\n" << got << "\n  tolerance " << tol);
  REQUIRE(wbtest::max_abs_diff(got, expected) <= tol);  // NaN fails
}

// Central differences in x_i of the force formula (imtest::spring_terms).
Mat2 fd_x(double rest, double damping) {
  Mat2 J;
  for (int c = 0; c < 2; ++c) {
    Vec2 e = Vec2::Zero();
    e[c] = kDelta;
    J.col(c) = (imtest::spring_terms(xi + e, xj, vi, vj, k, rest, damping).f -
                imtest::spring_terms(xi - e, xj, vi, vj, k, rest, damping).f) /
               (2 * kDelta);
  }
  return J;
}
}  // namespace

TEST_CASE("I2 spring derivatives: force is -(k (L - rest) + kd (v_i - v_j).u) u",
          "[implicit][I2][3pts]") {
  for (double rest : {0.5, 1.6}) {  // stretched (L = 1.14) and compressed
    Vec2 f;
    Mat2 K, D;
    spring_derivatives(xi, xj, vi, vj, k, rest, kd, false, f, K, D);
    const Vec2 e = imtest::spring_terms(xi, xj, vi, vj, k, rest, kd).f;
    wbtest::require_near(f, e, 0.0, "spring-damper force on end i, rest " + std::to_string(rest),
                         kRelTol);
  }
}

TEST_CASE("I2 spring derivatives: K matches central differences of the elastic force",
          "[implicit][I2][5pts]") {
  // The elastic force (kd = 0) stretched and compressed; definite = false: the exact block.
  for (double rest : {0.5, 1.6, 0.0}) {
    Vec2 f;
    Mat2 K, D;
    spring_derivatives(xi, xj, vi, vj, k, rest, 0.0, false, f, K, D);
    require_mat(K, fd_x(rest, 0.0), kFdTol * k,
                "K = df_i/dx_i against central differences, rest " + std::to_string(rest));
  }
}

TEST_CASE("I2 spring derivatives: D matches central differences in the velocities",
          "[implicit][I2][3pts]") {
  Vec2 f;
  Mat2 K, D, J;
  for (int c = 0; c < 2; ++c) {
    Vec2 e = Vec2::Zero();
    e[c] = kDelta;
    J.col(c) = (imtest::spring_terms(xi, xj, vi + e, vj, k, 0.8, kd).f -
                imtest::spring_terms(xi, xj, vi - e, vj, k, 0.8, kd).f) /
               (2 * kDelta);
  }
  spring_derivatives(xi, xj, vi, vj, k, 0.8, kd, false, f, K, D);
  require_mat(D, J, kFdTol * kd, "D = df_i/dv_i against central differences");
}

TEST_CASE("I2 spring derivatives: definite drops only a compressed spring's cross term",
          "[implicit][I2][3pts]") {
  Vec2 f;
  Mat2 K, D;
  const Vec2 u = (xi - xj).normalized();
  // Compressed (L = 1.14 < 1.6): K = -k u u^T, negative semi-definite.
  spring_derivatives(xi, xj, vi, vj, k, 1.6, kd, true, f, K, D);
  require_mat(K, -k * u * u.transpose(), kRelTol * k,
              "compressed spring with definite = true: K = -k u u^T");
  // Stretched: nothing to clamp, K is the exact block.
  spring_derivatives(xi, xj, vi, vj, k, 0.5, kd, true, f, K, D);
  require_mat(K, imtest::spring_terms(xi, xj, vi, vj, k, 0.5, kd).K, kRelTol * k,
              "stretched spring with definite = true: the exact K");
}

TEST_CASE("I2 spring derivatives: coincident ends give f = 0 and K = -k I",
          "[implicit][I2][3pts]") {
  // Whatever the rest length and the flag (spring_derivatives.h: L == 0).
  for (double rest : {0.0, 0.8}) {
    for (bool definite : {true, false}) {
      Vec2 f(1.0, 1.0);
      Mat2 K, D;
      spring_derivatives(xi, xi, vi, vj, k, rest, kd, definite, f, K, D);
      INFO("L = 0, rest " << rest << ", definite " << definite
                          << ": the direction is undefined; f = 0, K = -k I (the rest-0 "
                             "limit), D = 0; got f = "
                          << f.transpose() << ", K =\n"
                          << K << "\nD =\n"
                          << D);
      REQUIRE(f.allFinite());
      REQUIRE(K.allFinite());
      REQUIRE(D.allFinite());
      REQUIRE(f.norm() == 0.0);
      REQUIRE(wbtest::finite((K + k * Mat2::Identity()).norm()) <= kRelTol * k);
      REQUIRE(D.norm() == 0.0);
    }
  }
}

TEST_CASE("I2 held-out: random springs stretched or compressed give the header's f K and D",
          "[implicit][I2][held-out][3pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("I2")) {
    INFO(g.replay());
    for (int s = 0; s < 12; ++s) {
      const Vec2 a = g.vec2(-2, 2), va = g.vec2(-3, 3), vb = g.vec2(-3, 3);
      const Vec2 b = s == 0 ? a : Vec2(a + g.uniform(0.1, 2.0) * g.unit2());
      const double kk = g.uniform(1.0, 100.0), kdd = g.uniform(0.0, 5.0);
      const double L = (a - b).norm();
      // Half of them compressed (rest > L), half stretched (and two more compressed).
      const double rest = s == 0             ? g.uniform(0.0, 1.0)
                          : s % 2 || s >= 10 ? L * g.uniform(1.1, 2.0)
                                             : L * g.uniform(0.3, 0.9);
      // The last two compressed, with the clamp off, then on (where the clamp matters).
      const bool definite = s >= 10 ? s == 11 : g.coin();
      Vec2 f;
      Mat2 K, D;
      spring_derivatives(a, b, va, vb, kk, rest, kdd, definite, f, K, D);
      Vec2 fe(0, 0);
      Mat2 Ke = -kk * Mat2::Identity(), De = Mat2::Zero();
      if (L > 0) {
        const imtest::SpringTerms t = imtest::spring_terms(a, b, va, vb, kk, rest, kdd, definite);
        fe = t.f, Ke = t.K, De = t.D;
      }
      INFO("x_i = " << wbtest::str(a) << ", x_j = " << wbtest::str(b) << " (L = " << L
                    << "), v_i = " << wbtest::str(va) << ", v_j = " << wbtest::str(vb)
                    << ", k = " << kk << ", rest = " << rest << ", kd = " << kdd
                    << ", definite = " << definite << "\n  got f = " << f.transpose() << ", K =\n"
                    << K << "\n  D =\n"
                    << D << "\n  expected K =\n"
                    << Ke << "\n  D =\n"
                    << De);
      const double fscale = kk * (L + rest) + kdd * (va - vb).norm();
      wbtest::require_near(f, fe, kRelTol * (1 + fscale),
                           "f = -(k (L - rest) + kd (v_i - v_j).u) u (0 when L = 0)");
      REQUIRE(wbtest::max_abs_diff(K, Ke) <= kRelTol * kk * (1 + rest / (L > 0 ? L : 1)));
      REQUIRE(wbtest::max_abs_diff(D, De) <= kRelTol * (1 + kdd));
    }
  }
}

}  // namespace test_I2_spring_derivatives
