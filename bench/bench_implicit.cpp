// One backward-Euler step (Newton's method with a sparse solve, the implicit
// lab's solution) on a hanging rope and a hanging cloth from 10^2 to 10^5
// particles, against one semi-implicit Euler step (the euler lab's solution)
// of the same network in the same run. docs/benchmarks.md, section implicit.
//
//   be/<shape>_<solver>/<n>   the lab's backward_euler_step (the solution), h = 1/60 s,
//                             one NewtonWorkspace carried from step to step as a run
//                             carries it; default options (tol 1e-9, cg_tol 1e-12);
//                             solver ldlt, cg, or ldlt1 / cg1 = one_iteration (Baraff
//                             and Witkin: one solve per step; cg1 with cg_tol 1e-2, as
//                             the handout sets it for a cloth); counters: Newton
//                             solves per step (iters), steps that did not converge,
//                             particles (n)
//   fast/<shape>_<solver>[1]/<n>  the same step by the provided fast path
//                             (framework/drivers/implicit/fast_backward_euler.h): pattern
//                             analysed once (outside the timing), values assembled in
//                             place; solver auto, ldlt, cholmod or cg; "1" = one solve
//                             (baraff-witkin-fast), else Newton to tol 1e-9
//                             (backward-euler-fast); extra counter: cg_iters per step
//   fast/second_<shape>_<solver>[1]/<n>  the same, over exactly the first simulated
//                             second (60 steps from rest): the same motion at every n,
//                             so that times per step compare across sizes
//   fast_setup/<shape>/<n>    the fast path's analysis alone (once per run)
//   product/cloth_<how>/<n>   one product with I3's A: Eigen's upper-triangle product
//                             against the provided UpperBlocks that I4's CG uses
//   se/<shape>/<n>            symplectic_euler_step on the same springs and
//                             gravity (network_forces), h = 1e-4 s, inside its
//                             stability limit (h sqrt(k/m) = 0.1 per spring)
//
// The networks are those of the scenes' generators: springs of k = 1e4 N/m
// between particles of 10 g (k/m = 1e6), rest lengths = initial distances,
// gravity, the top pinned (rope: first bead; cloth: the two top corners;
// cloth springs: structural, shear, and bend of k/10). The state advances
// from one timed step to the next (the rope and cloth fall and swing), so the
// Newton count is an average over the first steps of a real motion.
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

#include "backward_euler.h"
#include "fast_backward_euler.h"
#include "network_forces.h"
#include "symplectic_euler.h"
#include "wb/dynamics.h"

namespace {

constexpr double kK = 1e4, kM = 0.01, kSpacing = 0.05, kG = -9.81;

struct Setup {
  SpringNetwork net;
  wb::Mat2X x, v, f_ext;
};

void add(Setup& s, Eigen::Index i, Eigen::Index j, double k) {
  NetworkSpring sp;
  sp.i = i;
  sp.j = j;
  sp.k = k;
  sp.rest = (s.x.col(i) - s.x.col(j)).norm();
  s.net.springs.push_back(sp);
}

Setup rope(Eigen::Index n) {
  Setup s;
  s.x.resize(2, n);
  for (Eigen::Index q = 0; q < n; ++q) s.x.col(q) = wb::Vec2(q * kSpacing, 0.0);
  for (Eigen::Index q = 1; q < n; ++q) add(s, q - 1, q, kK);
  s.net.pinned.assign(std::size_t(n), 0);
  s.net.pinned[0] = 1;
  return s;
}

Setup cloth(Eigen::Index side) {
  Setup s;
  const Eigen::Index n = side * side;
  s.x.resize(2, n);
  auto id = [side](Eigen::Index r, Eigen::Index c) { return r * side + c; };
  for (Eigen::Index r = 0; r < side; ++r)
    for (Eigen::Index c = 0; c < side; ++c) s.x.col(id(r, c)) = wb::Vec2(c, -r) * kSpacing;
  for (Eigen::Index r = 0; r < side; ++r) {
    for (Eigen::Index c = 0; c < side; ++c) {
      if (c + 1 < side) add(s, id(r, c), id(r, c + 1), kK);
      if (r + 1 < side) add(s, id(r, c), id(r + 1, c), kK);
      if (r + 1 < side && c + 1 < side) {
        add(s, id(r, c), id(r + 1, c + 1), kK);
        add(s, id(r, c + 1), id(r + 1, c), kK);
      }
      if (c + 2 < side) add(s, id(r, c), id(r, c + 2), 0.1 * kK);
      if (r + 2 < side) add(s, id(r, c), id(r + 2, c), 0.1 * kK);
    }
  }
  s.net.pinned.assign(std::size_t(n), 0);
  s.net.pinned[std::size_t(id(0, 0))] = 1;
  s.net.pinned[std::size_t(id(0, side - 1))] = 1;
  return s;
}

Setup make(bool is_cloth, Eigen::Index n) {
  Setup s = is_cloth ? cloth(Eigen::Index(std::lround(std::sqrt(double(n))))) : rope(n);
  const Eigen::Index N = s.x.cols();
  s.net.m = wb::VecX::Constant(N, kM);
  s.v = wb::Mat2X::Zero(2, N);
  s.f_ext = wb::Mat2X::Zero(2, N);
  s.f_ext.row(1).setConstant(kM * kG);
  for (Eigen::Index p = 0; p < N; ++p)
    if (s.net.is_pinned(p)) s.f_ext.col(p).setZero();
  return s;
}

void be(benchmark::State& state, bool is_cloth, NewtonOptions::Solver solver,
        bool one_iteration) {
  Setup s = make(is_cloth, state.range(0));
  NewtonOptions opt;
  opt.solver = solver;
  opt.one_iteration = one_iteration;
  if (solver == NewtonOptions::kCG && one_iteration) opt.cg_tol = 1e-2;
  NewtonWorkspace ws;
  long solves = 0, steps = 0, failed = 0;
  for (auto _ : state) {
    const NewtonReport r = backward_euler_step(s.net, s.f_ext, 1.0 / 60.0, opt, s.x, s.v, ws);
    solves += r.iterations;
    failed += r.converged ? 0 : 1;
    ++steps;
    benchmark::DoNotOptimize(s.x.data());
  }
  state.counters["iters"] = double(solves) / double(steps);
  state.counters["not_converged"] = double(failed);
  state.counters["n"] = double(s.x.cols());
}

void fast(benchmark::State& state, bool is_cloth, wb::FastSolverOptions::Solver solver,
          bool one_iteration) {
  Setup s = make(is_cloth, state.range(0));
  wb::FastSolverOptions fo;
  fo.solver = solver;
  if (solver == wb::FastSolverOptions::kCholmod && !wb::have_cholmod()) {
    state.SkipWithError("this build has no CHOLMOD (WB_CHOLMOD)");
    return;
  }
  wb::FastBackwardEuler fbe(s.net, fo);
  NewtonOptions opt;
  opt.one_iteration = one_iteration;
  long solves = 0, steps = 0, failed = 0;
  for (auto _ : state) {
    const NewtonReport r = fbe.step(s.f_ext, 1.0 / 60.0, opt, s.x, s.v);
    solves += r.iterations;
    failed += r.converged ? 0 : 1;
    ++steps;
    benchmark::DoNotOptimize(s.x.data());
  }
  state.counters["iters"] = double(solves) / double(steps);
  state.counters["cg_iters"] = double(fbe.cg_iterations()) / double(steps);
  state.counters["not_converged"] = double(failed);
  state.counters["n"] = double(s.x.cols());
  state.SetLabel(fbe.solver());
}

// The fast path's analysis, paid once per run (on its first step).
void fast_setup(benchmark::State& state, bool is_cloth) {
  Setup s = make(is_cloth, state.range(0));
  std::string solver;
  for (auto _ : state) {
    wb::FastBackwardEuler fbe(s.net, wb::FastSolverOptions{});
    solver = fbe.solver();
    benchmark::DoNotOptimize(&fbe);
  }
  state.counters["n"] = double(s.x.cols());
  state.SetLabel(solver);
}

void se(benchmark::State& state, bool is_cloth) {
  Setup s = make(is_cloth, state.range(0));
  const Eigen::Index n = s.x.cols();
  wb::Mat2X f(2, n);
  Eigen::Array<double, 1, Eigen::Dynamic> inv_m = 1.0 / s.net.m.transpose().array();
  for (Eigen::Index p = 0; p < n; ++p)
    if (s.net.is_pinned(p)) inv_m[p] = 0.0;
  wb::LambdaDynamics dyn([&](const wb::Mat2X& x, const wb::Mat2X& v, wb::Mat2X& a) {
    network_forces(s.net, x, v, f);
    a.array() = (f + s.f_ext).array().rowwise() * inv_m;
  });
  wb::Scratch scratch;
  scratch.resize(n);
  for (auto _ : state) {
    symplectic_euler_step(dyn, 1e-4, s.x, s.v, scratch);
    benchmark::DoNotOptimize(s.x.data());
  }
  state.counters["n"] = double(n);
}

// One product with I3's matrix A of the network at rest (the lab's assemble_system, h =
// 1/60 s): product/<shape>_upper: Eigen's A.selfadjointView<Eigen::Upper>() * x, as
// Eigen::ConjugateGradient<SparseMatrix, Upper> multiplies; product/<shape>_blocks: the
// same through the provided UpperBlocks (labs/implicit/upper_blocks.h), as I4's CG does;
// product/<shape>_blocks_compute: UpperBlocks::compute(A) with its pattern already
// analysed (once per solve). Counters: stored entries, and the two products' largest
// difference over |A x| (rounding).
void product(benchmark::State& state, bool is_cloth, int which) {
  Setup s = make(is_cloth, state.range(0));
  SparseSystem sys;
  assemble_system(s.net, s.x, s.v, s.x, s.v, s.f_ext, 1.0 / 60.0, true, sys);
  UpperBlocks blocks;
  blocks.compute(sys.A);
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(sys.A.rows(), -1.0, 1.0);
  Eigen::VectorXd y(x.size());
  const Eigen::VectorXd want = sys.A.selfadjointView<Eigen::Upper>() * x;
  for (auto _ : state) {
    if (which == 0) {
      y.noalias() = sys.A.selfadjointView<Eigen::Upper>() * x;
    } else if (which == 1) {
      y.noalias() = blocks * x;
    } else {
      blocks.compute(sys.A);
    }
    benchmark::DoNotOptimize(y.data());
    benchmark::ClobberMemory();
  }
  state.counters["nnz"] = double(sys.A.nonZeros());
  const Eigen::VectorXd got = blocks * x;
  state.counters["rel_diff"] = (got - want).cwiseAbs().maxCoeff() / want.cwiseAbs().maxCoeff();
}

void sizes(benchmark::internal::Benchmark* b) {
  for (long n : {100, 1000, 10000, 100000}) b->Arg(n);
  b->Unit(benchmark::kMicrosecond);
}

}  // namespace

// Names: be_<shape>_<solver>/<n> and se_<shape>/<n> (identifiers, so that
// clang-format leaves them alone).
BENCHMARK_CAPTURE(be, rope_ldlt, false, NewtonOptions::kLDLT, false)->Apply(sizes);
BENCHMARK_CAPTURE(be, rope_ldlt1, false, NewtonOptions::kLDLT, true)->Apply(sizes);
BENCHMARK_CAPTURE(se, rope, false)->Apply(sizes);
BENCHMARK_CAPTURE(be, cloth_ldlt, true, NewtonOptions::kLDLT, false)->Apply(sizes);
BENCHMARK_CAPTURE(be, cloth_ldlt1, true, NewtonOptions::kLDLT, true)->Apply(sizes);
BENCHMARK_CAPTURE(be, cloth_cg, true, NewtonOptions::kCG, false)->Apply(sizes);
BENCHMARK_CAPTURE(be, rope_cg1, false, NewtonOptions::kCG, true)->Apply(sizes);
BENCHMARK_CAPTURE(be, cloth_cg1, true, NewtonOptions::kCG, true)->Apply(sizes);
BENCHMARK_CAPTURE(se, cloth, true)->Apply(sizes);
BENCHMARK_CAPTURE(product, cloth_upper, true, 0)->Apply(sizes);
BENCHMARK_CAPTURE(product, cloth_blocks, true, 1)->Apply(sizes);
BENCHMARK_CAPTURE(product, cloth_blocks_compute, true, 2)->Apply(sizes);

BENCHMARK_CAPTURE(fast_setup, rope, false)->Apply(sizes);
BENCHMARK_CAPTURE(fast_setup, cloth, true)->Apply(sizes);

using FS = wb::FastSolverOptions;
void first_second(benchmark::internal::Benchmark* b) {
  for (long n : {1000, 10000, 100000}) b->Arg(n);
  b->Iterations(60);
  b->Unit(benchmark::kMicrosecond);
}
BENCHMARK_CAPTURE(fast, second_rope_auto1, false, FS::kAuto, true)->Apply(first_second);
BENCHMARK_CAPTURE(fast, second_rope_auto, false, FS::kAuto, false)->Apply(first_second);
BENCHMARK_CAPTURE(fast, second_cloth_auto1, true, FS::kAuto, true)->Apply(first_second);
BENCHMARK_CAPTURE(fast, second_cloth_auto, true, FS::kAuto, false)->Apply(first_second);
BENCHMARK_CAPTURE(fast, rope_auto1, false, FS::kAuto, true)->Apply(sizes);
BENCHMARK_CAPTURE(fast, rope_auto, false, FS::kAuto, false)->Apply(sizes);
BENCHMARK_CAPTURE(fast, rope_ldlt1, false, FS::kLDLT, true)->Apply(sizes);
BENCHMARK_CAPTURE(fast, rope_cholmod1, false, FS::kCholmod, true)->Apply(sizes);
BENCHMARK_CAPTURE(fast, rope_cg1, false, FS::kCG, true)->Apply(sizes);
BENCHMARK_CAPTURE(fast, cloth_auto1, true, FS::kAuto, true)->Apply(sizes);
BENCHMARK_CAPTURE(fast, cloth_auto, true, FS::kAuto, false)->Apply(sizes);
BENCHMARK_CAPTURE(fast, cloth_ldlt1, true, FS::kLDLT, true)->Apply(sizes);
BENCHMARK_CAPTURE(fast, cloth_cholmod1, true, FS::kCholmod, true)->Apply(sizes);
BENCHMARK_CAPTURE(fast, cloth_cg1, true, FS::kCG, true)->Apply(sizes);

BENCHMARK_MAIN();
