// The loops of the euler tests' long runs (10^6 steps), as one function each: in the grader's
// build a test's calls to the lab go to a separate worker process, and a call per step would
// cost a million round trips; this function runs beside the lab's code, so it is one call
// (docs/grading.md "Batching"). In an ordinary build it is a plain function.
//
// It runs beside student code: in the grader everything it returns comes from the worker and
// is hostile. So it returns the states it passed through (checkpoints), and the tests check
// every segment between two checkpoints with steps of the method they take themselves
// (eulertest::check_long_run, euler_test_helpers.h), then compute what they judge (energies)
// from those on their own side: a run that skipped steps or made up its states fails there.
#pragma once
#include "wb/types.h"

// n steps of the explicit (method 0) or semi-implicit (method 1) Euler step on the harmonic
// oscillator a = -w^2 x (unit masses) from (x, v), the work arrays NaN on entry to every step,
// as the tests' Run does; n must be a multiple of `every`. On return x, v are the final state
// and xs, vs hold the state before the first step and after every `every` steps: checkpoint c
// of particle i is column c * x.cols() + i (n / every + 1 checkpoints).
void euler_oscillator_run(int method, double w, double h, long n, long every, wb::Mat2X& x,
                          wb::Mat2X& v, wb::Mat2X& xs, wb::Mat2X& vs);
