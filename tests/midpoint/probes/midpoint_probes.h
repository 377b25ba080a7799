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
// detail instead of a part named on a guess. There a second evaluation asked at the start state
// reads as a midpoint state built wrongly (x_mid = x, v_mid = v); the new velocity under the
// stages' forces (stages_velocity, below) tells the two apart.
#pragma once
#include <algorithm>
#include <limits>
#include <string>

#include "wb_probe_step.h"

// The step probes of tests/common/wb_probe_step.h (one particle, no force and falling; three
// particles under one state dependence at a time and under all; the evaluations alone), every
// one a detail: a counterexample a student can redo by hand, left out when parts are told apart.
#define MIDPOINT_STEP_DETAILS(task, fn, name) \
  WB_STEP_PROBES(task, fn, name, wbprobe::kState, wbprobe::kDetailsOnly)

// The stages probe: three moving particles whose force is A_i at the state they start from and
// G_i at any other (the second evaluation's, wherever a step puts it), so that a(X) and a at the
// second state are free of each other and of the motion. For the trapezoid it tells its two
// parts apart: a mistake of the first stage (X_a, the evaluations) changes where the forces are
// evaluated, one of the second stage or the average (X_b, X') only the new state. The second
// stage and the average are one part: X' = (X_a + X_b) / 2, so any wrong X' is a wrong X_b
// averaged right or a right X_b averaged wrong, and no probe of the step's inputs and outputs
// can tell which (docs/grading.md, "Writing probes"). For the midpoint step it is a detail (its
// launch probe tells the parts apart; this one would blur them): `tells_parts` false.
// The new state is recorded particle by particle.
namespace wbprobe {
namespace stage_forces {
inline const wb::Mat2X x0 = cols({{1, 2}, {-0.5, 0.5}, {2, -1}});
inline const wb::Mat2X v0 = cols({{3, -1}, {0.5, 2}, {-1.5, -0.5}});
inline const char* const kWords =
    "A_i at particle i's start state, G_i anywhere else; A = (2, -3), (-1, 0.5), (0.5, 4); "
    "G = (-1, 1.5), (3, 2), (-2.5, -0.5)";
// a(x, v): A_i where particle i is at its start state (x0, v0), G_i anywhere else.
inline Accel accel() {
  const wb::Mat2X A = cols({{2, -3}, {-1, 0.5}, {0.5, 4}});
  const wb::Mat2X G = cols({{-1, 1.5}, {3, 2}, {-2.5, -0.5}});
  return [A, G](const wb::Mat2X& xx, const wb::Mat2X& vv, wb::Mat2X& a) {
    a.resize(2, xx.cols());
    for (Eigen::Index i = 0; i < xx.cols(); ++i) {
      const bool start = i < x0.cols() && vv.cols() == xx.cols() && xx.col(i) == x0.col(i) &&
                         vv.col(i) == v0.col(i);
      a.col(i) = start ? A.col(std::min(i, A.cols() - 1)) : G.col(std::min(i, G.cols() - 1));
    }
  };
}
}  // namespace stage_forces

inline void stages(Probe& P, wb::StepFn fn, const char* name, bool tells_parts) {
  if (!tells_parts) P.simple();
  step(P, fn, name, stage_forces::kWords, stage_forces::accel(), stage_forces::x0,
       stage_forces::v0, 0.25, kBoth | kEach);
}

// The new velocity alone under the stages' forces (M1 `stages-v`, a probe that tells parts
// apart, where `stages` is a detail). With a(X) free of a at the second state, v' = v + h a_2
// is right whatever state the second evaluation is asked at, except the start state itself: a
// midpoint state built wrongly, or the forces asked at another wrong state, leave it right
// (they show in the launch probe), where the forces asked at the start state a second time
// take A for G. At the launch (a(X) = 0) those read alike. A wrong velocity update shows here
// too; a wrong position update (x moved with another velocity) does not.
inline void stages_velocity(Probe& P, wb::StepFn fn, const char* name) {
  const Accel accel = stage_forces::accel();
  wb::LambdaDynamics dyn(
      [&](const wb::Mat2X& xx, const wb::Mat2X& vv, wb::Mat2X& a) { accel(xx, vv, a); });
  wb::Mat2X x = stage_forces::x0, v = stage_forces::v0;
  wb::Scratch s;
  s.resize(x.cols());
  for (wb::Mat2X* m : {&s.a0, &s.a1, &s.a2, &s.a3, &s.x1, &s.v1, &s.xs, &s.vs})
    m->setConstant(std::numeric_limits<double>::quiet_NaN());
  P.call(name);
  P.note(std::string("dyn: a(x, v) = ") + stage_forces::kWords);
  P.in("h", 0.25), P.in("x", x), P.in("v", v);
  fn(dyn, 0.25, x, v, s);
  P.out_each("v", v);
}
}  // namespace wbprobe
