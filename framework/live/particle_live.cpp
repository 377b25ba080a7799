// The particle labs' live simulation (live.h): a scene loaded as the executable loads
// it (scene_from_json, the lab's generators, its World, check_initial_state), stepped
// by the lab's integrators and after-step phase, under the run contract's divergence
// rule. In a live build this file's run_particle_lab takes the place of the run
// contract's (framework/src/particle_lab.cpp): it keeps the lab's LabInfo.
#include <algorithm>
#include <cmath>
#include <memory>

#include "live.h"
#include "wb/run.h"
#include "wb/sweep.h"

namespace wb {

namespace live {
namespace {

// The closed form of a scene whose only force is uniform gravity (no planes, pins or
// generators): x(t) = x0 + v0 t + g t^2 / 2 for every particle (tools/wbplot/exact.py's
// parabola). Returns false for any other scene.
bool free_fall(const Scene& s, Vec2& g) {
  const json& d = s.doc;
  for (const char* key : {"planes", "pinned", "rope", "cloth", "contact"}) {
    if (d.contains(key)) return false;
  }
  if (!d.contains("forces") || !d["forces"].is_array() || d["forces"].size() != 1) return false;
  const json& f = d["forces"][0];
  if (!f.is_object() || f.value("type", "") != "gravity" || !f.contains("g")) return false;
  const json& gj = f["g"];
  if (!gj.is_array() || gj.size() != 2 || !gj[0].is_number() || !gj[1].is_number()) return false;
  g = Vec2(gj[0].get<double>(), gj[1].get<double>());
  return true;
}

class ParticleSim : public Sim {
 public:
  explicit ParticleSim(const LabInfo& info) : info_(info) {}

  void load(const std::string& file, const std::string& text) override {
    file_ = file;
    build(text);
    integ_ = 0;
    if (scene_->integrator)
      integ_ = &find_integrator(info_, *scene_->integrator, file_ + ": integrator") -
               info_.integrators.data();
    check_integrator(integ_);
    reset();
  }

  void update(const std::string& text) override {
    const Eigen::Index n = x_.cols();
    Mat2X x = x_, v = v_;
    const Contract kept = contract_;
    build(text);
    check_integrator(integ_);
    if (scene_->n() != n) {
      reset();
      return;
    }
    x_ = std::move(x);
    v_ = std::move(v);
    contract_ = kept;
    contract_.scale = scale_;
    exact_valid_ = false;  // the closed form is of the scene's initial state
  }

  void reset() override {
    x_ = scene_->x;
    v_ = scene_->v;
    scratch_.resize(x_.cols());
    world_->dynamics().reset_evals();
    contract_.restart(scale_);
    exact_valid_ = true;
    moved_ = false;
    grabbed_ = -1;
  }

  void set_integrator(const std::string& name) override {
    const std::size_t i = &find_integrator(info_, name, "integrator") - info_.integrators.data();
    check_integrator(i);
    integ_ = i;
  }

  long step(double h, long n) override {
    const Integrator& it = info_.integrators[integ_];
    const Dynamics& dyn = world_->dynamics();
    long k = 0;
    while (k < n && contract_.diverged.empty()) {
      it.step(dyn, h, x_, v_, scratch_);
      world_->after_step(h, x_, v_);
      if (grabbed_ >= 0) pull(h);
      if (!moved_) moved_ = x_ != scene_->x || v_ != scene_->v;
      bool finite = false;
      const double E = world_->checked_energy(x_, v_, finite);
      ++k;
      contract_.after_step(h, finite, E);
    }
    contract_.check_unconverged(dyn.unconverged());
    return k;
  }

  const std::vector<double>& state() override {
    state_.resize(std::size_t(4 * x_.cols()));
    for (Eigen::Index i = 0; i < x_.cols(); ++i) {
      double* s = &state_[std::size_t(4 * i)];
      s[0] = x_(0, i);
      s[1] = x_(1, i);
      s[2] = v_(0, i);
      s[3] = v_(1, i);
    }
    return state_;
  }
  int values_per_item() const override { return 4; }

  const std::vector<double>& readouts() override {
    readouts_.assign(kCount, 0.0);
    const Energy e = world_->energy(x_, v_);
    const Vec2 p = momentum(v_, scene_->m);
    double L = 0;
    for (Eigen::Index i = 0; i < x_.cols(); ++i) {
      L += scene_->m[i] * cross(Vec2(x_.col(i)), Vec2(v_.col(i)));
    }
    readouts_[kT] = contract_.t;
    readouts_[kSteps] = double(contract_.steps);
    readouts_[kKinetic] = e.kinetic;
    readouts_[kPotential] = e.potential;
    readouts_[kEnergy] = e.total();
    readouts_[kPx] = p.x();
    readouts_[kPy] = p.y();
    readouts_[kLz] = L;
    readouts_[kEvals] = double(world_->dynamics().evals());
    readouts_[kUnconverged] = double(world_->dynamics().unconverged());
    readouts_[kExactDist] = NAN;
    if (!exact().empty()) {
      double worst = 0;
      for (Eigen::Index i = 0; i < x_.cols(); ++i) {
        const Vec2 d = Vec2(x_.col(i)) - Vec2(exact_xy_[2 * i], exact_xy_[2 * i + 1]);
        worst = std::isfinite(d.norm()) ? std::max(worst, d.norm()) : INFINITY;
      }
      readouts_[kExactDist] = worst;
    }
    return readouts_;
  }

  const std::vector<double>& exact() override {
    exact_xy_.clear();
    if (!exact_valid_ || grabbed_ >= 0) return exact_xy_;
    const double t = contract_.t;
    if (exact_sol_.kind != ExactSolution::kNone) {
      Vec2 x, v;
      exact_sol_.at(t, x, v);
      exact_xy_ = {x.x(), x.y()};
    } else if (falls_) {
      for (Eigen::Index i = 0; i < scene_->n(); ++i) {
        const Vec2 x = Vec2(scene_->x.col(i)) + t * Vec2(scene_->v.col(i)) + 0.5 * t * t * g_;
        exact_xy_.push_back(x.x());
        exact_xy_.push_back(x.y());
      }
    }
    return exact_xy_;
  }

  void grab(long i, const double* target, const double* /*at_body*/) override {
    if (i < 0 || i >= x_.cols()) return;
    grabbed_ = i;
    target_ = Vec2(target[0], target[1]);
    exact_valid_ = false;
  }
  void release() override { grabbed_ = -1; }

  std::string status() const override {
    std::vector<std::string> warnings;
    const Integrator& it = info_.integrators[integ_];
    const long k = contract_.steps;
    if (k > 0 && it.evals_per_step > 0 && world_->dynamics().evals() == 0) {
      warnings.push_back("the integrator \"" + it.name + "\" evaluated no forces in " +
                         std::to_string(k) + " steps: is its step function written yet?");
    }
    const bool could_move = !scene_->v.isZero(0) || !world_->terms().empty();
    if (k > 0 && !moved_ && scene_->n() > 0 && could_move) {
      warnings.push_back("the state never changed in " + std::to_string(k) +
                         " steps (no step moved a particle or changed a velocity): is the "
                         "step, or a force, still a stub?");
    }
    for (const std::string& w : world_->warnings(x_, v_)) warnings.push_back(w);
    std::vector<std::string> notes = world_->initial_notes();
    for (const std::string& n : world_->notes()) notes.push_back(n);
    return status_json(contract_, it.name, warnings, notes, "");
  }

 private:
  // A scene from its text, loaded and checked as the executable does
  // (framework/src/particle_lab.cpp), and its World.
  void build(const std::string& text) {
    std::vector<std::string> keys = info_.scene_keys;
    if (info_.sweep)
      keys.insert(keys.end(), sweep_scene_keys().begin(), sweep_scene_keys().end());
    auto scene = std::make_unique<Scene>(
        scene_from_json(file_, parse_json(text, file_), std::nullopt, keys));
    if (info_.expand_scene) {
      info_.expand_scene(*scene);
      check_particles(*scene, "the scene's generators");
    }
    std::unique_ptr<World> world = info_.make_world(*scene);
    check_initial_state(*scene, *world);
    ExactSolution ex = info_.sweep ? read_exact(*scene) : ExactSolution{};
    const Energy e0 = world->energy(scene->x, scene->v);
    scale_ = energy_scale(e0.kinetic, e0.potential, particle_work_scale(*scene, *world));
    world_.reset();  // the old world may refer to the old scene
    scene_ = std::move(scene);
    world_ = std::move(world);
    exact_sol_ = ex;
    falls_ = exact_sol_.kind == ExactSolution::kNone && free_fall(*scene_, g_);
  }

  void check_integrator(std::size_t i) const {
    const Integrator& it = info_.integrators.at(i);
    if (it.check) it.check(it, world_->dynamics());
  }

  // The cursor's soft constraint on the grabbed particle, after the step (live.h). Its
  // stiffness is that of a mass that carries what may hang on the particle (a rope's
  // other beads), up to 50 times its own: pulled by its own mass alone, the end of a
  // hanging rope would sag far below the cursor.
  void pull(double h) {
    const Eigen::Index i = grabbed_;
    const double m = scene_->m[i];
    double gamma = 0, beta = 0;
    grab_coefficients(h, std::max(m, std::min(scene_->m.sum(), kGrabLoad * m)), gamma, beta);
    const Vec2 C = Vec2(x_.col(i)) - target_;
    const Vec2 P = -(Vec2(v_.col(i)) + beta * C) / (1.0 / m + gamma);
    v_.col(i) += P / m;
  }

  LabInfo info_;
  std::string file_;
  std::unique_ptr<Scene> scene_;
  std::unique_ptr<World> world_;
  std::size_t integ_ = 0;
  double scale_ = 0;
  Mat2X x_, v_;
  Scratch scratch_;
  Contract contract_;
  bool moved_ = false;
  ExactSolution exact_sol_;
  bool falls_ = false, exact_valid_ = true;
  Vec2 g_ = Vec2::Zero();
  Eigen::Index grabbed_ = -1;
  Vec2 target_ = Vec2::Zero();
  std::vector<double> state_, readouts_, exact_xy_;
};

}  // namespace
}  // namespace live

// A live build's run contract for particle labs: the lab's main() hands its LabInfo
// over to the live page instead of running a scene.
int run_particle_lab(int /*argc*/, char** /*argv*/, const LabInfo& info) {
  json j;
  j["lab"] = info.lab;
  j["side"] = info.side;
  j["kind"] = "particles";
  j["summary"] = info.summary;
  j["integrators"] = json::array();
  for (const Integrator& it : info.integrators) {
    j["integrators"].push_back({{"name", it.name},
                                {"description", it.description},
                                {"order", it.order},
                                {"evals", it.evals_per_step}});
  }
  live::add_lab({info.lab, info.side, j.dump(),
                 [info] { return std::unique_ptr<live::Sim>(new live::ParticleSim(info)); }});
  return 0;
}

}  // namespace wb
