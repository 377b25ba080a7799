// The implicit lab's glue: scene generators, the spring network, and the
// adapters that call the student's implicit steps (labs/implicit/).
#include "implicit_world.h"

#include <cmath>
#include <iostream>

#include "backward_euler_spring.h"
#include "implicit_trapezoid.h"

namespace wb {

namespace {

const Range kPositive{0.0, std::numeric_limits<double>::infinity(), true};
const Range kNonNegative{0.0};
constexpr std::int64_t kMaxGenerated = 4'000'000;  // particles one generator may add

json spring_json(std::int64_t i, std::int64_t j, double k, double rest, double kd) {
  return json{{"type", "spring"}, {"i", i}, {"j", j}, {"k", k}, {"rest", rest}, {"damping", kd}};
}

// Appends one particle at rest to the scene.
void add_particle(Scene& s, const Vec2& x, double m) {
  const Eigen::Index n = s.x.cols();
  s.x.conservativeResize(2, n + 1);
  s.v.conservativeResize(2, n + 1);
  s.m.conservativeResize(n + 1);
  s.radius.conservativeResize(n + 1);
  s.x.col(n) = x;
  s.v.col(n).setZero();
  s.m[n] = m;
  s.radius[n] = 0.0;
}

void reserve(Scene& s, std::int64_t more) {
  const Eigen::Index n = s.x.cols();
  s.x.conservativeResize(2, n + more);
  s.v.conservativeResize(2, n + more);
  s.m.conservativeResize(n + more);
  s.radius.conservativeResize(n + more);
  s.x.conservativeResize(2, n);
  s.v.conservativeResize(2, n);
  s.m.conservativeResize(n);
  s.radius.conservativeResize(n);
}

// "rope": N beads on the segment start -> end, joined in a chain.
void expand_rope(Scene& s, json& forces, json& pinned) {
  JsonObject top(s.file, s.doc, "");
  JsonObject r = top.object("rope");
  r.only_keys({"start", "end", "beads", "m", "k", "damping", "pin"});
  const Vec2 a = r.vec2("start"), b = r.vec2("end");
  const std::int64_t N = r.integer("beads", 2, kMaxGenerated);
  const double m = r.number("m", kPositive), k = r.number("k", kNonNegative);
  const double kd = r.number_or("damping", 0.0, kNonNegative);
  const std::string pin = r.string_or("pin", "start");
  if (pin != "start" && pin != "ends" && pin != "none")
    r.fail("pin", &r.raw().at("pin"), "one of: start, ends, none");
  if (a == b) r.fail("end", &r.raw().at("end"), "a point other than \"start\"");
  const std::int64_t first = s.n();
  std::vector<json> springs;
  for (std::int64_t q = 0; q < N; ++q) {
    add_particle(s, a + (b - a) * (double(q) / double(N - 1)), m);
    if (q > 0) {
      const double rest = (s.x.col(first + q) - s.x.col(first + q - 1)).norm();
      forces.push_back(spring_json(first + q - 1, first + q, k, rest, kd));
    }
  }
  if (pin != "none") pinned.push_back(first);
  if (pin == "ends") pinned.push_back(first + N - 1);
}

// "cloth": a rows x cols grid hanging from its top row's corners.
void expand_cloth(Scene& s, json& forces, json& pinned) {
  JsonObject top(s.file, s.doc, "");
  JsonObject c = top.object("cloth");
  c.only_keys(
      {"origin", "rows", "cols", "spacing", "m", "k", "k_shear", "k_bend", "damping", "pin"});
  const Vec2 o = c.vec2("origin");
  const std::int64_t R = c.integer("rows", 2, kMaxGenerated),
                     C = c.integer("cols", 2, kMaxGenerated);
  if (R * C > kMaxGenerated) {
    c.fail("cols", &c.raw().at("cols"),
           "rows x cols at most " + std::to_string(kMaxGenerated) + " particles");
  }
  const double dx = c.number("spacing", kPositive), m = c.number("m", kPositive);
  const double k = c.number("k", kNonNegative);
  const double ks = c.number_or("k_shear", k, kNonNegative);
  const double kb = c.number_or("k_bend", 0.0, kNonNegative);
  const double kd = c.number_or("damping", 0.0, kNonNegative);
  const std::string pin = c.string_or("pin", "corners");
  if (pin != "corners" && pin != "top" && pin != "none")
    c.fail("pin", &c.raw().at("pin"), "one of: corners, top, none");
  const std::int64_t first = s.n();
  reserve(s, R * C);
  auto id = [&](std::int64_t r, std::int64_t q) { return first + r * C + q; };
  for (std::int64_t r = 0; r < R; ++r)
    for (std::int64_t q = 0; q < C; ++q) add_particle(s, o + Vec2(q * dx, -r * dx), m);
  auto spring = [&](std::int64_t i, std::int64_t j, double kk) {
    if (kk > 0) forces.push_back(spring_json(i, j, kk, (s.x.col(i) - s.x.col(j)).norm(), kd));
  };
  for (std::int64_t r = 0; r < R; ++r) {
    for (std::int64_t q = 0; q < C; ++q) {
      if (q + 1 < C) spring(id(r, q), id(r, q + 1), k);  // structural
      if (r + 1 < R) spring(id(r, q), id(r + 1, q), k);
      if (r + 1 < R && q + 1 < C) {  // shear
        spring(id(r, q), id(r + 1, q + 1), ks);
        spring(id(r, q + 1), id(r + 1, q), ks);
      }
      if (q + 2 < C) spring(id(r, q), id(r, q + 2), kb);  // bend
      if (r + 2 < R) spring(id(r, q), id(r + 2, q), kb);
    }
  }
  if (pin == "corners") {
    pinned.push_back(id(0, 0));
    pinned.push_back(id(0, C - 1));
  } else if (pin == "top") {
    for (std::int64_t q = 0; q < C; ++q) pinned.push_back(id(0, q));
  }
}

// The scene's pinned particle indices, checked against its particle count.
std::vector<char> read_pinned(const Scene& s) {
  JsonObject top(s.file, s.doc, "");
  std::vector<char> flags;
  const json& list = top.array_or_empty("pinned");
  if (list.empty()) return flags;
  flags.assign(std::size_t(s.n()), 0);
  for (std::size_t k = 0; k < list.size(); ++k) {
    const json& e = list[k];
    const std::string key = "pinned[" + std::to_string(k) + "]";
    if (!e.is_number_integer() || e.get<std::int64_t>() < 0 || e.get<std::int64_t>() >= s.n()) {
      top.fail(key, &e,
               "a particle index from 0 to " + std::to_string(s.n() - 1) +
                   (s.n() == 0 ? " (the scene has no particles)" : ""));
    }
    flags[std::size_t(e.get<std::int64_t>())] = 1;
  }
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
  top.array_or_empty("forces");
  json forces = scene.doc.contains("forces") ? scene.doc["forces"] : json::array();
  json pinned = scene.doc.contains("pinned") ? scene.doc["pinned"] : json::array();
  if (top.has("rope")) expand_rope(scene, forces, pinned);
  if (top.has("cloth")) expand_cloth(scene, forces, pinned);
  scene.doc["forces"] = std::move(forces);
  scene.doc["pinned"] = std::move(pinned);
  // Pinned particles start (and stay) at rest.
  const std::vector<char> flags = read_pinned(scene);
  for (std::size_t i = 0; i < flags.size(); ++i)
    if (flags[i]) scene.v.col(Eigen::Index(i)).setZero();
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
  if (++failed_ <= 3) {
    std::cerr << "implicit: " << file_ << ": " << integrator << " step " << steps_ << ": ";
    if (r.iterations == 0 && !r.solver_failed) {
      std::cerr << "the step did no linear solve and did not converge (see TODO(I4), "
                   "TODO(I5))\n";
    } else if (r.solver_failed) {
      std::cerr << "the linear solver failed after " << r.iterations
                << " solves; the step keeps the last good iterate\n";
    } else {
      std::cerr << "Newton did not converge in " << r.iterations << " solves (residual "
                << num(r.residual) << " > tol * scale = " << num(opt_.tol * r.scale) << ")\n";
    }
  }
}

ImplicitWorld::ImplicitWorld(const Scene& scene)
    : m_(scene.m), forces_(build_forces(scene)), dyn_(forces_, scene) {}

Energy ImplicitWorld::energy(const Mat2X& x, const Mat2X& v) const {
  return wb::energy(forces_, x, v, m_);
}

void backward_euler_1_adapter(const Dynamics& dyn, double h, Mat2X& x, Mat2X& v, Scratch& s) {
  const ImplicitDynamics& d = implicit_dynamics(dyn);
  const SpringNetwork& net = d.network();
  const bool ok = net.n() == 1 && net.springs.size() == 1 && net.springs[0].j < 0 &&
                  net.springs[0].rest == 0.0 && net.springs[0].kd == 0.0 && !net.is_pinned(0);
  if (!ok) {
    throw InputError(d.file() +
                     ": backward-euler-1 solves one free particle on one spring to an anchor "
                     "with rest 0 and damping 0 (drag and other forces are fine); this scene "
                     "has " +
                     std::to_string(net.n()) + " particles and " +
                     std::to_string(net.springs.size()) + " springs: use backward-euler");
  }
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
  d.external_forces(x, v, s.a0);
  NewtonOptions opt = d.options();
  opt.one_iteration = one_iteration;
  const NewtonReport r = trapezoid ? implicit_trapezoid_step(d.network(), s.a0, h, opt, x, v)
                                   : backward_euler_step(d.network(), s.a0, h, opt, x, v);
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
