// Graded tests for I3, assembly of one Newton step's system
// (labs/implicit/assemble_system.cpp). Expected values: the dense matrices
// M - h D - h^2 K and the right-hand side written from the formulas in
// assemble_system.h, with the test's own spring derivatives.
#include "assemble_system.h"
#include "implicit_checks.h"

// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace test_I3_assemble_system {

namespace {
using wb::Mat2X;
using wb::Vec2;

// A and b hold sums of a few products of O(1..100) numbers: rounding only.
constexpr double kRelTol = 1e-12;

// The public tests' network and linearisation point, or one drawn around them
// (tests/common/params.h: imtest::small_network's draws, the offsets, the load
// and h).
struct Setup {
  SpringNetwork net;
  Mat2X x0, v0, xl, vl, f_ext;
  double h = 0.1;
};

Setup setup(const wbtest::Params& p) {
  Setup s;
  imtest::small_network(p, s.net, s.x0, s.v0, 1.5, 0.3);
  // 0.1 or 0.2: x0 + h vl then has the published one's decimal places (0.08 would add one, and
  // its calls would be told apart by their digits).
  s.h = p.num(0.1, 0.1, 0.2);
  // A linearisation point away from x0 + h vl, so that b's K term counts.
  s.vl = s.v0 + Mat2X::Constant(2, 4, p.num(0.2, 0.1, 0.3));
  s.xl = s.x0 + s.h * s.vl;
  s.xl(0, 1) += p.num(0.03, 0.02, 0.04);
  s.xl(1, 3) -= p.num(0.02, 0.01, 0.03);
  s.f_ext.resize(2, 4);
  const double push[4] = {0.5, -0.3, 0.2, 0.4};
  for (int q = 0; q < 4; ++q) s.f_ext(0, q) = p.num(push[q], push[q] - 0.2, push[q] + 0.2);
  s.f_ext.row(1) = imtest::small_network_load(p, s.net.m, false).row(1);  // m g, as published
  return s;
}

// The dense A and b of assemble_system.h, pinned particles excluded; with
// `definite`, compressed springs' blocks clamped (in A and in b's K term).
void dense_reference(const Setup& s, Eigen::MatrixXd& A, Eigen::VectorXd& b,
                     bool definite = false) {
  Eigen::MatrixXd K, D;
  imtest::dense_jacobians(s.net, s.xl, s.vl, K, D, definite);
  const Eigen::Index n = s.net.n();
  Eigen::VectorXd M(2 * n);
  for (Eigen::Index p = 0; p < n; ++p) M.segment<2>(2 * p).setConstant(s.net.m[p]);
  const double h = s.h;
  A = Eigen::MatrixXd(M.asDiagonal()) - h * D - h * h * K;
  b = M.asDiagonal() * imtest::flat(s.v0 - s.vl) +
      h * imtest::flat(imtest::forces(s.net, s.xl, s.vl) + s.f_ext) +
      h * K * imtest::flat(s.x0 + h * s.vl - s.xl);
  for (Eigen::Index p = 0; p < n; ++p) {
    if (!s.net.is_pinned(p)) continue;
    A.middleRows(2 * p, 2).setZero();
    A.middleCols(2 * p, 2).setZero();
    A.block<2, 2>(2 * p, 2 * p) = s.net.m[p] * Eigen::Matrix2d::Identity();
    b.segment<2>(2 * p).setZero();
  }
}

// The symmetric matrix A stands for, from its stored upper triangle.
Eigen::MatrixXd full(const Eigen::SparseMatrix<double>& A) {
  const Eigen::SparseMatrix<double> both = A.selfadjointView<Eigen::Upper>();
  return Eigen::MatrixXd(both);
}

// The first stored entry below the diagonal (row > column), if any.
bool entry_below(const Eigen::SparseMatrix<double>& A, Eigen::Index& row, Eigen::Index& col) {
  for (int k = 0; k < A.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it) {
      if (it.row() > it.col()) {
        row = it.row();
        col = it.col();
        return true;
      }
    }
  }
  return false;
}

void require_dense(const SparseSystem& sys, const Eigen::MatrixXd& Ae, const Eigen::VectorXd& be,
                   const std::string& what) {
  const Eigen::SparseMatrix<double>& A = sys.A;
  const Eigen::VectorXd& b = sys.b;
  INFO(what << ": A is " << A.rows() << " x " << A.cols() << " and b has " << b.size()
            << " entries, expected " << Ae.rows() << " x " << Ae.cols() << " and " << be.size()
            << " (2n: two velocity unknowns per particle, pinned ones included)");
  REQUIRE(A.rows() == Ae.rows());
  REQUIRE(A.cols() == Ae.cols());
  REQUIRE(b.size() == be.size());
  Eigen::Index r = 0, c = 0;
  {
    const bool below = entry_below(A, r, c);
    INFO(what << ": A stores an entry below the diagonal, A(" << r << ", " << c
              << "): only the upper triangle (row <= column) is stored "
                 "(assemble_system.h)");
    REQUIRE_FALSE(below);
  }
  const Eigen::MatrixXd Ad = full(A);
  (Ad - Ae).cwiseAbs().maxCoeff(&r, &c);  // where, for the message (the check is NaN-safe)
  INFO(what << ": largest difference from the dense reference at A(" << r << ", " << c
            << ") (A's upper triangle, mirrored): got " << Ad(r, c) << ", expected " << Ae(r, c));
  REQUIRE(wbtest::max_abs_diff(Ad, Ae) <= kRelTol * wbtest::max_abs(Ae));  // NaN fails
  Eigen::Index i;
  (b - be).cwiseAbs().maxCoeff(&i);
  INFO(what << ": largest difference in b at " << i << ": got " << b[i] << ", expected "
            << be[i]);
  REQUIRE(wbtest::max_abs_diff(b, be) <= kRelTol * wbtest::max_abs(be));  // NaN fails
}
}  // namespace

namespace {
// The scenarios of the public tests below, each a function of its parameters:
// the public test runs it with the published ones (wbtest::Params()), the
// held-out test with drawn ones, in the same format (tests/common/params.h).

void pattern(const wbtest::Params& p) {
  const Setup s = setup(p);
  SparseSystem sys;
  assemble_system(s.net, s.x0, s.v0, s.xl, s.vl, s.f_ext, s.h, true, sys);
  const Eigen::SparseMatrix<double>& A = sys.A;
  INFO("A is " << A.rows() << " x " << A.cols()
               << ", expected 8 x 8 (2n for the 4 particles, pinned ones included)");
  REQUIRE(A.rows() == 8);
  REQUIRE(A.cols() == 8);
  // Blocks that may hold entries: diagonal, and the pairs joined by a spring;
  // entries on or above the diagonal only.
  Eigen::Matrix4i allowed = Eigen::Matrix4i::Identity();
  for (const NetworkSpring& sp : s.net.springs)
    if (sp.j >= 0) allowed(sp.i, sp.j) = allowed(sp.j, sp.i) = 1;
  for (int k = 0; k < A.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it) {
      INFO("stored entry A(" << it.row() << ", " << it.col() << ") between particles "
                             << it.row() / 2 << " and " << it.col() / 2);
      {
        INFO("no spring joins them");
        REQUIRE(allowed(it.row() / 2, it.col() / 2) == 1);
      }
      {
        INFO(
            "it is below the diagonal: A is symmetric, only its upper "
            "triangle (row <= "
            "column) is stored (assemble_system.h)");
        REQUIRE(it.row() <= it.col());  // nanfree: integers
      }
    }
  }
  // M - h D - h^2 K with -D, -K positive semi-definite (definite = true):
  // diagonal >= m.
  const Eigen::MatrixXd Ad = full(A);
  for (Eigen::Index p = 0; p < 4; ++p) {
    INFO("diagonal of particle " << p << ": " << Ad(2 * p, 2 * p) << ", "
                                 << Ad(2 * p + 1, 2 * p + 1) << ", expected at least its mass "
                                 << s.net.m[p]);
    REQUIRE(wbtest::finite(Ad(2 * p, 2 * p)) >= s.net.m[p]);
    REQUIRE(wbtest::finite(Ad(2 * p + 1, 2 * p + 1)) >= s.net.m[p]);
  }
  // The first assembly records where each of its values went
  // (assemble_system.h).
  INFO("sys.slot has " << sys.slot.size() << " entries for " << A.nonZeros()
                       << " stored ones: the first assembly records, for each value it adds, "
                          "its index in A.valuePtr() (at least one per stored entry)");
  REQUIRE(sys.slot.size() >= std::size_t(A.nonZeros()));  // nanfree: integers
  for (int k : sys.slot) {
    INFO("a slot " << k << " outside A's " << A.nonZeros() << " stored values");
    REQUIRE(k >= 0);            // nanfree: integers
    REQUIRE(k < A.nonZeros());  // nanfree: integers
  }
}

void dense(const wbtest::Params& p) {
  const Setup s = setup(p);
  SparseSystem sys;
  assemble_system(s.net, s.x0, s.v0, s.xl, s.vl, s.f_ext, s.h, false, sys);
  Eigen::MatrixXd Ae;
  Eigen::VectorXd be;
  dense_reference(s, Ae, be);
  require_dense(sys, Ae, be, "A = M - h D - h^2 K, b = M (v0 - vl) + h (f + f_ext) + h K w");
}

void start_rhs(const wbtest::Params& p) {
  Setup s = setup(p);
  s.xl = s.x0;
  s.vl = s.v0;
  SparseSystem sys;
  assemble_system(s.net, s.x0, s.v0, s.xl, s.vl, s.f_ext, s.h, false, sys);
  const Eigen::VectorXd& b = sys.b;
  Eigen::MatrixXd K, D;
  imtest::dense_jacobians(s.net, s.x0, s.v0, K, D);
  const Eigen::VectorXd be = s.h * (imtest::flat(imtest::forces(s.net, s.x0, s.v0) + s.f_ext) +
                                    s.h * K * imtest::flat(s.v0));
  INFO("b has " << b.size() << " entries, expected " << be.size() << " (2n)");
  REQUIRE(b.size() == be.size());
  Eigen::Index i;
  (b - be).cwiseAbs().maxCoeff(&i);
  INFO("Baraff and Witkin's right-hand side: at " << i << " got " << b[i] << ", expected "
                                                  << be[i]);
  REQUIRE(wbtest::max_abs_diff(b, be) <= kRelTol * wbtest::max_abs(be));  // NaN fails
}

void pinned(const wbtest::Params& p) {
  Setup s = setup(p);
  s.net.pinned = {0, 1, 0, 0};  // particle 1: springs to 0 and 2 act on them only
  s.vl.col(1).setZero();
  s.xl.col(1) = s.x0.col(1);
  SparseSystem sys;
  assemble_system(s.net, s.x0, s.v0, s.xl, s.vl, s.f_ext, s.h, false, sys);
  Eigen::MatrixXd Ae;
  Eigen::VectorXd be;
  dense_reference(s, Ae, be);
  require_dense(sys, Ae, be, "particle 1 pinned");
}

void definite(const wbtest::Params& p) {
  // Springs 0-1 and 2-0 compressed (rest 1.5 > L), the others stretched: with
  // definite = true their blocks lose the term across the spring, in A and in
  // b; with definite = false they keep it.
  Setup s = setup(p);
  s.net.springs[0].rest = p.num(1.5, 1.3, 1.7);  // L = 1.12 (1.07 to 1.17 drawn)
  s.net.springs[2].rest = p.num(1.5, 1.3, 1.7);  // L = 1.08 (1.03 to 1.13 drawn)
  for (bool definite : {true, false}) {
    SparseSystem sys;
    assemble_system(s.net, s.x0, s.v0, s.xl, s.vl, s.f_ext, s.h, definite, sys);
    Eigen::MatrixXd Ae;
    Eigen::VectorXd be;
    dense_reference(s, Ae, be, definite);
    require_dense(sys, Ae, be,
                  std::string("two compressed springs, definite = ") +
                      (definite ? "true: -K = k u u^T on them (spring_derivatives' clamp)"
                                : "false: the exact blocks"));
  }
}

void later_assembly(const wbtest::Params& p) {
  // One system, assembled at one state, then again at another (other
  // velocities, another linearisation point, another step size, definite
  // switched, particle 1 pinned in both): the second A and b are the dense
  // reference's at the second state, in the first one's pattern. Its values are
  // overwritten beforehand with NaN: a later assembly zeroes them before adding
  // (assemble_system.h).
  Setup s = setup(p);
  s.net.pinned = {0, 1, 0, 0};
  s.vl.col(1).setZero();
  s.xl.col(1) = s.x0.col(1);
  SparseSystem sys;
  assemble_system(s.net, s.x0, s.v0, s.xl, s.vl, s.f_ext, s.h, true, sys);
  // Slots outside A's values would make the second assembly write past them:
  // checked first.
  for (int k : sys.slot) {
    INFO("after the first assembly, a slot " << k << " outside A's " << sys.A.nonZeros()
                                             << " stored values (a slot is where a value went "
                                                "in A.valuePtr(): &A.coeffRef(row, col) - "
                                                "A.valuePtr())");
    REQUIRE(k >= 0);                // nanfree: integers
    REQUIRE(k < sys.A.nonZeros());  // nanfree: integers
  }
  const std::vector<int> outer(sys.A.outerIndexPtr(), sys.A.outerIndexPtr() + sys.A.cols() + 1);
  const std::vector<int> inner(sys.A.innerIndexPtr(), sys.A.innerIndexPtr() + sys.A.nonZeros());
  const std::vector<int> slot = sys.slot;
  sys.A.coeffs().setConstant(std::nan(""));
  sys.b.setConstant(std::nan(""));
  Setup t = s;
  t.v0 = s.v0.reverse().eval();
  t.vl = t.v0 + Mat2X::Constant(2, 4, p.num(-0.1, -0.2, -0.05));
  t.vl.col(1).setZero();
  t.xl = t.x0 + 0.5 * s.h * t.vl;
  t.xl(1, 2) += p.num(0.04, 0.02, 0.06);
  const double h2 = 0.5 * s.h;
  assemble_system(t.net, t.x0, t.v0, t.xl, t.vl, t.f_ext, h2, false, sys);
  {
    const std::vector<int> outer2(sys.A.outerIndexPtr(),
                                  sys.A.outerIndexPtr() + sys.A.cols() + 1);
    const std::vector<int> inner2(sys.A.innerIndexPtr(),
                                  sys.A.innerIndexPtr() + sys.A.nonZeros());
    INFO("the second assembly changed A's pattern (" << inner.size() << " stored entries, then "
                                                     << inner2.size()
                                                     << ") or sys.slot: the springs are the "
                                                        "same, so is the pattern");
    REQUIRE(outer2 == outer);
    REQUIRE(inner2 == inner);
    REQUIRE(sys.slot == slot);
  }
  // The reference at the second state, with its own h.
  Eigen::MatrixXd K, D;
  imtest::dense_jacobians(t.net, t.xl, t.vl, K, D);
  const Eigen::Index n = t.net.n();
  Eigen::VectorXd M(2 * n);
  for (Eigen::Index p = 0; p < n; ++p) M.segment<2>(2 * p).setConstant(t.net.m[p]);
  Eigen::MatrixXd Ae = Eigen::MatrixXd(M.asDiagonal()) - h2 * D - h2 * h2 * K;
  Eigen::VectorXd be = M.asDiagonal() * imtest::flat(t.v0 - t.vl) +
                       h2 * imtest::flat(imtest::forces(t.net, t.xl, t.vl) + t.f_ext) +
                       h2 * K * imtest::flat(t.x0 + h2 * t.vl - t.xl);
  Ae.middleRows(2, 2).setZero();
  Ae.middleCols(2, 2).setZero();
  Ae.block<2, 2>(2, 2) = t.net.m[1] * Eigen::Matrix2d::Identity();
  be.segment<2>(2).setZero();
  require_dense(sys, Ae, be,
                "the second assembly (its values first set to NaN; h = " + std::to_string(h2) +
                    ", definite false)");
}
}  // namespace

TEST_CASE(
    "I3 assembly: A is 2n x 2n and stores its upper triangle with the "
    "network's sparsity",
    "[implicit][I3][3pts]") {
  pattern(wbtest::Params());
}

TEST_CASE("I3 assembly: A and b equal a dense reference on a small network",
          "[implicit][I3][4pts]") {
  dense(wbtest::Params());
}

TEST_CASE("I3 assembly: at the start b is h (f + f_ext + h K v)", "[implicit][I3][3pts]") {
  start_rhs(wbtest::Params());
}

TEST_CASE("I3 assembly: a pinned particle's rows hold only its mass and b = 0",
          "[implicit][I3][3pts]") {
  pinned(wbtest::Params());
}

TEST_CASE("I3 assembly: definite is passed on to the compressed springs' blocks",
          "[implicit][I3][2pts]") {
  definite(wbtest::Params());
}

TEST_CASE(
    "I3 assembly: a later assembly writes its values into the first "
    "one's pattern",
    "[implicit][I3][2pts]") {
  later_assembly(wbtest::Params());
}

TEST_CASE(
    "I3 held-out: random networks assemble A = M - h D - h^2 K and b "
    "with only the allowed "
    "blocks",
    "[implicit][I3][held-out][3pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("I3")) {
    INFO(g.replay());
    // Every public scenario above again, its parameters drawn from the held-out
    // seed in the public tests' format (short decimals, the same network's
    // shape and largest number), so that no call tells the public tests from
    // this one (tools/adversary --inputs); then random networks, assembled
    // twice each.
    {
      const wbtest::Params p(g);
      pattern(p);
      dense(p);
      start_rhs(p);
      pinned(p);
      definite(p);
      later_assembly(p);
    }
    // Each network with the clamp off and on (a compressed spring is where it
    // matters), each assembled twice into the same system at two linearisation
    // points (the second call reuses the pattern and its slots: every value
    // must be replaced, none added).
    for (const bool pin : {false, true}) {
      for (const bool definite : {false, true}) {
        imtest::Network w = imtest::random_network(g, pin, true);
        const Eigen::Index n = w.net.n();
        // One significant digit, as the published 0.1: x + h vl keeps few digits.
        const double hd = g.log_uniform(1e-3, 0.1),
                     h = wbtest::Params(g).num(0.1, 0.8 * hd, 1.2 * hd);
        SparseSystem sys;
        for (int call = 0; call < 2; ++call) {
          // As the public tests write theirs: vl and xl offsets of one or two significant digits
          // from v and x + h vl, the sums as computed (every spring longer than 0.1 m at xl).
          Mat2X vl, xl;
          for (bool near = true; near;) {
            vl = w.v, xl = w.x;
            for (Eigen::Index k = 0; k < vl.size(); ++k)
              vl.data()[k] += imtest::public_decimal(g, -0.5, 0.5);
            xl += h * vl;
            for (Eigen::Index k = 0; k < xl.size(); ++k)
              xl.data()[k] += imtest::public_decimal(g, -0.05, 0.05);
            // One call in eight at the start (b = h (f + f_ext + h K v)), as one public call in
            // eight is.
            if (call == 0 && !pin && !definite) vl = w.v, xl = w.x;
            near = false;
            for (const NetworkSpring& sp : w.net.springs)
              near = near ||
                     (Vec2(xl.col(sp.i)) - (sp.j < 0 ? sp.anchor : Vec2(xl.col(sp.j)))).norm() <=
                         0.1;
          }
          for (Eigen::Index p = 0; p < n; ++p) {
            if (w.net.is_pinned(p))
              vl.col(p).setZero(), xl.col(p) = w.x.col(p);  // as the caller does
          }
          assemble_system(w.net, w.x, w.v, xl, vl, w.f_ext, h, definite, sys);
          const Eigen::SparseMatrix<double>& A = sys.A;
          const Eigen::VectorXd& b = sys.b;
          Eigen::MatrixXd Ae;
          Eigen::VectorXd be;
          imtest::dense_system(w.net, w.x, w.v, xl, vl, w.f_ext, h, definite, Ae, be);
          INFO(n << " particles, " << w.net.springs.size() << " springs, h = " << h
                 << ", definite = " << definite << (pin ? ", one particle pinned" : "")
                 << (call ? "; the second assembly into the same system" : ""));
          {
            INFO("A is " << A.rows() << " x " << A.cols() << " and b has " << b.size()
                         << " entries, expected " << 2 * n << " x " << 2 * n << " and " << 2 * n);
            REQUIRE(A.rows() == 2 * n);
            REQUIRE(A.cols() == 2 * n);
            REQUIRE(b.size() == 2 * n);
          }
          // Blocks that may hold entries: each particle's own, and pairs of
          // free particles joined by a spring.
          Eigen::MatrixXi allowed = Eigen::MatrixXi::Identity(n, n);
          for (const NetworkSpring& sp : w.net.springs)
            if (sp.j >= 0 && !w.net.is_pinned(sp.i) && !w.net.is_pinned(sp.j))
              allowed(sp.i, sp.j) = allowed(sp.j, sp.i) = 1;
          for (int k = 0; k < A.outerSize(); ++k) {
            for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it) {
              INFO("stored entry A("
                   << it.row() << ", " << it.col() << ") between particles " << it.row() / 2
                   << " and " << it.col() / 2
                   << ": only a particle's own block and the blocks of a spring "
                      "between two free particles may be stored, on or above "
                      "the "
                      "diagonal (the upper triangle)");
              REQUIRE(allowed(it.row() / 2, it.col() / 2) == 1);
              REQUIRE(it.row() <= it.col());  // nanfree: integers
            }
          }
          const Eigen::MatrixXd Ad = full(A);
          INFO("A (its upper triangle, mirrored) =\n"
               << Ad << "\nexpected\n"
               << Ae << "\nb = " << b.transpose() << "\nexpected " << be.transpose());
          REQUIRE(wbtest::max_abs_diff(Ad, Ae) <= kRelTol * wbtest::max_abs(Ae));
          REQUIRE(wbtest::max_abs_diff(b, be) <= kRelTol * (1 + wbtest::max_abs(be)));
        }
      }
    }
  }
}

}  // namespace test_I3_assemble_system
