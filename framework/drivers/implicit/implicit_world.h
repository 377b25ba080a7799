// The implicit lab's glue: a scene's springs become the SpringNetwork the
// student's implicit steps solve; every other force (gravity, ...) is taken
// explicitly, at the start of the step. Pinned particles (scene key "pinned")
// get zero acceleration under every integrator. Scene generators "rope" and
// "cloth" add particles, springs and pins (docs/scenes.md, ## implicit).
#pragma once
#include <memory>
#include <string>

#include "backward_euler.h"
#include "fast_backward_euler.h"
#include "forces_world.h"
#include "spring_network.h"
#include "wb/run.h"
#include "wb/world.h"

namespace wb {

// The top-level scene keys this lab reads: pinned, rope, cloth, newton.
const std::vector<std::string>& implicit_scene_keys();

// Adds the particles, springs and pins of a scene's "rope" and "cloth" keys.
void expand_implicit_scene(Scene& scene);

// Every force of the scene, with the spring network visible to the implicit
// integrators (they downcast the Dynamics they receive to this class).
class ImplicitDynamics : public Dynamics {
 public:
  ImplicitDynamics(const ForceList& forces, const Scene& scene);
  const SpringNetwork& network() const { return net_; }
  const NewtonOptions& options() const { return opt_; }
  // The provided fast path (fast_backward_euler.h), made on its first use:
  // its pattern analysis is paid once per run, by the runs that use it.
  FastBackwardEuler& fast() const;
  const std::string& file() const { return file_; }
  // The forces other than springs and drag (N), at (x, v): one counted evaluation.
  void external_forces(const Mat2X& x, const Mat2X& v, Mat2X& f) const;
  // Keeps count of Newton's work; reports a step that did not converge on stderr.
  void record(const char* integrator, const NewtonReport& r) const;
  ~ImplicitDynamics() override;

 protected:
  void eval(const Mat2X& x, const Mat2X& v, Mat2X& a) const override;

 private:
  const ForceList& forces_;
  SpringNetwork net_;
  NewtonOptions opt_;
  FastSolverOptions fast_opt_;
  mutable std::unique_ptr<FastBackwardEuler> fast_;
  std::string file_;
  Eigen::Array<double, 1, Eigen::Dynamic> inv_m_;
  mutable bool external_only_ = false;
  mutable long steps_ = 0, iterations_ = 0, failed_ = 0;
  mutable int max_iterations_ = 0;
};

class ImplicitWorld : public World {
 public:
  explicit ImplicitWorld(const Scene& scene);
  const Dynamics& dynamics() const override { return dyn_; }
  Energy energy(const Mat2X& x, const Mat2X& v) const override;

 private:
  VecX m_;
  ForceList forces_;
  ImplicitDynamics dyn_;
};

// The implicit integrators' wb::StepFn adapters.
void backward_euler_1_adapter(const Dynamics& dyn, double h, Mat2X& x, Mat2X& v, Scratch& s);
void backward_euler_adapter(const Dynamics& dyn, double h, Mat2X& x, Mat2X& v, Scratch& s);
void baraff_witkin_adapter(const Dynamics& dyn, double h, Mat2X& x, Mat2X& v, Scratch& s);
void implicit_trapezoid_adapter(const Dynamics& dyn, double h, Mat2X& x, Mat2X& v, Scratch& s);
// The same two steps by the provided fast path (FastBackwardEuler).
void backward_euler_fast_adapter(const Dynamics& dyn, double h, Mat2X& x, Mat2X& v, Scratch& s);
void baraff_witkin_fast_adapter(const Dynamics& dyn, double h, Mat2X& x, Mat2X& v, Scratch& s);

// Sets make_world, expand_scene, scene_keys and the help paragraphs.
void use_implicit(LabInfo& info);

}  // namespace wb
