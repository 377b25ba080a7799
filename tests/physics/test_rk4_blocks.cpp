// rk4 by blocks (framework/src/rk4.cpp, docs/benchmarks.md "RK4 in blocks"): on
// per-particle forces the provided rk4 steps 256 particles at a time, in cache, and sums
// the run's bookkeeping (kinetic energy, gravity's potential) while each block is there.
// Not graded, no student code: the forces lab's solution. What must hold:
// - every particle's arithmetic is unchanged: the same bits as the whole arrays' step
//   (a defect here would change every figure of a run past 256 particles);
// - a step counts four evaluations, whatever the number of blocks;
// - the bookkeeping's sums taken by the step give the energy a separate pass gives, and
//   are used only for the state they were taken of;
// - the blocked step is still RK4: a damped fall matches its closed form to RK4's error.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>

#include "forces_world.h"
#include "wb/dynamics.h"
#include "wb/rk4.h"

namespace {

wb::Scene make_scene(Eigen::Index n, const char* forces) {
  wb::Scene s;
  s.file = "<test_rk4_blocks>";
  s.name = "blocks";
  s.x.resize(2, n);
  s.v.resize(2, n);
  s.m.resize(n);
  s.radius = wb::VecX::Zero(n);
  for (Eigen::Index i = 0; i < n; ++i) {  // spread, and not symmetric: no bit is equal by luck
    s.x.col(i) = wb::Vec2(std::sin(1.3 * i) * 40.0 + 0.01 * i, std::cos(0.7 * i) * 30.0);
    s.v.col(i) = wb::Vec2(std::sin(2.1 * i + 0.3) * 5.0, std::cos(1.9 * i) * 4.0);
    s.m[i] = 0.5 + 0.25 * (1.0 + std::sin(0.37 * i));
  }
  s.doc = wb::json::parse(forces);
  return s;
}

// The whole arrays' path: the same accelerations through a Dynamics that does not say it
// is per-particle.
struct Whole : wb::Dynamics {
  const wb::Dynamics& inner;
  explicit Whole(const wb::Dynamics& d) : inner(d) {}
  void eval(const wb::Mat2X& x, const wb::Mat2X& v, wb::Mat2X& a) const override {
    inner.acceleration(x, v, a);
  }
};

const char* const kGravityDamping =
    R"({"forces":[{"type":"gravity","g":[0.3,-9.81]},{"type":"damping","b":0.4}]})";
const char* const kWithVortex =  // the vortex reads positions: the stages' positions count
    R"({"forces":[{"type":"gravity","g":[0,-9.81]},{"type":"damping","b":0.1},)"
    R"({"type":"vortex","center":[1,2],"omega":3,"core":5,"drag":0.5}]})";

// A scene's world and the state a test steps: one set-up for the tests below.
struct Run {
  wb::Scene scene;
  wb::ForceWorld world;
  wb::Mat2X x, v;
  wb::Scratch s;
  Run(Eigen::Index n, const char* forces)
      : scene(make_scene(n, forces)), world(scene), x(scene.x), v(scene.v) {
    s.resize(n);
  }
  Run(const Run&) = delete;  // world's dynamics refers to its own terms
};

// The bookkeeping's energy of (x, v) is the energy summed apart, to rounding (about n eps
// of the largest term).
bool checked_agrees(const wb::ForceWorld& world, const wb::Mat2X& x, const wb::Mat2X& v) {
  bool finite = false;
  const double checked = world.checked_energy(x, v, finite);
  const wb::Energy e = world.energy(x, v);
  return finite && std::abs(checked - e.total()) <= 1e-12 * (std::abs(e.total()) + e.kinetic);
}

}  // namespace

TEST_CASE("rk4 by blocks: the same bits as the whole arrays, four evaluations a step",
          "[physics][rk4]") {
  for (const char* forces : {kGravityDamping, kWithVortex}) {
    for (Eigen::Index n : {Eigen::Index(256), Eigen::Index(257), Eigen::Index(1000)}) {
      const wb::Scene scene = make_scene(n, forces);
      const wb::ForceList terms = wb::build_forces(scene);
      const wb::ParticleDynamics dyn(terms, scene.m);
      REQUIRE(dyn.per_particle());
      const Whole whole(dyn);
      wb::Mat2X xb = scene.x, vb = scene.v, xw = scene.x, vw = scene.v;
      wb::Scratch sb, sw;
      sb.resize(n);
      sw.resize(n);
      dyn.reset_evals();
      for (int k = 0; k < 25; ++k) {
        wb::rk4_step(dyn, 0.01, xb, vb, sb);
        wb::rk4_step(whole, 0.01, xw, vw, sw);
      }
      INFO(forces << ", n = " << n);
      CHECK(dyn.evals() == 25 * 4 * 2);  // 4 by blocks + 4 through the whole path
      CHECK((xb.array() == xw.array()).all());
      CHECK((vb.array() == vw.array()).all());
    }
  }
}

TEST_CASE("rk4 by blocks: the step's energy sums are the separate pass's, for that state only",
          "[physics][rk4]") {
  Run r(1000, kGravityDamping);
  wb::rk4_step(r.world.dynamics(), 0.01, r.x, r.v, r.s);
  CHECK(checked_agrees(r.world, r.x, r.v));  // the step's sums
  CHECK(checked_agrees(r.world, r.x, r.v));  // taken once: now a pass of its own
  // Sums are used only for the arrays the step wrote: a copy of the state, or the state
  // after another step taken through the whole path, is summed anew.
  const wb::Mat2X x2 = r.x, v2 = r.v;
  wb::rk4_step(r.world.dynamics(), 0.01, r.x, r.v, r.s);
  CHECK(checked_agrees(r.world, x2, v2));
  const Whole whole(r.world.dynamics());
  wb::rk4_step(r.world.dynamics(), 0.01, r.x, r.v, r.s);  // sums ready for (x, v) ...
  wb::rk4_step(whole, 0.01, r.x, r.v, r.s);               // ... which this step moves again
  r.v.col(3) *= 100.0;
  CHECK(checked_agrees(r.world, r.x, r.v));
}

TEST_CASE("rk4 by blocks: a damped fall matches its closed form to RK4's error",
          "[physics][rk4]") {
  // v' = g - (b/m) v: v(t) = v_inf + (v0 - v_inf) e^{-ct}, c = b/m, v_inf = g/c, and
  // x(t) = x0 + v_inf t + (v0 - v_inf)(1 - e^{-ct})/c. RK4's global error on it is about
  // (ch)^4/120 of the transient per unit time: with c <= 0.8 s^-1, h = 0.01 s, t = 2 s it
  // is below 1e-10 m/s; kTol = 1e-8 (relative to the speeds, 10 m/s) leaves room.
  constexpr double kTol = 1e-8;
  const Eigen::Index n = 700;
  Run r(n, kGravityDamping);
  const wb::Scene& scene = r.scene;
  const wb::Mat2X &x = r.x, &v = r.v;
  const double h = 0.01, b = 0.4, t = 2.0;
  for (int k = 0; k < 200; ++k) wb::rk4_step(r.world.dynamics(), h, r.x, r.v, r.s);
  const wb::Vec2 g(0.3, -9.81);
  double worst = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double c = b / scene.m[i], e = std::exp(-c * t);
    const wb::Vec2 vinf = g / c, v0 = scene.v.col(i), x0 = scene.x.col(i);
    const wb::Vec2 ve = vinf + (v0 - vinf) * e;
    const wb::Vec2 xe = x0 + vinf * t + (v0 - vinf) * (1 - e) / c;
    worst = std::max({worst, (v.col(i) - ve).norm() / 10.0, (x.col(i) - xe).norm() / 10.0});
  }
  CHECK(worst <= kTol);
}

TEST_CASE("rk4 by blocks: a Dynamics that says it is per-particle without blocks fails loudly",
          "[physics][rk4]") {
  // A Dynamics that claims per_particle() but has no eval_block would otherwise get zero
  // accelerations from the default, silently: a run of a still body, not an error.
  struct NoBlocks : wb::Dynamics {
    bool per_particle() const override { return true; }
    void eval(const wb::Mat2X&, const wb::Mat2X& v, wb::Mat2X& a) const override { a = -v; }
  };
  const Eigen::Index n = 300;  // more than one block
  wb::Mat2X x = wb::Mat2X::Zero(2, n), v = wb::Mat2X::Ones(2, n);
  wb::Scratch s;
  s.resize(n);
  CHECK_THROWS_AS(wb::rk4_step(NoBlocks{}, 0.01, x, v, s), std::logic_error);
}

// The bookkeeping's sums run in whichever vector instructions the processor has
// (a clone per instruction set, chosen when the program loads). Every clone must
// give the bits of this scalar loop in the same order (no fused multiply-add, no
// other grouping): else a run's divergence verdict could depend on the machine.
TEST_CASE("the bookkeeping's energy sums give the same bits as their scalar order",
          "[physics][rk4]") {
  struct {  // splitmix64: uniform doubles in [0, 1)
    std::uint64_t s = 2024;
    double next() {
      std::uint64_t z = (s += 0x9e3779b97f4a7c15ULL);
      z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
      z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
      return double((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
    }
  } rng;
  // a b rounded on its own, never fused into the sum it is added to (as the kernel does)
  auto product = [](double a, double b) {
    const volatile double ab = a * b;
    return double(ab);
  };
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Index n = 1 + Eigen::Index(rng.next() * 600);
    const Eigen::Index first = Eigen::Index(rng.next() * double(n));
    wb::Mat2X x(2, n), v(2, n);
    wb::VecX m(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      x.col(i) = wb::Vec2(2e3 * rng.next() - 1e3, 2e3 * rng.next() - 1e3);
      v.col(i) = wb::Vec2(std::exp(20 * rng.next() - 10), -std::exp(20 * rng.next() - 10));
      m[i] = std::exp(10 * rng.next() - 5);
    }
    // The kernel's order: eight particles at a time in four sums of four lanes
    // (x, y of particles i, i+1 in sum 0, i+2, i+3 in sum 1, ...), the sums added
    // as (0 + 1) + (2 + 3) lane by lane, then per axis lanes c + (c + 2), then the
    // rest of the particles one by one.
    double sum[4][4] = {}, wsum[4][4] = {};
    Eigen::Index i = first;
    for (; i + 7 < n; i += 8)
      for (int s = 0; s < 4; ++s)
        for (int l = 0; l < 4; ++l) {
          const Eigen::Index p = i + 2 * s + l / 2;
          sum[s][l] += product(m[p], v(l % 2, p) * v(l % 2, p));
          wsum[s][l] += product(m[p], x(l % 2, p));
        }
    double kl[4], wl[4];
    for (int l = 0; l < 4; ++l) {
      kl[l] = (sum[0][l] + sum[1][l]) + (sum[2][l] + sum[3][l]);
      wl[l] = (wsum[0][l] + wsum[1][l]) + (wsum[2][l] + wsum[3][l]);
    }
    double k[2], w[2];
    for (int c = 0; c < 2; ++c) {
      k[c] = kl[c] + kl[c + 2];
      w[c] = wl[c] + wl[c + 2];
    }
    for (; i < n; ++i)
      for (int c = 0; c < 2; ++c) {
        k[c] += product(m[i], v(c, i) * v(c, i));
        w[c] += product(m[i], x(c, i));
      }
    Eigen::Array2d kk(1.5, -2.5), ww(0.25, 4.0);  // the sums add to what is there
    wb::add_energy_sums(x, v, m, first, n, kk, ww);
    INFO("n = " << n << ", first = " << first);
    CHECK(kk[0] == 1.5 + k[0]);
    CHECK(kk[1] == -2.5 + k[1]);
    CHECK(ww[0] == 0.25 + w[0]);
    CHECK(ww[1] == 4.0 + w[1]);
  }
}
