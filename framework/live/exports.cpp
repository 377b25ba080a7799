// What a live page calls (docs/live.md): plain C functions over handles of Sims, each
// catching what the lab's code throws, so that a bad knob or a work overrun becomes a
// message on the page, not a dead module. The lab registers itself on first use: its
// main() (renamed wb_live_lab_main by cmake/live.cmake) runs once.
#include <memory>
#include <string>
#include <vector>

#include "live.h"
#include "wb/input.h"

#ifdef __EMSCRIPTEN__
#include <emscripten.h>
#define WB_EXPORT extern "C" EMSCRIPTEN_KEEPALIVE
#else
#define WB_EXPORT extern "C"
#endif

int wb_live_lab_main(int argc, char** argv);

namespace {

using wb::live::Sim;

struct Slot {
  std::unique_ptr<Sim> sim;
  bool loaded = false;  // a scene was loaded: the other calls have a state to work on
  std::string error;    // the last call's failure, "" when it succeeded
  std::string status;
};

std::vector<Slot>& slots() {
  static std::vector<Slot> s;
  return s;
}

std::string& last_error() {
  static std::string e;
  return e;
}

const wb::live::LabEntry& lab() {
  static bool started = false;
  if (!started) {
    started = true;
    char name[] = "live";
    char* argv[] = {name, nullptr};
    wb_live_lab_main(1, argv);
  }
  if (wb::live::labs().empty()) throw std::logic_error("no lab registered itself");
  return wb::live::labs().front();
}

Slot* slot(int h, bool loaded = true) {
  if (h < 0 || std::size_t(h) >= slots().size()) return nullptr;
  Slot& s = slots()[std::size_t(h)];
  return s.sim && (s.loaded || !loaded) ? &s : nullptr;
}

// Runs f on slot h: 0 done, 2 bad input (wb::InputError), 1 anything else; the
// message in wb_live_error().
template <class F>
int guarded(int h, F f, bool loading = false) {
  Slot* s = slot(h, !loading);
  if (!s) {
    last_error() = "no simulation " + std::to_string(h) + " with a scene loaded";
    return 1;
  }
  try {
    f(*s->sim);
    s->error.clear();
    last_error().clear();
    return 0;
  } catch (const wb::InputError& e) {
    s->error = last_error() = e.what();
    return 2;
  } catch (const std::exception& e) {
    s->error = last_error() = std::string("internal error: ") + e.what();
    return 1;
  }
}

}  // namespace

// The lab's name, side, kind and integrators (JSON), or null if none registered.
WB_EXPORT const char* wb_live_info() {
  static std::string info;
  try {
    info = lab().info;
  } catch (const std::exception& e) {
    last_error() = e.what();
    return nullptr;
  }
  return info.c_str();
}

// A new simulation; its handle (>= 0), or -1.
WB_EXPORT int wb_live_new() {
  try {
    slots().push_back({lab().make(), false, "", ""});
  } catch (const std::exception& e) {
    last_error() = e.what();
    return -1;
  }
  return int(slots().size()) - 1;
}

// Frees a simulation (its handle is not reused).
WB_EXPORT void wb_live_delete(int h) {
  if (Slot* s = slot(h, false)) *s = Slot{};
}

WB_EXPORT int wb_live_load(int h, const char* file, const char* text) {
  const int rc = guarded(
      h, [&](Sim& s) { s.load(file, text); }, true);
  if (Slot* s = slot(h, false)) s->loaded = s->loaded || rc == 0;
  return rc;
}
WB_EXPORT int wb_live_update(int h, const char* text) {
  return guarded(h, [&](Sim& s) { s.update(text); });
}
WB_EXPORT int wb_live_reset(int h) {
  return guarded(h, [&](Sim& s) { s.reset(); });
}
WB_EXPORT int wb_live_integrator(int h, const char* name) {
  return guarded(h, [&](Sim& s) { s.set_integrator(name); });
}

// Up to n steps of size dt: the steps taken, or -1 when the lab's code threw (the
// message in wb_live_error(); the simulation keeps the state it reached).
WB_EXPORT double wb_live_step(int h, double dt, double n) {
  long taken = 0;
  const int rc = guarded(h, [&](Sim& s) { taken = s.step(dt, long(n)); });
  return rc == 0 ? double(taken) : -1.0;
}

WB_EXPORT const double* wb_live_state(int h) {
  Slot* s = slot(h);
  return s ? s->sim->state().data() : nullptr;
}
WB_EXPORT int wb_live_state_size(int h) {
  Slot* s = slot(h);
  return s ? int(s->sim->state().size()) : 0;
}
WB_EXPORT int wb_live_values_per_item(int h) {
  Slot* s = slot(h);
  return s ? s->sim->values_per_item() : 0;
}
WB_EXPORT const double* wb_live_readouts(int h) {
  Slot* s = slot(h);
  return s ? s->sim->readouts().data() : nullptr;
}
WB_EXPORT int wb_live_readout_count() { return wb::live::kCount; }
WB_EXPORT const double* wb_live_exact(int h) {
  Slot* s = slot(h);
  return s ? s->sim->exact().data() : nullptr;
}
WB_EXPORT int wb_live_exact_size(int h) {
  Slot* s = slot(h);
  return s ? int(s->sim->exact().size()) : 0;
}

WB_EXPORT void wb_live_grab(int h, int i, double x, double y, double z, double bx, double by,
                            double bz) {
  const double target[3] = {x, y, z}, at[3] = {bx, by, bz};
  guarded(h, [&](Sim& s) { s.grab(i, target, at); });
}
WB_EXPORT void wb_live_release(int h) {
  guarded(h, [&](Sim& s) { s.release(); });
}

// The run's words (JSON): integrator, steps, diverged and its step, warnings, notes,
// and the last call's error.
WB_EXPORT const char* wb_live_status(int h) {
  Slot* s = slot(h);
  if (!s) return nullptr;
  try {
    s->status = s->sim->status();
    if (!s->error.empty()) {
      s->status.pop_back();  // the object's closing brace
      s->status += ",\"error\":" + wb::json(s->error).dump() + "}";
    }
  } catch (const std::exception& e) {
    s->status = wb::json({{"error", std::string("internal error: ") + e.what()}}).dump();
  }
  return s->status.c_str();
}

WB_EXPORT const char* wb_live_error() { return last_error().c_str(); }
