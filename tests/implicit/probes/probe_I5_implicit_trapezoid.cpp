// Diagnosis probes of I5 (tests/common/wb_probe.h): a linear spring, external forces, a pinned
// particle, a nonlinear network; the new state and the report recorded apart.
#include "implicit_probes.h"
#include "implicit_trapezoid.h"

// The lab's probe files compile as one unit (cmake/labs.cmake): each keeps its helpers in a
// namespace of its own.
namespace probe_I5_implicit_trapezoid {

namespace {
using improbe::Mat2X;
using improbe::spring;
using improbe::Vec2;

void run(wbprobe::Probe& P, const SpringNetwork& net, const Mat2X& f_ext, double h, Mat2X x,
         Mat2X v) {
  P.call("implicit_trapezoid_step");
  improbe::network_in(P, net);
  NewtonOptions o;
  o.tol = 1e-9;
  P.in("f_ext", f_ext), P.in("h", h), P.in("x", x), P.in("v", v);
  P.tol(1e-6, 1e-8);
  NewtonWorkspace ws1;  // empty: a run's first step
  const NewtonReport r = implicit_trapezoid_step(net, f_ext, h, o, x, v, ws1);
  P.group("everything");  // one part's mistakes change some, another's others
  P.out("x", x), P.out("v", v);
  improbe::report_out(P, r, false);
}
}  // namespace

// The half steps alone: no external force, nothing pinned, and a mass of 1, which silences the
// explicit half's own mistakes (a = F without the division by m, or times m, is right here): what
// goes wrong here is the steps' sizes or their order, never the explicit half's acceleration.
WB_PROBE("I5", "linear",
         "one particle of mass 1 on a zero-rest-length spring to the origin, moving, h = 0.1") {
  SpringNetwork net;
  net.m = Eigen::VectorXd::Constant(1, 1.0);
  net.springs = {spring(0, -1, 50, 0)};
  run(P, net, Mat2X::Zero(2, 1), 0.1, wbprobe::cols({{1, 0.5}}), wbprobe::cols({{0.3, -0.8}}));
}
// External forces alone.
WB_PROBE("I5", "external", "two free particles under external forces only, no spring") {
  P.simple();
  SpringNetwork net;
  net.m = Eigen::Vector2d(1.5, 0.5);
  run(P, net, wbprobe::cols({{0, -14.7}, {2, -4.9}}), 0.1, wbprobe::cols({{0, 0}, {3, 4}}),
      wbprobe::cols({{0.5, -1}, {-0.5, 0.25}}));
}
// A pinned particle that arrives moving.
WB_PROBE("I5", "pinned", "a chain of three, the middle one pinned and arriving with a velocity") {
  P.simple();
  SpringNetwork net;
  net.m = Eigen::Vector3d(1.5, 2, 0.5);
  net.drag = 0.5;
  net.pinned = {0, 1, 0};
  net.springs = {spring(0, 1, 20, 2, 0.3), spring(1, 2, 15, 1, 0.2)};
  run(P, net, wbprobe::cols({{0, -1}, {0, -1}, {0, -1}}), 0.1,
      wbprobe::cols({{0, 0}, {3, 4}, {4, 2}}),
      wbprobe::cols({{0.5, -1}, {0.3, 0.2}, {-0.5, 0.25}}));
}
// The explicit half: external forces, and a pinned particle that arrives moving, in one group.
WB_PROBE("I5", "explicit-half",
         "two free particles under external forces only, then a chain of three whose middle one "
         "is pinned and arriving with a velocity") {
  P.call("implicit_trapezoid_step (twice)");
  NewtonOptions o;
  o.tol = 1e-9;
  P.tol(1e-6, 1e-8);
  SpringNetwork free;
  free.m = Eigen::Vector2d(1.5, 0.5);
  Mat2X x1 = wbprobe::cols({{0, 0}, {3, 4}}), v1 = wbprobe::cols({{0.5, -1}, {-0.5, 0.25}});
  const Mat2X f1 = wbprobe::cols({{0, -14.7}, {2, -4.9}});
  SpringNetwork chain;
  chain.m = Eigen::Vector3d(1.5, 2, 0.5);
  chain.drag = 0.5;
  chain.pinned = {0, 1, 0};
  chain.springs = {spring(0, 1, 20, 2, 0.3), spring(1, 2, 15, 1, 0.2)};
  Mat2X x2 = wbprobe::cols({{0, 0}, {3, 4}, {4, 2}}),
        v2 = wbprobe::cols({{0.5, -1}, {0.3, 0.2}, {-0.5, 0.25}});
  const Mat2X f2 = wbprobe::cols({{0, -1}, {0, -1}, {0, -1}});
  improbe::network_in(P, free);
  P.in("f_ext", f1), P.in("x", x1), P.in("v", v1);
  improbe::network_in(P, chain);
  P.in("f_ext", f2), P.in("x", x2), P.in("v", v2), P.in("h", 0.1);
  NewtonWorkspace ws2;  // empty: a run's first step
  const NewtonReport r1 = implicit_trapezoid_step(free, f1, 0.1, o, x1, v1, ws2);
  NewtonWorkspace ws3;  // empty: a run's first step
  const NewtonReport r2 = implicit_trapezoid_step(chain, f2, 0.1, o, x2, v2, ws3);
  P.group("everything");
  P.out("free: x", x1), P.out("free: v", v1);
  P.out("free: report (iterations, converged, solver_failed, scale)", improbe::report(r1, false));
  P.out("chain: x", x2), P.out("chain: v", v2);
  P.out("chain: report (iterations, converged, solver_failed, scale)",
        improbe::report(r2, false));
}
// The half steps on a nonlinear network, one particle of it pinned and moving.
WB_PROBE("I5", "network",
         "a small nonlinear network with drag and gravity, particle 1 pinned, h = 0.05") {
  SpringNetwork net;
  Mat2X x, v;
  improbe::small_network(net, x, v);
  net.pinned = {0, 1, 0, 0};
  run(P, net, wbprobe::cols({{0, -9.8}, {0, -19.6}, {0, -4.9}, {0, -14.7}}), 0.05, x, v);
}

}  // namespace probe_I5_implicit_trapezoid
