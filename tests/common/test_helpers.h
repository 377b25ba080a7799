// Shared helpers for the graded tests: comparisons that say what was expected,
// what came out, and where.
//
// Conventions (docs/grading.md):
//   TEST_CASE("F5 spring: force along the spring is -k (L - rest)", "[forces][F5][6pts]")
//   - the name starts with the task id; no ; , [ ] * ~ " or \ in names
//   - tags: the lab, the task, and the points as [<N>pts]; each lab sums to 100
//   - every test must fail on the skeleton (a stub) and pass on any correct
//     implementation; expected values come from closed forms or laws
#pragma once
#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>
#include <string>

#include <catch2/catch.hpp>

#include "wb/types.h"

// Every helper has internal linkage (the unnamed namespace): no other object linked into a
// test binary can replace one (in the grader's build no student object is linked at all).
namespace wbtest {
namespace {

// |a - b| <= abs_tol + rel_tol * max(|a|, |b|) for finite a and b. A value that is not finite is
// near only the same value (+inf only +inf, NaN only NaN): the one comparison every test uses
// (docs/grading.md, "Every value from the worker is hostile"). Without that rule an infinity
// passed every relative tolerance: |inf - b| <= abs_tol + rel_tol * inf is inf <= inf.
inline bool same_non_finite(double a, double b) {
  return a == b || (std::isnan(a) && std::isnan(b));
}
inline bool near(double a, double b, double abs_tol, double rel_tol = 0.0) {
  if (!std::isfinite(a) || !std::isfinite(b)) return same_non_finite(a, b);
  return std::abs(a - b) <= abs_tol + rel_tol * std::max(std::abs(a), std::abs(b));
}
// x when it is finite, else NaN: every comparison with the result fails when x is not finite
// (an ordering comparison of a raw value lets one infinity through: +inf > bound, -inf < bound).
// tools/pattern nanfree wants it (or another NaN-sticky helper below) in every ordering
// comparison an assertion makes.
inline double finite(double x) { return std::isfinite(x) ? x : std::nan(""); }

// A number as a failure message prints it: the shortest text that reads back as the same
// double (0.1, not 0.10000000000000001; 1.0000000000000002, not 1), so that two values that
// differ never print alike. The grader shows a student the digits that tell expected from got.
inline std::string num(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

inline std::string str(const wb::Vec2& v) { return "(" + num(v.x()) + ", " + num(v.y()) + ")"; }

// A matrix or vector on one line: a column vector (x, y, z), a matrix by rows [a, b; c, d]
// (Eigen's own operator<< spreads it over lines, which a one-line reason cannot hold).
template <class M>
std::string text(const Eigen::DenseBase<M>& m) {
  std::string s = m.cols() == 1 ? "(" : "[";
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    if (m.cols() == 1) {
      s += (i ? ", " : "") + num(double(m(i, 0)));
      continue;
    }
    for (Eigen::Index j = 0; j < m.cols(); ++j)
      s += (j ? ", " : (i ? "; " : "")) + num(double(m(i, j)));
  }
  return s + (m.cols() == 1 ? ")" : "]");
}

// Checks one vector against its expected value; `what` names the quantity
// (and the law it comes from) for the failure message.
inline void require_near(const wb::Vec2& got, const wb::Vec2& expected, double abs_tol,
                         const std::string& what, double rel_tol = 0.0) {
  INFO(what << "\n  expected " << str(expected) << "\n  got      " << str(got) << "\n  tolerance "
            << num(abs_tol) << " + " << num(rel_tol) << " * |value|");
  REQUIRE(near(got.x(), expected.x(), abs_tol, rel_tol));
  REQUIRE(near(got.y(), expected.y(), abs_tol, rel_tol));
}

inline void require_near(double got, double expected, double abs_tol, const std::string& what,
                         double rel_tol = 0.0) {
  INFO(what << "\n  expected " << num(expected) << "\n  got      " << num(got) << "\n  tolerance "
            << num(abs_tol) << " + " << num(rel_tol) << " * |value|");
  REQUIRE(near(got, expected, abs_tol, rel_tol));
}

// Checks every column of a 2 x n matrix, reporting the first bad column.
inline void require_near(const wb::Mat2X& got, const wb::Mat2X& expected, double abs_tol,
                         const std::string& what, double rel_tol = 0.0) {
  {
    INFO(what << ": expected " << expected.cols() << " columns, got " << got.cols());
    REQUIRE(got.cols() == expected.cols());
  }
  for (Eigen::Index i = 0; i < got.cols(); ++i) {
    const wb::Vec2 g = got.col(i), e = expected.col(i);
    if (near(g.x(), e.x(), abs_tol, rel_tol) && near(g.y(), e.y(), abs_tol, rel_tol)) continue;
    require_near(g, e, abs_tol, what + " (particle " + std::to_string(i) + ")", rel_tol);
  }
}

// A running maximum that a NaN or an infinity cannot hide from: once x is not finite the
// result is NaN for good (std::max(acc, NaN) returns acc, and the NaN is lost).
inline double worst_of(double acc, double x) {
  return std::isfinite(x) && !std::isnan(acc) ? std::max(acc, x) : std::nan("");
}
// The same for a running minimum.
inline double least_of(double acc, double x) {
  return std::isfinite(x) && !std::isnan(acc) ? std::min(acc, x) : std::nan("");
}

// The one NaN-safe way to measure a difference (docs/grading.md, "Every value from the worker
// is hostile"): a value that came back from the lab's code may be NaN or infinite anywhere,
// and Eigen's maxCoeff() may skip a NaN that is not the first entry, so that
// "(got - expected).cwiseAbs().maxCoeff() <= tol" passes. These return NaN when an entry of
// either side is not finite (unless both sides hold the same non-finite value there, as near
// does), or when the shapes differ: every comparison with NaN is false, so "<= tol", "> tol"
// and "== 0" all fail.
template <class A, class B>
double max_abs_diff(const Eigen::DenseBase<A>& a, const Eigen::DenseBase<B>& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) return std::nan("");
  double worst = 0;
  for (Eigen::Index j = 0; j < a.cols(); ++j) {
    for (Eigen::Index i = 0; i < a.rows(); ++i) {
      const double x = double(a(i, j)), y = double(b(i, j));
      if ((!std::isfinite(x) || !std::isfinite(y)) && same_non_finite(x, y)) continue;
      if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(x - y)) return std::nan("");
      worst = worst_of(worst, std::abs(x - y));
    }
  }
  return worst;
}

// The largest |entry|, NaN when an entry is not finite.
template <class A>
double max_abs(const Eigen::DenseBase<A>& a) {
  double worst = 0;
  for (Eigen::Index j = 0; j < a.cols(); ++j) {
    for (Eigen::Index i = 0; i < a.rows(); ++i) {
      const double v = double(a(i, j));
      if (!std::isfinite(v)) return std::nan("");
      worst = worst_of(worst, std::abs(v));
    }
  }
  return worst;
}

inline void require_finite(const wb::Mat2X& m, const std::string& what) {
  if (m.allFinite()) return;
  // The first columns only: the matrix came from the lab's code and may be huge.
  INFO(what << ": every entry must be finite (no NaN or inf)\n  got (first columns of "
            << m.cols() << ") " << text(m.leftCols(std::min<Eigen::Index>(m.cols(), 8))));
  REQUIRE(m.allFinite());
}

}  // namespace
}  // namespace wbtest

// ---- Appended for the forces tests (random clusters, finite differences) ----
#include <cstdint>
#include <functional>
#include <random>

namespace wbtest {
namespace {

// n points with coordinates uniform in [lo, hi), from a fixed seed: the same
// numbers on every platform (mt19937_64 is fully specified, and the mapping to
// doubles is ours, not the library's distribution).
inline wb::Mat2X random_points(Eigen::Index n, std::uint64_t seed, double lo, double hi) {
  std::mt19937_64 gen(seed);
  wb::Mat2X p(2, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (int r = 0; r < 2; ++r) {
      const double u = double(gen() >> 11) * 0x1.0p-53;  // uniform in [0, 1)
      p(r, i) = lo + (hi - lo) * u;
    }
  }
  return p;
}

// -dV/dx by central differences, column by column: entry (r, i) is
//   -(V(x + h e_ri) - V(x - h e_ri)) / (2 h),
// whose error is h^2/6 |d^3V/dx_ri^3| (truncation) plus about eps_mach |V| / h (rounding).
inline wb::Mat2X minus_gradient(const std::function<double(const wb::Mat2X&)>& V,
                                const wb::Mat2X& x, double h) {
  wb::Mat2X g(2, x.cols());
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    for (int r = 0; r < 2; ++r) {
      wb::Mat2X xp = x, xm = x;
      xp(r, i) += h;
      xm(r, i) -= h;
      g(r, i) = -(V(xp) - V(xm)) / (2 * h);
    }
  }
  return g;
}

}  // namespace
}  // namespace wbtest
