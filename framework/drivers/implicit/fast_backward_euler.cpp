// The provided fast path of backward Euler (see fast_backward_euler.h).
#include "fast_backward_euler.h"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>
#ifdef WB_HAVE_CHOLMOD
#include <Eigen/CholmodSupport>
#endif

#include "spring_derivatives.h"
#include "wb/budget.h"

namespace wb {

bool have_cholmod() {
#ifdef WB_HAVE_CHOLMOD
  return true;
#else
  return false;
#endif
}

namespace {

using SpMat = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

// auto chooses a direct solver when one factorisation costs at most this many
// CG iterations (flops against flops). A CG solve on the stiff networks of the
// lab takes tens to hundreds of iterations; a refactorisation also pays for its
// triangular solves and its memory traffic, hence a budget below that.
constexpr double kDirectBudget = 30.0;
// Newton's later solves (not one_iteration) with CG: |r| <= this * |b|, so
// that each iteration still gains three digits (inexact Newton).
constexpr double kNewtonForcing = 1e-3;
constexpr int kCgMaxIterations = 5000;  // a cap far above what a solve needs

// Where a 2 x 2 block (p, q) of A sits in the value array: c0 is the entry
// (2p, 2q) of column 2q (the next one is (2p + 1, 2q)), c1 the entry
// (2p, 2q + 1) of column 2q + 1. -1: the block is not stored.
struct BlockAt {
  int c0 = -1, c1 = -1;
};

// val[block] += s * B
inline void add_block(double* val, const BlockAt& at, const Mat2& B, double s) {
  if (at.c0 < 0) return;
  val[at.c0] += s * B(0, 0);
  val[at.c0 + 1] += s * B(1, 0);
  val[at.c1] += s * B(0, 1);
  val[at.c1 + 1] += s * B(1, 1);
}

// The particle graph: row i lists, sorted and once each, the free particles
// joined to free particle i by a spring (compressed rows, no diagonal).
struct Graph {
  std::vector<int> start, adj;
  int n() const { return int(start.size()) - 1; }
};

// Column counts of the Cholesky factor of the graph's matrix, taken in the
// order `place` (place[i]: particle i's position): the elimination-tree walk
// of Eigen's SimplicialCholesky, one pass over the rows of L. Returns the sum
// over columns of count^2, the factorisation's multiply-adds, and nnz_l.
// With `cap` > 0 the walk stops once the work passes it (and returns what it counted,
// more than `cap`): a pattern that fills in is known to be too dear in O(cap) time.
double factor_work(const Graph& g, const std::vector<int>& place, double& nnz_l, double cap = 0) {
  const int n = g.n();
  const std::size_t size = std::size_t(n);
  std::vector<int> old_of(size), parent(size, -1), tag(size, 0), count(size, 0);
  for (int i = 0; i < n; ++i) old_of[std::size_t(place[std::size_t(i)])] = i;
  double so_far = 0;  // sum of count^2 as the counts grow
  for (int k = 0; k < n; ++k) {
    tag[std::size_t(k)] = k;
    const int o = old_of[std::size_t(k)];
    for (int e = g.start[std::size_t(o)]; e < g.start[std::size_t(o) + 1]; ++e) {
      for (int i = place[std::size_t(g.adj[std::size_t(e)])]; i < k && tag[std::size_t(i)] != k;
           i = parent[std::size_t(i)]) {
        if (parent[std::size_t(i)] == -1) parent[std::size_t(i)] = k;
        so_far += 2.0 * count[std::size_t(i)] + 1;
        ++count[std::size_t(i)];
        tag[std::size_t(i)] = k;
      }
    }
    if (cap > 0 && so_far > cap) break;
  }
  double work = 0;
  nnz_l = 0;
  for (int c : count) {
    work += double(c) * double(c);
    nnz_l += c;
  }
  return work;
}

// The particle graph of a network: free particles joined by a spring, each neighbour
// once, sorted (compressed rows, no diagonal).
Graph particle_graph(const SpringNetwork& net) {
  const auto free_particle = [&](Eigen::Index i) { return i >= 0 && !net.is_pinned(i); };
  const auto coupled = [&](const NetworkSpring& s) {
    return free_particle(s.i) && free_particle(s.j) && s.i != s.j;
  };
  Graph graph;
  const std::size_t n = std::size_t(net.n());
  graph.start.assign(n + 1, 0);
  for (const NetworkSpring& s : net.springs) {
    if (!coupled(s)) continue;
    ++graph.start[std::size_t(s.i) + 1];
    ++graph.start[std::size_t(s.j) + 1];
  }
  for (std::size_t i = 0; i < n; ++i) graph.start[i + 1] += graph.start[i];
  std::vector<int> fill(graph.start.begin(), graph.start.end() - 1);
  graph.adj.resize(std::size_t(graph.start.back()));
  for (const NetworkSpring& s : net.springs) {
    if (!coupled(s)) continue;
    graph.adj[std::size_t(fill[std::size_t(s.i)]++)] = int(s.j);
    graph.adj[std::size_t(fill[std::size_t(s.j)]++)] = int(s.i);
  }
  // Sorted, each neighbour once (two springs between the same particles share blocks).
  std::vector<int> start(n + 1, 0), adj;
  adj.reserve(graph.adj.size());
  for (std::size_t i = 0; i < n; ++i) {
    auto b = graph.adj.begin() + graph.start[i], e = graph.adj.begin() + graph.start[i + 1];
    std::sort(b, e);
    adj.insert(adj.end(), b, std::unique(b, e));
    start[i + 1] = int(adj.size());
  }
  graph.start.swap(start);
  graph.adj.swap(adj);
  return graph;
}

// One CG iteration's multiply-adds on the graph: the product (a 2 x 2 block per particle
// and two per coupling) and five vector operations.
double cg_iteration_work(const Graph& g) {
  const double couplings = 0.5 * double(g.adj.size());
  return 8.0 * double(g.n()) + 16.0 * couplings + 20.0 * double(g.n());
}

// Approximate minimum degree order of the graph (Eigen's AMDOrdering):
// place[i] is particle i's position.
std::vector<int> amd_order(const Graph& g) {
  const int n = g.n();
  std::vector<int> outer(std::size_t(n) + 1), inner;
  inner.reserve(g.adj.size() + std::size_t(n));
  for (int i = 0; i < n; ++i) {  // the graph plus the diagonal
    outer[std::size_t(i)] = int(inner.size());
    bool diag = false;
    for (int e = g.start[std::size_t(i)]; e < g.start[std::size_t(i) + 1]; ++e) {
      const int j = g.adj[std::size_t(e)];
      if (!diag && j > i) {
        inner.push_back(i);
        diag = true;
      }
      inner.push_back(j);
    }
    if (!diag) inner.push_back(i);
  }
  outer[std::size_t(n)] = int(inner.size());
  std::vector<double> ones(inner.size(), 1.0);
  const SpMat G = Eigen::Map<const SpMat>(n, n, Eigen::Index(inner.size()), outer.data(),
                                          inner.data(), ones.data());
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> pinv;
  Eigen::AMDOrdering<int> amd;
  amd(G, pinv);
  const Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> p = pinv.inverse();
  return std::vector<int>(p.indices().data(), p.indices().data() + n);
}

}  // namespace

double natural_order_factor_ratio(const SpringNetwork& net, double cap) {
  const Graph g = particle_graph(net);
  std::vector<int> place(std::size_t(g.n()));
  for (int i = 0; i < g.n(); ++i) place[std::size_t(i)] = i;
  const double iteration = std::max(1.0, cg_iteration_work(g));
  double nnz_l = 0;
  return 8.0 * factor_work(g, place, nnz_l, cap * iteration / 8.0) / iteration;
}

double direct_budget_iterations() { return kDirectBudget; }

struct FastBackwardEuler::Impl {
  const SpringNetwork& net;
  FastSolverOptions fo;
  std::string solver, reason;
  long cg_iterations = 0, factorisations = 0;
  bool direct = true;  // ldlt or cholmod: A in compressed form; cg: A by springs (cg_springs)

  // Direct solvers: A, 2n x 2n, both triangles, its pattern fixed at the start.
  // Its unknowns are numbered in the fill-reducing order found once (particle i's
  // two are 2 at[i], 2 at[i] + 1): the factorisation then needs no permuted copy
  // of A at each solve, and b and dv are permuted instead (2n numbers).
  SpMat A;
  std::vector<int> place;     // per particle: its place in A (identity for CG)
  std::vector<BlockAt> diag;  // per particle: its diagonal block
  std::vector<BlockAt> at;    // per spring: ii, jj, ij, ji (4 entries)
  Eigen::SimplicialLDLT<SpMat, Eigen::Upper, Eigen::NaturalOrdering<int>> ldlt;
  bool ldlt_analysed = false;
#ifdef WB_HAVE_CHOLMOD
  Eigen::CholmodSupernodalLLT<SpMat, Eigen::Lower> cholmod;
#endif

  // CG: A = M' + sum over springs, stored spring by spring. A spring between
  // free particles i < j puts its symmetric block B (3 numbers) at (i, i) and
  // (j, j) and -B at (i, j) and (j, i): A p gets B (p_i - p_j) at i and its
  // negative at j, so the spring is stored once, not as two 2 x 2 blocks in the
  // rows of i and j. The CG solve of a large cloth is bound by memory traffic:
  // these are the bytes it streams at each iteration, so a spring is 16 bytes:
  // B in single precision (mixed-precision CG: the vectors, the sums and the
  // diagonal blocks stay double; B's rounding, 6e-8 relative, perturbs A far
  // less than the solve's tolerance of 1e-2, and A stays symmetric), and only j
  // (the springs are sorted by i: particle i's are cg_first[i] to cg_first[i+1]).
  struct CgSpring {
    float b00, b10, b11;  // B (symmetric)
    int j;                // its second free particle (j > i)
  };
  static_assert(sizeof(CgSpring) == 16, "a spring: a quarter of a cache line");
  std::vector<CgSpring> cg_springs;  // sorted by i, then j: the product sweeps forward
  std::vector<int> cg_first;         // per particle i, then n: where i's springs start
  Eigen::Index cg_lead = 0;          // the largest j - i: how far ahead a spring reaches
  std::vector<int> cg_slot;  // per spring of the network: its place in cg_springs (-1: none)
  // Per particle (a00, a10, a11): dblk, mass and drag plus the blocks of the
  // springs to a pinned particle or an anchor (those couple to nothing that
  // moves: pinned rows are the identity times m, dv = 0 there); dinv, the
  // inverse of the whole diagonal block (dblk and the coupled springs' B).
  Eigen::Matrix<double, 3, Eigen::Dynamic> dblk, dinv;
  Eigen::VectorXd r, z, p, q;  // CG's residual, preconditioned residual, direction, A p

  Eigen::VectorXd b, dv, dv0, zero;  // right-hand side, solution, last step's first dv, 0
  Mat2X rhs, w, y, xl;               // 2 x n work arrays (b is rhs's storage)

  Impl(const SpringNetwork& n, const FastSolverOptions& o) : net(n), fo(o) {
    choose_solver();
    if (direct) {
      build_pattern();
      analyse();
    } else {
      build_blocks();
    }
    const Eigen::Index n2 = 2 * net.n();
    b.resize(n2);
    dv.setZero(n2);
    dv0.setZero(n2);
    zero.setZero(n2);
    for (Mat2X* m : {&rhs, &w, &y, &xl}) m->resize(2, net.n());
  }

  Graph graph;  // the particle graph (free particles joined by a spring)

  bool free_particle(Eigen::Index i) const { return i >= 0 && !net.is_pinned(i); }

  void build_graph() { graph = particle_graph(net); }
  bool coupled(const NetworkSpring& s) const {
    return free_particle(s.i) && free_particle(s.j) && s.i != s.j;
  }

  // The compressed pattern, once: every particle's diagonal block, and for each
  // spring between two free particles its two off-diagonal blocks; then where
  // each spring's blocks sit in the value array.
  void build_pattern() {
    // Column 2 p and 2 p + 1 (p = place[i]) hold rows 2 q, 2 q + 1 for q = p and
    // the places of i's neighbours, sorted: the same rows in both columns.
    const Eigen::Index n = net.n();
    const std::size_t size = std::size_t(n);
    std::vector<int> old_of(size);
    for (Eigen::Index i = 0; i < n; ++i) old_of[std::size_t(place[std::size_t(i)])] = int(i);
    std::vector<int> outer(std::size_t(2 * n) + 1, 0), inner;
    inner.reserve(std::size_t(4 * n) + 4 * graph.adj.size());
    std::vector<int> rows;  // the block rows of one column, in A's order
    std::vector<std::vector<int>> rows_of(size);
    for (Eigen::Index p = 0; p < n; ++p) {
      const int i = old_of[std::size_t(p)];
      rows.assign(1, int(p));
      for (int e = graph.start[std::size_t(i)]; e < graph.start[std::size_t(i) + 1]; ++e)
        rows.push_back(place[std::size_t(graph.adj[std::size_t(e)])]);
      std::sort(rows.begin(), rows.end());
      for (int c = 0; c < 2; ++c) {
        outer[std::size_t(2 * p + c)] = int(inner.size());
        for (int q : rows) {
          inner.push_back(2 * q);
          inner.push_back(2 * q + 1);
        }
      }
      rows_of[std::size_t(p)] = rows;
    }
    outer[std::size_t(2 * n)] = int(inner.size());
    A.resize(2 * n, 2 * n);
    A.resizeNonZeros(Eigen::Index(inner.size()));
    std::copy(outer.begin(), outer.end(), A.outerIndexPtr());
    std::copy(inner.begin(), inner.end(), A.innerIndexPtr());
    std::fill(A.valuePtr(), A.valuePtr() + inner.size(), 0.0);
    // Where block (i, j) sits: column 2 place[j], at the position of place[i].
    auto at_of = [&](Eigen::Index i, Eigen::Index j) {
      const int pi = place[std::size_t(i)], pj = place[std::size_t(j)];
      const std::vector<int>& r = rows_of[std::size_t(pj)];
      const int k = int(std::lower_bound(r.begin(), r.end(), pi) - r.begin());
      return BlockAt{outer[std::size_t(2 * pj)] + 2 * k, outer[std::size_t(2 * pj + 1)] + 2 * k};
    };
    diag.resize(std::size_t(n));
    for (Eigen::Index i = 0; i < n; ++i) diag[std::size_t(i)] = at_of(i, i);
    at.assign(4 * net.springs.size(), BlockAt{});
    for (std::size_t k = 0; k < net.springs.size(); ++k) {
      const NetworkSpring& s = net.springs[k];
      if (free_particle(s.i)) at[4 * k] = at_of(s.i, s.i);
      if (free_particle(s.j)) at[4 * k + 1] = at_of(s.j, s.j);
      if (coupled(s)) {
        at[4 * k + 2] = at_of(s.i, s.j);
        at[4 * k + 3] = at_of(s.j, s.i);
      }
    }
  }

  void build_blocks() {
    const Eigen::Index n = net.n();
    struct Key {
      int i, j;
      std::size_t k;
    };
    std::vector<Key> keys;
    keys.reserve(net.springs.size());
    for (std::size_t k = 0; k < net.springs.size(); ++k) {
      const NetworkSpring& s = net.springs[k];
      if (coupled(s)) keys.push_back({int(std::min(s.i, s.j)), int(std::max(s.i, s.j)), k});
    }
    // By first particle, then second: the product's sweep then reads and writes
    // the vectors near its position (a cloth's springs reach two rows ahead).
    std::stable_sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) {
      return a.i != b.i ? a.i < b.i : a.j < b.j;
    });
    cg_springs.resize(keys.size());
    cg_first.assign(std::size_t(n) + 1, 0);
    cg_slot.assign(net.springs.size(), -1);
    cg_lead = 0;
    for (std::size_t c = 0; c < keys.size(); ++c) {
      cg_springs[c] = CgSpring{0.0f, 0.0f, 0.0f, keys[c].j};
      ++cg_first[std::size_t(keys[c].i) + 1];
      cg_slot[keys[c].k] = int(c);
      cg_lead = std::max(cg_lead, Eigen::Index(keys[c].j - keys[c].i));
    }
    for (Eigen::Index i = 0; i < n; ++i) cg_first[std::size_t(i) + 1] += cg_first[std::size_t(i)];
    dblk.resize(3, n);
    dinv.resize(3, n);
    for (Eigen::VectorXd* v : {&r, &z, &p, &q}) v->setZero(2 * n);
  }

  void choose_solver() {
    const Eigen::Index n = net.n();
    // The factorisation's work, estimated on the particle graph (a scalar
    // entry there is a 2 x 2 block of A: 8 times the multiply-adds), against
    // one CG iteration: the product (a 2 x 2 block per particle and two per
    // coupling) and five vector operations.
    build_graph();
    const double couplings = 0.5 * double(graph.adj.size());
    // The generator's order first (a rope's chain has no fill in it), else AMD.
    place.resize(std::size_t(n));
    for (Eigen::Index i = 0; i < n; ++i) place[std::size_t(i)] = int(i);
    double nnz_l = 0;
    double factor = 8.0 * factor_work(graph, place, nnz_l);
    if (nnz_l > couplings) {
      place = amd_order(graph);
      factor = 8.0 * factor_work(graph, place, nnz_l);
    }
    const double iteration = cg_iteration_work(graph);
    const double ratio = factor / std::max(1.0, iteration);
    FastSolverOptions::Solver s = fo.solver;
    if (s == FastSolverOptions::kAuto) {
      s = ratio <= kDirectBudget ? FastSolverOptions::kLDLT : FastSolverOptions::kCG;
      char buf[160];
      std::snprintf(buf, sizeof buf,
                    "auto: a factorisation costs %.3g CG iterations (budget %g): %s", ratio,
                    kDirectBudget, ratio <= kDirectBudget ? "direct" : "conjugate gradients");
      reason = buf;
    } else {
      reason = "chosen in the scene (newton.fast_solver)";
    }
    if (s == FastSolverOptions::kCholmod && !have_cholmod()) {
      s = FastSolverOptions::kLDLT;
      reason += "; this build has no CHOLMOD (WB_CHOLMOD): ldlt instead";
    }
    direct = s != FastSolverOptions::kCG;
    if (!direct || s == FastSolverOptions::kCholmod) {  // CHOLMOD orders A itself
      for (Eigen::Index i = 0; i < n; ++i) place[std::size_t(i)] = int(i);
    }
    solver = s == FastSolverOptions::kCG        ? "cg"
             : s == FastSolverOptions::kCholmod ? "cholmod"
                                                : "ldlt";
  }

  // The direct solver's analysis of the pattern (ordering, elimination tree,
  // the factor's structure): once, here; each solve refactorises numerically.
  void analyse() {
#ifdef WB_HAVE_CHOLMOD
    if (solver == "cholmod") cholmod.analyzePattern(A);
#endif
    if (solver == "ldlt") analyse_ldlt();
  }
  void analyse_ldlt() {
    ldlt.analyzePattern(A);
    ldlt_analysed = true;
  }

  // Adds B to particle i's diagonal block (CG storage).
  void add_diag(Eigen::Index i, const Mat2& B) {
    dblk(0, i) += B(0, 0);
    dblk(1, i) += B(1, 0);
    dblk(2, i) += B(1, 1);
  }

  // A and b linearised at (xl, vl), the formulas of assemble_system.h, written
  // straight into A's values (or CG's springs and diagonal blocks).
  void assemble(const Mat2X& x0, const Mat2X& v0, const Mat2X& xl_, const Mat2X& vl,
                const Mat2X& f_ext, double h, bool definite) {
    double* val = direct ? A.valuePtr() : nullptr;
    if (direct) std::fill(val, val + A.nonZeros(), 0.0);
    const Eigen::Index n = net.n();
    // Mass and drag, and the right-hand side's terms that need no spring.
    for (Eigen::Index i = 0; i < n; ++i) {
      const double d = net.is_pinned(i) ? net.m[i] : net.m[i] + h * net.drag;
      if (direct) {
        val[diag[std::size_t(i)].c0] = d;
        val[diag[std::size_t(i)].c1 + 1] = d;
      } else {
        dblk.col(i) << d, 0.0, d;
      }
    }
    w = x0 + h * vl - xl_;  // where the positions are, minus where K is taken
    rhs = (v0 - vl) * net.m.asDiagonal();
    rhs += h * (f_ext - net.drag * vl);
    // Springs: force and the blocks of -h D - h^2 K.
    Vec2 f;
    Mat2 K, D;
    for (std::size_t k = 0; k < net.springs.size(); ++k) {
      const NetworkSpring& s = net.springs[k];
      const bool anchored = s.j < 0;
      const Vec2 xj = anchored ? s.anchor : Vec2(xl_.col(s.j));
      const Vec2 vj = anchored ? Vec2::Zero() : Vec2(vl.col(s.j));
      spring_derivatives(xl_.col(s.i), xj, vl.col(s.i), vj, s.k, s.rest, s.kd, definite, f, K, D);
      const Mat2 B = -h * D - h * h * K;
      const Vec2 dw = anchored ? Vec2(w.col(s.i)) : Vec2(w.col(s.i) - w.col(s.j));
      const Vec2 fi = f + K * dw;
      rhs.col(s.i) += h * fi;
      if (!anchored) rhs.col(s.j) -= h * fi;
      if (direct) {
        add_block(val, at[4 * k], B, 1.0);
        add_block(val, at[4 * k + 1], B, 1.0);
        add_block(val, at[4 * k + 2], B, -1.0);
        add_block(val, at[4 * k + 3], B, -1.0);
      } else if (cg_slot[k] >= 0) {
        CgSpring& c = cg_springs[std::size_t(cg_slot[k])];
        c.b00 = float(B(0, 0));
        c.b10 = float(B(1, 0));
        c.b11 = float(B(1, 1));
      } else {
        if (free_particle(s.i)) add_diag(s.i, B);
        if (free_particle(s.j)) add_diag(s.j, B);
      }
    }
    // Pinned particles: dv = 0.
    for (Eigen::Index i = 0; i < n; ++i)
      if (net.is_pinned(i)) rhs.col(i).setZero();
    for (Eigen::Index i = 0; i < n; ++i) b.segment<2>(2 * place[std::size_t(i)]) = rhs.col(i);
  }

  // y = A x in one forward sweep over the particles and the springs: y_k
  // starts as dblk_k x_k, and each spring (i < j) adds t = B (x_i - x_j) to
  // y_i and subtracts it from y_j. Particle k's entries of x are first made by
  // make(k), called once per particle in increasing k before x_k is read (CG
  // folds p = z + beta p in here: no pass of its own). Returns x . y (x^T A x).
  template <class Make>
  double product(double* x, double* y, Make make) const {
    const Eigen::Index n = net.n();
    const CgSpring* const springs = cg_springs.data();
    Eigen::Index ready = 0;  // particles below: made, and y = dblk x there
    double quad = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      // Made up to i + cg_lead, the farthest the springs from i reach.
      for (const Eigen::Index to = std::min(n - 1, i + cg_lead); ready <= to; ++ready) {
        make(ready);
        const double x0 = x[2 * ready], x1 = x[2 * ready + 1];
        y[2 * ready] = dblk(0, ready) * x0 + dblk(1, ready) * x1;
        y[2 * ready + 1] = dblk(1, ready) * x0 + dblk(2, ready) * x1;
      }
      const Vec2 xi = Eigen::Map<const Vec2>(x + 2 * i);
      Vec2 yi = Eigen::Map<const Vec2>(y + 2 * i);
      const CgSpring* const end = springs + cg_first[std::size_t(i) + 1];
      for (const CgSpring* s = springs + cg_first[std::size_t(i)]; s != end; ++s) {
        const Vec2 d = xi - Eigen::Map<const Vec2>(x + 2 * s->j);
        // B's columns (b00, b10) and (b10, b11) overlap in memory: two packet
        // loads, each widened to double in one instruction.
        const Vec2 t = Eigen::Map<const Eigen::Vector2f>(&s->b00).cast<double>() * d[0] +
                       Eigen::Map<const Eigen::Vector2f>(&s->b10).cast<double>() * d[1];
        yi += t;
        Eigen::Map<Vec2>(y + 2 * s->j) -= t;
      }
      // Every spring with i as its second particle came earlier: y_i is final.
      Eigen::Map<Vec2>(y + 2 * i) = yi;
      quad += xi.dot(yi);
    }
    return quad;
  }

  // Preconditioned conjugate gradients on A dv = b from `start`, until
  // |b - A dv| <= abs_tol (kCgMaxIterations: a failure). The preconditioner is
  // the inverse of each particle's 2 x 2 diagonal block (block Jacobi): a
  // spring acts along its direction, and the block sees that direction where a
  // scalar (Jacobi) preconditioner would see only x and y. One iteration is
  // two sweeps: the product (which also makes p = z + beta p) and the update.
  bool solve_cg(const Eigen::VectorXd& start, double abs_tol) {
    const Eigen::Index n = net.n();
    dinv = dblk;  // the whole diagonal blocks first, inverted in place below
    for (Eigen::Index i = 0; i < n; ++i) {
      for (int c = cg_first[std::size_t(i)]; c < cg_first[std::size_t(i) + 1]; ++c) {
        const CgSpring& s = cg_springs[std::size_t(c)];
        const Eigen::Vector3d B(s.b00, s.b10, s.b11);
        dinv.col(i) += B;
        dinv.col(s.j) += B;
      }
    }
    for (Eigen::Index i = 0; i < n; ++i) {
      const double a = dinv(0, i), c = dinv(1, i), d = dinv(2, i), det = a * d - c * c;
      if (det > 0.0) {
        dinv.col(i) << d / det, -c / det, a / det;
      } else {
        dinv.col(i) << 1.0, 0.0, 1.0;  // never for A = M - h D - h^2 K with definite blocks
      }
    }
    // r = b - A dv, z = P r (P the preconditioner), p = z.
    dv = start;
    product(dv.data(), q.data(), [](Eigen::Index) {});
    double rz = 0, rr = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double r0 = b[2 * i] - q[2 * i], r1 = b[2 * i + 1] - q[2 * i + 1];
      const double z0 = dinv(0, i) * r0 + dinv(1, i) * r1, z1 = dinv(1, i) * r0 + dinv(2, i) * r1;
      r[2 * i] = r0;
      r[2 * i + 1] = r1;
      z[2 * i] = p[2 * i] = z0;
      z[2 * i + 1] = p[2 * i + 1] = z1;
      rz += r0 * z0 + r1 * z1;
      rr += r0 * r0 + r1 * r1;
    }
    const double tol2 = abs_tol * abs_tol;
    double beta = 0;  // p = z + beta p, made in the product (0: p = z, as set above)
    double* pp = p.data();
    const double* zp = z.data();
    auto make_p = [&](Eigen::Index k) {
      pp[2 * k] = zp[2 * k] + beta * pp[2 * k];
      pp[2 * k + 1] = zp[2 * k + 1] + beta * pp[2 * k + 1];
    };
    for (int it = 0; it < kCgMaxIterations && rr > tol2; ++it) {
      const double pq = product(pp, q.data(), make_p);
      if (!(pq > 0.0)) return false;  // A not positive definite along p
      const double alpha = rz / pq;
      // dv += alpha p, r -= alpha q, z = P r, and the new r.z and r.r, in one pass.
      double rz_new = 0;
      rr = 0;
      for (Eigen::Index i = 0; i < n; ++i) {
        dv[2 * i] += alpha * p[2 * i];
        dv[2 * i + 1] += alpha * p[2 * i + 1];
        const double r0 = r[2 * i] - alpha * q[2 * i], r1 = r[2 * i + 1] - alpha * q[2 * i + 1];
        const double z0 = dinv(0, i) * r0 + dinv(1, i) * r1;
        const double z1 = dinv(1, i) * r0 + dinv(2, i) * r1;
        r[2 * i] = r0;
        r[2 * i + 1] = r1;
        z[2 * i] = z0;
        z[2 * i + 1] = z1;
        rz_new += r0 * z0 + r1 * z1;
        rr += r0 * r0 + r1 * r1;
      }
      beta = rz_new / rz;
      rz = rz_new;
      ++cg_iterations;
      if (fo.cg_meter) fo.cg_meter->count(1);
    }
    return rr <= tol2;
  }

  bool solve_ldlt() {
    if (!ldlt_analysed) analyse_ldlt();  // cholmod's fallback, the first time
    ldlt.factorize(A);
    ++factorisations;
    if (ldlt.info() != Eigen::Success) return false;
    dv = ldlt.solve(b);
    return ldlt.info() == Eigen::Success;
  }

  // A dv = b; start: CG's starting point; abs_tol: CG's bound on |A dv - b|.
  bool solve(const Eigen::VectorXd& start, double abs_tol) {
    bool ok = false;
    if (!direct) {
      const budget::PhaseScope phase(budget::kCg);
      ok = solve_cg(start, abs_tol);
#ifdef WB_HAVE_CHOLMOD
    } else if (solver == "cholmod") {
      cholmod.factorize(A);
      ++factorisations;
      if (cholmod.info() == Eigen::Success) {
        dv = cholmod.solve(b);
        ok = cholmod.info() == Eigen::Success;
      } else {
        ok = solve_ldlt();  // not positive definite (definite: false): LDLT still works
      }
#endif
    } else {
      ok = solve_ldlt();
    }
    return ok && dv.allFinite();
  }

  // y += dv, dv in A's order.
  void add_dv(Eigen::Map<Eigen::VectorXd>& yv) const {
    for (Eigen::Index i = 0; i < net.n(); ++i)
      yv.segment<2>(2 * i) += dv.segment<2>(2 * place[std::size_t(i)]);
  }

  NewtonReport step(const Mat2X& f_ext, double h, const NewtonOptions& opt, Mat2X& x, Mat2X& v) {
    NewtonReport rep;
    const Eigen::Index n = net.n();
    for (WorkMeter* m : {fo.cg_meter, fo.newton_meter})
      if (m) m->next_step();
    for (Eigen::Index i = 0; i < n; ++i)
      if (net.is_pinned(i)) v.col(i).setZero();
    y = v;
    Eigen::Map<Eigen::VectorXd> yv(y.data(), 2 * n);

    // First solve, linearised at the start (Baraff and Witkin). CG starts from
    // the last step's first dv: in a smooth motion dv changes little from one
    // step to the next.
    assemble(x, v, x, v, f_ext, h, opt.definite);
    rep.scale = (v * net.m.asDiagonal()).norm() + b.norm() + h * f_ext.norm();
    if (fo.newton_meter) fo.newton_meter->count(1);
    if (!solve(dv0, fo.cg_tol * rep.scale)) {
      rep.solver_failed = true;
    } else {
      dv0 = dv;
      add_dv(yv);
      rep.iterations = 1;
    }
    if (opt.one_iteration) {
      // Not measured: it would cost one more assembly.
      rep.residual = std::nan("");
      rep.converged = !rep.solver_failed;
    }

    // Newton iterations on the residual G(y) = -b at (x + h y, y).
    while (!rep.solver_failed && !opt.one_iteration) {
      xl = x + h * y;
      assemble(x, v, xl, y, f_ext, h, opt.definite);
      rep.residual = b.norm();
      rep.converged = rep.residual <= opt.tol * rep.scale;
      if (rep.converged || rep.iterations >= opt.max_iterations) break;
      if (fo.newton_meter) fo.newton_meter->count(1);
      if (!solve(zero, std::max(kNewtonForcing * rep.residual, 0.1 * opt.tol * rep.scale))) {
        rep.solver_failed = true;
        break;
      }
      add_dv(yv);
      ++rep.iterations;
    }
    if (rep.solver_failed && rep.iterations == 0) rep.residual = std::nan("");

    x += h * y;
    v = y;
    return rep;
  }
};

FastBackwardEuler::FastBackwardEuler(const SpringNetwork& net, const FastSolverOptions& fo)
    : impl_(std::make_unique<Impl>(net, fo)) {}
FastBackwardEuler::~FastBackwardEuler() = default;

NewtonReport FastBackwardEuler::step(const Mat2X& f_ext, double h, const NewtonOptions& opt,
                                     Mat2X& x, Mat2X& v) {
  return impl_->step(f_ext, h, opt, x, v);
}
const std::string& FastBackwardEuler::solver() const { return impl_->solver; }
const std::string& FastBackwardEuler::reason() const { return impl_->reason; }
long FastBackwardEuler::cg_iterations() const { return impl_->cg_iterations; }
long FastBackwardEuler::factorisations() const { return impl_->factorisations; }

}  // namespace wb
