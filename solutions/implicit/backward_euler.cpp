#include "backward_euler.h"

#include <Eigen/IterativeLinearSolvers>
#include <cmath>

namespace {

// Solves A dv = b (ws.sys) with the chosen solver: the workspace's LDLT,
// analysed once; or CG from `guess`, until |A dv - b| <= cg_tol * scale.
// False when the solver fails.
bool solve(NewtonWorkspace& ws, const NewtonOptions& opt, double scale,
           const Eigen::VectorXd& guess, Eigen::VectorXd& dv) {
  const Eigen::SparseMatrix<double>& A = ws.sys.A;
  const Eigen::VectorXd& b = ws.sys.b;
  if (opt.solver == NewtonOptions::kCG) {
    ws.blocks.compute(A);  // A's upper triangle, read block by block
    Eigen::ConjugateGradient<UpperBlocks, Eigen::Lower | Eigen::Upper, UpperBlocksJacobi> cg;
    const double bn = b.norm();
    if (bn > 0) cg.setTolerance(opt.cg_tol * scale / bn);
    cg.compute(ws.blocks);
    if (cg.info() != Eigen::Success) return false;
    dv = cg.solveWithGuess(b, guess);
    if (cg.info() != Eigen::Success) return false;
  } else {
    if (ws.ldlt.rows() != A.rows() || A.rows() == 0) ws.ldlt.analyzePattern(A);
    ws.ldlt.factorize(A);
    if (ws.ldlt.info() != Eigen::Success) return false;
    dv = ws.ldlt.solve(b);
    if (ws.ldlt.info() != Eigen::Success) return false;
  }
  return dv.allFinite();
}

}  // namespace

// TODO(I4) backward Euler step of a spring network by Newton's method (see backward_euler.h).
NewtonReport backward_euler_step(const SpringNetwork& net, const wb::Mat2X& f_ext, double h,
                                 const NewtonOptions& opt, wb::Mat2X& x, wb::Mat2X& v,
                                 NewtonWorkspace& ws) {
  NewtonReport rep;
  const Eigen::Index n = net.n();
  // Pinned particles never move.
  for (Eigen::Index p = 0; p < n; ++p)
    if (net.is_pinned(p)) v.col(p).setZero();

  Eigen::VectorXd dv;
  wb::Mat2X y = v;
  Eigen::Map<Eigen::VectorXd> yv(y.data(), 2 * n);

  // First solve, linearised at the start (Baraff and Witkin), from the last
  // step's first dv.
  assemble_system(net, x, v, x, v, f_ext, h, opt.definite, ws.sys);
  rep.scale = (v * net.m.asDiagonal()).norm() + ws.sys.b.norm() + h * f_ext.norm();
  if (ws.dv.size() != 2 * n) ws.dv = Eigen::VectorXd::Zero(2 * n);
  if (!solve(ws, opt, rep.scale, ws.dv, dv)) {
    rep.solver_failed = true;
  } else {
    yv += dv;
    ws.dv = dv;
    rep.iterations = 1;
  }

  // Baraff and Witkin stop here, without measuring the residual (a second
  // assembly, or a force evaluation, that a game stopping at one solve skips).
  if (opt.one_iteration && !rep.solver_failed) {
    rep.residual = std::nan("");
    rep.converged = true;
  }
  // Newton iterations on the residual G(y) = -b at (x + h y, y); each solve
  // corrects y, from dv = 0.
  while (!opt.one_iteration && !rep.solver_failed) {
    const wb::Mat2X xl = x + h * y;
    assemble_system(net, x, v, xl, y, f_ext, h, opt.definite, ws.sys);
    rep.residual = ws.sys.b.norm();
    rep.converged = rep.residual <= opt.tol * rep.scale;
    if (rep.converged || rep.iterations >= opt.max_iterations) break;
    if (!solve(ws, opt, rep.scale, Eigen::VectorXd::Zero(2 * n), dv)) {
      rep.solver_failed = true;
      break;
    }
    yv += dv;
    ++rep.iterations;
  }
  if (rep.solver_failed && rep.iterations == 0) rep.residual = std::nan("");

  // Advance with the last good iterate.
  x += h * y;
  v = y;
  return rep;
}
