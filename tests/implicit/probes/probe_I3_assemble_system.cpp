// Diagnosis probes of I3 (tests/common/wb_probe.h): A and b of small networks, linearised at a
// Newton iterate (x_l = x0 + h v_l: the K term of b vanishes) and at the start, with drag, a
// pinned particle, a compressed spring with and without the clamp.
#include "assemble_system.h"
#include "implicit_probes.h"

// The lab's probe files compile as one unit (cmake/labs.cmake): each keeps its helpers in a
// namespace of its own.
namespace probe_I3_assemble_system {

namespace {
using improbe::Mat2X;
using improbe::spring;
using improbe::Vec2;

// What A stores below its diagonal: nothing (only the upper triangle is stored). Its own
// output: a triangle stored the other way round goes wrong here, not only in A.
void stored_below(wbprobe::Probe& P, const SparseSystem& sys) {
  const Eigen::MatrixXd below = Eigen::MatrixXd(sys.A).triangularView<Eigen::StrictlyLower>();
  P.out("what A stores below its diagonal (nothing: only the upper triangle)", below);
}

// The symmetric matrix A's values stand for, whichever triangle holds them: each entry off
// the diagonal read from the upper triangle, or from the lower one where the upper holds
// nothing. A wrong value goes wrong here; a triangle stored the other way round, or both, goes
// wrong in what A stores below its diagonal alone (the storage, apart from the values).
Eigen::MatrixXd values(const Eigen::SparseMatrix<double>& A) {
  Eigen::MatrixXd V(A);
  if (V.rows() != V.cols()) return V;  // the wrong size shows as it is
  for (Eigen::Index j = 0; j < V.cols(); ++j)
    for (Eigen::Index i = 0; i < j; ++i) V(i, j) = V(j, i) = V(i, j) != 0 ? V(i, j) : V(j, i);
  return V;
}

// A as a solver that reads its upper triangle sees it (Eigen::Upper, as backward_euler does).
Eigen::MatrixXd as_upper(const Eigen::SparseMatrix<double>& A) {
  return Eigen::MatrixXd(Eigen::SparseMatrix<double>(A.selfadjointView<Eigen::Upper>()));
}

void run(wbprobe::Probe& P, const SpringNetwork& net, const Mat2X& x0, const Mat2X& v0,
         const Mat2X& xl, const Mat2X& vl, const Mat2X& f_ext, double h, bool definite) {
  P.call("assemble_system");
  improbe::network_in(P, net);
  P.in("x0", x0), P.in("v0", v0), P.in("xl", xl), P.in("vl", vl), P.in("f_ext", f_ext);
  P.in("h", h), P.in("definite", definite);
  SparseSystem sys;
  assemble_system(net, x0, v0, xl, vl, f_ext, h, definite, sys);
  P.out("A (the values, from whichever triangle stores them)", values(sys.A));
  P.out("b", sys.b);
  stored_below(P, sys);
}

// Two free particles on a spring, stretched, drag 0.5.
SpringNetwork pair(double rest) {
  SpringNetwork net;
  net.m = Eigen::Vector2d(1.5, 0.5);
  net.drag = 0.5;
  net.springs = {spring(0, 1, 20, rest, 0.3)};
  return net;
}
const Mat2X kX = wbprobe::cols({{0, 0}, {3, 4}});
const Mat2X kV = wbprobe::cols({{0.5, -1}, {-0.5, 0.25}});

// Three particles in a chain, the middle one pinned, drag 0.5; its state and a Newton
// iterate's velocity (the middle particle's 0).
SpringNetwork chain() {
  SpringNetwork net;
  net.m = Eigen::Vector3d(1.5, 2, 0.5);
  net.drag = 0.5;
  net.pinned = {0, 1, 0};
  net.springs = {spring(0, 1, 20, 2, 0.3), spring(1, 2, 15, 1, 0.2)};
  return net;
}
const Mat2X kChainX = wbprobe::cols({{0, 0}, {3, 4}, {4, 2}});
const Mat2X kChainV = wbprobe::cols({{0.5, -1}, {0, 0}, {-0.5, 0.25}});
const Mat2X kChainVl = wbprobe::cols({{0.25, -0.5}, {0, 0}, {-0.75, 0.5}});
}  // namespace

WB_PROBE("I3", "one-anchored",
         "one particle of mass 1 on a spring to an anchor, at rest, h = 0.1") {
  P.simple();
  SpringNetwork net;
  net.m = Eigen::VectorXd::Constant(1, 1.0);
  net.springs = {spring(0, -1, 10, 0.5, 0, Vec2(0, 0))};
  const Mat2X x = wbprobe::cols({{1, 0}}), v = wbprobe::cols({{0, 0}});
  run(P, net, x, v, x, v, wbprobe::cols({{0, 0}}), 0.1, true);
}
// What a solver reading the upper triangle sees (a detail: a storage mistake shows here as a
// wrong value, and it tells the lower triangle from both).
WB_PROBE("I3", "upper",
         "two free particles on a stretched spring: A read from its upper "
         "triangle (Eigen::Upper)") {
  P.simple();
  const Mat2X vl = wbprobe::cols({{0.25, -0.5}, {-0.75, 0.5}});
  P.call("assemble_system");
  improbe::network_in(P, pair(2));
  P.in("x0", kX), P.in("v0", kV), P.in("xl", kX + 0.1 * vl), P.in("vl", vl);
  P.in("f_ext", wbprobe::cols({{0, -1.5}, {0.5, 0}})), P.in("h", 0.1), P.in("definite", true);
  SparseSystem sys;
  assemble_system(pair(2), kX, kV, kX + 0.1 * vl, vl, wbprobe::cols({{0, -1.5}, {0.5, 0}}), 0.1,
                  true, sys);
  P.out("A read from its upper triangle, mirrored", as_upper(sys.A));
}
// The matrix and b at a Newton iterate (x_l = x0 + h v_l).
WB_PROBE("I3", "iterate",
         "two free particles on a stretched spring, drag 0.5, at a Newton iterate") {
  const Mat2X vl = wbprobe::cols({{0.25, -0.5}, {-0.75, 0.5}});
  run(P, pair(2), kX, kV, kX + 0.1 * vl, vl, wbprobe::cols({{0, -1.5}, {0.5, 0}}), 0.1, true);
}
// The K term of b: linearised away from the iterate.
WB_PROBE("I3", "start", "the same pair linearised at the start (x_l = x0, v_l = v0)") {
  run(P, pair(2), kX, kV, kX, kV, wbprobe::cols({{0, -1.5}, {0.5, 0}}), 0.1, true);
}
// A compressed spring: the clamp (definite) matters.
WB_PROBE("I3", "compressed-exact",
         "the pair compressed to half its rest length, definite = false") {
  const Mat2X vl = wbprobe::cols({{0.25, -0.5}, {-0.75, 0.5}});
  run(P, pair(10), kX, kV, kX + 0.1 * vl, vl, wbprobe::cols({{0, 0}, {0, 0}}), 0.1, false);
}
WB_PROBE("I3", "compressed-clamped",
         "the pair compressed to half its rest length, definite = true") {
  const Mat2X vl = wbprobe::cols({{0.25, -0.5}, {-0.75, 0.5}});
  run(P, pair(10), kX, kV, kX + 0.1 * vl, vl, wbprobe::cols({{0, 0}, {0, 0}}), 0.1, true);
}
// A pinned particle between two free ones.
WB_PROBE("I3", "pinned",
         "three particles in a chain, the middle one pinned, at a Newton iterate") {
  const SpringNetwork net = chain();
  const Mat2X &x = kChainX, &v = kChainV, &vl = kChainVl;
  run(P, net, x, v, x + 0.1 * vl, vl, wbprobe::cols({{0, -1}, {0, -1}, {0, -1}}), 0.1, true);
}

// A later assembly of the same system: the chain above assembled at the start, then again
// (the same sys: its pattern and slots kept) at a Newton iterate. The header asks that it be
// what a first assembly there gives (A's values zeroed, then each value added at its slot), so
// the probe records the difference from a first assembly at that point (a fresh sys) by the
// same code: 0, whatever the values. A mistake in the values themselves shows in the other
// probes, one in reusing the pattern only here.
WB_PROBE("I3", "again",
         "the pinned chain assembled at the start, then again into the same sys at a Newton "
         "iterate: minus a first assembly there") {
  const SpringNetwork net = chain();
  const Mat2X &x = kChainX, &v = kChainV, &vl = kChainVl;
  const Mat2X xl = x + 0.1 * vl;
  const Mat2X f = wbprobe::cols({{0, -1}, {0, -1}, {0, -1}});
  P.call("assemble_system");
  improbe::network_in(P, net);
  P.note(
      "first assemble_system(net, x0, v0, x0, v0, f_ext, h, definite, sys) with sys empty, "
      "then the call below with that sys, compared with the call below on an empty sys");
  P.in("x0", x), P.in("v0", v), P.in("xl", xl), P.in("vl", vl), P.in("f_ext", f);
  P.in("h", 0.1), P.in("definite", true);
  SparseSystem sys, fresh;
  assemble_system(net, x, v, x, v, f, 0.1, true, sys);
  assemble_system(net, x, v, xl, vl, f, 0.1, true, sys);
  assemble_system(net, x, v, xl, vl, f, 0.1, true, fresh);
  const Eigen::MatrixXd again =
      Eigen::SparseMatrix<double>(sys.A.selfadjointView<Eigen::Upper>());
  const Eigen::MatrixXd first =
      Eigen::SparseMatrix<double>(fresh.A.selfadjointView<Eigen::Upper>());
  P.group("the second assembly");
  P.out("A of the second assembly minus A of a first one (0)", Eigen::MatrixXd(again - first));
  P.out("b of the second assembly minus b of a first one (0)", Eigen::VectorXd(sys.b - fresh.b));
  P.group("");
}

}  // namespace probe_I3_assemble_system
