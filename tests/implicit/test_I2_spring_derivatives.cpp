// Graded tests for I2, the spring's force and derivatives
// (labs/implicit/spring_derivatives.cpp). Expected values: the force formula,
// and central finite differences of it.
#include <limits>

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
// What the outputs hold before the call: NaN, which every call must overwrite (and the same in
// every call, public or held-out, rather than whatever the stack held).
const Vec2 kUnset = Vec2::Constant(std::numeric_limits<double>::quiet_NaN());
const Mat2 kUnsetBlock = Mat2::Constant(std::numeric_limits<double>::quiet_NaN());

void require_mat(const Mat2& got, const Mat2& expected, double tol, const std::string& what) {
  INFO(what << "\n  expected\n" << expected << "\n  got\n" << got << "\n  tolerance " << tol);
  REQUIRE(wbtest::max_abs_diff(got, expected) <= tol);  // NaN fails
}

// The public tests' spring, or one drawn around it (tests/common/params.h): x_i - x_j within
// (0.7..1.1, 0.5..0.9), so L in [0.86, 1.42] (published 1.14), between the stretched rests
// (0.3 to 0.7) and the compressed ones (1.5 to 1.8). k = 30 as published: it is the largest
// number of every public call (the positions, velocities and rests are O(1)), so a drawn one
// would tell the held-out calls apart by their magnitude alone.
struct Spring {
  Vec2 xi, xj, vi, vj;
  double k = 30.0, kd;
  explicit Spring(const wbtest::Params& p)
      : xi(p.num(0.4, -1.0, 1.0), p.num(1.3, 0.5, 2.0)),
        vi(p.num(0.7, -1.0, 1.0), p.num(-0.2, -1.0, 1.0)),
        vj(p.num(-0.3, -1.0, 1.0), p.num(0.9, -1.0, 1.0)),
        kd(p.num(2.5, 1.0, 4.0)) {
    // x_j drawn itself, with the published -0.5 and 0.6's one digit, where x_i - x_j falls in
    // (0.7..1.1, 0.5..0.9).
    xj = Vec2(p.num(-0.5, xi.x() - 1.1, xi.x() - 0.7), p.num(0.6, xi.y() - 0.9, xi.y() - 0.5));
  }
  double stretched(const wbtest::Params& p) const { return p.num(0.5, 0.3, 0.7); }
  double compressed(const wbtest::Params& p) const { return p.num(1.6, 1.5, 1.8); }
  std::string str() const {
    return "x_i = " + wbtest::str(xi) + ", x_j = " + wbtest::str(xj) +
           ", v_i = " + wbtest::str(vi) + ", v_j = " + wbtest::str(vj) +
           ", k = " + std::to_string(k) + ", kd = " + std::to_string(kd);
  }

  // Central differences in x_i of the force formula (imtest::spring_terms).
  Mat2 fd_x(double rest, double damping) const {
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
};

// The scenarios of the public tests below, each a function of its parameters: the public test
// runs it with the published ones (wbtest::Params()), the held-out test with drawn ones.

void force(const wbtest::Params& p) {
  const Spring s(p);
  INFO(s.str());
  for (double rest : {s.stretched(p), s.compressed(p)}) {  // stretched (L = 1.14) and compressed
    Vec2 f = kUnset;
    Mat2 K = kUnsetBlock, D = kUnsetBlock;
    spring_derivatives(s.xi, s.xj, s.vi, s.vj, s.k, rest, s.kd, false, f, K, D);
    const Vec2 e = imtest::spring_terms(s.xi, s.xj, s.vi, s.vj, s.k, rest, s.kd).f;
    wbtest::require_near(f, e, 0.0, "spring-damper force on end i, rest " + std::to_string(rest),
                         kRelTol);
  }
}

void stiffness_block(const wbtest::Params& p) {
  // The elastic force (kd = 0) stretched and compressed; definite = false: the exact block.
  const Spring s(p);
  INFO(s.str());
  for (double rest : {s.stretched(p), s.compressed(p), 0.0}) {
    Vec2 f = kUnset;
    Mat2 K = kUnsetBlock, D = kUnsetBlock;
    spring_derivatives(s.xi, s.xj, s.vi, s.vj, s.k, rest, 0.0, false, f, K, D);
    require_mat(K, s.fd_x(rest, 0.0), kFdTol * s.k,
                "K = df_i/dx_i against central differences, rest " + std::to_string(rest));
  }
}

void damping_block(const wbtest::Params& p) {
  const Spring s(p);
  INFO(s.str());
  const double rest = p.num(0.8, 0.6, 1.0);
  Vec2 f = kUnset;
  Mat2 K = kUnsetBlock, D = kUnsetBlock, J;
  for (int c = 0; c < 2; ++c) {
    Vec2 e = Vec2::Zero();
    e[c] = kDelta;
    J.col(c) = (imtest::spring_terms(s.xi, s.xj, s.vi + e, s.vj, s.k, rest, s.kd).f -
                imtest::spring_terms(s.xi, s.xj, s.vi - e, s.vj, s.k, rest, s.kd).f) /
               (2 * kDelta);
  }
  spring_derivatives(s.xi, s.xj, s.vi, s.vj, s.k, rest, s.kd, false, f, K, D);
  require_mat(D, J, kFdTol * s.kd, "D = df_i/dv_i against central differences");
}

void definite_clamp(const wbtest::Params& p) {
  const Spring s(p);
  INFO(s.str());
  Vec2 f = kUnset;
  Mat2 K = kUnsetBlock, D = kUnsetBlock;
  const Vec2 u = (s.xi - s.xj).normalized();
  // Compressed (L = 1.14 < 1.6): K = -k u u^T, negative semi-definite.
  spring_derivatives(s.xi, s.xj, s.vi, s.vj, s.k, s.compressed(p), s.kd, true, f, K, D);
  require_mat(K, -s.k * u * u.transpose(), kRelTol * s.k,
              "compressed spring with definite = true: K = -k u u^T");
  // Stretched: nothing to clamp, K is the exact block.
  const double rest = s.stretched(p);
  spring_derivatives(s.xi, s.xj, s.vi, s.vj, s.k, rest, s.kd, true, f, K, D);
  require_mat(K, imtest::spring_terms(s.xi, s.xj, s.vi, s.vj, s.k, rest, s.kd).K, kRelTol * s.k,
              "stretched spring with definite = true: the exact K");
}

void coincident(const wbtest::Params& p) {
  // Whatever the rest length and the flag (spring_derivatives.h: L == 0).
  const Spring s(p);
  const double k = s.k;
  for (double rest : {0.0, p.num(0.8, 0.3, 1.5)}) {
    for (bool definite : {true, false}) {
      Vec2 f(1.0, 1.0);
      Mat2 K = kUnsetBlock, D = kUnsetBlock;
      spring_derivatives(s.xi, s.xi, s.vi, s.vj, k, rest, s.kd, definite, f, K, D);
      INFO(s.str() << "\nL = 0, rest " << rest << ", definite " << definite
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

// The held-out test's own check: springs anywhere, stretched or compressed, every input written
// as in the public tests (one or two significant digits: imtest::public_decimal; one spring
// with three, imtest::three_digit_decimal); k as published in two of three (see Spring), else
// drawn.
void random_springs(wbtest::HeldOut& g) {
  bool three = false;  // spring 9 (compressed): every number with three digits
  auto dec = [&](double lo, double hi) {
    return three ? imtest::three_digit_decimal(g, lo, hi) : imtest::public_decimal(g, lo, hi);
  };
  auto vec = [&](double lo, double hi) { return Vec2(dec(lo, hi), dec(lo, hi)); };
  auto written = [&](double z) {
    return three ? wbtest::Params::short_decimal(z) : imtest::public_rounded(g, z);
  };
  for (int s = 0; s < 12; ++s) {
    three = s == 9;
    const Vec2 a = vec(-2, 2), va = vec(-3, 3), vb = vec(-3, 3);
    Vec2 b = a;
    while (s != 0 && !((a - b).norm() >= 0.1)) {  // 0.1 to 2 m from a, then rounded
      const Vec2 d = g.uniform(0.1, 2.0) * g.unit2();
      b = Vec2(written(a.x() + d.x()), written(a.y() + d.y()));
    }
    const double kk = s % 3 == 1 ? dec(10.0, 50.0) : 30.0, kdd = dec(0.0, 5.0);
    const double L = (a - b).norm();
    // Half of them compressed (rest > L), half stretched (and two more compressed).
    const double rest = s == 0             ? dec(0.0, 1.0)
                        : s % 2 || s >= 10 ? dec(1.1 * L, 2.0 * L)
                                           : dec(0.3 * L, 0.9 * L);
    // The last two compressed, with the clamp off, then on (where the clamp matters).
    const bool definite = s >= 10 ? s == 11 : g.coin();
    // f holds (1, 1) before a third of the calls, as before the public test's calls with
    // coincident ends (4 of its 12): whatever it holds, it must be overwritten.
    Vec2 f = s % 3 == 0 ? Vec2(1.0, 1.0) : kUnset;
    Mat2 K = kUnsetBlock, D = kUnsetBlock;
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
}  // namespace

TEST_CASE("I2 spring derivatives: force is -(k (L - rest) + kd (v_i - v_j).u) u",
          "[implicit][I2][3pts]") {
  force(wbtest::Params());
}

TEST_CASE("I2 spring derivatives: K matches central differences of the elastic force",
          "[implicit][I2][5pts]") {
  stiffness_block(wbtest::Params());
}

TEST_CASE("I2 spring derivatives: D matches central differences in the velocities",
          "[implicit][I2][3pts]") {
  damping_block(wbtest::Params());
}

TEST_CASE("I2 spring derivatives: definite drops only a compressed spring's cross term",
          "[implicit][I2][3pts]") {
  definite_clamp(wbtest::Params());
}

TEST_CASE("I2 spring derivatives: coincident ends give f = 0 and K = -k I",
          "[implicit][I2][3pts]") {
  coincident(wbtest::Params());
}

// Every public scenario above again, its parameters drawn from the held-out seed in the public
// tests' format (short decimals, the same magnitudes), so that no call tells the public tests
// from this one (tools/adversary --inputs); then random springs anywhere.
TEST_CASE("I2 held-out: random springs stretched or compressed give the header's f K and D",
          "[implicit][I2][held-out][3pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("I2")) {
    INFO(g.replay());
    const wbtest::Params p(g);
    force(p);
    stiffness_block(p);
    damping_block(p);
    definite_clamp(p);
    coincident(p);
    random_springs(g);
  }
}

}  // namespace test_I2_spring_derivatives
