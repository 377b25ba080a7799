// The loop of the rigid tests' million-step run, as one function: in the grader's build a
// test's calls to the lab go to a separate worker process, and a call per step would cost a
// million round trips; this function runs beside the lab's code, so it is one call
// (docs/grading.md "Batching"). In an ordinary build it is a plain function.
//
// It runs beside student code: in the grader what it returns comes from the worker and is
// hostile. So it also returns the body every `every` steps (checkpoints), and the test checks
// every segment between two checkpoints with the header's update taken by the test itself
// (test_R4_integrate_position.cpp): a run that skipped steps or made up its result fails there.
#pragma once
#include <vector>

#include "rigid_body.h"

// n steps of integrate_position(b, h), b.omega left as it is (a constant spin); n a multiple
// of `every`. states: the body before the first step and after every `every` steps
// (n / every + 1 of them).
void rigid_spin_run(rigid::Body& b, double h, long n, long every,
                    std::vector<rigid::Body>& states);
