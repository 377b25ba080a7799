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
#include <cmath>
#include <sstream>
#include <string>

#include <catch2/catch.hpp>

#include "wb/types.h"

namespace wbtest {

// |a - b| <= abs_tol + rel_tol * max(|a|, |b|)
inline bool near(double a, double b, double abs_tol, double rel_tol = 0.0) {
  return std::abs(a - b) <= abs_tol + rel_tol * std::max(std::abs(a), std::abs(b));
}

inline std::string str(const wb::Vec2& v) {
  std::ostringstream s;
  s.precision(17);
  s << "(" << v.x() << ", " << v.y() << ")";
  return s.str();
}

// Checks one vector against its expected value; `what` names the quantity
// (and the law it comes from) for the failure message.
inline void require_near(const wb::Vec2& got, const wb::Vec2& expected, double abs_tol,
                         const std::string& what, double rel_tol = 0.0) {
  INFO(what << "\n  expected " << str(expected) << "\n  got      " << str(got)
            << "\n  tolerance " << abs_tol << " + " << rel_tol << " * |value|");
  REQUIRE(near(got.x(), expected.x(), abs_tol, rel_tol));
  REQUIRE(near(got.y(), expected.y(), abs_tol, rel_tol));
}

inline void require_near(double got, double expected, double abs_tol, const std::string& what,
                         double rel_tol = 0.0) {
  INFO(what << "\n  expected " << expected << "\n  got      " << got << "\n  tolerance "
            << abs_tol << " + " << rel_tol << " * |value|");
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

inline void require_finite(const wb::Mat2X& m, const std::string& what) {
  INFO(what << ": every entry must be finite (no NaN or inf)\n  got " << m);
  REQUIRE(m.allFinite());
}

}  // namespace wbtest
