#include <Eigen/IterativeLinearSolvers>
#include <cmath>

#include "assemble_system.h"
#include "backward_euler.h"
#include "network_forces.h"

// Alternative I4: the residual G(y) = M (y - v) - h (f(x + h y, y) + f_ext) is
// computed from the network's forces (network_forces.h), not read off b, and
// measured after every solve, one_iteration's included; the system is assembled
// again only when another solve is needed; the scale's norms are summed particle
// by particle; one loop for every solve.
namespace {

double residual(const SpringNetwork& net, const wb::Mat2X& f_ext, double h, const wb::Mat2X& x,
                const wb::Mat2X& v, const wb::Mat2X& y) {
  wb::Mat2X f;
  network_forces(net, x + h * y, y, f);
  double sum = 0.0;
  for (Eigen::Index p = 0; p < net.n(); ++p) {
    if (net.is_pinned(p)) continue;
    const wb::Vec2 g = net.m[p] * (y.col(p) - v.col(p)) - h * (f.col(p) + f_ext.col(p));
    sum += g.squaredNorm();
  }
  return std::sqrt(sum);
}

bool solve(NewtonWorkspace& ws, const NewtonOptions& opt, double scale, bool first,
           Eigen::VectorXd& dv) {
  const Eigen::SparseMatrix<double>& A = ws.sys.A;
  const Eigen::VectorXd& b = ws.sys.b;
  if (opt.solver == NewtonOptions::kCG) {
    Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Upper> cg(A);
    if (b.norm() > 0) cg.setTolerance(opt.cg_tol * scale / b.norm());
    if (first && ws.dv.size() == b.size()) {
      dv = cg.solveWithGuess(b, ws.dv);
    } else {
      dv = cg.solve(b);
    }
    if (cg.info() != Eigen::Success) return false;
    if (first) ws.dv = dv;
  } else {
    if (ws.ldlt.rows() != A.rows() || A.rows() == 0) ws.ldlt.analyzePattern(A);
    ws.ldlt.factorize(A);
    if (ws.ldlt.info() != Eigen::Success) return false;
    dv = ws.ldlt.solve(b);
  }
  return dv.allFinite();
}

}  // namespace

NewtonReport backward_euler_step(const SpringNetwork& net, const wb::Mat2X& f_ext, double h,
                                 const NewtonOptions& opt, wb::Mat2X& x, wb::Mat2X& v,
                                 NewtonWorkspace& ws) {
  NewtonReport rep;
  const Eigen::Index n = net.n();
  for (Eigen::Index p = 0; p < n; ++p)
    if (net.is_pinned(p)) v.col(p).setZero();
  double mv2 = 0.0, f2 = 0.0;
  for (Eigen::Index p = 0; p < n; ++p) {
    mv2 += net.m[p] * net.m[p] * v.col(p).squaredNorm();
    f2 += f_ext.col(p).squaredNorm();
  }
  wb::Mat2X y = v;
  Eigen::VectorXd dv;
  rep.residual = std::nan("");
  for (int k = 0;; ++k) {
    // The first system at the start, then at each Newton iterate.
    assemble_system(net, x, v, k == 0 ? x : wb::Mat2X(x + h * y), y, f_ext, h, opt.definite,
                    ws.sys);
    if (k == 0) rep.scale = std::sqrt(mv2) + ws.sys.b.norm() + h * std::sqrt(f2);
    if (!solve(ws, opt, rep.scale, k == 0, dv)) {
      rep.solver_failed = true;
      break;
    }
    y += Eigen::Map<const wb::Mat2X>(dv.data(), 2, n);
    ++rep.iterations;
    rep.residual = residual(net, f_ext, h, x, v, y);
    rep.converged = opt.one_iteration || rep.residual <= opt.tol * rep.scale;
    if (rep.converged || rep.iterations >= opt.max_iterations) break;
  }
  x += h * y;
  v = y;
  return rep;
}
