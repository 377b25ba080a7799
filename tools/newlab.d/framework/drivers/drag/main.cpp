// The drag lab executable: particles slowed by linear drag a = -b v, stepped with the
// student's Heun step. The glue is this file: a scene's "drag" key is b (1/s).
#include <memory>

#include "heun_drag.h"
#include "wb/run.h"

namespace {

class DragWorld : public wb::World {
 public:
  explicit DragWorld(const wb::Scene& scene)
      : b_(wb::JsonObject(scene.file, scene.doc, "").number("drag", {.min = 0})),
        m_(scene.m),
        dyn_([b = b_](const wb::Mat2X&, const wb::Mat2X& v, wb::Mat2X& a) { a = -b * v; }) {}
  const wb::Dynamics& dynamics() const override { return dyn_; }
  wb::Energy energy(const wb::Mat2X&, const wb::Mat2X& v) const override {
    wb::Energy e;
    e.kinetic = 0.5 * v.colwise().squaredNorm().dot(m_);
    return e;
  }

 private:
  double b_;    // drag rate (1/s)
  wb::VecX m_;  // masses (kg)
  wb::LambdaDynamics dyn_;
};

}  // namespace

int main(int argc, char** argv) {
  wb::LabInfo info;
  info.lab = WB_LAB;
  info.side = WB_SIDE;
  info.summary = "Drag lab: Heun's step on particles under linear drag.";
  info.integrators = {
      {"heun", heun_step, 2, 2, "Heun's method (TODO D1): the explicit trapezoid"}};
  info.scene_keys = {"drag"};
  info.make_world = [](const wb::Scene& scene) -> std::unique_ptr<wb::World> {
    return std::make_unique<DragWorld>(scene);
  };
  return wb::run_particle_lab(argc, argv, info);
}
