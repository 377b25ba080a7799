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
#include <algorithm>

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
inline void stages(Probe& P, wb::StepFn fn, const char* name, bool tells_parts) {
  if (!tells_parts) P.simple();
  const wb::Mat2X x = cols({{1, 2}, {-0.5, 0.5}, {2, -1}});
  const wb::Mat2X v = cols({{3, -1}, {0.5, 2}, {-1.5, -0.5}});
  const wb::Mat2X A = cols({{2, -3}, {-1, 0.5}, {0.5, 4}});
  const wb::Mat2X G = cols({{-1, 1.5}, {3, 2}, {-2.5, -0.5}});
  const Accel accel = [x, v, A, G](const wb::Mat2X& xx, const wb::Mat2X& vv, wb::Mat2X& a) {
    a.resize(2, xx.cols());
    for (Eigen::Index i = 0; i < xx.cols(); ++i) {
      const bool start = i < x.cols() && vv.cols() == xx.cols() && xx.col(i) == x.col(i) &&
                         vv.col(i) == v.col(i);
      a.col(i) = start ? A.col(std::min(i, A.cols() - 1)) : G.col(std::min(i, G.cols() - 1));
    }
  };
  step(P, fn, name,
       "A_i at particle i's start state, G_i anywhere else; A = (2, -3), (-1, 0.5), (0.5, 4); "
       "G = (-1, 1.5), (3, 2), (-2.5, -0.5)",
       accel, x, v, 0.25, kBoth | kEach);
}
}  // namespace wbprobe
