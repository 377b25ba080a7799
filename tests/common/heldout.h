// Held-out inputs (docs/grading.md, "Held-out checks"): every task has a test tagged
// [held-out] that checks the student's function on inputs drawn from a seeded generator, with
// the expected values from the test's own closed forms and laws. The public tests' inputs are
// in the student pack; these are not known before grading: on the autograder the seed is
// secret and differs per submission, locally tools/grade draws one and prints it.
//
//   TEST_CASE("F5 held-out: random springs", "[forces][F5][held-out][3pts]") {
//     for (wbtest::HeldOut& g : wbtest::held_out("F5")) {
//       INFO(g.replay());            // which seed, and how to replay it
//       const double k = g.uniform(0.5, 50.0);
//       ...
//     }
//   }
//
// The seed: WB_HELDOUT_SEED (decimal or 0x hex; the grader sets it, given with --seed or
// derived from the autograder's secret and the submission), else a fresh random one.
// WB_HELDOUT_SEEDS=N checks N consecutive seeds from it in one process, the test case run once
// per seed (tools/mutants --heldout-seeds: the measurement that no correct implementation ever
// fails, and that every catalogued mistake is caught on every seed).
// Each task draws from its own stream (the seed mixed with the task's id), so adding a draw to
// one task changes no other task's inputs.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "wb/types.h"

namespace wbtest {
namespace {

inline std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

inline std::uint64_t task_hash(const std::string& task) {
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a
  for (unsigned char c : task) h = (h ^ c) * 1099511628211ull;
  return h;
}

struct HeldOutSeeds {
  std::uint64_t first = 0;
  long count = 1;
  bool given = false;  // from WB_HELDOUT_SEED (else drawn here)
};

inline HeldOutSeeds heldout_seeds() {
  static const HeldOutSeeds seeds = [] {
    HeldOutSeeds s;
    if (const char* e = std::getenv("WB_HELDOUT_SEED"); e && *e) {
      s.first = std::strtoull(e, nullptr, 0);
      s.given = true;
    } else {
      std::random_device rd;
      s.first = (std::uint64_t(rd()) << 32) ^ rd();
    }
    if (const char* e = std::getenv("WB_HELDOUT_SEEDS"); e && *e)
      s.count = std::max(1L, std::strtol(e, nullptr, 10));
    return s;
  }();
  return seeds;
}

inline std::string hex(std::uint64_t v) {
  std::ostringstream s;
  s << "0x" << std::hex << v;
  return s.str();
}

// One seed's inputs of one task: uniform draws from mt19937_64 (fully specified), mapped to
// doubles by us (not by a library distribution), so the same seed gives the same inputs on
// every platform.
class HeldOut {
 public:
  HeldOut(const std::string& task, std::uint64_t seed)
      : task_(task), seed_(seed), gen_(splitmix64(seed ^ task_hash(task))) {}

  std::uint64_t seed() const { return seed_; }
  const std::string& task() const { return task_; }

  // What a failure prints first: the inputs are not in the pack, so say how to see them again.
  std::string replay() const {
    return "held-out inputs of " + task_ + " from seed " + hex(seed_) +
           " (replay: tools/grade ... --seed " + hex(seed_) +
           ", or WB_HELDOUT_SEED=" + hex(seed_) + " when running the tests)";
  }

  double unit() { return double(gen_() >> 11) * 0x1.0p-53; }  // [0, 1)
  double uniform(double lo, double hi) { return lo + (hi - lo) * unit(); }
  // log-uniform in [lo, hi] (lo > 0): every order of magnitude as likely
  double log_uniform(double lo, double hi) { return lo * std::exp(std::log(hi / lo) * unit()); }
  // an integer in [lo, hi]
  long integer(long lo, long hi) { return lo + long(gen_() % std::uint64_t(hi - lo + 1)); }
  bool coin(double p = 0.5) { return unit() < p; }
  double sign() { return coin() ? 1.0 : -1.0; }
  // a magnitude in [lo, hi] with a random sign
  double signed_uniform(double lo, double hi) { return sign() * uniform(lo, hi); }
  wb::Vec2 vec2(double lo, double hi) { return wb::Vec2(uniform(lo, hi), uniform(lo, hi)); }
  wb::Vec3 vec3(double lo, double hi) {
    return wb::Vec3(uniform(lo, hi), uniform(lo, hi), uniform(lo, hi));
  }
  wb::Vec2 unit2() {
    const double a = uniform(0.0, 2.0 * M_PI);
    return wb::Vec2(std::cos(a), std::sin(a));
  }
  wb::Vec3 unit3() {  // uniform on the sphere
    const double z = uniform(-1.0, 1.0), a = uniform(0.0, 2.0 * M_PI), r = std::sqrt(1 - z * z);
    return wb::Vec3(r * std::cos(a), r * std::sin(a), z);
  }
  wb::Mat2X points(Eigen::Index n, double lo, double hi) {
    wb::Mat2X p(2, n);
    for (Eigen::Index i = 0; i < n; ++i) p.col(i) = vec2(lo, hi);
    return p;
  }
  wb::VecX values(Eigen::Index n, double lo, double hi) {
    wb::VecX v(n);
    for (Eigen::Index i = 0; i < n; ++i) v[i] = uniform(lo, hi);
    return v;
  }
  template <class T>
  const T& pick(const std::vector<T>& options) {
    return options[std::size_t(integer(0, long(options.size()) - 1))];
  }

 private:
  std::string task_;
  std::uint64_t seed_;
  std::mt19937_64 gen_;
};

// The generator of this run for one task. With WB_HELDOUT_SEEDS=N the test case runs N times,
// once per seed (Catch's GENERATE): a seed that fails does not stop the next, and each failure
// names its seed (g.replay()), so that tools/mutants counts the seeds that catch a mistake.
inline std::vector<HeldOut> held_out(const std::string& task) {
  const HeldOutSeeds s = heldout_seeds();
  const long count = s.count;
  const long k = count > 1 ? GENERATE_COPY(Catch::Generators::range(0L, count)) : 0L;
  return {HeldOut(task, s.first + std::uint64_t(k))};
}

// A random nonlinear a(x, v) of n particles, each its own, drawn from g: the held-out system
// of the midpoint lab's one-step checks (the euler lab's held-out tests now re-run its public
// scenarios instead: tests/common/params.h):
//   a_i = c0_i + c1_i x_i + c2_i v_i + c3_i * (x_i.y x_i.x, v_i.x v_i.y)   (* per coordinate)
inline auto random_accel(HeldOut& g, Eigen::Index n) {
  std::vector<wb::Mat2> c1(static_cast<std::size_t>(n)), c2(static_cast<std::size_t>(n));
  const wb::Mat2X c0 = g.points(n, -3.0, 3.0), c3 = g.points(n, -0.5, 0.5);
  for (Eigen::Index i = 0; i < n; ++i) {
    c1[std::size_t(i)] << g.uniform(-4, 4), g.uniform(-4, 4), g.uniform(-4, 4), g.uniform(-4, 4);
    c2[std::size_t(i)] << g.uniform(-2, 2), g.uniform(-2, 2), g.uniform(-2, 2), g.uniform(-2, 2);
  }
  return [=](const wb::Mat2X& x, const wb::Mat2X& v, wb::Mat2X& a) {
    for (Eigen::Index i = 0; i < x.cols(); ++i) {
      a.col(i) = c0.col(i) + c1[std::size_t(i)] * x.col(i) + c2[std::size_t(i)] * v.col(i) +
                 c3.col(i).cwiseProduct(wb::Vec2(x(1, i) * x(0, i), v(0, i) * v(1, i)));
    }
  };
}

}  // namespace
}  // namespace wbtest
