// The trusted side's connection to the worker, and the callbacks it runs (client.h).
#include "client.h"

#include <csignal>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace wbrpc {

Session& session() {
  static Session* s = [] {
    const char* fds = std::getenv("WB_WORKER_FDS");
    int in = -1, out = -1;
    if (!fds || std::sscanf(fds, "%d,%d", &in, &out) != 2 || in < 0 || out < 0)
      throw std::runtime_error(
          "this test binary calls the lab's functions through the grader's worker "
          "(tools/grade): run the tests of an ordinary build instead");
    // A write to a worker that died fails with EPIPE (the worker's crash is then reported,
    // from its own status) instead of killing this process with SIGPIPE: otherwise the
    // verdict of one crash depended on whether this side was reading or writing when the
    // worker died, and the same code was reported two ways from one run to the next.
    std::signal(SIGPIPE, SIG_IGN);
    return new Session{Channel(in, out), {}, {}, {}, {}, nullptr, 0};
  }();
  return *s;
}

[[noreturn]] void worker_gone(const char* name, const std::exception& e) {
  throw std::runtime_error(std::string("the lab's code stopped answering during ") + name + " (" +
                           e.what() + "): its process crashed, called exit() or hit a limit");
}

// A function of a point: the index of a copy of it in the session's table (a value the
// worker may keep: Session::points), -1 for an empty one.
void put(Out& o, const PointFunction& f) {
  Session& s = session();
  if (!f) {
    put(o, std::int32_t(-1));
    return;
  }
  if (s.points.size() >= std::size_t(INT32_MAX))
    throw std::runtime_error("too many functions sent");
  put(o, std::int32_t(s.points.size()));
  s.points.push_back(f);
}
void get(In&, PointFunction&) { throw ProtocolError("a function sent by the worker"); }

template <class T>
static const T& checked(const std::vector<T>& table, std::int64_t id) {
  if (id < 0 || std::size_t(id) >= table.size()) throw ProtocolError("an unknown callback");
  return table[std::size_t(id)];
}

// A callback's arrays must have one column (entry) per particle of the call that passed it.
static void require_particles(const char* what, const char* name, Eigen::Index got,
                              std::int64_t n) {
  if (n < 0 || got != n)
    throw std::invalid_argument(
        std::string("the lab's code called ") + what + " with " + name + " of " +
        std::to_string(got) +
        (n < 0 ? " particles, in a call that has no particles"
               : " columns (entries), but the system has " + std::to_string(n) + " particles"));
}

void run_callback(Session& s, In& in) {
  std::int32_t what = 0, id = 0;
  get(in, what), get(in, id);
  Out o;
  put(o, kCbResult);
  try {
    if (what == 0) {  // Dynamics::acceleration
      wb::Mat2X x, v, a;
      get(in, x), get(in, v), get(in, a);
      const auto& d = checked(s.dyn, id);
      require_particles("Dynamics::acceleration", "x", x.cols(), d.n);
      require_particles("Dynamics::acceleration", "v", v.cols(), d.n);
      require_particles("Dynamics::acceleration", "a", a.cols(), d.n);
      d.what->acceleration(x, v, a);
      put(o, a);
    } else if (what == 4) {  // a function of a point
      Eigen::Matrix<double, 2, 1> x;
      get(in, x);
      put(o, checked(s.points, id)(x));
    } else {  // one term of a force list
      std::int64_t k = 0;
      get(in, k);
      const auto& entry = checked(s.forces, id);
      const auto& terms = *entry.what;
      if (k < 0 || std::size_t(k) >= terms.size()) throw ProtocolError("an unknown force term");
      const wb::Force& term = *terms[std::size_t(k)];
      wb::Mat2X x, v, f;
      wb::VecX m;
      if (what == 1) {
        get(in, x), get(in, v), get(in, m), get(in, f);
        require_particles("Force::add", "x", x.cols(), entry.n);
        require_particles("Force::add", "v", v.cols(), entry.n);
        require_particles("Force::add", "m", m.size(), entry.n);
        require_particles("Force::add", "f", f.cols(), entry.n);
        term.add(x, v, m, f);
        put(o, f);
      } else if (what == 2) {
        get(in, x), get(in, m);
        require_particles("Force::potential", "x", x.cols(), entry.n);
        require_particles("Force::potential", "m", m.size(), entry.n);
        put(o, term.potential(x, m));
      } else if (what == 3) {
        put(o, term.type());
      } else {
        throw ProtocolError("an unknown callback");
      }
    }
  } catch (const std::exception& e) {
    if (!s.callback_error) s.callback_error = std::current_exception();
    o = Out();
    put(o, kCbError), put(o, std::string(e.what()));
  } catch (...) {
    if (!s.callback_error) s.callback_error = std::current_exception();
    o = Out();
    put(o, kCbError), put(o, std::string("an exception"));
  }
  s.ch.send(o);
}

}  // namespace wbrpc
