// Diagnosis probes of F6 (tests/common/wb_probe.h): f coming in empty, of the right size
// holding old forces, of the wrong size; no terms; terms that depend on x, v and m.
#include <stdexcept>
#include <string>

#include "accumulate_forces.h"
#include "wb_probe.h"

// The lab's probe files compile as one unit (cmake/labs.cmake): each keeps its helpers in a
// namespace of its own.
namespace probe_F6_accumulate_forces {

using wbprobe::cols;
using wbprobe::vec;

namespace {
using wb::Mat2X;
using wb::Vec2;
using wb::VecX;
using Terms = std::vector<std::unique_ptr<wb::Force>>;

void check_size(const Mat2X& x, const Mat2X& f) {
  if (f.cols() != x.cols())
    // The words of the grader's worker (tools/grader/cpp/client.cpp), which checks the size
    // before the term runs: the probe says the same linked directly and through the worker.
    throw std::logic_error("the lab's code called Force::add with f of " +
                           std::to_string(f.cols()) + " columns (entries), but the system has " +
                           std::to_string(x.cols()) + " particles");
}
// f_i += m_i (1, -2)
struct MassTerm : wb::Force {
  void add(const Mat2X& x, const Mat2X&, const VecX& m, Mat2X& f) const override {
    check_size(x, f);
    for (Eigen::Index i = 0; i < x.cols(); ++i) f.col(i) += m[i] * Vec2(1, -2);
  }
  std::string type() const override { return "probe-mass"; }
};
// f_i += -2 x_i - 0.5 v_i
struct StateTerm : wb::Force {
  void add(const Mat2X& x, const Mat2X& v, const VecX&, Mat2X& f) const override {
    check_size(x, f);
    f += -2.0 * x - 0.5 * v;
  }
  std::string type() const override { return "probe-state"; }
};

void run(wbprobe::Probe& P, bool two_terms, const Mat2X& x, const Mat2X& v, const VecX& m,
         Mat2X f) {
  Terms terms;
  terms.push_back(std::make_unique<MassTerm>());
  if (two_terms) terms.push_back(std::make_unique<StateTerm>());
  P.note(two_terms ? "forces = {f_i += m_i (1, -2); f_i += -2 x_i - 0.5 v_i}"
                   : "forces = {f_i += m_i (1, -2)}");
  P.call("accumulate_forces");
  P.in("x", x), P.in("v", v), P.in("m", m), P.in("f", f);
  accumulate_forces(terms, x, v, m, f);
  P.out("f", f);
}
}  // namespace

WB_PROBE("F6", "empty-f", "one term, two particles, f coming in empty (0 columns)") {
  P.simple();
  run(P, false, cols({{0, 0}, {1, 0}}), cols({{0, 0}, {0, 0}}), vec({1, 2}), Mat2X(2, 0));
}
WB_PROBE("F6", "old-f", "one term, two particles, f holding last step's forces") {
  P.simple();
  run(P, false, cols({{0, 0}, {1, 0}}), cols({{0, 0}, {0, 0}}), vec({1, 2}),
      cols({{5, 5}, {-3, 1}}));
}
WB_PROBE("F6", "wrong-size", "one term, two particles, f coming in with three columns") {
  run(P, false, cols({{0, 0}, {1, 0}}), cols({{0, 0}, {0, 0}}), vec({1, 2}),
      cols({{5, 5}, {-3, 1}, {2, 2}}));
}
WB_PROBE("F6", "no-terms", "no terms at all, f holding old forces: f must come out zero") {
  P.simple();
  Terms terms;
  const Mat2X x = cols({{0, 0}, {1, 0}}), v = cols({{0, 0}, {0, 0}});
  const VecX m = vec({1, 2});
  Mat2X f = cols({{5, 5}, {-3, 1}});
  P.note("forces = {} (no terms)");
  P.call("accumulate_forces");
  P.in("x", x), P.in("v", v), P.in("m", m), P.in("f", f);
  accumulate_forces(terms, x, v, m, f);
  P.out("f", f);
}
// The loop over the terms: three terms, each its own force, f coming in zero and of the right
// size (clearing it is then silent: only a term left out, or added twice, shows).
struct ConstantTerm : wb::Force {
  void add(const Mat2X& x, const Mat2X&, const VecX&, Mat2X& f) const override {
    check_size(x, f);
    f.colwise() += Vec2(0.5, 0.25);
  }
  std::string type() const override { return "probe-constant"; }
};
WB_PROBE("F6", "three-terms",
         "three terms (masses, positions and velocities, a constant), f zero") {
  Terms terms;
  terms.push_back(std::make_unique<MassTerm>());
  terms.push_back(std::make_unique<StateTerm>());
  terms.push_back(std::make_unique<ConstantTerm>());
  const Mat2X x = cols({{0.5, -1}, {2, 0.25}}), v = cols({{1, 0}, {0, -2}});
  const VecX m = vec({1, 2});
  Mat2X f = Mat2X::Zero(2, 2);
  P.note("forces = {f_i += m_i (1, -2); f_i += -2 x_i - 0.5 v_i; f_i += (0.5, 0.25)}");
  P.call("accumulate_forces");
  P.in("x", x), P.in("v", v), P.in("m", m), P.in("f", f);
  accumulate_forces(terms, x, v, m, f);
  P.out("f", f);
}
// Clearing f: old forces in an f of the wrong size.
WB_PROBE("F6", "two-terms",
         "two terms (masses, positions and velocities), f holding old forces for two particles") {
  run(P, true, cols({{0.5, -1}, {2, 0.25}, {-1, 1}}), cols({{1, 0}, {0, -2}, {0.5, 0.5}}),
      vec({1, 2, 0.5}), cols({{5, 5}, {-3, 1}}));
}

}  // namespace probe_F6_accumulate_forces
