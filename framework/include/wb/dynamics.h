// What an integrator sees of a particle system: accelerations a(x, v).
#pragma once
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "wb/types.h"

namespace wb {

class Dynamics {
 public:
  virtual ~Dynamics() = default;
  // a = f(x, v) / m for every particle (2 x n; a already has that size).
  // Each call is one force evaluation and is counted.
  void acceleration(const Mat2X& x, const Mat2X& v, Mat2X& a) const {
    ++evals_;
    eval(x, v, a);
  }
  long evals() const { return evals_; }

  // Per-particle dynamics: a_i depends only on x_i, v_i and particle i's own data
  // (gravity, damping, a vortex; not springs or gravity between particles). Such
  // a system is many independent ones, and the provided rk4 steps it a block of
  // particles at a time, in cache (docs/benchmarks.md, "RK4 in blocks"). False
  // unless a Dynamics says so.
  virtual bool per_particle() const { return false; }
  // a for the particles first .. first + x.cols() - 1 alone, x and v theirs
  // (only when per_particle()). Not counted: count whole evaluations with
  // count_evals once every block is done.
  void block_acceleration(Eigen::Index first, const Mat2X& x, const Mat2X& v, Mat2X& a) const {
    eval_block(first, x, v, a);
  }
  void count_evals(long k) const { evals_ += k; }
  // A step that went by blocks tells the dynamics each block's new state
  // (columns first .. first + count - 1 of x and v, still in cache), then that
  // the step is done: a Dynamics may sum what the run's bookkeeping will ask of
  // that state (ParticleDynamics: the kinetic energy and the uniform gravity's
  // potential), so that the bookkeeping needs no pass of its own.
  virtual void block_stepped(Eigen::Index /*first*/, Eigen::Index /*count*/, const Mat2X& /*x*/,
                             const Mat2X& /*v*/) const {}
  virtual void blocks_stepped(const Mat2X& /*x*/, const Mat2X& /*v*/) const {}
  // False when a(x, v) does not depend on x (uniform gravity and damping
  // alone): rk4 then skips its stages' positions (a scene pays only for what
  // it declares). True unless a Dynamics says so.
  virtual bool reads_positions() const { return true; }
  // Steps whose implicit solve did not converge (counted by the labs that
  // solve; a share above kMaxUnconvergedShare makes the run diverged).
  long unconverged() const { return unconverged_; }
  void count_unconverged() const { ++unconverged_; }
  void reset_evals() const { evals_ = unconverged_ = 0; }

 protected:
  virtual void eval(const Mat2X& x, const Mat2X& v, Mat2X& a) const = 0;
  // Dynamics whose per_particle() is true override this; the default says
  // that a step asked for blocks of a Dynamics that has none.
  virtual void eval_block(Eigen::Index /*first*/, const Mat2X& /*x*/, const Mat2X& /*v*/,
                          Mat2X& /*a*/) const {
    throw std::logic_error("Dynamics::eval_block: this Dynamics is not per_particle()");
  }

 private:
  mutable long evals_ = 0, unconverged_ = 0;
};

// Dynamics from a callable, for tests and small examples.
class LambdaDynamics : public Dynamics {
 public:
  using Fn = std::function<void(const Mat2X& x, const Mat2X& v, Mat2X& a)>;
  explicit LambdaDynamics(Fn fn) : fn_(std::move(fn)) {}

 protected:
  void eval(const Mat2X& x, const Mat2X& v, Mat2X& a) const override { fn_(x, v, a); }

 private:
  Fn fn_;
};

// Work arrays owned by the caller and already sized 2 x n, so that a step
// allocates nothing. A step may use any of them; their contents on entry are
// undefined.
struct Scratch {
  Mat2X a0, a1, a2, a3;  // accelerations
  Mat2X x1, v1;          // intermediate state
  Mat2X xs, vs;          // running sums
  void resize(Eigen::Index n) {
    for (Mat2X* m : {&a0, &a1, &a2, &a3, &x1, &v1, &xs, &vs}) m->resize(2, n);
  }
};

// One step of size h: advances x and v in place.
using StepFn = void (*)(const Dynamics& dyn, double h, Mat2X& x, Mat2X& v, Scratch& s);

struct Integrator {
  std::string name;         // as given to --integrator
  StepFn step;              // the step function
  int evals_per_step;       // force evaluations per step
  int order;                // global order of accuracy
  std::string description;  // one line for --help
  // Optional: throws InputError when this integrator cannot run the scene
  // (backward-euler-1 on a scene of many springs, a Newton system over its
  // limit); returns a warning sentence when it can but slowly (empty: nothing
  // to say). Called before the first step of a run, and for every integrator
  // of a sweep before its first run.
  std::string (*check)(const Integrator& self, const Dynamics& dyn) = nullptr;
};

}  // namespace wb
