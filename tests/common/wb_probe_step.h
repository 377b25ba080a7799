// Probes of one integrator step (tests/common/wb_probe.h), for the labs whose tasks are step
// functions (euler, midpoint): the step is taken once from a given state with accelerations
// written here, and the probe records the new state, how many times the forces were evaluated
// and at which states (the first four evaluations), so that a wrong evaluation point shows
// apart from a wrong update.
#pragma once
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "wb/dynamics.h"
#include "wb_probe.h"

namespace wbprobe {

using Accel = std::function<void(const wb::Mat2X& x, const wb::Mat2X& v, wb::Mat2X& a)>;

// A step of `name` (the step function `fn`) of size h from (x, v) under a(x, v) = `accel`,
// described in words by `words`. The scratch holds NaN on entry (its contents are undefined:
// any value is one a correct step ignores), or `fill` when given, and a note then says so.
// What a step probe records: the new state, the evaluations, or both; kEach: the new state
// particle by particle (P.out_each), where a particle may go wrong alone.
enum Record { kState = 1, kEvaluations = 2, kBoth = 3, kEach = 4 };

inline void step(Probe& P, wb::StepFn fn, const char* name, const std::string& words,
                 const Accel& accel, wb::Mat2X x, wb::Mat2X v, double h, int what = kBoth,
                 std::optional<double> fill = std::nullopt) {
  std::vector<wb::Mat2X> seen_x, seen_v;
  wb::LambdaDynamics dyn([&](const wb::Mat2X& xx, const wb::Mat2X& vv, wb::Mat2X& a) {
    seen_x.push_back(xx), seen_v.push_back(vv);
    accel(xx, vv, a);
  });
  wb::Scratch s;
  s.resize(x.cols());
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  for (wb::Mat2X* m : {&s.a0, &s.a1, &s.a2, &s.a3, &s.x1, &s.v1, &s.xs, &s.vs})
    m->setConstant(fill.value_or(nan));
  P.call(name);
  P.note("dyn: a(x, v) = " + words);
  if (fill)
    P.note(*fill == 0          ? "the scratch s holds zeros on entry"
           : std::isnan(*fill) ? "the scratch s holds NaN on entry"
                               : "the scratch s holds " + std::to_string(*fill) + " on entry");
  P.in("h", h), P.in("x", x), P.in("v", v);
  fn(dyn, h, x, v, s);
  if ((what & kState) && (what & kEach))
    P.out_each("x", x), P.out_each("v", v);
  else if (what & kState)
    P.out("x", x), P.out("v", v);
  if (!(what & kEvaluations)) return;
  // The evaluations in one output: one column each (the first four), the state it was asked
  // at, particle after particle: (x_0, v_0, x_1, v_1, ...).
  const Eigen::Index n = x.cols(), k = std::min<Eigen::Index>(4, Eigen::Index(seen_x.size()));
  Eigen::MatrixXd at(4 * n, k);
  for (Eigen::Index e = 0; e < k; ++e) {
    const wb::Mat2X& sx = seen_x[std::size_t(e)];
    const wb::Mat2X& sv = seen_v[std::size_t(e)];
    if (sx.cols() != n || sv.cols() != n) {
      at.resize(4 * n, 0);  // an evaluation of another size: shown as none
      break;
    }
    for (Eigen::Index i = 0; i < n; ++i) at.col(e).segment<4>(4 * i) << sx.col(i), sv.col(i);
  }
  P.out("force evaluations: (x_i, v_i) of each", at);
}

// Accelerations used by the step probes: none; constant per particle; a spring to the origin
// (depends on x only); a drag (depends on v only); all of them.
inline Accel no_force() {
  return [](const wb::Mat2X& x, const wb::Mat2X&, wb::Mat2X& a) { a.setZero(2, x.cols()); };
}
inline Accel constant(const wb::Mat2X& g) {
  return [g](const wb::Mat2X& x, const wb::Mat2X&, wb::Mat2X& a) {
    a = g.leftCols(std::min(g.cols(), x.cols()));
  };
}
inline Accel spring(double w2) {
  return [w2](const wb::Mat2X& x, const wb::Mat2X&, wb::Mat2X& a) { a = -w2 * x; };
}
inline Accel drag(double c) {
  return [c](const wb::Mat2X&, const wb::Mat2X& v, wb::Mat2X& a) { a = -c * v; };
}
inline Accel mixed(double w2, double c, const wb::Vec2& g) {
  return [w2, c, g](const wb::Mat2X& x, const wb::Mat2X& v, wb::Mat2X& a) {
    a = -w2 * x - c * v;
    a.colwise() += g;
  };
}

// The step probes of one integrator task, the same for every step function: the simple cases
// first (one particle, no force; one particle falling from rest: the new state and the
// evaluations), then the new state under one state dependence at a time and under all, then
// the evaluations alone (where an update goes wrong apart from where the forces are asked).
//
// Which probes tell parts apart (docs/grading.md, "Writing probes"): the general one (every
// dependence at once, generic values), the spring (a force that depends on x: where a force
// evaluated at the wrong state shows in v) and the evaluations; the others isolate one factor
// and are details. No force, a constant force and a drag alone are where a step that never
// asks for the forces goes wrong and a force evaluated at a moved position does not, where a
// position moved with the old velocity is right (at rest) and one moved with h/2 is not: as
// part-telling probes they split the force evaluation and the position update in two.
// `general`: how the general probe records the new state, kState or kState | kEach (particle
// by particle: where a position moved with the new velocity makes a velocity mistake change x
// and v of every particle, as a loop that skips the last particle changes them of that one).
// `which`: kTellParts, or kDetailsOnly where another probe tells the parts apart (midpoint's
// two-stage steps: tests/midpoint/probes/midpoint_probes.h says why).
enum StepProbes { kTellParts, kDetailsOnly };

#define WB_STEP_PROBES(task, fn, name, general, which)                                           \
  WB_PROBE(task, "free", "one particle, no force: h = 0.1") {                                    \
    P.simple();                                                                                  \
    wbprobe::step(P, &fn, name, "0", wbprobe::no_force(), wbprobe::cols({{1, 2}}),               \
                  wbprobe::cols({{3, -1}}), 0.1);                                                \
  }                                                                                              \
  WB_PROBE(task, "falling", "one particle falling from rest, a = (0, -10), h = 0.1") {           \
    P.simple();                                                                                  \
    wbprobe::step(P, &fn, name, "(0, -10)", wbprobe::constant(wbprobe::cols({{0, -10}})),        \
                  wbprobe::cols({{1, 2}}), wbprobe::cols({{0, 0}}), 0.1);                        \
  }                                                                                              \
  WB_PROBE(task, "drift", "three particles moving with no force, h = 0.25") {                    \
    P.simple();                                                                                  \
    wbprobe::step(P, &fn, name, "0", wbprobe::no_force(),                                        \
                  wbprobe::cols({{1, 2}, {-0.5, 0}, {2, -1}}),                                   \
                  wbprobe::cols({{3, -1}, {0.5, 2}, {-1.5, -0.5}}), 0.25, wbprobe::kState);      \
  }                                                                                              \
  WB_PROBE(task, "kick", "three particles at rest under constant forces, h = 0.25") {            \
    P.simple();                                                                                  \
    const wb::Mat2X g = wbprobe::cols({{0, -10}, {2, 1}, {-3, 0.5}});                            \
    wbprobe::step(P, &fn, name, "a constant per particle: (0, -10), (2, 1), (-3, 0.5)",          \
                  wbprobe::constant(g), wbprobe::cols({{1, 2}, {-0.5, 0}, {2, -1}}),             \
                  wbprobe::cols({{0, 0}, {0, 0}, {0, 0}}), 0.25, wbprobe::kState);               \
  }                                                                                              \
  WB_PROBE(task, "spring",                                                                       \
           "three moving particles on springs to the origin, a = -4 x, h = 0.25") {              \
    if ((which) == wbprobe::kDetailsOnly) P.simple();                                            \
    wbprobe::step(P, &fn, name, "-4 x", wbprobe::spring(4),                                      \
                  wbprobe::cols({{1, 2}, {-0.5, 0}, {2, -1}}),                                   \
                  wbprobe::cols({{3, -1}, {0.5, 2}, {-1.5, -0.5}}), 0.25, wbprobe::kState);      \
  }                                                                                              \
  WB_PROBE(task, "drag", "three moving particles under a drag, a = -3 v, h = 0.25") {            \
    P.simple();                                                                                  \
    wbprobe::step(P, &fn, name, "-3 v", wbprobe::drag(3),                                        \
                  wbprobe::cols({{1, 2}, {-0.5, 0}, {2, -1}}),                                   \
                  wbprobe::cols({{3, -1}, {0.5, 2}, {-1.5, -0.5}}), 0.25, wbprobe::kState);      \
  }                                                                                              \
  WB_PROBE(task, "general", "three moving particles, a = -4 x - 3 v + (0, -10), h = 0.25") {     \
    if ((which) == wbprobe::kDetailsOnly) P.simple();                                            \
    wbprobe::step(P, &fn, name, "-4 x - 3 v + (0, -10)", wbprobe::mixed(4, 3, wb::Vec2(0, -10)), \
                  wbprobe::cols({{1, 2}, {-0.5, 0}, {2, -1}}),                                   \
                  wbprobe::cols({{3, -1}, {0.5, 2}, {-1.5, -0.5}}), 0.25, general);              \
  }                                                                                              \
  WB_PROBE(task, "evaluations",                                                                  \
           "where the forces are evaluated: three moving particles, a = -4 x - 3 v + (0, -10), " \
           "h = 0.25") {                                                                         \
    if ((which) == wbprobe::kDetailsOnly) P.simple();                                            \
    wbprobe::step(P, &fn, name, "-4 x - 3 v + (0, -10)", wbprobe::mixed(4, 3, wb::Vec2(0, -10)), \
                  wbprobe::cols({{1, 2}, {-0.5, 0}, {2, -1}}),                                   \
                  wbprobe::cols({{3, -1}, {0.5, 2}, {-1.5, -0.5}}), 0.25,                        \
                  wbprobe::kEvaluations);                                                        \
  }
}  // namespace wbprobe
