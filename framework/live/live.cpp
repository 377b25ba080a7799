// The live simulation's parts shared by every lab (live.h): the labs registered, the
// run contract's bookkeeping of a live run, the cursor's spring and the status text.
#include "live.h"

#include <cmath>

#include "wb/input.h"

namespace wb::live {

namespace {
std::vector<LabEntry>& registry() {
  static std::vector<LabEntry> r;
  return r;
}
}  // namespace

void add_lab(LabEntry e) { registry().push_back(std::move(e)); }
const std::vector<LabEntry>& labs() { return registry(); }

bool Contract::after_step(double h, bool finite, double energy) {
  ++steps;
  t += h;
  if (!diverges(finite, finite ? energy : NAN, scale)) return true;
  diverged = divergence(finite, finite ? energy : NAN, scale, steps);
  diverged_at = steps;
  return false;
}

void Contract::check_unconverged(long unconverged) {
  if (!diverged.empty()) return;
  diverged = unconverged_divergence(steps, unconverged);
  if (!diverged.empty()) diverged_at = steps;
}

void grab_coefficients(double h, double m, double& gamma, double& beta) {
  const double w = 2.0 * M_PI * kGrabHz;
  const double k = m * w * w, d = 2.0 * m * kGrabDamping * w;
  const double g = h * (d + h * k);
  gamma = g > 0 ? 1.0 / g : 0.0;
  beta = h * k * gamma;
}

std::string status_json(const Contract& c, const std::string& integrator,
                        const std::vector<std::string>& warnings,
                        const std::vector<std::string>& notes, const std::string& error) {
  json j;
  j["integrator"] = integrator;
  j["steps"] = c.steps;
  j["t"] = c.t;
  j["scale"] = c.scale;
  if (!c.diverged.empty()) {
    j["diverged"] = c.diverged;
    j["diverged_at"] = c.diverged_at;
  }
  j["warnings"] = warnings;
  j["notes"] = notes;
  if (!error.empty()) j["error"] = error;
  return j.dump(-1, ' ', false, json::error_handler_t::replace);
}

}  // namespace wb::live
