// The implicit lab's glue: scene generators, the spring network, and the
// adapters that call the student's implicit steps (labs/implicit/).
#include "implicit_world.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "backward_euler_spring.h"
#include "implicit_trapezoid.h"
#include "wb/budget.h"

namespace wb {

namespace {

const Range kPositive{0.0, std::numeric_limits<double>::infinity(), true};
const Range kNonNegative{0.0};
// A relative tolerance a residual of doubles can meet (kMinTolerance), at most 1.
const Range kTolerance{kMinTolerance, 1.0};

std::string count_text(std::int64_t n) { return std::to_string(n); }

RopeDef read_rope(const JsonObject& top) {
  JsonObject r = top.object("rope");
  r.only_keys({"start", "end", "beads", "m", "k", "damping", "pin"});
  RopeDef d;
  d.a = r.vec2("start");
  d.b = r.vec2("end");
  d.N = r.integer("beads", 2, kMaxGenerated);
  d.m = r.number("m", kPositive);
  if (!std::isfinite(1.0 / d.m)) {
    r.fail("m", &r.raw().at("m"), "a mass whose inverse 1/m is finite (m >= 5.6e-309)");
  }
  d.k = r.number("k", kNonNegative);
  d.kd = r.number_or("damping", 0.0, kNonNegative);
  d.pin = r.string_or("pin", "start");
  if (d.pin != "start" && d.pin != "ends" && d.pin != "none")
    r.fail("pin", &r.raw().at("pin"), "one of: start, ends, none");
  if (d.a == d.b) r.fail("end", &r.raw().at("end"), "a point other than \"start\"");
  // Every bead lies on the segment and every spring is shorter than it: a
  // finite segment length keeps positions and rest lengths finite.
  const Vec2 ab = d.b - d.a;
  if (!ab.allFinite() || !std::isfinite(ab.norm())) {
    r.fail("end", &r.raw().at("end"),
           "a point whose distance from \"start\" is finite (|end - start| overflows)");
  }
  return d;
}

ClothDef read_cloth(const JsonObject& top) {
  JsonObject c = top.object("cloth");
  c.only_keys(
      {"origin", "rows", "cols", "spacing", "m", "k", "k_shear", "k_bend", "damping", "pin"});
  ClothDef d;
  d.o = c.vec2("origin");
  d.R = c.integer("rows", 2, kMaxGenerated);
  d.C = c.integer("cols", 2, kMaxGenerated);
  if (d.R * d.C > kMaxGenerated) {
    c.fail("cols", &c.raw().at("cols"),
           "rows x cols at most " + std::to_string(kMaxGenerated) + " particles (rows " +
               count_text(d.R) + " x cols " + count_text(d.C) + " = " + count_text(d.R * d.C) +
               ")");
  }
  d.dx = c.number("spacing", kPositive);
  d.m = c.number("m", kPositive);
  if (!std::isfinite(1.0 / d.m)) {
    c.fail("m", &c.raw().at("m"), "a mass whose inverse 1/m is finite (m >= 5.6e-309)");
  }
  d.k = c.number("k", kNonNegative);
  d.ks = c.number_or("k_shear", d.k, kNonNegative);
  d.kb = c.number_or("k_bend", 0.0, kNonNegative);
  d.kd = c.number_or("damping", 0.0, kNonNegative);
  d.pin = c.string_or("pin", "corners");
  if (d.pin != "corners" && d.pin != "top" && d.pin != "none")
    c.fail("pin", &c.raw().at("pin"), "one of: corners, top, none");
  // The far corner and the longest spring (a bend spring spans 2 spacings, a
  // shear spring sqrt(2)) finite: then every position and rest length is.
  const Vec2 corner = d.o + Vec2(double(d.C - 1) * d.dx, -double(d.R - 1) * d.dx);
  if (!corner.allFinite() || !std::isfinite(2.0 * d.dx) ||
      !std::isfinite(Vec2(d.dx, d.dx).norm())) {
    c.fail("spacing", &c.raw().at("spacing"),
           "a spacing whose grid is finite (origin + (cols - 1) x spacing and (rows - 1) x "
           "spacing overflow)");
  }
  return d;
}

// Makes room for `more` particles at the end of the scene's arrays (at rest,
// radius 0) and returns the index of the first.
Eigen::Index append_particles(Scene& s, std::int64_t more) {
  const Eigen::Index n = s.x.cols(), total = n + Eigen::Index(more);
  s.x.conservativeResize(2, total);
  s.v.conservativeResize(2, total);
  s.m.conservativeResize(total);
  s.radius.conservativeResize(total);
  s.v.rightCols(Eigen::Index(more)).setZero();
  s.radius.tail(Eigen::Index(more)).setZero();
  return n;
}

// One generated spring between particles i and j, at their initial distance.
void add_spring(const Scene& s, std::vector<SpringDef>& out, Eigen::Index i, Eigen::Index j,
                double k, double kd) {
  SpringDef d;
  d.i = i;
  d.j = j;
  d.anchor = Vec2::Zero();
  d.k = k;
  d.rest = (s.x.col(i) - s.x.col(j)).norm();
  d.kd = kd;
  out.push_back(d);
}

// "rope": N beads on the segment start -> end, joined in a chain.
void build_rope(const RopeDef& d, Scene& s, GeneratedNetwork& g) {
  const Eigen::Index first = g.rope_first = append_particles(s, d.N);
  for (std::int64_t q = 0; q < d.N; ++q) {
    s.x.col(first + q) = d.a + (d.b - d.a) * (double(q) / double(d.N - 1));
    s.m[first + q] = d.m;
  }
  if (d.pin != "none") g.pinned.push_back(first);
  if (d.pin == "ends") g.pinned.push_back(first + d.N - 1);
}

void rope_springs(const RopeDef& d, Eigen::Index first, const Scene& s,
                  std::vector<SpringDef>& out) {
  for (std::int64_t q = 1; q < d.N; ++q) add_spring(s, out, first + q - 1, first + q, d.k, d.kd);
}

// "cloth": a rows x cols grid hanging from its top row's corners.
void build_cloth(const ClothDef& d, Scene& s, GeneratedNetwork& g) {
  const Eigen::Index first = g.cloth_first = append_particles(s, d.R * d.C);
  const std::int64_t C = d.C;
  auto id = [&](std::int64_t r, std::int64_t q) { return first + r * C + q; };
  for (std::int64_t r = 0; r < d.R; ++r) {
    for (std::int64_t q = 0; q < C; ++q) {
      s.x.col(id(r, q)) = d.o + Vec2(double(q) * d.dx, -double(r) * d.dx);
      s.m[id(r, q)] = d.m;
    }
  }
  if (d.pin == "corners") {
    g.pinned.push_back(id(0, 0));
    g.pinned.push_back(id(0, C - 1));
  } else if (d.pin == "top") {
    for (std::int64_t q = 0; q < C; ++q) g.pinned.push_back(id(0, q));
  }
}

void cloth_springs(const ClothDef& d, Eigen::Index first, const Scene& s,
                   std::vector<SpringDef>& out) {
  const std::int64_t R = d.R, C = d.C;
  auto id = [&](std::int64_t r, std::int64_t q) { return first + r * C + q; };
  auto spring = [&](std::int64_t i, std::int64_t j, double k) {
    if (k > 0) add_spring(s, out, i, j, k, d.kd);
  };
  for (std::int64_t r = 0; r < R; ++r) {
    for (std::int64_t q = 0; q < C; ++q) {
      if (q + 1 < C) spring(id(r, q), id(r, q + 1), d.k);  // structural
      if (r + 1 < R) spring(id(r, q), id(r + 1, q), d.k);
      if (r + 1 < R && q + 1 < C) {  // shear
        spring(id(r, q), id(r + 1, q + 1), d.ks);
        spring(id(r, q + 1), id(r + 1, q), d.ks);
      }
      if (q + 2 < C) spring(id(r, q), id(r, q + 2), d.kb);  // bend
      if (r + 2 < R) spring(id(r, q), id(r + 2, q), d.kb);
    }
  }
}

// The scene's pinned particles (its "pinned" key and the generators' pins)
// as one flag per particle (empty: none), indices checked against the count.
std::vector<char> read_pinned(const Scene& s) {
  JsonObject top(s.file, s.doc, "");
  const json& list = top.array_or_empty("pinned");
  const auto* gen = std::any_cast<GeneratedNetwork>(&s.generated);
  std::vector<char> flags;
  if (list.empty() && (!gen || gen->pinned.empty())) return flags;
  flags.assign(std::size_t(s.n()), 0);
  const std::string note = s.n() == 0 ? " (the scene has no particles)" : " (a particle index)";
  for (std::size_t k = 0; k < list.size(); ++k) {
    flags[std::size_t(top.integer_in("pinned", k, 0, s.n() - 1, note))] = 1;
  }
  if (gen)
    for (Eigen::Index i : gen->pinned) flags[std::size_t(i)] = 1;
  return flags;
}

// The scene's newton options; `automatic` says whether newton.solver is "auto" (its
// default): the glue then picks LDLT or CG from the network's pattern (lab_solver).
NewtonOptions read_newton(const Scene& s, bool* automatic = nullptr) {
  NewtonOptions opt;
  if (automatic) *automatic = true;
  JsonObject top(s.file, s.doc, "");
  if (!top.has("newton")) return opt;
  JsonObject o = top.object("newton");
  o.only_keys(
      {"solver", "tol", "max_iterations", "definite", "cg_tol", "fast_solver", "fast_cg_tol"});
  const std::string solver = o.string_or("solver", "auto");
  if (solver == "cg") {
    opt.solver = NewtonOptions::kCG;
  } else if (solver != "ldlt" && solver != "auto") {
    o.fail("solver", &o.raw().at("solver"), "one of: auto, ldlt, cg");
  }
  if (automatic) *automatic = solver == "auto";
  opt.tol = o.number_or("tol", opt.tol, kTolerance);
  opt.max_iterations = int(o.integer_or("max_iterations", opt.max_iterations, 1, 1000));
  opt.definite = o.boolean_or("definite", opt.definite);
  opt.cg_tol = o.number_or("cg_tol", opt.cg_tol, kTolerance);
  return opt;
}

// The provided fast path's keys (newton.fast_solver, newton.fast_cg_tol).
FastSolverOptions read_fast(const Scene& s) {
  FastSolverOptions fo;
  JsonObject top(s.file, s.doc, "");
  if (!top.has("newton")) return fo;
  JsonObject o = top.object("newton");
  const std::string solver = o.string_or("fast_solver", "auto");
  if (solver == "ldlt") {
    fo.solver = FastSolverOptions::kLDLT;
  } else if (solver == "cholmod") {
    fo.solver = FastSolverOptions::kCholmod;
  } else if (solver == "cg") {
    fo.solver = FastSolverOptions::kCG;
  } else if (solver != "auto") {
    o.fail("fast_solver", &o.raw().at("fast_solver"), "one of: auto, ldlt, cholmod, cg");
  }
  fo.cg_tol = o.number_or("fast_cg_tol", fo.cg_tol, kTolerance);
  return fo;
}

// The cost model's rates of the implicit integrators (docs/scenes.md, "Cost"),
// measured with the solution (docs/benchmarks.md has more). One linear solve of
// the lab's Newton step as the handout asks since issue 34 (backward_euler.h:
// the pattern assembled in place, Eigen's SimplicialLDLT in the particles' own
// order, analysed once, refactorised in place) takes about 0.1 us per particle of
// a chain (a rope: 0.06 us at 10^4 beads; 0.3 us at 10^5, where the solves meet
// subnormal numbers); on a 2D grid, whose factor fills the band the particles'
// order leaves (a spring joins particles up to `band` apart), 2 n (2 band)^2
// flops at kSecondsPerBandFlop (a 100 x 100 cloth with bend springs: 0.93 s);
// by CG (newton.solver "cg") about kTypicalCgIterations products with the upper
// triangle, kSecondsPerLabCgParticle each (a 100 x 100 cloth at cg_tol 1e-2: 48
// iterations of 0.28 ms). The provided fast path's factorisation takes
// kSecondsPerSolveGrid n^1.5 sqrt(1 + n / kGridCacheParticles) on a 2D grid
// (0.33 s at 100 x 100, 33 s at 316 x 316: past 10^4 particles the factor
// leaves the cache and the work grows as n^2). The
// fast path's factorisation of a chain, its CG iteration per particle (19 to 24
// ns), its assembly per spring, its analysis per particle. The factor's entries
// (16 bytes each) per particle of a chain, per particle log2(particles) of a grid
// (20 at 100 x 100, 24 at 316 x 316); the network's and the fast path's copies of a
// spring.
constexpr double kSecondsPerSolveChain = 0.1e-6;
constexpr double kSecondsPerBandFlop = 0.3e-9;
constexpr double kSecondsPerLabCgParticle = 28e-9;
constexpr double kSecondsPerSolveGrid = 3.3e-7;
constexpr double kGridCacheParticles = 1e4;
constexpr double kSecondsPerSolveSpring = 20e-9;
constexpr double kSecondsPerFastFactorChain = 0.2e-6;
constexpr double kSecondsPerCgParticle = 22e-9;
constexpr double kSecondsPerFastAssembly = 40e-9;
constexpr double kSecondsPerFastAnalysis = 1.0e-6;
constexpr double kFactorEntriesChain = 12;
constexpr double kFactorEntriesGrid = 24;
constexpr double kBytesPerFactorEntry = 16;
constexpr double kBytesPerSystemSpring = 16 * 16;  // a spring's 4 blocks as triplets, and A
// NetworkSpring, and the fast path's copy (blocks, positions in A, the pattern's
// graph): a 1000 x 1000 cloth's 6 * 10^6 springs and 10^6 particles hold 0.9 GB in
// an explicit step, 1.7 GB in a step of the fast path.
constexpr double kBytesPerNetworkSpring = 64;
constexpr double kBytesPerFastSpring = 120;
constexpr double kSecondsPerSpringCopy = 40e-9;

// A factorisation's time on a 2D grid of n particles (above).
double grid_solve_seconds(double n) {
  return kSecondsPerSolveGrid * std::pow(n, 1.5) * std::sqrt(1.0 + n / kGridCacheParticles);
}

// Which solve an implicit-lab integrator does each step (by its step function).
enum class SolveKind { kNone, kNewton, kOneSolve, kFastNewton, kFastOneSolve };

SolveKind solve_kind(const Integrator& it) {
  if (it.step == backward_euler_adapter || it.step == implicit_trapezoid_adapter) {
    return SolveKind::kNewton;
  }
  if (it.step == baraff_witkin_adapter) return SolveKind::kOneSolve;
  if (it.step == backward_euler_fast_adapter) return SolveKind::kFastNewton;
  if (it.step == baraff_witkin_fast_adapter) return SolveKind::kFastOneSolve;
  return SolveKind::kNone;  // explicit, or backward-euler-1 (one 2 x 2 solve)
}

const ImplicitDynamics& implicit_dynamics(const Dynamics& dyn) {
  const auto* d = dynamic_cast<const ImplicitDynamics*>(&dyn);
  if (!d) throw std::logic_error("an implicit integrator needs the implicit lab's World");
  return *d;
}

}  // namespace

const std::vector<std::string>& implicit_scene_keys() {
  static const std::vector<std::string> keys = {"pinned", "rope", "cloth", "newton"};
  return keys;
}

void expand_implicit_scene(Scene& scene) {
  JsonObject top(scene.file, scene.doc, "");
  top.array_or_empty("pinned");  // type checks before anything is added
  // Every key read and every total checked before anything is built.
  std::optional<RopeDef> rope;
  std::optional<ClothDef> cloth;
  if (top.has("rope")) rope = read_rope(top);
  if (top.has("cloth")) cloth = read_cloth(top);
  const std::int64_t generated = (rope ? rope->N : 0) + (cloth ? cloth->R * cloth->C : 0);
  if (generated > kMaxGenerated) {
    top.fail("cloth", &scene.doc.at("cloth"),
             "a rope and a cloth of at most " + std::to_string(kMaxGenerated) +
                 " particles together (rope.beads " + std::to_string(rope->N) +
                 " + cloth.rows x cloth.cols " + std::to_string(cloth->R * cloth->C) + " = " +
                 std::to_string(generated) + ")");
  }
  if (scene.n() + generated > kMaxParticles) {
    top.fail(cloth ? "cloth" : "rope", &scene.doc.at(cloth ? "cloth" : "rope"),
             "at most " + std::to_string(kMaxParticles) + " particles in a scene (" +
                 std::to_string(scene.n()) + " declared + " + std::to_string(generated) +
                 " generated)");
  }
  GeneratedNetwork g;
  g.rope = rope;
  g.cloth = cloth;
  if (rope) build_rope(*rope, scene, g);
  if (cloth) build_cloth(*cloth, scene, g);
  scene.generated = std::move(g);
  // Pinned particles start (and stay) at rest.
  const std::vector<char> flags = read_pinned(scene);
  for (std::size_t i = 0; i < flags.size(); ++i)
    if (flags[i]) scene.v.col(Eigen::Index(i)).setZero();
}

ForceList implicit_forces(const Scene& scene) {
  ForceList forces = build_forces(scene);
  const auto* gen = std::any_cast<GeneratedNetwork>(&scene.generated);
  if (!gen || (!gen->rope && !gen->cloth)) return forces;
  // Made in place, in the spring term the integrators read.
  Springs& term = spring_term(forces);
  if (term.key.empty()) term.key = gen->rope ? "rope" : "cloth";
  std::vector<SpringDef>& springs = term.springs;
  springs.reserve(springs.size() + std::size_t((gen->rope ? gen->rope->springs() : 0) +
                                               (gen->cloth ? gen->cloth->springs() : 0)));
  if (gen->rope) {
    term.origins.push_back({springs.size(), "rope"});
    rope_springs(*gen->rope, gen->rope_first, scene, springs);
  }
  if (gen->cloth) {
    term.origins.push_back({springs.size(), "cloth"});
    cloth_springs(*gen->cloth, gen->cloth_first, scene, springs);
  }
  return forces;
}

ImplicitDynamics::ImplicitDynamics(const ForceList& forces, const Scene& scene)
    : forces_(forces),
      opt_(read_newton(scene, &auto_solver_)),
      fast_opt_(read_fast(scene)),
      file_(scene.file),
      inv_m_(scene.m.transpose().array().inverse()),
      newton_(scene.file, "Newton linear solves", kTypicalNewtonIterations,
              "newton.tol may be below what this scene's solve reaches, or the step too "
              "large for Newton; newton.max_iterations caps the solves of a step"),
      cg_(scene.file, "CG iterations (the fast path)",
          kTypicalCgIterations * kTypicalNewtonIterations,
          "newton.fast_cg_tol may be too small for this scene, or its springs too stiff for "
          "CG (newton.fast_solver \"ldlt\" factorises instead)") {
  fast_opt_.cg_meter = &cg_;
  fast_opt_.newton_meter = &newton_;
  net_.m = scene.m;
  net_.pinned = read_pinned(scene);
  for (const auto& term : forces_) {
    if (const auto* springs = dynamic_cast<const Springs*>(term.get())) {
      net_.springs.reserve(net_.springs.size() + springs->springs.size());
      for (const SpringDef& d : springs->springs) {
        NetworkSpring s;
        s.i = d.i;
        s.j = d.j;
        s.anchor = d.anchor;
        s.k = d.k;
        s.rest = d.rest;
        s.kd = d.kd;
        net_.springs.push_back(s);
      }
    }
  }
  // The drag of "damping" entries joins the network (taken implicitly).
  JsonObject top(scene.file, scene.doc, "");
  const json& list = top.array_or_empty("forces");
  for (std::size_t k = 0; k < list.size(); ++k) {
    JsonObject o = top.element("forces", k);
    if (o.string("type") == "damping") net_.drag += o.number("b", kNonNegative);
  }
  // newton.solver "auto" (the default): the solver the pattern needs, as the provided
  // path's auto chooses it (fast_backward_euler.h): LDLT in the unknowns' own order (the
  // lab's) when one factorisation costs at most kDirectBudget CG iterations (a rope, a
  // small cloth), else CG (a large cloth, whose factor fills its band), which needs the
  // clamped, definite blocks (newton.definite, true by default).
  // A scene that sets no cg_tol: a one-solve step (baraff-witkin) needs no more than 1e-2
  // of the momenta at stake (its own linearisation error is larger), Newton keeps the
  // default, below its tol (newton_adapter).
  one_solve_cg_tol_ = !(scene.doc.contains("newton") && scene.doc.at("newton").is_object() &&
                        scene.doc.at("newton").contains("cg_tol"));
  if (auto_solver_) {
    const budget::PhaseScope phase(budget::kPrepare);
    const double budget = direct_budget_iterations();
    const double ratio = natural_order_factor_ratio(net_, budget);
    opt_.solver = ratio > budget && opt_.definite ? NewtonOptions::kCG : NewtonOptions::kLDLT;
  }
}

FastBackwardEuler& ImplicitDynamics::fast() const {
  if (!fast_) fast_ = std::make_unique<FastBackwardEuler>(net_, fast_opt_);
  return *fast_;
}

void ImplicitDynamics::eval(const Mat2X& x, const Mat2X& v, Mat2X& a) const {
  const budget::PhaseScope phase(budget::kForces);
  a.setZero();
  for (const auto& term : forces_) {
    if (external_only_ && (term->type() == "spring" || term->type() == "damping")) continue;
    term->add(x, v, net_.m, a);
  }
  if (!external_only_) a.array().rowwise() *= inv_m_;
  for (std::size_t i = 0; i < net_.pinned.size(); ++i)
    if (net_.pinned[i]) a.col(Eigen::Index(i)).setZero();
}

void ImplicitDynamics::external_forces(const Mat2X& x, const Mat2X& v, Mat2X& f) const {
  external_only_ = true;
  try {
    acceleration(x, v, f);
  } catch (...) {
    external_only_ = false;
    throw;
  }
  external_only_ = false;
}

void ImplicitDynamics::record(const char* integrator, const NewtonReport& r) const {
  ++steps_;
  iterations_ += r.iterations;
  max_iterations_ = std::max(max_iterations_, r.iterations);
  if (std::string(integrator).find("-fast") ==
      std::string::npos) {  // the fast path counts its own
    newton_.next_step();
    newton_.count(r.iterations);
  }
  if (r.converged && !r.solver_failed) return;
  count_unconverged();  // the run contract's share rule (docs/run-contract.md)
  if (++failed_ > 1) return;
  first_failure_ = std::string(integrator) + " step " + std::to_string(steps_) + ": ";
  if (r.iterations == 0 && !r.solver_failed) {
    stub_failure_ = true;
    first_failure_ +=
        "the step did no linear solve: are backward_euler_step (TODO(I4)) and "
        "implicit_trapezoid_step (TODO(I5)) still stubs?";
  } else if (r.solver_failed) {
    // r.iterations counts the solves that succeeded before the failed one.
    first_failure_ += "the linear solver failed on solve " + std::to_string(r.iterations + 1) +
                      (r.iterations == 0 ? " (the step's first)" : "") +
                      "; the step keeps the last good iterate";
  } else {
    first_failure_ += "Newton did not converge in " + std::to_string(r.iterations) +
                      " solves (residual " + num(r.residual) +
                      " > tol * scale = " + num(opt_.tol * r.scale) + ")";
  }
}

std::string ImplicitDynamics::unconverged_warning() const {
  if (failed_ == 0) return "";
  return std::to_string(failed_) + " of " + std::to_string(steps_) +
         " implicit steps did not converge (most Newton solves in one step: " +
         std::to_string(max_iterations_) + "); the first, " + first_failure_;
}

ImplicitWorld::ImplicitWorld(const Scene& scene)
    : m_(scene.m), forces_(implicit_forces(scene)), dyn_(forces_, scene), terms_(forces_) {}

std::vector<const Force*> ImplicitWorld::terms() const {
  std::vector<const Force*> out;
  for (const auto& f : forces_) out.push_back(f.get());
  return out;
}

std::vector<std::string> ImplicitWorld::warnings(const Mat2X& /*x*/, const Mat2X& /*v*/) const {
  const std::string w = dyn_.unconverged_warning();
  if (w.empty() || !dyn_.unconverged_by_stub()) return {};
  return {w};
}

std::vector<std::string> ImplicitWorld::notes() const {
  const std::string w = dyn_.unconverged_warning();
  if (w.empty() || dyn_.unconverged_by_stub()) return {};
  return {w};
}

Energy ImplicitWorld::energy(const Mat2X& x, const Mat2X& v) const {
  return wb::energy(forces_, x, v, m_);
}

std::string backward_euler_1_check(const Integrator& self, const Dynamics& dyn) {
  const ImplicitDynamics& d = implicit_dynamics(dyn);
  const SpringNetwork& net = d.network();
  const bool ok = net.n() == 1 && net.springs.size() == 1 && net.springs[0].j < 0 &&
                  net.springs[0].rest == 0.0 && net.springs[0].kd == 0.0 && !net.is_pinned(0);
  if (!ok) {
    throw InputError(d.file() + ": " + self.name +
                     " solves one free particle on one spring to an anchor with rest 0 and "
                     "damping 0 (drag and other forces are fine); this scene has " +
                     std::to_string(net.n()) + " particles and " +
                     std::to_string(net.springs.size()) + " springs: use backward-euler");
  }
  return "";
}

void implicit_step_cost(const Scene& scene, const Integrator& it, StepCost& c) {
  const auto* gen = std::any_cast<GeneratedNetwork>(&scene.generated);
  const double generated = gen ? double((gen->rope ? gen->rope->springs() : 0) +
                                        (gen->cloth ? gen->cloth->springs() : 0))
                               : 0.0;
  forces_step_cost(scene, it, c, generated);
  // The implicit executable links the sparse solvers (CHOLMOD, BLAS): its start
  // takes about twice a particle lab's.
  c.once.add("start: the sparse solvers' libraries", "", 1, kStartSeconds);
  // Springs written in "forces". The cost is estimated before the forces are
  // read (and refused if malformed), so every entry's shape is checked here.
  double written = 0;
  const json* list = scene.doc.contains("forces") ? &scene.doc.at("forces") : nullptr;
  for (std::size_t k = 0; list && list->is_array() && k < list->size(); ++k) {
    const json& f = (*list)[k];
    written += f.is_object() && f.contains("type") && f.at("type").is_string() &&
               f.at("type").get<std::string>() == "spring";
  }
  const double springs = generated + written;
  c.once.add("the spring network: " + num(springs) + " springs", "forces", springs,
             kSecondsPerSpringCopy, springs * kBytesPerNetworkSpring);
  const SolveKind kind = solve_kind(it);
  if (kind == SolveKind::kNone) return;
  bool automatic = false;
  const NewtonOptions opt = read_newton(scene, &automatic);
  const FastSolverOptions fo = read_fast(scene);
  const double n = double(scene.n());
  // A cloth, or many hand-written springs, is a 2D network (its factor fills in).
  const bool grid = (gen && gen->cloth) || written > 1000;
  const std::string shape = grid ? "a 2D network" : "a chain";
  const std::string size =
      std::to_string(scene.n()) + " particles, " + num(springs) + " springs (" + shape + ")";
  const double entries =
      grid ? kFactorEntriesGrid * n * std::log2(std::max(n, 2.0)) : kFactorEntriesChain * n;
  const bool one = kind == SolveKind::kOneSolve || kind == SolveKind::kFastOneSolve;
  const double solves = one ? 1 : std::min(double(opt.max_iterations), kTypicalNewtonIterations);
  const double cap =
      one ? 1 : std::min(double(opt.max_iterations), kOverrunFactor * kTypicalNewtonIterations);
  const std::string key = one ? "--integrator" : "newton.max_iterations";
  const std::string per =
      one ? " x 1 solve" : " x " + num(solves) + " to " + num(cap) + " solves";
  if (kind == SolveKind::kNewton || kind == SolveKind::kOneSolve) {
    // The lab's step (backward_euler.h): CG, or LDLT in the particles' order, whose
    // factor on a 2D network fills the band (a cloth's: its row, twice with bend springs;
    // hand-written springs: about sqrt(n)).
    const double band = gen && gen->cloth
                            ? double(gen->cloth->C) * (gen->cloth->kb > 0 ? 2.0 : 1.0)
                            : std::sqrt(n);
    double t = kSecondsPerSolveChain * n, held = kFactorEntriesChain * n;
    std::string how = "LDLT", solver_key = key;
    const double cg_t = kTypicalCgIterations * kSecondsPerLabCgParticle * n;
    const double band_t = kSecondsPerBandFlop * 2.0 * n * std::pow(2.0 * band, 2.0);
    // "auto" takes the cheaper: CG where LDLT's band would cost more (and CG may run).
    const bool cg =
        opt.solver == NewtonOptions::kCG || (automatic && grid && opt.definite && cg_t < band_t);
    if (cg) {
      t = cg_t;
      held = 0;
      how = "CG, about " + num(kTypicalCgIterations) + " iterations";
    } else if (grid) {
      t = band_t;
      held = 2.0 * n * 2.0 * band;
      how = "LDLT in the particles' order, a band of " + num(band) +
            " (newton.solver \"cg\" is made for 2D networks)";
      // The key to change: the solver, unless the scene raised the cap on the solves
      // (then the worst case, every step at its cap, is what that key bought).
      if (opt.max_iterations <= NewtonOptions{}.max_iterations) solver_key = "newton.solver";
    }
    c.step.add(it.name + ": linear solves (I3 assembly, " + how + "): " + size + per, solver_key,
               solves, t + kSecondsPerSolveSpring * springs,
               held * kBytesPerFactorEntry + springs * kBytesPerSystemSpring,
               one ? 1 : double(opt.max_iterations));
    return;
  }
  // The provided fast path: its analysis once, then per solve a numeric
  // factorisation or CG (auto: CG for a 2D network, a factorisation for a chain).
  const bool direct =
      fo.solver == FastSolverOptions::kAuto ? !grid : fo.solver != FastSolverOptions::kCG;
  c.once.add(it.name + ": the pattern's analysis: " + size, "newton.fast_solver", n,
             kSecondsPerFastAnalysis,
             springs * kBytesPerFastSpring + (direct ? entries * kBytesPerFactorEntry : 0.0));
  const double assembly = kSecondsPerFastAssembly * springs;
  if (direct) {
    const double t = (grid ? grid_solve_seconds(n) : kSecondsPerFastFactorChain * n) + assembly;
    c.step.add(it.name + ": factorisations: " + size + per, key, solves, t, 0.0, cap);
  } else {
    const double iteration = kSecondsPerCgParticle * n;
    c.step.add(
        it.name + ": CG: " + size + per + " x about " + num(kTypicalCgIterations) + " iterations",
        "newton.fast_cg_tol", solves * kTypicalCgIterations, iteration, 0.0,
        kOverrunFactor * kTypicalCgIterations * kTypicalNewtonIterations);
    c.step.add(it.name + ": assembly: " + num(springs) + " springs" + per, key, solves, assembly,
               0.0, cap);
  }
}

void backward_euler_1_adapter(const Dynamics& dyn, double h, Mat2X& x, Mat2X& v, Scratch& s) {
  const ImplicitDynamics& d = implicit_dynamics(dyn);
  const SpringNetwork& net = d.network();
  static const Integrator self{"backward-euler-1", backward_euler_1_adapter, 1, 1, ""};
  backward_euler_1_check(self, dyn);  // also when called without the run's check
  d.external_forces(x, v, s.a0);
  const NetworkSpring& sp = net.springs[0];
  Vec2 xi = x.col(0), vi = v.col(0);
  backward_euler_spring_step(net.m[0], sp.k, net.drag, sp.anchor, Vec2(s.a0.col(0)), h, xi, vi);
  x.col(0) = xi;
  v.col(0) = vi;
}

namespace {
void newton_adapter(const char* name, bool trapezoid, bool one_iteration, const Dynamics& dyn,
                    double h, Mat2X& x, Mat2X& v, Scratch& s) {
  const ImplicitDynamics& d = implicit_dynamics(dyn);
  NewtonWorkspace& ws = d.workspace();
  // A run's first step (no evaluation counted yet: every run resets the count)
  // starts CG from 0, not from another run's last step: the same run, alone or
  // in a sweep, takes the same steps.
  if (d.evals() == 0) ws.dv.resize(0);
  d.external_forces(x, v, s.a0);
  NewtonOptions opt = d.options();
  opt.one_iteration = one_iteration;
  if (one_iteration && d.one_solve_cg_tol()) opt.cg_tol = kOneSolveCgTol;
  // The lab's step (the student's I3-I5): its solves are CG's iterations or LDLT's.
  const budget::PhaseScope phase(opt.solver == NewtonOptions::kCG ? budget::kCg
                                                                  : budget::kNewton);
  const NewtonReport r = trapezoid ? implicit_trapezoid_step(d.network(), s.a0, h, opt, x, v, ws)
                                   : backward_euler_step(d.network(), s.a0, h, opt, x, v, ws);
  d.record(name, r);
}
void fast_adapter(const char* name, bool one_iteration, const Dynamics& dyn, double h, Mat2X& x,
                  Mat2X& v, Scratch& s) {
  const ImplicitDynamics& d = implicit_dynamics(dyn);
  d.external_forces(x, v, s.a0);
  NewtonOptions opt = d.options();
  opt.one_iteration = one_iteration;
  const budget::PhaseScope phase(budget::kNewton);  // its CG iterations say so themselves
  d.record(name, d.fast().step(s.a0, h, opt, x, v));
}
}  // namespace

void backward_euler_adapter(const Dynamics& dyn, double h, Mat2X& x, Mat2X& v, Scratch& s) {
  newton_adapter("backward-euler", false, false, dyn, h, x, v, s);
}
void baraff_witkin_adapter(const Dynamics& dyn, double h, Mat2X& x, Mat2X& v, Scratch& s) {
  newton_adapter("baraff-witkin", false, true, dyn, h, x, v, s);
}
void implicit_trapezoid_adapter(const Dynamics& dyn, double h, Mat2X& x, Mat2X& v, Scratch& s) {
  newton_adapter("implicit-trapezoid", true, false, dyn, h, x, v, s);
}
void backward_euler_fast_adapter(const Dynamics& dyn, double h, Mat2X& x, Mat2X& v, Scratch& s) {
  fast_adapter("backward-euler-fast", false, dyn, h, x, v, s);
}
void baraff_witkin_fast_adapter(const Dynamics& dyn, double h, Mat2X& x, Mat2X& v, Scratch& s) {
  fast_adapter("baraff-witkin-fast", true, dyn, h, x, v, s);
}

void use_implicit(LabInfo& info) {
  info.make_world = [](const Scene& scene) -> std::unique_ptr<World> {
    return std::make_unique<ImplicitWorld>(scene);
  };
  info.expand_scene = expand_implicit_scene;
  info.step_cost = implicit_step_cost;
  info.scene_keys = implicit_scene_keys();
  std::string types;
  for (const auto& t : force_types()) types += (types.empty() ? "" : ", ") + t;
  info.help_sections.push_back(
      "Force types (scene \"forces\"):\n  " + types +
      "\n  Springs and \"damping\" are taken implicitly by the implicit integrators; the\n"
      "  other forces explicitly, at the start of each step.\n");
  info.help_sections.push_back(
      "Scene keys of this lab (docs/scenes.md, ## implicit):\n"
      "  pinned  [i, ...]  particles that never move\n"
      "  rope    {start, end, beads, m, k, damping, pin: start|ends|none}\n"
      "  cloth   {origin, rows, cols, spacing, m, k, k_shear, k_bend, damping,\n"
      "           pin: corners|top|none}\n"
      "  newton  {solver: auto|ldlt|cg, tol, max_iterations, definite, cg_tol,\n"
      "           fast_solver: auto|ldlt|cholmod|cg, fast_cg_tol}\n");
}

}  // namespace wb
