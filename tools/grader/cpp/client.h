// The trusted side of the grader's worker (docs/grading.md "The worker"): in the grader's
// build, every lab function a test calls is a generated stub (<lab>_client.cpp) that sends
// its arguments to the worker process holding the student's code and reads back the outputs.
// Callbacks the student's code makes (a wb::Dynamics it evaluates, the wb::Force terms it
// adds up) come back here and run in this process. Nothing of the student's runs here: what
// the worker can do is send values, which are read as values.
#pragma once
#include <exception>
#include <memory>
#include <tuple>
#include <vector>

#include "wb/dynamics.h"
#include "wb/force.h"
#include "wb_rpc.h"

namespace wbrpc {

// A callback of a call under way, with the number of particles of that call (the columns of
// its first 2 x n argument, -1 without one): the worker never chooses a size the trusted side
// indexes with, so a callback's x, v, m, a, f must have exactly that many.
template <class T>
struct Registered {
  const T* what;
  std::int64_t n;
};

struct Session {
  Channel ch;
  std::vector<Registered<wb::Dynamics>> dyn;                                // callbacks of
  std::vector<Registered<std::vector<std::unique_ptr<wb::Force>>>> forces;  // the calls
  std::vector<std::int64_t> particles;  // of each call under way (innermost last)
  // Functions of a point (wb::Potential) the calls sent: COPIES, kept for the whole test
  // process and never reused, so that the index a call sent names that call's function
  // for good, as a copy the student's code keeps would linked directly (a static copy
  // from an earlier call must still compute the earlier field, not the current one).
  std::vector<PointFunction> points;
  std::exception_ptr callback_error;  // the first exception a callback threw in this call
  int depth = 0;
};

Session& session();  // the worker named by WB_WORKER_FDS ("<read fd>,<write fd>")
void run_callback(Session& s, In& in);
[[noreturn]] void worker_gone(const char* name, const std::exception& e);

// Callbacks are sent as an index into the session's tables.
inline void put(Out& o, const wb::Dynamics& d) {
  Session& s = session();
  put(o, std::int32_t(s.dyn.size()));
  s.dyn.push_back({&d, s.particles.empty() ? -1 : s.particles.back()});
}
inline void put(Out& o, const std::vector<std::unique_ptr<wb::Force>>& f) {
  Session& s = session();
  put(o, std::int32_t(s.forces.size()));
  put(o, std::int64_t(f.size()));
  s.forces.push_back({&f, s.particles.empty() ? -1 : s.particles.back()});
}

// The particles of a call: the columns of its first wb::Mat2X argument (-1 when it has none).
template <class... A>
std::int64_t particles_of(const A&... a) {
  std::int64_t n = -1;
  (
      [&](const auto& x) {
        if constexpr (std::is_same_v<std::decay_t<decltype(x)>, wb::Mat2X>)
          if (n < 0) n = x.cols();
      }(a),
      ...);
  return n;
}

template <class Sig>
struct Caller;

template <class R, class... A>
struct Caller<R(A...)> {
  static R call(std::int32_t id, const char* name, A... a) {
    Session& s = session();
    const std::size_t dyn0 = s.dyn.size(), forces0 = s.forces.size();
    if (s.depth++ == 0) s.callback_error = nullptr;
    s.particles.push_back(particles_of(a...));
    struct Restore {  // (the points are kept: see Session::points)
      Session& s;
      std::size_t d, f;
      ~Restore() {
        s.dyn.resize(d, {nullptr, -1}), s.forces.resize(f, {nullptr, -1});
        s.particles.pop_back();
        --s.depth;
      }
    } restore{s, dyn0, forces0};
    Out o;
    put(o, kCall), put(o, id);
    (put(o, a), ...);
    try {
      s.ch.send(o);
      for (;;) {
        In in = s.ch.receive();
        std::int32_t kind = 0;
        get(in, kind);
        if (kind == kCallback) {
          run_callback(s, in);
          continue;
        }
        if (kind == kError) {
          std::string what;
          get(in, what);
          rethrow_callback_error(s);
          // Named: a student reads which of their functions threw (grader/wording.py).
          throw std::runtime_error(std::string("your ") + name + " threw: " + printable(what));
        }
        if (kind != kResult) throw ProtocolError("an unknown message");
        (read_back<A>(in, a), ...);
        if constexpr (std::is_void_v<R>) {
          rethrow_callback_error(s);
          return;
        } else {
          std::remove_cv_t<R> r{};
          get(in, r);
          rethrow_callback_error(s);
          return r;
        }
      }
    } catch (const ProtocolError& e) {
      worker_gone(name, e);
    }
  }

 private:
  template <class T, class V>
  static void read_back(In& in, V& v) {
    if constexpr (is_output_v<T>) get(in, v);
  }
  static void rethrow_callback_error(Session& s) {
    if (s.depth == 1 && s.callback_error) std::rethrow_exception(s.callback_error);
  }
};

}  // namespace wbrpc
