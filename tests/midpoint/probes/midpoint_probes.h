// Shared by the midpoint lab's probes (tests/common/wb_probe_step.h): the step probes of the
// euler lab, all written as details here, and the probe that tells the parts of a two-stage
// step apart.
//
// Why only one probe tells parts apart (docs/grading.md, "Writing probes"): the mistakes of a
// two-stage step all change the new state, and most of them also change where the forces are
// evaluated, so a generic probe sees every mistake everywhere. A velocity built wrongly for the
// second stage (a stale or missing start acceleration, a midpoint velocity off by a factor)
// shows exactly as a force evaluated at the wrong velocity does, and the diagnosis would name
// one for the other. The launch below starts at the centre of a spring, where the start
// acceleration is zero: what depends on it (the midpoint velocity, the start acceleration in
// the update) cannot go wrong there, and what is left tells the second stage's position, the
// final update and the evaluations apart. Mistakes it cannot see get the counterexample of a
// detail instead of a part named on a guess.
#pragma once
#include <limits>
#include <string>
#include <vector>

#include "wb_probe_step.h"

namespace midprobe {

// One step of `fn` from (x, v) under `accel`, like wbprobe::step, with the scratch filled with
// `fill` on entry (its contents are undefined: any value is one a correct step ignores), and
// x, v and the evaluations recorded as three outputs that go wrong apart.
inline void step(wbprobe::Probe& P, wb::StepFn fn, const char* name, const std::string& words,
                 const wbprobe::Accel& accel, wb::Mat2X x, wb::Mat2X v, double h, double fill) {
  std::vector<wb::Mat2X> seen_x, seen_v;
  wb::LambdaDynamics dyn([&](const wb::Mat2X& xx, const wb::Mat2X& vv, wb::Mat2X& a) {
    seen_x.push_back(xx), seen_v.push_back(vv);
    accel(xx, vv, a);
  });
  wb::Scratch s;
  s.resize(x.cols());
  for (wb::Mat2X* m : {&s.a0, &s.a1, &s.a2, &s.a3, &s.x1, &s.v1, &s.xs, &s.vs})
    m->setConstant(fill);
  P.call(name);
  P.note("dyn: a(x, v) = " + words);
  P.note(fill == 0 ? "the scratch s holds zeros on entry" : "the scratch s holds NaN on entry");
  P.in("h", h), P.in("x", x), P.in("v", v);
  fn(dyn, h, x, v, s);
  P.out("x", x), P.out("v", v);
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

}  // namespace midprobe

// The step probes of tests/common/wb_probe_step.h (one particle, no force and falling; three
// particles under one state dependence at a time and under all; the evaluations alone), every
// one a detail: a counterexample a student can redo by hand, left out when parts are told apart.
#define MIDPOINT_STEP_DETAILS(task, fn, name)                                                    \
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
    P.simple();                                                                                  \
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
    P.simple();                                                                                  \
    wbprobe::step(P, &fn, name, "-4 x - 3 v + (0, -10)", wbprobe::mixed(4, 3, wb::Vec2(0, -10)), \
                  wbprobe::cols({{1, 2}, {-0.5, 0}, {2, -1}}),                                   \
                  wbprobe::cols({{3, -1}, {0.5, 2}, {-1.5, -0.5}}), 0.25, wbprobe::kState);      \
  }                                                                                              \
  WB_PROBE(task, "evaluations",                                                                  \
           "where the forces are evaluated: three moving particles, a = -4 x - 3 v + (0, -10), " \
           "h = 0.25") {                                                                         \
    P.simple();                                                                                  \
    wbprobe::step(P, &fn, name, "-4 x - 3 v + (0, -10)", wbprobe::mixed(4, 3, wb::Vec2(0, -10)), \
                  wbprobe::cols({{1, 2}, {-0.5, 0}, {2, -1}}),                                   \
                  wbprobe::cols({{3, -1}, {0.5, 2}, {-1.5, -0.5}}), 0.25,                        \
                  wbprobe::kEvaluations);                                                        \
  }
