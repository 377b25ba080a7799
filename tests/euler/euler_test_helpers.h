// Test-written dynamics and a stepping loop for the euler lab's graded tests.
// Nothing here uses the forces lab: every acceleration is written in the test.
#pragma once
#include <cmath>
#include <limits>
#include <vector>

#include "test_helpers.h"
#include "wb/dynamics.h"

namespace eulertest {

using wb::Mat2X;
using wb::Vec2;

// Runs one step function on a state, with a scratch that holds NaN on entry to
// every step (its contents are undefined: a step must write before it reads).
// Records the state each force evaluation saw.
struct Run {
  wb::LambdaDynamics dyn;
  Mat2X x, v;
  wb::Scratch s;
  std::vector<Mat2X> seen_x, seen_v;  // the arguments of every evaluation, if recording
  bool record = false;

  Run(wb::LambdaDynamics::Fn accel, const Mat2X& x0, const Mat2X& v0)
      : dyn([this, accel](const Mat2X& xx, const Mat2X& vv, Mat2X& a) {
          if (record) seen_x.push_back(xx), seen_v.push_back(vv);
          accel(xx, vv, a);
        }),
        x(x0),
        v(v0) {
    s.resize(x0.cols());
  }
  Run(const Run&) = delete;  // dyn refers to this object
  Run& operator=(const Run&) = delete;

  void step(wb::StepFn fn, double h) {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    for (Mat2X* m : {&s.a0, &s.a1, &s.a2, &s.a3, &s.x1, &s.v1, &s.xs, &s.vs}) m->setConstant(nan);
    fn(dyn, h, x, v, s);
  }
};

// a_i = -w^2 x_i for every particle: a harmonic oscillator about the origin
// (a zero-rest-length spring to an anchor at the origin, k / m = w^2).
inline wb::LambdaDynamics::Fn oscillator(double w) {
  return [w](const Mat2X& x, const Mat2X&, Mat2X& a) { a = -(w * w) * x; };
}

// E = 1/2 m |v|^2 + 1/2 k |x|^2, summed over particles of mass m, stiffness k.
inline double oscillator_energy(const Mat2X& x, const Mat2X& v, double m, double k) {
  return 0.5 * m * v.squaredNorm() + 0.5 * k * x.squaredNorm();
}

// a = -GM x / |x|^3: a point attractor of strength GM at the origin.
inline wb::LambdaDynamics::Fn attractor(double GM) {
  return [GM](const Mat2X& x, const Mat2X&, Mat2X& a) {
    for (Eigen::Index i = 0; i < x.cols(); ++i) {
      const double r = x.col(i).norm();
      a.col(i) = -GM / (r * r * r) * x.col(i);
    }
  };
}

inline Mat2X cols(std::initializer_list<Vec2> list) {
  Mat2X m(2, Eigen::Index(list.size()));
  Eigen::Index i = 0;
  for (const Vec2& c : list) m.col(i++) = c;
  return m;
}

}  // namespace eulertest
