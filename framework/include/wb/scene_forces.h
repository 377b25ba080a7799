// The forces a particle scene declares, built from its "forces" list, and the
// dynamics they define. Each term calls the forces lab's function of the same
// side (the student's in `forces`, euler, midpoint; the solution's in the
// -solution executables).
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "wb/dynamics.h"
#include "wb/force.h"
#include "wb/scene.h"

namespace wb {

using ForceList = std::vector<std::unique_ptr<Force>>;

// The force types a scene may name, for --help and error messages.
const std::vector<std::string>& force_types();

// Builds only what the scene declares; throws InputError on bad entries.
ForceList build_forces(const Scene& scene);

// a = (sum of the forces) / m, through the student's accumulate_forces.
class ParticleDynamics : public Dynamics {
 public:
  ParticleDynamics(const ForceList& forces, const VecX& m);
  const Mat2X& last_forces() const { return f_; }

 protected:
  void eval(const Mat2X& x, const Mat2X& v, Mat2X& a) const override;

 private:
  const ForceList& forces_;
  VecX m_;
  Eigen::Array<double, 1, Eigen::Dynamic> inv_m_;
  mutable Mat2X f_;
};

struct Energy {
  double kinetic = 0, potential = 0;
  double total() const { return kinetic + potential; }
};
Energy energy(const ForceList& forces, const Mat2X& x, const Mat2X& v, const VecX& m);
Vec2 momentum(const Mat2X& v, const VecX& m);

}  // namespace wb
