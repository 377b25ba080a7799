// Classic RK4 on the first-order system (x, v)' = (v, a(x, v)).
#include "wb/rk4.h"

#include <algorithm>

namespace wb {

// The position slopes are velocities, so they need no arrays of their own:
// k2x = v + h/2 a0, k3x = v + h/2 a1, k4x = v + h a2, and
//   k1x + 2 k2x + 2 k3x + k4x = 6 v + h (a0 + a1 + a2).
// Each stage's point and the final combination are then one pass each over
// the arrays they read (the update moves 512 bytes per particle, where
// running sums of the slopes moved 736; bench/results/HISTORY.md).
namespace {

// Particles per block when the dynamics is per-particle: a block's arrays
// (state, stage point, four accelerations; the forces and masses inside the
// evaluation) take 2 x 256 doubles or fewer each, under 40 KiB in all, so a
// whole step of a block stays in a core's first-level cache (48 KiB here).
// Measured against 64, 128, 512 and 2048 (docs/benchmarks.md).
constexpr Eigen::Index kBlock = 256;

// rk4's arrays for one block of particles: a state, the stage point and four
// accelerations. Kept by each thread from step to step (the last block of a
// step has its own, its size may differ), so that no step after the first
// allocates; not in wb::Scratch, whose arrays the labs' steps share.
struct BlockArrays {
  Mat2X x, v, x1, v1, a0, a1, a2, a3;
};

// One step from (x, v), written to (xo, vo): x and v themselves, or the
// columns a block was copied from (xo holds x's values; the step adds to it).
// With eval(x, v, a) the dynamics' accelerations. With positions false
// (a(x, v) ignores x) the stages' positions are not computed, and x, which the
// evaluations are then handed, need only have the right size.
template <class Eval, class XOut, class VOut>
void rk4_arrays(const Eval& eval, bool positions, double h, const Mat2X& x, const Mat2X& v,
                Mat2X& a0, Mat2X& a1, Mat2X& a2, Mat2X& a3, Mat2X& x1, Mat2X& v1, XOut&& xo,
                VOut&& vo) {
  const double h2 = 0.5 * h, hh4 = 0.25 * h * h, hh2 = 0.5 * h * h;
  const Mat2X& xs = positions ? x1 : x;  // where the stages evaluate

  // Stage 1 at the start: k1 = (v, a0).
  eval(x, v, a0);

  // Stage 2 at the half step along k1: k2 = (v + h/2 a0, a1).
  if (positions) x1 = x + h2 * v;
  v1 = v + h2 * a0;
  eval(xs, v1, a1);

  // Stage 3 at the half step along k2: x + h/2 k2x = x + h/2 v + h^2/4 a0.
  if (positions) x1 = x + h2 * v + hh4 * a0;
  v1 = v + h2 * a1;
  eval(xs, v1, a2);

  // Stage 4 at the full step along k3: x + h k3x = x + h v + h^2/2 a1.
  if (positions) x1 = x + h * v + hh2 * a1;
  v1 = v + h * a2;
  eval(xs, v1, a3);

  // Combine: x += h/6 (6 v + h (a0 + a1 + a2)), v += h/6 (a0 + 2 a1 + 2 a2 + a3).
  // (xo is written before v is read: it may be x, never v.)
  xo += h * v + (h * h / 6.0) * (a0 + a1 + a2);
  vo = v + (h / 6.0) * (a0 + 2.0 * a1 + 2.0 * a2 + a3);
}

}  // namespace

// Each particle's arithmetic is the same in both paths (element by element, in
// the same order), so a run gives the same bits whether it went by blocks or
// not; only the order in which memory is visited changes. By blocks, a step
// reads x, v and m once from memory and writes x and v once, where the whole
// arrays' passes move every stage's arrays through memory (docs/benchmarks.md).
void rk4_step(const Dynamics& dyn, double h, Mat2X& x, Mat2X& v, Scratch& s) {
  const Eigen::Index n = x.cols();
  if (n <= kBlock || !dyn.per_particle()) {
    rk4_arrays(
        [&dyn](const Mat2X& xa, const Mat2X& va, Mat2X& a) { dyn.acceleration(xa, va, a); },
        dyn.reads_positions(), h, x, v, s.a0, s.a1, s.a2, s.a3, s.x1, s.v1, x, v);
    return;
  }
  const bool positions = dyn.reads_positions();
  for (Eigen::Index first = 0; first < n; first += kBlock) {
    const Eigen::Index nb = std::min(kBlock, n - first);
    static thread_local BlockArrays block, last_block;
    BlockArrays& b = first + nb == n ? last_block : block;
    if (positions) {
      b.x = x.middleCols(first, nb);
    } else if (b.x.cols() != nb) {
      b.x.setZero(2, nb);  // never read; sized for the evaluations' checks
    }
    b.v = v.middleCols(first, nb);
    rk4_arrays([&dyn, first](const Mat2X& xa, const Mat2X& va,
                             Mat2X& a) { dyn.block_acceleration(first, xa, va, a); },
               positions, h, b.x, b.v, b.a0, b.a1, b.a2, b.a3, b.x1, b.v1,
               x.middleCols(first, nb), v.middleCols(first, nb));
    dyn.block_stepped(first, nb, x, v);
  }
  dyn.blocks_stepped(x, v);
  dyn.count_evals(4);
}

Integrator rk4_integrator() {
  return {"rk4", rk4_step, 4, 4, "classic Runge-Kutta 4, provided (the sweep's reference)"};
}

}  // namespace wb
