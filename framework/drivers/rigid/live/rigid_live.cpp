// The rigid lab's live simulation (framework/live/live.h): a scene loaded as the
// executable loads it (scene_from_json), stepped by the glue's step (your functions),
// under the run contract's divergence rule on the same energy scale as a run
// (rigid_run.cpp). In a live build this file's run_rigid_lab takes the place of the
// run contract's: it keeps the lab's LabInfo for the page.
#include <cmath>
#include <memory>

#include "live.h"
#include "rigid_world.h"

namespace rigid {

namespace {

using wb::live::Contract;

class RigidSim : public wb::live::Sim {
 public:
  explicit RigidSim(const LabInfo& info) : info_(info) {}

  void load(const std::string& file, const std::string& text) override {
    file_ = file;
    build(text);
    integ_ = 0;
    if (scene_.integrator) integ_ = find(*scene_.integrator, file_ + ": integrator");
    reset();
  }

  void update(const std::string& text) override {
    const std::vector<Body> bodies = bodies_;
    const Contract kept = contract_;
    const std::size_t n = bodies.size();
    build(text);
    if (scene_.bodies.size() != n) {
      reset();
      return;
    }
    // The state goes on; what the scene sets of each body (its mass and inertia) is new.
    for (std::size_t i = 0; i < n; ++i) {
      Body b = scene_.bodies[i].body;
      b.x = bodies[i].x;
      b.v = bodies[i].v;
      b.q = bodies[i].q;
      b.omega = bodies[i].omega;
      bodies_[i] = b;
    }
    contract_ = kept;
    contract_.scale = scale_;
  }

  void reset() override {
    bodies_.clear();
    for (const BodyDef& d : scene_.bodies) bodies_.push_back(d.body);
    start_ = bodies_;
    state_ = StepState{};
    contract_.restart(scale_);
    grabbed_ = -1;
  }

  void set_integrator(const std::string& name) override { integ_ = find(name, "integrator"); }

  long step(double h, long n) override {
    const Integrator& it = info_.integrators[integ_];
    long k = 0;
    while (k < n && contract_.diverged.empty()) {
      rigid::step(scene_, it, h, bodies_, state_);
      if (grabbed_ >= 0) pull(h);
      ++k;
      const bool finite = all_finite();
      contract_.after_step(h, finite, finite ? totals(scene_, bodies_).energy() : NAN);
    }
    return k;
  }

  const std::vector<double>& state() override {
    out_.resize(13 * bodies_.size());
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      const Body& b = bodies_[i];
      double* s = &out_[13 * i];
      const double v[13] = {b.x.x(),     b.x.y(),     b.x.z(),    b.q.w(), b.q.x(),
                            b.q.y(),     b.q.z(),     b.v.x(),    b.v.y(), b.v.z(),
                            b.omega.x(), b.omega.y(), b.omega.z()};
      std::copy(v, v + 13, s);
    }
    return out_;
  }
  int values_per_item() const override { return 13; }

  const std::vector<double>& readouts() override {
    using namespace wb::live;
    const Totals t = totals(scene_, bodies_);
    readouts_.assign(kCount, 0.0);
    readouts_[kT] = contract_.t;
    readouts_[kSteps] = double(contract_.steps);
    readouts_[kKinetic] = t.kinetic;
    readouts_[kPotential] = t.potential;
    readouts_[kEnergy] = t.energy();
    readouts_[kPx] = t.p.x();
    readouts_[kPy] = t.p.y();
    readouts_[kPz] = t.p.z();
    readouts_[kLx] = t.L.x();
    readouts_[kLy] = t.L.y();
    readouts_[kLz] = t.L.z();
    readouts_[kEvals] = double(contract_.steps);  // one force accumulation per step
    readouts_[kExactDist] = NAN;
    return readouts_;
  }

  const std::vector<double>& exact() override { return none_; }

  void grab(long i, const double* target, const double* at_body) override {
    if (i < 0 || std::size_t(i) >= bodies_.size()) return;
    grabbed_ = i;
    target_ = Vec3(target[0], target[1], target[2]);
    at_body_ = Vec3(at_body[0], at_body[1], at_body[2]);
  }
  void release() override { grabbed_ = -1; }

  std::string status() const override {
    std::vector<std::string> warnings;
    const long k = contract_.steps;
    bool moved = false;
    for (std::size_t i = 0; i < bodies_.size() && !moved; ++i) {
      moved = bodies_[i].x != start_[i].x || bodies_[i].q.coeffs() != start_[i].q.coeffs();
    }
    const bool pulled = scene_.g != Vec3::Zero() || !scene_.point_forces.empty();
    if (k > 0 && !moved && contract_.diverged.empty() && pulled && !state_.velocity_changed) {
      warnings.push_back("no body's velocity changed in " + std::to_string(k) +
                         " steps under the scene's forces: are apply_force and apply_gravity "
                         "(R3) or integrate_velocity (R5) still stubs?");
    }
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      if (!(bodies_[i].I_body.diagonal().minCoeff() > 0)) {
        warnings.push_back("body " + std::to_string(i) +
                           ": its inertia tensor has an entry <= 0 (or NaN): are the R1 "
                           "inertia functions written yet?");
      }
    }
    return wb::live::status_json(contract_, info_.integrators[integ_].name, warnings,
                                 initial_overlap_notes(scene_), "");
  }

 private:
  void build(const std::string& text) {
    Scene s = scene_from_json(file_, wb::parse_json(text, file_));
    std::vector<Body> bodies;
    for (const BodyDef& d : s.bodies) bodies.push_back(d.body);
    const Totals t0 = totals(s, bodies);
    scale_ = wb::energy_scale(t0.kinetic, t0.potential, work_scale(s, bodies));
    scene_ = std::move(s);
  }

  std::size_t find(const std::string& name, const std::string& where) const {
    std::string known;
    for (std::size_t i = 0; i < info_.integrators.size(); ++i) {
      if (info_.integrators[i].name == name) return i;
      known += (i ? ", " : "") + info_.integrators[i].name;
    }
    throw wb::InputError(where + ": got \"" + name + "\", expected one of: " + known);
  }

  bool all_finite() const {
    for (const Body& b : bodies_) {
      if (!(b.x.allFinite() && b.v.allFinite() && b.q.coeffs().allFinite() &&
            b.omega.allFinite())) {
        return false;
      }
    }
    return true;
  }

  // The cursor's soft constraint on the grabbed body's point, after the step
  // (framework/live/live.h): an impulse P at the point p = x + R r,
  // P = -K^-1 (v_p + beta (p - target)), K = (1/m + gamma) E - [r] I^-1 [r].
  void pull(double h) {
    Body& b = bodies_[std::size_t(grabbed_)];
    const Mat3 R = b.q.toRotationMatrix();
    const Vec3 r = R * at_body_;
    const Vec3 d = b.I_body.diagonal();
    Mat3 I_inv = Mat3::Zero();
    if (d.minCoeff() > 0 && d.allFinite()) {
      I_inv = R * d.cwiseInverse().asDiagonal() * R.transpose();
    }
    double gamma = 0, beta = 0;
    wb::live::grab_coefficients(h, b.m, gamma, beta);
    const Mat3 K = (1.0 / b.m + gamma) * Mat3::Identity() - skew(r) * I_inv * skew(r);
    const Vec3 vp = b.v + b.omega.cross(r);
    const Vec3 P = -K.ldlt().solve(vp + beta * (b.x + r - target_));
    if (!P.allFinite()) return;
    b.v += P / b.m;
    b.omega += I_inv * r.cross(P);
  }

  LabInfo info_;
  std::string file_;
  Scene scene_;
  std::size_t integ_ = 0;
  double scale_ = 0;
  std::vector<Body> bodies_, start_;
  StepState state_;
  Contract contract_;
  long grabbed_ = -1;
  Vec3 target_ = Vec3::Zero(), at_body_ = Vec3::Zero();
  std::vector<double> out_, readouts_, none_;
};

}  // namespace

// A live build's run contract for the rigid lab: main() hands its LabInfo over to the
// live page instead of running a scene.
int run_rigid_lab(int /*argc*/, char** /*argv*/, const LabInfo& info) {
  wb::json j;
  j["lab"] = info.lab;
  j["side"] = info.side;
  j["kind"] = "rigid";
  j["summary"] = info.summary;
  j["integrators"] = wb::json::array();
  for (const Integrator& it : info.integrators) {
    j["integrators"].push_back(
        {{"name", it.name}, {"description", it.description}, {"order", 1}, {"evals", 1}});
  }
  wb::live::add_lab({info.lab, info.side, j.dump(),
                     [info] { return std::unique_ptr<wb::live::Sim>(new RigidSim(info)); }});
  return 0;
}

}  // namespace rigid
