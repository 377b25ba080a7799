// The particle labs' scenes for the run contract's main (wb/lab.h): loading,
// the core's cost terms (the lab's glue adds its own: LabInfo::step_cost), the
// World, a run (simulate) and sweep mode (ParticleSweep).
#include <memory>

#include "wb/lab.h"
#include "wb/rk4.h"
#include "wb/run.h"
#include "wb/sweep.h"

namespace wb {

namespace {

// The core's rates for particle runs (docs/scenes.md, "Cost"; measured with the
// solution under gravity at 10^6 particles, where a step streams its arrays from
// memory: 26 ns per particle per step with semi-implicit Euler): the memory of a
// particle in a run (265 bytes: the scene's state, the run's copies, the
// integrator's scratch, the forces' copies), loading and checking it (emitting,
// the initial checks, the first pages: 180 ns at 10^6), the integrator's
// arithmetic per particle per force evaluation, the divergence rule's check per
// particle per step.
constexpr double kBytesPerParticle = 265;
constexpr double kSecondsPerParticleLoad = 150e-9;
constexpr double kSecondsPerParticleEval = 8e-9;
constexpr double kSecondsPerParticleCheck = 6e-9;
// A written step's rows hold about 160 bytes per particle until they are flushed.
constexpr double kBytesPerTraceParticle = 160;
// The step loop's own work per step (the hooks, the integrator's call, the
// energy's virtual calls): what a one-particle scene spends.
constexpr double kSecondsPerStep = 40e-9;

std::string count(Eigen::Index n) { return std::to_string(n); }

class ParticleScene : public LabScene {
 public:
  ParticleScene(const LabInfo& info, Scene scene) : info_(info), scene_(std::move(scene)) {
    file = scene_.file;
    name = scene_.name;
    dt = scene_.dt;
    t_end = scene_.t_end;
    integrator = scene_.integrator;
  }

  void cost(std::size_t i, StepCost& c) const override {
    const Integrator& it = info_.integrators.at(i);
    const Eigen::Index n = scene_.n();
    const double evals = it.evals_per_step;
    c.once.add("particles: " + count(n) + " (state, run copies, scratch)", "particles", double(n),
               kSecondsPerParticleLoad, double(n) * kBytesPerParticle);
    c.step.add(it.name + ": " + count(n) + " particles x " + std::to_string(it.evals_per_step) +
                   " evaluations",
               "--integrator", double(n) * evals, kSecondsPerParticleEval);
    c.step.add("divergence rule: " + count(n) + " particles", "", double(n),
               kSecondsPerParticleCheck);
    c.step.add("the step loop", "", 1, kSecondsPerStep);
    c.record.add("trace and stats rows: " + count(n) + " particles", "--out", double(n),
                 kSecondsPerTraceRow, double(n) * kBytesPerTraceParticle);
    if (info_.step_cost) info_.step_cost(scene_, it, c);
  }

  void sweep_cost(const SweepPlan& plan, Estimate& e) const override {
    if (read_exact(scene_).kind != ExactSolution::kNone) return;
    // The rk4 reference: RK4's 4 evaluations per step, and the after-step phase.
    Integrator rk4 = rk4_integrator();
    rk4.name = "rk4 reference";
    StepCost c;
    if (info_.step_cost) info_.step_cost(scene_, rk4, c);
    c.step.add("rk4 reference: " + count(scene_.n()) + " particles x 4 evaluations", "--dts",
               double(scene_.n()) * 4, kSecondsPerParticleEval);
    for (const ReferenceRun& r : reference_runs(plan)) {
      e.add_times(c.step, double(r.steps),
                  " x " + std::to_string(r.steps) + " reference steps to t = " + num(r.t));
    }
  }

  double reference_steps(const SweepPlan& plan) const override {
    if (read_exact(scene_).kind != ExactSolution::kNone) return 0;
    double n = 0;
    for (const ReferenceRun& r : reference_runs(plan)) n += double(r.steps);
    return n;
  }

  std::vector<std::string> prepare(const std::vector<std::size_t>& integrators,
                                   const SweepPlan* sweep) override {
    if (!info_.make_world) throw std::logic_error("LabInfo.make_world is not set");
    world_ = info_.make_world(scene_);
    check_initial_state(scene_, *world_);
    if (info_.sweep) exact_ = read_exact(scene_);  // checks the "exact" key in every mode
    std::vector<std::string> warnings = world_->initial_notes();
    for (std::size_t i : integrators) {
      const Integrator& it = info_.integrators.at(i);
      if (!it.check) continue;
      const std::string w = it.check(it, world_->dynamics());
      if (!w.empty()) warnings.push_back(w);
    }
    if (sweep) {
      check_sweep(scene_, exact_, *sweep, sweep->ladder);
      sweep_ = std::make_unique<ParticleSweep>(info_, scene_, *world_, exact_, *sweep, exe);
    }
    return warnings;
  }

  Summary run(const RunRequest& r, RunFiles& files) override {
    RunOptions opt;
    opt.integrator = &info_.integrators.at(r.integrator);
    opt.dt = r.dt;
    opt.steps = r.steps;
    opt.every = r.every;
    opt.trace = &files.trace;
    opt.stats = &files.stats;
    const Summary s = summary_of(simulate(scene_, *world_, opt));
    for (const std::string& n : world_->notes()) say(exe, "warning", n);
    return s;
  }

  SweepHooks sweep_hooks() override { return sweep_->hooks(); }

 private:
  const LabInfo& info_;
  Scene scene_;
  std::unique_ptr<World> world_;
  ExactSolution exact_;
  std::unique_ptr<ParticleSweep> sweep_;  // sweep mode's state
};

}  // namespace

int run_particle_lab(int argc, char** argv, const LabInfo& info) {
  LabSpec spec;
  spec.lab = info.lab;
  spec.side = info.side;
  spec.summary = info.summary;
  for (const Integrator& it : info.integrators) {
    spec.integrators.push_back({it.name, it.description, it.order, it.evals_per_step});
  }
  spec.help_sections = info.help_sections;
  spec.trace_columns = "t,id,x,y,vx,vy";
  spec.stats_columns = "step,t,energy,kinetic,potential,px,py,force_evals";
  spec.seed = true;
  spec.sweep = info.sweep;
  spec.sweep_errors =
      "Errors against the scene's \"exact\" motion or an RK4 run at the smallest\n"
      "dt/16.";
  return run_lab(argc, argv, spec, [&info](const RunFlags& flags) -> std::unique_ptr<LabScene> {
    std::vector<std::string> keys = info.scene_keys;
    if (info.sweep) keys.insert(keys.end(), sweep_scene_keys().begin(), sweep_scene_keys().end());
    Scene scene = load_scene(flags.scene_file, flags.seed, keys);
    if (info.expand_scene) {
      info.expand_scene(scene);
      check_particles(scene, "the scene's generators");
    }
    return std::make_unique<ParticleScene>(info, std::move(scene));
  });
}

}  // namespace wb
