#include <algorithm>
#include <vector>

#include "assemble_system.h"
#include "spring_derivatives.h"

// Alternative I3: springs first, last to first (their upper-triangle entries, and
// K w gathered per particle), then the mass and drag diagonal, then the
// right-hand side particle by particle; the first assembly's triplets and every
// later one's values go through one list of (row, column, value) made the same
// way, its slots looked up once.
void assemble_system(const SpringNetwork& net, const wb::Mat2X& x0, const wb::Mat2X& v0,
                     const wb::Mat2X& xl, const wb::Mat2X& vl, const wb::Mat2X& f_ext, double h,
                     bool definite, SparseSystem& sys) {
  const Eigen::Index n = net.n();
  std::vector<Eigen::Triplet<double>> t;
  wb::Mat2X fs = wb::Mat2X::Zero(2, n);  // spring forces plus K w
  for (std::size_t q = net.springs.size(); q-- > 0;) {
    const NetworkSpring& s = net.springs[q];
    const bool anchored = s.j < 0;
    const wb::Vec2 xj = anchored ? s.anchor : wb::Vec2(xl.col(s.j));
    const wb::Vec2 vj = anchored ? wb::Vec2::Zero() : wb::Vec2(vl.col(s.j));
    wb::Vec2 f;
    wb::Mat2 K, D;
    spring_derivatives(xl.col(s.i), xj, vl.col(s.i), vj, s.k, s.rest, s.kd, definite, f, K, D);
    wb::Vec2 wi = x0.col(s.i) + h * vl.col(s.i) - xl.col(s.i);
    if (!anchored) wi -= x0.col(s.j) + h * vl.col(s.j) - xl.col(s.j);
    fs.col(s.i) += f + K * wi;
    if (!anchored) fs.col(s.j) -= f + K * wi;
    const wb::Mat2 B = -h * D - h * h * K;
    const bool pi = net.is_pinned(s.i), pj = anchored || net.is_pinned(s.j);
    const Eigen::Index lo = anchored ? s.i : std::min(s.i, s.j);
    const Eigen::Index hi = anchored ? s.i : std::max(s.i, s.j);
    for (int r = 0; r < 2; ++r) {
      for (int c = 0; c < 2; ++c) {
        if (!pi && r <= c) t.emplace_back(2 * s.i + r, 2 * s.i + c, B(r, c));
        if (!anchored && !pj && r <= c) t.emplace_back(2 * s.j + r, 2 * s.j + c, B(r, c));
        if (!pi && !pj) t.emplace_back(2 * lo + r, 2 * hi + c, -B(r, c));
      }
    }
  }
  sys.b.resize(2 * n);
  for (Eigen::Index p = 0; p < n; ++p) {
    const bool pinned = net.is_pinned(p);
    const double diag = pinned ? net.m[p] : net.m[p] + h * net.drag;
    t.emplace_back(2 * p, 2 * p, diag);
    t.emplace_back(2 * p + 1, 2 * p + 1, diag);
    const wb::Vec2 bp = net.m[p] * (v0.col(p) - vl.col(p)) +
                        h * (fs.col(p) - net.drag * vl.col(p) + f_ext.col(p));
    sys.b.segment<2>(2 * p) = pinned ? wb::Vec2::Zero() : bp;
  }
  if (sys.slot.empty()) {
    sys.A.resize(2 * n, 2 * n);
    sys.A.setFromTriplets(t.begin(), t.end());
    for (const Eigen::Triplet<double>& e : t)
      sys.slot.push_back(int(&sys.A.coeffRef(e.row(), e.col()) - sys.A.valuePtr()));
  } else {
    sys.A.coeffs().setZero();
    for (std::size_t k = 0; k < t.size(); ++k) sys.A.valuePtr()[sys.slot[k]] += t[k].value();
  }
}
