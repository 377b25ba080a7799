// The implicit lab's glue: scene generators, the spring network, and the
// adapters that call the student's implicit steps (labs/implicit/).
#include "implicit_world.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <optional>

#include "backward_euler_spring.h"
#include "implicit_trapezoid.h"

namespace wb {

namespace {

const Range kPositive{0.0, std::numeric_limits<double>::infinity(), true};
const Range kNonNegative{0.0};

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

NewtonOptions read_newton(const Scene& s) {
  NewtonOptions opt;
  JsonObject top(s.file, s.doc, "");
  if (!top.has("newton")) return opt;
  JsonObject o = top.object("newton");
  o.only_keys(
      {"solver", "tol", "max_iterations", "definite", "cg_tol", "fast_solver", "fast_cg_tol"});
  const std::string solver = o.string_or("solver", "ldlt");
  if (solver == "cg") {
    opt.solver = NewtonOptions::kCG;
  } else if (solver != "ldlt") {
    o.fail("solver", &o.raw().at("solver"), "one of: ldlt, cg");
  }
  opt.tol = o.number_or("tol", opt.tol, kPositive);
  opt.max_iterations = int(o.integer_or("max_iterations", opt.max_iterations, 1, 1000));
  opt.definite = o.boolean_or("definite", opt.definite);
  opt.cg_tol = o.number_or("cg_tol", opt.cg_tol, kPositive);
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
  fo.cg_tol = o.number_or("fast_cg_tol", fo.cg_tol, kPositive);
  return fo;
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

ForceList implicit_forces(const Scene& scene, std::vector<std::string>* warnings) {
  ForceList forces = build_forces(scene, warnings);
  const auto* gen = std::any_cast<GeneratedNetwork>(&scene.generated);
  if (!gen || (!gen->rope && !gen->cloth)) return forces;
  // Made in place, in the spring term the integrators read.
  std::vector<SpringDef>& springs = spring_term(forces).springs;
  springs.reserve(springs.size() + std::size_t((gen->rope ? gen->rope->springs() : 0) +
                                               (gen->cloth ? gen->cloth->springs() : 0)));
  if (gen->rope) rope_springs(*gen->rope, gen->rope_first, scene, springs);
  if (gen->cloth) cloth_springs(*gen->cloth, gen->cloth_first, scene, springs);
  return forces;
}

ImplicitDynamics::ImplicitDynamics(const ForceList& forces, const Scene& scene)
    : forces_(forces),
      opt_(read_newton(scene)),
      fast_opt_(read_fast(scene)),
      file_(scene.file),
      inv_m_(scene.m.transpose().array().inverse()) {
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
}

ImplicitDynamics::~ImplicitDynamics() {
  if (failed_ > 0) {
    std::cerr << "implicit: " << file_ << ": " << failed_ << " of " << steps_
              << " implicit steps did not converge (most Newton solves in one step: "
              << max_iterations_ << ")\n";
  }
}

FastBackwardEuler& ImplicitDynamics::fast() const {
  if (!fast_) fast_ = std::make_unique<FastBackwardEuler>(net_, fast_opt_);
  return *fast_;
}

void ImplicitDynamics::eval(const Mat2X& x, const Mat2X& v, Mat2X& a) const {
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
  if (r.converged && !r.solver_failed) return;
  count_unconverged();  // the run contract's share rule (docs/run-contract.md)
  if (++failed_ <= 3) {
    std::cerr << "implicit: " << file_ << ": " << integrator << " step " << steps_ << ": ";
    if (r.iterations == 0 && !r.solver_failed) {
      std::cerr << "the step did no linear solve and did not converge (see TODO(I4), "
                   "TODO(I5))\n";
    } else if (r.solver_failed) {
      // r.iterations counts the solves that succeeded before the failed one.
      std::cerr << "the linear solver failed on solve " << r.iterations + 1
                << (r.iterations == 0 ? " (the step's first)" : "")
                << "; the step keeps the last good iterate\n";
    } else {
      std::cerr << "Newton did not converge in " << r.iterations << " solves (residual "
                << num(r.residual) << " > tol * scale = " << num(opt_.tol * r.scale) << ")\n";
    }
  }
}

ImplicitWorld::ImplicitWorld(const Scene& scene)
    : m_(scene.m), forces_(implicit_forces(scene, &cost_warnings)), dyn_(forces_, scene) {}

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

std::string newton_check(const Integrator& self, const Dynamics& dyn) {
  const ImplicitDynamics& d = implicit_dynamics(dyn);
  const SpringNetwork& net = d.network();
  const std::string size = std::to_string(2 * net.n()) + " unknowns (2 per particle) and " +
                           std::to_string(net.springs.size()) + " springs";
  if (net.n() > kMaxNewtonParticles) {
    throw InputError(d.file() + ": " + self.name + ": each step solves a Newton system of " +
                     size + ", expected at most " + std::to_string(2 * kMaxNewtonParticles) +
                     " unknowns (" + std::to_string(kMaxNewtonParticles) +
                     " particles: a cloth of that size takes minutes per step); use an "
                     "explicit integrator or fewer particles");
  }
  if (net.n() > kNewtonWarnParticles) {
    return d.file() + ": " + self.name + ": each step solves a Newton system of " + size +
           " (a sparse factorisation per Newton iteration): expect up to seconds per step "
           "(a cloth of 10^4 particles: about 1 s)";
  }
  // LDLT factorises in the particles' own order (backward_euler.h): a factor as wide as the
  // band, the largest index distance a spring between two free particles spans (a rope: 1,
  // a 2D grid: its row length or more).
  if (d.options().solver == NewtonOptions::kLDLT) {
    Eigen::Index band = 0;
    for (const NetworkSpring& s : net.springs)
      if (s.j >= 0 && !net.is_pinned(s.i) && !net.is_pinned(s.j))
        band = std::max(band, s.i > s.j ? s.i - s.j : s.j - s.i);
    const double flops = 2.0 * double(net.n()) * std::pow(2.0 * double(band), 2.0);
    if (flops > kLdltWarnFlops) {
      return d.file() + ": " + self.name + ": newton.solver \"ldlt\" factorises in the "
             "particles' order, and this network's springs join particles up to " +
             std::to_string(band) + " apart: about " + num(flops) +
             " flops per factorisation, every step; \"newton\": {\"solver\": \"cg\", "
             "\"cg_tol\": 1e-2} is made for such networks (2D cloths)";
    }
  }
  return "";
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
      "  newton  {solver: ldlt|cg, tol, max_iterations, definite, cg_tol,\n"
      "           fast_solver: auto|ldlt|cholmod|cg, fast_cg_tol}\n");
}

}  // namespace wb
