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
#include "wb_probe_step.h"

// The step probes of tests/common/wb_probe_step.h (one particle, no force and falling; three
// particles under one state dependence at a time and under all; the evaluations alone), every
// one a detail: a counterexample a student can redo by hand, left out when parts are told apart.
#define MIDPOINT_STEP_DETAILS(task, fn, name) \
  WB_STEP_PROBES(task, fn, name, wbprobe::kState, wbprobe::kDetailsOnly)
