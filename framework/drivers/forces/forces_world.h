// The forces lab's glue: a scene's "forces" list -> Force objects that call
// the forces lab's functions (of the side the executable is built from), and
// the World every particle lab that runs forces steps with. The euler,
// midpoint and later particle labs reuse it (WB lab dependency "forces").
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "wb/force.h"
#include "wb/run.h"
#include "wb/world.h"

namespace wb {

using ForceList = std::vector<std::unique_ptr<Force>>;

// The force types a scene may name, for --help and error messages.
const std::vector<std::string>& force_types();

// Builds only what the scene declares; throws InputError on bad entries (and on
// numbers whose derived quantities would not be finite or resolvable: a curl
// noise's potential size, lattice coordinates and difference step). Each term's
// key is its entry ("forces[2] (spring)").
ForceList build_forces(const Scene& scene);

// The cost model's terms of a scene's "forces" list for one integrator
// (docs/scenes.md, "Cost"), read from the scene's numbers before anything is
// built: each term per evaluation, the divergence rule's potentials per step,
// the initial checks once; `extra_springs` more springs (a lab's generators).
void forces_step_cost(const Scene& scene, const Integrator& it, StepCost& c,
                      double extra_springs = 0);

// One "spring" entry of a scene. All of a scene's springs form one Springs term.
struct SpringDef {
  Eigen::Index i, j;   // particle indices; j < 0: anchored to `anchor`
  Vec2 anchor;         // fixed end (m) when j < 0
  double k, rest, kd;  // stiffness (N/m), rest length (m), damping (N s/m)
};

// Every spring of a scene, as one force term (type "spring"); other labs'
// glue finds it in a ForceList to read the network.
class Springs : public Force {
 public:
  std::vector<SpringDef> springs;
  // (first spring, scene entry) for each entry the springs came from, in order:
  // "forces[3] (spring)", or a generator ("rope", "cloth").
  std::vector<std::pair<std::size_t, std::string>> origins;
  void add(const Mat2X& x, const Mat2X& v, const VecX& m, Mat2X& f) const override;
  double potential(const Mat2X& x, const VecX& m) const override;
  std::string type() const override { return "spring"; }
  void bound(const Mat2X& x, const Mat2X& v, const VecX& m, VecX& b) const override;
  std::string blame(const Mat2X& x, const Mat2X& v) const override;
};

// The list's spring term, made (at the end) if it has none: where a lab's
// generators add springs without a JSON entry per spring.
Springs& spring_term(ForceList& forces);

// a = (sum of the forces) / m, through the student's accumulate_forces (F6).
class ParticleDynamics : public Dynamics {
 public:
  ParticleDynamics(const ForceList& forces, const VecX& m);
  // Did any evaluation give a non-zero force (what the forces' stubs never do)?
  bool any_force() const { return any_force_; }
  // Every term is per-particle (Force::per_particle): rk4 then goes by blocks.
  bool per_particle() const override;
  // Some term's force depends on x (Force::reads_positions).
  bool reads_positions() const override;
  // Sums k = sum m v.*v and w = sum m x over the blocks of a step (rk4 by blocks).
  void block_stepped(Eigen::Index first, Eigen::Index count, const Mat2X& x,
                     const Mat2X& v) const override;
  void blocks_stepped(const Mat2X& x, const Mat2X& v) const override;
  // The sums of the last step, if it went by blocks and ended in exactly this
  // x and v (the same arrays; no evaluation since): true once, then the next
  // question needs another step. For a world that changes nothing between
  // its step and its bookkeeping (ForceWorld: no after_step).
  bool take_step_sums(const Mat2X& x, const Mat2X& v, Eigen::Array2d& k, Eigen::Array2d& w) const;

 protected:
  void eval(const Mat2X& x, const Mat2X& v, Mat2X& a) const override;
  // accumulate_forces on one block: its masses, its own f.
  void eval_block(Eigen::Index first, const Mat2X& x, const Mat2X& v, Mat2X& a) const override;

 private:
  const ForceList& forces_;
  VecX m_;
  // 1/m_i twice in column i: a = f * inv_m2_ coefficient by coefficient (the
  // same products as f_i * (1/m_i), without shuffling pairs of columns).
  Eigen::Array<double, 2, Eigen::Dynamic> inv_m2_;
  mutable Mat2X f_;
  struct Block {  // eval_block's arrays: the block's masses and forces
    Eigen::Index first = -1;
    VecX m;
    Mat2X f;
  };
  mutable Block block_[2];  // [1]: the last block's
  struct StepSums {         // block_stepped's sums, and the state they were taken of
    Eigen::Array2d k = Eigen::Array2d::Zero(), w = Eigen::Array2d::Zero();
    Eigen::Index done = 0;  // particles summed
    const double *x = nullptr, *v = nullptr;
    bool ready = false;
  };
  mutable StepSums sums_;
  mutable bool any_force_ = false;
};

Energy energy(const ForceList& forces, const Mat2X& x, const Mat2X& v, const VecX& m);

// k += sum m_i v_i.*v_i and w += sum m_i x_i over particles first .. end - 1
// (per axis: k / 2 is the kinetic energy, -g . w the uniform gravity's
// potential): the run's per-step bookkeeping (checked_energy, and rk4's blocks
// as each ends). Vectorised for the processor it runs on, in one fixed order
// of operations and without fused multiply-adds (the kernel in
// forces_world.cpp), so that every processor gets the same bits
// (tests/physics/test_rk4_blocks.cpp holds it against a scalar loop).
void add_energy_sums(const Mat2X& x, const Mat2X& v, const VecX& m, Eigen::Index first,
                     Eigen::Index end, Eigen::Array2d& k, Eigen::Array2d& w);

// A world's force list as checked_energy sums it, sorted once when the world is
// made: the uniform gravity terms' field, summed (their potential is -g . w, from
// the one pass's sums), and the other terms, in the list's order (each adds its own
// potential). Sorting on every step took two dynamic_casts per term, a fifth of the
// cheapest step in WebAssembly (docs/benchmarks.md, "Live pages").
struct EnergyTerms {
  Vec2 g = Vec2::Zero();
  std::vector<const Force*> others;
  explicit EnergyTerms(const ForceList& forces);
};

// World::checked_energy of a world with these forces (`terms`, made from them): the
// finiteness of x and v, the kinetic energy and the uniform gravity's potential in
// one pass over the particles, then the other terms' potentials.
double checked_energy(const ForceList& forces, const EnergyTerms& terms, const Mat2X& x,
                      const Mat2X& v, const VecX& m, bool& finite,
                      const ParticleDynamics* dyn = nullptr);

// A particle scene's World: its forces, summed by accumulate_forces.
class ForceWorld : public World {
 public:
  explicit ForceWorld(const Scene& scene);
  const Dynamics& dynamics() const override { return dyn_; }
  Energy energy(const Mat2X& x, const Mat2X& v) const override;
  double checked_energy(const Mat2X& x, const Mat2X& v, bool& finite) const override {
    return wb::checked_energy(forces_, terms_, x, v, m_, finite, &dyn_);
  }
  std::vector<const Force*> terms() const override;
  // A scene with forces whose every evaluation gave zero: the forces' stubs.
  std::vector<std::string> warnings(const Mat2X& x, const Mat2X& v) const override;
  const ForceList& forces() const { return forces_; }
  const VecX& masses() const { return m_; }

 private:
  VecX m_;
  ForceList forces_;
  ParticleDynamics dyn_;
  EnergyTerms terms_;
};

// Makes a lab run its scenes with the forces lab: sets info.make_world and
// adds the force types to --help.
void use_forces(LabInfo& info);

}  // namespace wb
