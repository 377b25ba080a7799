#include "assemble_system.h"

#include <algorithm>
#include <vector>

#include "spring_derivatives.h"

// TODO(I3) assembly of one Newton step's sparse system (see assemble_system.h).
void assemble_system(const SpringNetwork& net, const wb::Mat2X& x0, const wb::Mat2X& v0,
                     const wb::Mat2X& xl, const wb::Mat2X& vl, const wb::Mat2X& f_ext, double h,
                     bool definite, SparseSystem& sys) {
  const Eigen::Index n = net.n();
  Eigen::SparseMatrix<double>& A = sys.A;
  // The first assembly makes triplets; every later one adds the same values,
  // in the same order, where the first one found they go.
  const bool first = sys.slot.empty();
  std::vector<Eigen::Triplet<double>> t;
  if (first) {
    t.reserve(std::size_t(3 * n + 10 * net.springs.size()));
  } else {
    A.coeffs().setZero();
  }
  std::size_t k = 0;
  auto add = [&](Eigen::Index row, Eigen::Index col, double value) {
    if (first) {
      t.emplace_back(row, col, value);
    } else {
      A.coeffs()[sys.slot[k++]] += value;  // index-checked in a checked build
    }
  };
  // Adds the 2 x 2 block B at particles (p, q), p <= q, if neither is pinned:
  // its entries in the upper triangle.
  auto block = [&](Eigen::Index p, Eigen::Index q, const wb::Mat2& B) {
    if (net.is_pinned(p) || net.is_pinned(q)) return;
    add(2 * p, 2 * q, B(0, 0));
    add(2 * p, 2 * q + 1, B(0, 1));
    if (p != q) add(2 * p + 1, 2 * q, B(1, 0));
    add(2 * p + 1, 2 * q + 1, B(1, 1));
  };

  // Mass, drag, and the parts of the right-hand side that need no spring.
  sys.b.resize(2 * n);
  Eigen::Map<wb::Mat2X> rhs(sys.b.data(), 2, n);
  rhs = (v0 - vl) * net.m.asDiagonal();
  rhs += h * (f_ext - net.drag * vl);
  for (Eigen::Index p = 0; p < n; ++p) {
    const double diag = net.is_pinned(p) ? net.m[p] : net.m[p] + h * net.drag;
    add(2 * p, 2 * p, diag);
    add(2 * p + 1, 2 * p + 1, diag);
  }

  // Springs: force and the blocks of -h D - h^2 K.
  wb::Vec2 f;
  wb::Mat2 K, D;
  for (const NetworkSpring& s : net.springs) {
    const bool anchored = s.j < 0;
    const wb::Vec2 xj = anchored ? s.anchor : wb::Vec2(xl.col(s.j));
    const wb::Vec2 vj = anchored ? wb::Vec2::Zero() : wb::Vec2(vl.col(s.j));
    spring_derivatives(xl.col(s.i), xj, vl.col(s.i), vj, s.k, s.rest, s.kd, definite, f, K, D);
    const wb::Mat2 B = -h * D - h * h * K;
    // w = x0 + h vl - xl: where the positions are, minus where K was taken.
    wb::Vec2 dw = x0.col(s.i) + h * vl.col(s.i) - xl.col(s.i);
    if (!anchored) dw -= x0.col(s.j) + h * vl.col(s.j) - xl.col(s.j);
    const wb::Vec2 fi = f + K * dw;  // force, plus the correction of the K term
    rhs.col(s.i) += h * fi;
    block(s.i, s.i, B);
    if (!anchored) {
      rhs.col(s.j) -= h * fi;
      block(s.j, s.j, B);
      block(std::min(s.i, s.j), std::max(s.i, s.j), -B);  // B is symmetric
    }
  }

  // Pinned particles: dv = 0.
  for (Eigen::Index p = 0; p < n; ++p)
    if (net.is_pinned(p)) rhs.col(p).setZero();

  if (first) {
    A.resize(2 * n, 2 * n);
    A.setFromTriplets(t.begin(), t.end());
    sys.slot.reserve(t.size());
    for (const Eigen::Triplet<double>& e : t)
      sys.slot.push_back(int(&A.coeffRef(e.row(), e.col()) - A.valuePtr()));
  }
}
