// Scene force terms: JSON -> Force objects that call the forces lab's functions.
#include "forces_world.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "accumulate_forces.h"
#include "attractor.h"
#include "boids.h"
#include "curl_noise.h"
#include "damping.h"
#include "newton_gravity.h"
#include "spring.h"
#include "uniform_gravity.h"
#include "vortex.h"
#include "wb/budget.h"

namespace wb {

namespace {

const Range kNonNegative{0.0};
const Range kPositive{0.0, std::numeric_limits<double>::infinity(), true};

// The cost model's rates of the force terms (docs/scenes.md, "Cost"), measured
// with the solution's functions: seconds per particle (or pair, spring) per force
// evaluation, and per potential evaluation (the divergence rule's energy, every
// step). accumulate_forces' own work (zeroing f, a = f/m) is kSecondsPerParticle.
constexpr double kSecondsPerParticle = 4e-9;
constexpr double kSecondsPerGravity = 2e-9;
constexpr double kSecondsPerNewtonPair = 5e-9;
constexpr double kSecondsPerNewtonPotentialPair = 6e-9;
constexpr double kSecondsPerAttractor = 6e-9;
constexpr double kSecondsPerDamping = 1e-9;
constexpr double kSecondsPerSpring = 12e-9;
constexpr double kSecondsPerSpringPotential = 6e-9;
constexpr double kSecondsPerBoidsPair = 4e-9;
constexpr double kSecondsPerVortex = 6e-9;
constexpr double kSecondsPerNoise = 40e-9;        // one psi: 4 lattice gradients and the fade
constexpr double kSecondsPerObstacle = 3e-9;      // one disc's distance, in one psi
constexpr double kBytesPerSpring = 56;            // SpringDef
constexpr double kSecondsPerSpringBuilt = 60e-9;  // made from its entry or generator

// Curl noise (docs/scenes.md, forces): a position is resolvable when its lattice
// coordinate x / scale has at least a cell's worth of bits below 2^53 (floor and
// the cell offset exact), and the difference step h when it moves the largest
// position by at least 2^-36 of it (the central difference keeps ~16 bits).
constexpr double kMaxLatticeCoordinate = 0x1p40;
constexpr double kMinStepFraction = 0x1p-36;
// The largest |grad N| of the gradient noise (N is quintic-faded gradient noise of
// unit gradients: |grad N| < 1 + 2 * 15/8 on a cell, a bound with room).
constexpr double kNoiseGradientBound = 5.0;

class UniformGravity : public Force {
 public:
  explicit UniformGravity(const Vec2& g) : g_(g) {}
  void add(const Mat2X&, const Mat2X&, const VecX& m, Mat2X& f) const override {
    add_uniform_gravity(m, g_, f);
  }
  double potential(const Mat2X& x, const VecX& m) const override {
    return -(g_.transpose() * x).dot(m);  // -sum m_i g . x_i
  }
  std::string type() const override { return "gravity"; }
  bool per_particle() const override { return true; }
  bool reads_positions() const override { return false; }
  const Vec2& g() const { return g_; }
  void bound(const Mat2X&, const Mat2X&, const VecX& m, VecX& b) const override {
    b += g_.cwiseAbs().maxCoeff() * m;
  }

 private:
  Vec2 g_;
};

class NewtonGravity : public Force {
 public:
  NewtonGravity(double G, double eps) : G_(G), eps_(eps) {}
  void add(const Mat2X& x, const Mat2X&, const VecX& m, Mat2X& f) const override {
    add_newton_gravity(x, m, G_, eps_, f);
  }
  double potential(const Mat2X& x, const VecX& m) const override {
    double V = 0;
    for (Eigen::Index i = 0; i < x.cols(); ++i) {
      for (Eigen::Index j = i + 1; j < x.cols(); ++j) {
        double s = (x.col(j) - x.col(i)).squaredNorm() + eps_ * eps_;
        if (s > 0) V -= G_ * m[i] * m[j] / std::sqrt(s);
      }
    }
    return V;
  }
  std::string type() const override { return "newton"; }
  // |f_i| <= sum_j G m_i m_j / (r^2 + eps^2) (a pair at one point without softening
  // has no direction: skipped, as in the potential).
  void bound(const Mat2X& x, const Mat2X&, const VecX& m, VecX& b) const override {
    for (Eigen::Index i = 0; i < x.cols(); ++i) {
      for (Eigen::Index j = i + 1; j < x.cols(); ++j) {
        const double s = (x.col(j) - x.col(i)).squaredNorm() + eps_ * eps_;
        if (!(s > 0)) continue;
        const double f = G_ * m[i] * m[j] / s;
        b[i] += f;
        b[j] += f;
      }
    }
  }

 private:
  double G_, eps_;
};

class Attractor : public Force {
 public:
  Attractor(const Vec2& c, double GM) : c_(c), GM_(GM) {}
  void add(const Mat2X& x, const Mat2X&, const VecX& m, Mat2X& f) const override {
    add_attractor(x, m, c_, GM_, f);
  }
  double potential(const Mat2X& x, const VecX& m) const override {
    double V = 0;
    for (Eigen::Index i = 0; i < x.cols(); ++i) {
      double r = (x.col(i) - c_).norm();
      if (r > 0) V -= GM_ * m[i] / r;
    }
    return V;
  }
  std::string type() const override { return "attractor"; }
  bool per_particle() const override { return true; }
  void bound(const Mat2X& x, const Mat2X&, const VecX& m, VecX& b) const override {
    for (Eigen::Index i = 0; i < x.cols(); ++i) {
      const double r2 = (x.col(i) - c_).squaredNorm();
      if (r2 > 0) b[i] += GM_ * m[i] / r2;
    }
  }

 private:
  Vec2 c_;
  double GM_;
};

class Damping : public Force {
 public:
  explicit Damping(double b) : b_(b) {}
  void add(const Mat2X&, const Mat2X& v, const VecX&, Mat2X& f) const override {
    add_damping(v, b_, f);
  }
  std::string type() const override { return "damping"; }
  bool per_particle() const override { return true; }
  bool reads_positions() const override { return false; }
  void bound(const Mat2X&, const Mat2X& v, const VecX&, VecX& b) const override {
    b += b_ * v.cwiseAbs().colwise().maxCoeff().transpose();
  }

 private:
  double b_;
};

class Boids : public Force {
 public:
  explicit Boids(const BoidsParams& p) : p_(p) {}
  void add(const Mat2X& x, const Mat2X& v, const VecX& m, Mat2X& f) const override {
    add_boids(x, v, m, p_, f);
  }
  std::string type() const override { return "boids"; }
  // |s_i| <= w_sep sum_{0 < r_ij < R_sep} 1/r_ij + w_align (max_j |v_j| + |v_i|)
  //          + w_coh R_coh + goal_weight, and f_i = m_i s_i.
  void bound(const Mat2X& x, const Mat2X& v, const VecX& m, VecX& b) const override {
    const Eigen::Index n = x.cols();
    const double vmax = n > 0 ? v.colwise().norm().maxCoeff() : 0.0;
    for (Eigen::Index i = 0; i < n; ++i) {
      double sep = 0;
      if (p_.separation.weight > 0) {
        for (Eigen::Index j = 0; j < n; ++j) {
          const double r = (x.col(i) - x.col(j)).norm();
          if (r > 0 && r < p_.separation.radius) sep += 1.0 / r;
        }
      }
      const double s = p_.separation.weight * sep +
                       p_.alignment.weight * (vmax + v.col(i).norm()) +
                       p_.cohesion.weight * p_.cohesion.radius + p_.goal_weight;
      b[i] += m[i] * s;
    }
  }

 private:
  BoidsParams p_;
};

class Vortex : public Force {
 public:
  explicit Vortex(const VortexParams& p) : p_(p) {}
  void add(const Mat2X& x, const Mat2X& v, const VecX&, Mat2X& f) const override {
    add_vortex(x, v, p_, f);
  }
  std::string type() const override { return "vortex"; }
  bool per_particle() const override { return true; }
  // |u| <= |omega| R (the Rankine vortex is fastest at its core's edge).
  void bound(const Mat2X&, const Mat2X& v, const VecX&, VecX& b) const override {
    b += (p_.drag * (std::abs(p_.omega) * p_.core + v.colwise().norm().array()))
             .matrix()
             .transpose();
  }

 private:
  VortexParams p_;
};

class CurlNoise : public Force {
 public:
  explicit CurlNoise(CurlNoiseParams p) : p_(std::move(p)) {}
  void add(const Mat2X& x, const Mat2X& v, const VecX&, Mat2X& f) const override {
    add_curl_noise(x, v, p_, f);
  }
  std::string type() const override { return "curl-noise"; }
  bool per_particle() const override { return true; }
  // |u| <= |grad psi| + (15/8) |psi| / d0 (the ramp's slope) with
  // |grad psi| <= 5 U / 0.883 + |wind| and |psi| <= U L / 0.883 + |wind| |x|.
  void bound(const Mat2X& x, const Mat2X& v, const VecX&, VecX& b) const override {
    for (Eigen::Index i = 0; i < x.cols(); ++i) {
      const double psi = k_ + wind_ * x.col(i).norm();
      const double u = kNoiseGradientBound * k_ / scale_ + wind_ + 15.0 / 8.0 * psi / p_.ramp;
      b[i] += p_.b * (u + v.col(i).norm());
    }
  }
  double k_ = 0, scale_ = 1, wind_ = 0;  // U L / 0.883, L, |wind|: for the bound

 private:
  CurlNoiseParams p_;
};

// The central-difference step of curl noise, as a fraction of the smallest
// length of the field (its scale, the ramp width): truncation (h/L)^2 ~ 1e-8
// and rounding eps L/h ~ 1e-12, both far below what a run can see.
constexpr double kCurlStepFraction = 1e-4;

Eigen::Index particle_index(const JsonObject& o, const char* key, std::int64_t n) {
  if (n == 0)
    o.fail(key, o.has(key) ? &o.raw().at(key) : nullptr,
           "a particle index, but the scene has no particles");
  return Eigen::Index(o.integer(key, 0, n - 1));
}

// What a curl-noise entry derives from its numbers, finite and resolvable
// (docs/scenes.md, forces): the difference step h > 0; the potential's size
// U L / 0.883; every particle's lattice coordinate x / L, at most 2^40 (so that
// floor and the cell offset are exact); h at least 2^-36 of the largest
// coordinate (so that x + h differs from x by h to 16 bits).
void check_curl_noise(const JsonObject& o, const Scene& scene, double amplitude, double scale,
                      const CurlNoiseParams& p) {
  const char* step_key = scale <= p.ramp ? "scale" : "ramp";
  const json* step_value = o.has(step_key) ? &o.raw().at(step_key) : &o.raw().at("scale");
  if (!(p.h > 0)) {
    o.fail(step_key, step_value,
           "a length whose 10^-4 (the curl's difference step) is still a positive number");
  }
  if (!std::isfinite(amplitude * scale / kNoiseGradientRms)) {
    o.fail("amplitude", &o.raw().at("amplitude"),
           "an amplitude whose product with scale (" + num(scale) +
               "), the potential's size U L / 0.883, is finite");
  }
  const double xmax = scene.n() > 0 ? scene.x.cwiseAbs().maxCoeff() : 0.0;
  if (!(xmax / scale <= kMaxLatticeCoordinate)) {
    o.fail("scale", &o.raw().at("scale"),
           "a scale of at least 2^-40 times the largest particle coordinate (" + num(xmax) +
               " m), so that x / scale is a lattice coordinate the noise resolves");
  }
  if (!(p.h >= kMinStepFraction * xmax)) {
    o.fail(step_key, step_value,
           "a length whose 10^-4, the curl's difference step " + num(p.h) +
               " m, is at least 2^-36 of the largest particle coordinate (" + num(xmax) +
               " m), so that x + h differs from x (else the flow silently vanishes)");
  }
}

BoidRule boid_rule(const JsonObject& o, const char* key) {
  BoidRule r;
  if (!o.has(key)) return r;
  JsonObject b = o.object(key);
  b.only_keys({"weight", "radius"});
  r.weight = b.number("weight", kNonNegative);
  r.radius = b.number("radius", kNonNegative);
  return r;
}

}  // namespace

void Springs::add(const Mat2X& x, const Mat2X& v, const VecX&, Mat2X& f) const {
  for (const SpringDef& s : springs) {
    if (s.j < 0) {
      f.col(s.i) +=
          spring_force(x.col(s.i), s.anchor, v.col(s.i), Vec2::Zero(), s.k, s.rest, s.kd);
    } else {
      Vec2 fi = spring_force(x.col(s.i), x.col(s.j), v.col(s.i), v.col(s.j), s.k, s.rest, s.kd);
      f.col(s.i) += fi;
      f.col(s.j) -= fi;
    }
  }
}

void Springs::bound(const Mat2X& x, const Mat2X& v, const VecX&, VecX& b) const {
  for (const SpringDef& s : springs) {
    const Vec2 xj = s.j < 0 ? s.anchor : Vec2(x.col(s.j));
    const Vec2 vj = s.j < 0 ? Vec2::Zero() : Vec2(v.col(s.j));
    const double f =
        s.k * std::abs((x.col(s.i) - xj).norm() - s.rest) + s.kd * (v.col(s.i) - vj).norm();
    b[s.i] += f;
    if (s.j >= 0) b[s.j] += f;
  }
}

std::string Springs::blame(const Mat2X& x, const Mat2X& v) const {
  // The first spring whose force or energy is not finite, and the entry it came from.
  for (std::size_t k = 0; k < springs.size(); ++k) {
    const SpringDef& s = springs[k];
    const Vec2 xj = s.j < 0 ? s.anchor : Vec2(x.col(s.j));
    const Vec2 vj = s.j < 0 ? Vec2::Zero() : Vec2(v.col(s.j));
    const double stretch = (x.col(s.i) - xj).norm() - s.rest;
    const double f = s.k * std::abs(stretch) + s.kd * (v.col(s.i) - vj).norm();
    if (std::isfinite(f) && std::isfinite(0.5 * s.k * stretch * stretch)) continue;
    std::string where = key;
    for (const auto& [first, entry] : origins)
      if (first <= k) where = entry;
    return where;
  }
  return key;
}

double Springs::potential(const Mat2X& x, const VecX&) const {
  double V = 0;
  for (const SpringDef& s : springs) {
    Vec2 xj = s.j < 0 ? s.anchor : Vec2(x.col(s.j));
    double stretch = (x.col(s.i) - xj).norm() - s.rest;
    V += 0.5 * s.k * stretch * stretch;
  }
  return V;
}

const std::vector<std::string>& force_types() {
  static const std::vector<std::string> types = {"gravity", "newton", "attractor", "damping",
                                                 "spring",  "boids",  "vortex",    "curl-noise"};
  return types;
}

ForceList build_forces(const Scene& scene) {
  ForceList out;
  JsonObject top(scene.file, scene.doc, "");
  const json& list = top.array_or_empty("forces");
  Springs* springs = nullptr;
  for (std::size_t k = 0; k < list.size(); ++k) {
    JsonObject o = top.element("forces", k);
    std::string type = o.string("type");
    const std::size_t before = out.size();
    if (type == "gravity") {
      o.only_keys({"type", "g"});
      out.push_back(std::make_unique<UniformGravity>(o.vec2("g")));
    } else if (type == "newton") {
      o.only_keys({"type", "G", "softening"});
      out.push_back(std::make_unique<NewtonGravity>(o.number("G", kNonNegative),
                                                    o.number_or("softening", 0.0, kNonNegative)));
    } else if (type == "attractor") {
      o.only_keys({"type", "center", "GM"});
      out.push_back(std::make_unique<Attractor>(o.vec2_or("center", Vec2::Zero()),
                                                o.number("GM", kNonNegative)));
    } else if (type == "damping") {
      o.only_keys({"type", "b"});
      out.push_back(std::make_unique<Damping>(o.number("b", kNonNegative)));
    } else if (type == "spring") {
      o.only_keys({"type", "i", "j", "anchor", "k", "rest", "damping"});
      SpringDef s;
      s.i = particle_index(o, "i", scene.n());
      if (o.has("j") == o.has("anchor")) {
        o.fail("j", o.has("j") ? &o.raw().at("j") : nullptr,
               "exactly one of \"j\" (a particle index) or \"anchor\" (a point)");
      }
      s.j = o.has("j") ? particle_index(o, "j", scene.n()) : -1;
      if (s.j == s.i) o.fail("j", &o.raw().at("j"), "a particle other than i");
      s.anchor = o.vec2_or("anchor", Vec2::Zero());
      s.k = o.number("k", kNonNegative);
      Vec2 xj = s.j < 0 ? s.anchor : Vec2(scene.x.col(s.j));
      const double initial = (scene.x.col(s.i) - xj).norm();
      if (!o.has("rest") && !std::isfinite(initial)) {
        o.fail("rest", nullptr,
               "a rest length: its default, the initial distance, overflows (the ends are too "
               "far apart)");
      }
      s.rest = o.number_or("rest", initial, kNonNegative);
      s.kd = o.number_or("damping", 0.0, kNonNegative);
      if (!springs) {
        out.push_back(std::make_unique<Springs>());
        springs = static_cast<Springs*>(out.back().get());
      }
      springs->origins.push_back({springs->springs.size(), o.path()});
      springs->springs.push_back(s);
    } else if (type == "boids") {
      o.only_keys({"type", "separation", "alignment", "cohesion", "goal", "goal_weight"});
      BoidsParams p;
      p.separation = boid_rule(o, "separation");
      p.alignment = boid_rule(o, "alignment");
      p.cohesion = boid_rule(o, "cohesion");
      p.goal = o.vec2_or("goal", Vec2::Zero());
      p.goal_weight = o.number_or("goal_weight", 0.0, kNonNegative);
      out.push_back(std::make_unique<Boids>(p));
    } else if (type == "vortex") {
      o.only_keys({"type", "center", "omega", "core", "drag"});
      VortexParams p;
      p.center = o.vec2_or("center", Vec2::Zero());
      p.omega = o.number("omega");
      p.core = o.number("core", kPositive);
      p.drag = o.number("drag", kNonNegative);
      out.push_back(std::make_unique<Vortex>(p));
    } else if (type == "curl-noise") {
      o.only_keys({"type", "b", "amplitude", "scale", "seed", "wind", "obstacles", "ramp"});
      CurlNoiseParams p;
      p.b = o.number("b", kNonNegative);
      const double amplitude = o.number("amplitude", kNonNegative);
      const double scale = o.number("scale", kPositive);
      const auto seed = std::uint64_t(o.integer("seed", 0, std::int64_t(1) << 53));
      const Vec2 wind = o.vec2_or("wind", Vec2::Zero());
      p.psi = noise_potential(seed, amplitude, scale, wind);
      p.ramp = o.number_or("ramp", scale, kPositive);
      const json& discs = o.array_or_empty("obstacles");
      for (std::size_t k = 0; k < discs.size(); ++k) {
        JsonObject d = o.element("obstacles", k);
        d.only_keys({"center", "radius"});
        p.obstacles.push_back({d.vec2("center"), d.number("radius", kPositive)});
      }
      p.h = kCurlStepFraction * std::min(scale, p.ramp);
      check_curl_noise(o, scene, amplitude, scale, p);
      auto term = std::make_unique<CurlNoise>(std::move(p));
      term->k_ = amplitude * scale / kNoiseGradientRms;
      term->scale_ = scale;
      term->wind_ = wind.norm();
      out.push_back(std::move(term));
    } else {
      std::string known;
      for (const auto& t : force_types()) known += (known.empty() ? "" : ", ") + t;
      o.fail("type", &o.raw().at("type"), "one of: " + known);
    }
    if (out.size() > before) out.back()->key = o.path() + " (" + type + ")";
  }
  return out;
}

Springs& spring_term(ForceList& forces) {
  for (auto& f : forces) {
    if (auto* s = dynamic_cast<Springs*>(f.get())) return *s;
  }
  forces.push_back(std::make_unique<Springs>());
  return static_cast<Springs&>(*forces.back());
}

ParticleDynamics::ParticleDynamics(const ForceList& forces, const VecX& m)
    : forces_(forces),
      m_(m),
      inv_m2_(m.transpose().array().inverse().replicate<2, 1>()),
      f_(Mat2X::Zero(2, m.size())) {}

void ParticleDynamics::eval(const Mat2X& x, const Mat2X& v, Mat2X& a) const {
  const budget::PhaseScope phase(budget::kForces);
  sums_.ready = false;  // a step through the whole arrays: no sums of its state
  accumulate_forces(forces_, x, v, m_, f_);
  if (f_.cols() != x.cols()) {
    throw std::runtime_error("accumulate_forces left f with " + std::to_string(f_.cols()) +
                             " columns, expected one per particle (" + std::to_string(x.cols()) +
                             "): see TODO(F6)");
  }
  a.array() = f_.array() * inv_m2_;  // a_i = f_i / m_i
  if (!any_force_) any_force_ = !f_.isZero(0);
}

bool ParticleDynamics::per_particle() const {
  for (const auto& term : forces_)
    if (!term->per_particle()) return false;
  return true;
}

bool ParticleDynamics::reads_positions() const {
  for (const auto& term : forces_)
    if (term->reads_positions()) return true;
  return false;
}

void ParticleDynamics::eval_block(Eigen::Index first, const Mat2X& x, const Mat2X& v,
                                  Mat2X& a) const {
  const Eigen::Index nb = x.cols();
  if (first < 0 || first + nb > m_.size()) {
    throw std::logic_error("ParticleDynamics::eval_block: particles " + std::to_string(first) +
                           ".." + std::to_string(first + nb) + " of " +
                           std::to_string(m_.size()));
  }
  // The last block has arrays of its own (its size may differ), so that no
  // step after the first allocates. A block's masses are copied when it
  // starts: rk4 evaluates one block four times before the next.
  Block& b = block_[first + nb == m_.size() ? 1 : 0];
  if (b.first != first || b.m.size() != nb) {
    b.first = first;
    b.m = m_.segment(first, nb);
  }
  // An f of the block's size starts at zero (what the skeleton's F6, which does
  // nothing, then leaves); F6 zeroes it (TODO(F6)) and every term adds to it.
  if (b.f.cols() != nb) b.f.setZero(2, nb);
  const budget::PhaseScope phase(budget::kForces);
  accumulate_forces(forces_, x, v, b.m, b.f);
  if (b.f.cols() != nb) {
    throw std::runtime_error("accumulate_forces left f with " + std::to_string(b.f.cols()) +
                             " columns, expected one per particle (" + std::to_string(nb) +
                             "): see TODO(F6)");
  }
  a.array() = b.f.array() * inv_m2_.middleCols(first, nb).array();
  if (!any_force_) any_force_ = !b.f.isZero(0);
}

Energy energy(const ForceList& forces, const Mat2X& x, const Mat2X& v, const VecX& m) {
  Energy e;
  e.kinetic = 0.5 * v.colwise().squaredNorm().dot(m);
  for (const auto& term : forces) e.potential += term->potential(x, m);
  return e;
}

namespace {

// The sums' kernel over particles first .. end - 1 of the flat arrays x, v
// (2 per particle) and m: eight particles at a time, in four-lane vectors
// (x and y of two particles each) and eight independent vector sums, so that
// an addition waits only for the one before it in its own sum. In SSE2's
// two-lane instructions (the project's baseline) the sums took 0.54 ns a
// particle, 7 % of a blocked rk4 step (docs/benchmarks.md, "RK4 in blocks");
// the same lanes run in half as many AVX2 instructions where the processor has
// them (the "avx2" clone, chosen when the program loads). Both clones add the
// same products in the same order in every lane, with no fused multiply-add,
// so they give the same bits. (An AVX-512 clone was slower in the run, beside
// the step's SSE2 code; eight-lane vectors made GCC's AVX2 clone spill.)
typedef double Lanes __attribute__((vector_size(32)));

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && defined(__linux__)
#define WB_SUMS_CLONES \
  __attribute__((target_clones("avx2", "default"), optimize("fp-contract=off")))
#elif defined(__GNUC__) && !defined(__clang__)
#define WB_SUMS_CLONES __attribute__((optimize("fp-contract=off")))  // FMA-capable targets too
#else
#define WB_SUMS_CLONES
#endif

WB_SUMS_CLONES void sums_kernel(const double* x, const double* v, const double* m, long first,
                                long end, double* k, double* w) {
  Lanes k0 = {0, 0, 0, 0}, k1 = k0, k2 = k0, k3 = k0, w0 = k0, w1 = k0, w2 = k0, w3 = k0;
  long i = first;
  for (; i + 7 < end; i += 8) {
    const Lanes m0 = {m[i], m[i], m[i + 1], m[i + 1]};
    const Lanes m1 = {m[i + 2], m[i + 2], m[i + 3], m[i + 3]};
    const Lanes m2 = {m[i + 4], m[i + 4], m[i + 5], m[i + 5]};
    const Lanes m3 = {m[i + 6], m[i + 6], m[i + 7], m[i + 7]};
    Lanes v0, v1, v2, v3, x0, x1, x2, x3;  // 4 doubles each, aligned or not
    __builtin_memcpy(&v0, v + 2 * i, sizeof v0);
    __builtin_memcpy(&v1, v + 2 * i + 4, sizeof v1);
    __builtin_memcpy(&v2, v + 2 * i + 8, sizeof v2);
    __builtin_memcpy(&v3, v + 2 * i + 12, sizeof v3);
    __builtin_memcpy(&x0, x + 2 * i, sizeof x0);
    __builtin_memcpy(&x1, x + 2 * i + 4, sizeof x1);
    __builtin_memcpy(&x2, x + 2 * i + 8, sizeof x2);
    __builtin_memcpy(&x3, x + 2 * i + 12, sizeof x3);
    k0 += m0 * (v0 * v0);
    k1 += m1 * (v1 * v1);
    k2 += m2 * (v2 * v2);
    k3 += m3 * (v3 * v3);
    w0 += m0 * x0;
    w1 += m1 * x1;
    w2 += m2 * x2;
    w3 += m3 * x3;
  }
  const Lanes ks = (k0 + k1) + (k2 + k3), ws = (w0 + w1) + (w2 + w3);
  double kx = ks[0] + ks[2], ky = ks[1] + ks[3], wx = ws[0] + ws[2], wy = ws[1] + ws[3];
  for (; i < end; ++i) {
    kx += m[i] * (v[2 * i] * v[2 * i]);
    ky += m[i] * (v[2 * i + 1] * v[2 * i + 1]);
    wx += m[i] * x[2 * i];
    wy += m[i] * x[2 * i + 1];
  }
  k[0] += kx;
  k[1] += ky;
  w[0] += wx;
  w[1] += wy;
}

}  // namespace

void add_energy_sums(const Mat2X& x, const Mat2X& v, const VecX& m, Eigen::Index first,
                     Eigen::Index end, Eigen::Array2d& k, Eigen::Array2d& w) {
  if (first < 0 || end > m.size() || x.cols() < end || v.cols() < end) {
    throw std::logic_error("add_energy_sums: particles " + std::to_string(first) + ".." +
                           std::to_string(end) + " of " + std::to_string(m.size()));
  }
  sums_kernel(x.data(), v.data(), m.data(), long(first), long(end), k.data(), w.data());
}

void ParticleDynamics::block_stepped(Eigen::Index first, Eigen::Index count, const Mat2X& x,
                                     const Mat2X& v) const {
  if (first == 0) sums_ = StepSums{};
  if (first != sums_.done || first + count > m_.size() || x.cols() != m_.size() ||
      v.cols() != m_.size()) {
    sums_.done = -1;  // not the blocks of one step in order: no sums
    return;
  }
  add_energy_sums(x, v, m_, first, first + count, sums_.k, sums_.w);
  sums_.done = first + count;
}

void ParticleDynamics::blocks_stepped(const Mat2X& x, const Mat2X& v) const {
  sums_.ready = sums_.done == m_.size();
  sums_.x = x.data();
  sums_.v = v.data();
}

bool ParticleDynamics::take_step_sums(const Mat2X& x, const Mat2X& v, Eigen::Array2d& k,
                                      Eigen::Array2d& w) const {
  const bool ok = sums_.ready && sums_.x == x.data() && sums_.v == v.data() &&
                  x.cols() == m_.size() && v.cols() == m_.size();
  sums_.ready = false;
  if (ok) k = sums_.k, w = sums_.w;
  return ok;
}

EnergyTerms::EnergyTerms(const ForceList& forces) {
  for (const auto& term : forces) {
    if (const auto* u = dynamic_cast<const UniformGravity*>(term.get())) {
      g += u->g();
    } else {
      others.push_back(term.get());
    }
  }
}

double checked_energy(const ForceList& forces, const EnergyTerms& terms, const Mat2X& x,
                      const Mat2X& v, const VecX& m, bool& finite, const ParticleDynamics* dyn) {
  const Vec2& g = terms.g;  // every uniform gravity term's field, summed
  // k = sum m v.*v (twice the kinetic energy, per axis) and w = sum m x, from
  // which V_g = -g . w: summed by the step itself when it went by blocks (rk4
  // on per-particle forces, while each block was in cache), else in one pass
  // here. A coordinate that is not finite makes k or w not finite (m > 0; each
  // term of k is >= 0); the converse fails only when the finite sums overflow,
  // and then the exact questions below decide.
  const Eigen::Index n = x.cols() == m.size() && v.cols() == m.size() ? m.size() : 0;
  Eigen::Array2d k = Eigen::Array2d::Zero(), w = Eigen::Array2d::Zero();
  if (!(dyn && dyn->take_step_sums(x, v, k, w))) add_energy_sums(x, v, m, 0, n, k, w);
  if (n != m.size() || !k.allFinite() || !w.allFinite()) {  // rare: the run stops here
    finite = all_finite(x, v);
    return finite ? energy(forces, x, v, m).total() : NAN;
  }
  finite = true;
  double e = 0.5 * k.sum() - (g.array() * w).sum();
  for (const Force* term : terms.others) e += term->potential(x, m);
  return e;
}

ForceWorld::ForceWorld(const Scene& scene)
    : m_(scene.m), forces_(build_forces(scene)), dyn_(forces_, m_), terms_(forces_) {}

std::vector<const Force*> ForceWorld::terms() const {
  std::vector<const Force*> out;
  for (const auto& f : forces_) out.push_back(f.get());
  return out;
}

Energy ForceWorld::energy(const Mat2X& x, const Mat2X& v) const {
  return wb::energy(forces_, x, v, m_);
}

std::vector<std::string> ForceWorld::warnings(const Mat2X& /*x*/, const Mat2X& /*v*/) const {
  // No evaluation at all (--steps 0, or evaluations not counted since): nothing to say.
  if (forces_.empty() || dyn_.any_force() || dyn_.evals() == 0) return {};
  return {
      "every force evaluation gave zero force on every particle, although the scene "
      "declares " +
      std::to_string(forces_.size()) +
      " force(s): are the forces lab's functions (F1-F8, accumulate_forces) still stubs?"};
}

void forces_step_cost(const Scene& scene, const Integrator& it, StepCost& c,
                      double extra_springs) {
  const double n = double(scene.n()), pairs = n * (n - 1) / 2;
  const double evals = it.evals_per_step;
  const std::string n_text = std::to_string(scene.n()) + " particles";
  const std::string x_evals = " x " + std::to_string(it.evals_per_step) + " evaluations";
  // Every term once per evaluation; the divergence rule's potentials once per step
  // and per written step (--stats); the initial checks: a bound and a potential.
  auto term = [&](const std::string& what, const std::string& key, double units, double per_eval,
                  double per_potential) {
    c.step.add(what + x_evals, key, units * evals, per_eval);
    if (per_potential > 0) {
      c.step.add(what + ": its potential (divergence rule)", key, units, per_potential);
      c.record.add(what + ": its potential (stats)", key, units, per_potential);
    }
    c.once.add(what + ": initial checks", key, units, 2 * per_eval + per_potential);
  };
  c.step.add("accumulate_forces: " + n_text + x_evals, "", n * evals, kSecondsPerParticle);
  const json* list = scene.doc.contains("forces") ? &scene.doc.at("forces") : nullptr;
  double springs = extra_springs;
  std::string spring_key = extra_springs > 0 ? "rope, cloth" : "";
  for (std::size_t k = 0; list && list->is_array() && k < list->size(); ++k) {
    const json& f = (*list)[k];
    if (!f.is_object() || !f.contains("type") || !f.at("type").is_string()) continue;
    const std::string type = f.at("type").get<std::string>();
    const std::string key = "forces[" + std::to_string(k) + "]";
    const std::string what = key + " (" + type + "): ";
    if (type == "gravity") {
      term(what + n_text, key, n, kSecondsPerGravity, kSecondsPerGravity);
    } else if (type == "newton") {
      term(what + num(pairs) + " pairs of " + n_text, key, pairs, kSecondsPerNewtonPair,
           kSecondsPerNewtonPotentialPair);
    } else if (type == "attractor") {
      term(what + n_text, key, n, kSecondsPerAttractor, kSecondsPerAttractor);
    } else if (type == "damping") {
      term(what + n_text, key, n, kSecondsPerDamping, 0);
    } else if (type == "spring") {
      springs += 1;
      if (spring_key.empty()) spring_key = key;
    } else if (type == "boids") {
      term(what + num(pairs) + " pairs of " + n_text, key, pairs, kSecondsPerBoidsPair, 0);
    } else if (type == "vortex") {
      term(what + n_text, key, n, kSecondsPerVortex, 0);
    } else if (type == "curl-noise") {
      const json* obstacles = f.contains("obstacles") ? &f.at("obstacles") : nullptr;
      const double discs = obstacles && obstacles->is_array() ? double(obstacles->size()) : 0.0;
      // 4 potentials per particle (central differences), each the noise and every disc.
      term(what + n_text + " x 4 potentials x (the noise + " + num(discs) + " obstacles)",
           key + ".obstacles", 4 * n, kSecondsPerNoise + discs * kSecondsPerObstacle, 0);
    }
  }
  if (springs > 0) {
    term("springs: " + num(springs), spring_key, springs, kSecondsPerSpring,
         kSecondsPerSpringPotential);
    c.once.add("springs: " + num(springs) + " (their definitions)", spring_key, springs,
               kSecondsPerSpringBuilt, springs * kBytesPerSpring);
  }
}

void use_forces(LabInfo& info) {
  info.make_world = [](const Scene& scene) -> std::unique_ptr<World> {
    return std::make_unique<ForceWorld>(scene);
  };
  info.step_cost = [](const Scene& scene, const Integrator& it, StepCost& c) {
    forces_step_cost(scene, it, c);
  };
  std::string types;
  for (const auto& t : force_types()) types += (types.empty() ? "" : ", ") + t;
  info.help_sections.push_back("Force types (scene \"forces\"):\n  " + types + "\n");
}

}  // namespace wb
