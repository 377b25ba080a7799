// Diagnosis probes of I4 (tests/common/wb_probe.h): a linear spring (one solve is exact), a
// nonlinear network (several Newton iterations), the single solve of Baraff and Witkin, a
// capped iteration, the three terms of the scale one at a time, a pinned particle, a solve that
// fails. The new state and each field of the report are recorded apart.
#include "implicit_probes.h"

// The lab's probe files compile as one unit (cmake/labs.cmake): each keeps its helpers in a
// namespace of its own.
namespace probe_I4_backward_euler {

namespace {
using improbe::Mat2X;
using improbe::spring;
using improbe::Vec2;

NewtonOptions options() {
  NewtonOptions o;
  o.tol = 1e-9, o.max_iterations = 20;
  return o;
}

void run(wbprobe::Probe& P, const SpringNetwork& net, const Mat2X& f_ext, double h,
         const NewtonOptions& o, Mat2X x, Mat2X v, bool residual, bool together = false) {
  P.call("backward_euler_step");
  improbe::network_in(P, net);
  P.in("f_ext", f_ext), P.in("h", h);
  P.in("opt.one_iteration", o.one_iteration), P.in("opt.max_iterations", o.max_iterations);
  P.in("opt.tol", o.tol), P.in("opt.definite", o.definite);
  if (o.solver == NewtonOptions::kCG) P.in("opt.solver (1: CG)", 1), P.in("opt.cg_tol", o.cg_tol);
  P.in("x", x), P.in("v", v);
  P.tol(1e-6, 1e-8);    // Newton stops within tol = 1e-9 of the scale: alternatives differ there
  NewtonWorkspace ws1;  // empty: a run's first step
  const NewtonReport r = backward_euler_step(net, f_ext, h, o, x, v, ws1);
  if (together) P.group("everything");  // one part's mistakes change some, another's others
  P.out("x", x), P.out("v", v);
  improbe::report_out(P, r, residual);
  P.group("");
}
}  // namespace

// A linear spring: the first solve is exact, so only the updates around Newton's iteration show.
WB_PROBE("I4", "linear",
         "one particle on a zero-rest-length spring to the origin, moving, h = 0.1") {
  SpringNetwork net;
  net.m = Eigen::VectorXd::Constant(1, 2.0);
  net.springs = {spring(0, -1, 50, 0)};
  run(P, net, Mat2X::Zero(2, 1), 0.1, options(), wbprobe::cols({{1, 0.5}}),
      wbprobe::cols({{0.3, -0.8}}), false);
}
// Newton's iteration on a nonlinear network.
WB_PROBE("I4", "network", "a small nonlinear network with drag and gravity, h = 0.05") {
  SpringNetwork net;
  Mat2X x, v;
  improbe::small_network(net, x, v);
  run(P, net, wbprobe::cols({{0, -9.8}, {0, -19.6}, {0, -4.9}, {0, -14.7}}), 0.05, options(), x,
      v, false);
}
// The single solve (its residual is not specified: NaN, or |G(y)|; backward_euler.h).
WB_PROBE("I4", "one-iteration", "the same network, one_iteration (Baraff and Witkin)") {
  P.simple();
  SpringNetwork net;
  Mat2X x, v;
  improbe::small_network(net, x, v);
  NewtonOptions o = options();
  o.one_iteration = true;
  run(P, net, wbprobe::cols({{0, -9.8}, {0, -19.6}, {0, -4.9}, {0, -14.7}}), 0.05, o, x, v,
      false);
}
// A capped iteration: the residual left after two solves.
WB_PROBE("I4", "capped", "the same network, at most 2 solves") {
  P.simple();
  SpringNetwork net;
  Mat2X x, v;
  improbe::small_network(net, x, v);
  NewtonOptions o = options();
  o.max_iterations = 2;
  run(P, net, wbprobe::cols({{0, -9.8}, {0, -19.6}, {0, -4.9}, {0, -14.7}}), 0.05, o, x, v, true);
}
// Newton's iteration, in one output: the same network capped at 2 solves, then with
// one_iteration.
WB_PROBE(
    "I4", "iteration",
    "the network capped at 2 solves, then with one_iteration: states and reports in one output") {
  SpringNetwork net;
  Mat2X x, v;
  improbe::small_network(net, x, v);
  const Mat2X g = wbprobe::cols({{0, -9.8}, {0, -19.6}, {0, -4.9}, {0, -14.7}});
  NewtonOptions capped = options(), one = options();
  capped.max_iterations = 2, one.one_iteration = true;
  P.call("backward_euler_step");
  improbe::network_in(P, net);
  P.in("f_ext", g), P.in("h", 0.05), P.in("x", x), P.in("v", v);
  P.tol(1e-6, 1e-8);
  Mat2X x1 = x, v1 = v, x2 = x, v2 = v;
  NewtonWorkspace ws2;  // empty: a run's first step
  const NewtonReport r1 = backward_euler_step(net, g, 0.05, capped, x1, v1, ws2);
  NewtonWorkspace ws3;  // empty: a run's first step
  const NewtonReport r2 = backward_euler_step(net, g, 0.05, one, x2, v2, ws3);
  P.group("everything");
  P.out("capped: x", x1), P.out("capped: v", v1);
  P.out("capped: report (iterations, converged, solver_failed, scale, residual)",
        improbe::report(r1, true));
  P.out("one_iteration: x", x2), P.out("one_iteration: v", v2);
  // (one_iteration's residual is not specified: NaN, or |G(y)|; backward_euler.h)
  P.out("one_iteration: report (iterations, converged, solver_failed, scale)",
        improbe::report(r2, false));
  // (the header leaves one_iteration's residual open, NaN or |G(y)|, but never 0, which reads
  // as solved)
  P.out("one_iteration: residual reported as 0 (1: yes; expected NaN or |G(y)|)",
        int(r2.residual == 0));
}
// The scale, one term at a time.
WB_PROBE("I4", "gliding",
         "two particles gliding with their spring at rest length, no force: scale |M v|") {
  P.simple();
  SpringNetwork net;
  net.m = Eigen::Vector2d(1.5, 0.5);
  net.springs = {spring(0, 1, 20, 5)};
  run(P, net, Mat2X::Zero(2, 2), 0.1, options(), wbprobe::cols({{0, 0}, {3, 4}}),
      wbprobe::cols({{0.5, -1}, {0.5, -1}}), false);
}
WB_PROBE("I4", "released",
         "two particles released from rest on a stretched spring: scale |b_0|") {
  P.simple();
  SpringNetwork net;
  net.m = Eigen::Vector2d(1.5, 0.5);
  net.springs = {spring(0, 1, 20, 2)};
  run(P, net, Mat2X::Zero(2, 2), 0.1, options(), wbprobe::cols({{0, 0}, {3, 4}}),
      Mat2X::Zero(2, 2), false);
}
WB_PROBE("I4", "hanging", "a particle at rest in equilibrium under gravity: scale h |f_ext|") {
  P.simple();
  SpringNetwork net;
  net.m = Eigen::VectorXd::Constant(1, 2.0);
  net.springs = {spring(0, -1, 49, 0, 0, Vec2(0, 1))};
  run(P, net, wbprobe::cols({{0, -19.6}}), 0.1, options(), wbprobe::cols({{0, 0.6}}),
      Mat2X::Zero(2, 1), false);
}
// A pinned particle that arrives moving.
WB_PROBE("I4", "pinned", "a chain of three, the middle one pinned and arriving with a velocity") {
  SpringNetwork net;
  net.m = Eigen::Vector3d(1.5, 2, 0.5);
  net.drag = 0.5;
  net.pinned = {0, 1, 0};
  net.springs = {spring(0, 1, 20, 2, 0.3), spring(1, 2, 15, 1, 0.2)};
  run(P, net, wbprobe::cols({{0, -1}, {0, -1}, {0, -1}}), 0.1, options(),
      wbprobe::cols({{0, 0}, {3, 4}, {4, 2}}),
      wbprobe::cols({{0.5, -1}, {0.3, 0.2}, {-0.5, 0.25}}), false);
}
// A failed solve: with the exact block (definite = false) of a spring compressed to half its
// rest length across x, and m = h^2 k, A has an exact zero pivot.
WB_PROBE("I4", "failed-solve",
         "the first solve fails (a zero pivot; then an infinite dv): reported, never NaN") {
  SpringNetwork net;
  net.m = Eigen::Vector3d(1.0, 2.0, 1.5);
  net.pinned = {0, 1, 0};
  net.springs = {spring(0, -1, 1.0, 2.0, 0.0, Vec2(0, 0)), spring(2, 1, 3.0, 1.0)};
  NewtonOptions o = options();
  o.definite = false;
  run(P, net, wbprobe::cols({{0, 0}, {0, 0}, {0, -1}}), 1.0, o,
      wbprobe::cols({{1, 0}, {5, 0}, {5, 1.5}}),
      wbprobe::cols({{0.5, 0}, {0.25, 1}, {-0.5, 0.25}}), true, true);
  // A solve that reports success and still returns an infinite dv (backward_euler.h: a failed
  // solve too): the same compressed spring alone, k a hair below m / h^2 (the pivot is
  // 2^-52 m), moving across it at 1e300 m/s. Recorded as flags (its state is 1e300: as numbers
  // it would set the probe's absolute tolerance).
  SpringNetwork tiny;
  tiny.m = Eigen::VectorXd::Constant(1, 1.0);
  tiny.springs = {spring(0, -1, 1.0 - 0x1.0p-52, 2.0, 0.0, Vec2(0, 0))};
  const Mat2X x1 = wbprobe::cols({{1, 0}}), v1 = wbprobe::cols({{0, 1e300}});
  Mat2X xt = x1, vt = v1;
  NewtonWorkspace wst;  // empty: a run's first step
  const NewtonReport rt = backward_euler_step(tiny, Mat2X::Zero(2, 1), 1.0, o, xt, vt, wst);
  P.note(
      "then one particle of mass 1 on a spring (k = 1 - 2^-52, rest 2) to the origin, at "
      "x = (1, 0), v = (0, 1e300), no f_ext, h = 1: LDLT succeeds, dv is infinite");
  P.group("everything");
  P.out("pivot 2^-52, v = 1e300: report (iterations, converged, solver_failed)",
        Eigen::Vector3d(rt.iterations, rt.converged, rt.solver_failed));
  P.out("pivot 2^-52, v = 1e300: residual NaN (1: yes)", int(std::isnan(rt.residual)));
  P.out("pivot 2^-52, v = 1e300: v' = v and x' = x + h v exactly (1: yes)",
        int(vt == v1 && xt == Mat2X(x1 + v1)));
  P.group("");
}

// Newton's iteration with CG, from an empty workspace (no warm start to use): each solve must
// hand the new A to CG's view of it (NewtonWorkspace::blocks, upper_blocks.h). A view never
// handed A fails; one handed only the first A makes Newton a chord method, linear: at h = 0.1
// with the exact Jacobian (definite false) it needs more solves than Newton's few.
WB_PROBE("I4", "cg-newton",
         "the network by Newton's method with CG (cg_tol 1e-12), h = 0.1, definite false") {
  SpringNetwork net;
  Mat2X x, v;
  improbe::small_network(net, x, v);
  NewtonOptions o = options();
  o.solver = NewtonOptions::kCG;
  o.cg_tol = 1e-12;
  o.definite = false;
  run(P, net, wbprobe::cols({{0, -9.8}, {0, -19.6}, {0, -4.9}, {0, -14.7}}), 0.1, o, x, v, false);
}

// CG's warm start (NewtonWorkspace::dv): a workspace left by an earlier step holds a guess; the
// step's first CG solve starts from it and leaves its own dv there. Two steps of the network
// with one_iteration, each from such a workspace: with a tolerance the guess already meets
// (cg_tol = 1e3: v' = v + guess), and with the default one (ws.dv: the solve's dv). One
// output: a guess ignored shows in the first, a dv not kept in the second.
WB_PROBE("I4", "warm-start",
         "CG from the workspace's dv: the network with one_iteration, ws.dv a guess, "
         "cg_tol 1e3 then 1e-12") {
  SpringNetwork net;
  Mat2X x, v;
  improbe::small_network(net, x, v);
  const Mat2X g = wbprobe::cols({{0, -9.8}, {0, -19.6}, {0, -4.9}, {0, -14.7}});
  Eigen::VectorXd guess(8);
  guess << 0.01, -0.02, 0.015, 0.005, -0.01, 0.02, 0.0, -0.005;
  NewtonOptions tight = options(), loose = options();
  tight.solver = loose.solver = NewtonOptions::kCG;
  tight.one_iteration = loose.one_iteration = true;
  loose.cg_tol = 1e3;
  P.call("backward_euler_step");
  improbe::network_in(P, net);
  P.in("f_ext", g), P.in("h", 0.05), P.in("opt.solver (1: CG)", int(NewtonOptions::kCG));
  P.in("opt.one_iteration", true), P.in("opt.cg_tol, then", 1e3), P.in("opt.cg_tol", 1e-12);
  P.in("x", x), P.in("v", v), P.in("ws.dv (a workspace left by an earlier step)", guess);
  P.tol(1e-6, 1e-8);  // CG stops within cg_tol of the scale
  Mat2X x1 = x, v1 = v, x2 = x, v2 = v;
  NewtonWorkspace ws1, ws2;
  ws1.dv = guess, ws2.dv = guess;
  backward_euler_step(net, g, 0.05, loose, x1, v1, ws1);
  backward_euler_step(net, g, 0.05, tight, x2, v2, ws2);
  P.group("warm start");
  P.out("cg_tol 1e3: v", v1), P.out("cg_tol 1e3: ws.dv after", ws1.dv);
  P.out("cg_tol 1e-12: ws.dv after", ws2.dv);
  P.group("");
}

}  // namespace probe_I4_backward_euler
