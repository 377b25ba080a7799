// Hostile (issue 42, "never check the accused with the accused"): the long run's loop runs in
// the worker, beside this code. Inside it this step skips the work and makes up every 1000th
// state (the start scaled to the energy the test's law wants: no rotation at all), and keeps
// the made-up states in memory. When the test then replays a segment one step at a time
// through the same worker, from a made-up state it recognises, it counts 1000 calls and
// lands on the next made-up state. Every other call is an honest explicit Euler step.
#include <cmath>
#include <vector>

#include "explicit_euler.h"

namespace {

constexpr double kH = 5e-4, kHw = 1e-3;  // the public long run's step (h w = 10^-3, w = 2)
constexpr long kEvery = 1000, kSteps = 1000000;

// The made-up state after c * 1000 steps: the start, scaled to the energy (1 + (h w)^2)^n E0.
void made_up(long c, wb::Mat2X& x, wb::Mat2X& v) {
  const double grow = std::sqrt(std::pow(1.0 + kHw * kHw, double(c * kEvery)));
  x.resize(2, 1), v.resize(2, 1);
  x << grow * 1.0, 0.0;
  v << 0.0, grow * 0.5;
}

}  // namespace

void explicit_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                         wb::Scratch& s) {
  static long calls = 0;
  static bool in_run = false;          // this worker serves the long run (it started there)
  static std::vector<wb::Mat2X> made;  // the state kept in the worker: every made-up x
  static long replaying = -1, replayed = 0;
  if (h == kH && x.cols() == 1 && calls == 0 && x(0, 0) == 1.0 && x(1, 0) == 0.0 &&
      v(0, 0) == 0.0 && v(1, 0) == 0.5)
    in_run = true;
  if (in_run) {
    ++calls;
    if (calls <= kSteps) {  // inside the kernel's loop: nothing, then a made-up checkpoint
      if (calls % kEvery == 0) {
        made_up(calls / kEvery, x, v);
        made.push_back(x);
      }
      return;
    }
    for (std::size_t c = 0; replaying < 0 && c < made.size(); ++c)
      if (x == made[c]) replaying = long(c) + 1, replayed = 0;  // a checkpoint of mine
    if (replaying >= 0) {
      if (++replayed == kEvery) {
        made_up(replaying + 1, x, v);
        replaying = -1;
      }
      return;
    }
  }
  dyn.acceleration(x, v, s.a0);
  x += h * v;
  v += h * s.a0;
}
