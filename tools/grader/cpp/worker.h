// The worker: the process that holds the student's code (docs/grading.md "The worker"). It
// reads a call, runs the lab's function on the arguments, and sends back the outputs; a
// callback the function makes (a wb::Dynamics, a wb::Force) is sent to the trusted test
// process, which runs it and answers. The worker runs in the sandbox; whatever it does, the
// test process only reads values from it.
#pragma once
#include <memory>
#include <tuple>
#include <utility>
#include <vector>

#include "wb/dynamics.h"
#include "wb/force.h"
#include "wb_rpc.h"

namespace wbrpc {

Channel& worker_channel();
void dispatch(std::int32_t id, In& in);  // generated: <lab>_worker.cpp
void handle_call(In& in);                // runs one call, answers kResult or kError
In wait_callback();                      // the answer to a callback (serving nested calls)

struct CallbackFailed : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A wb::Dynamics whose evaluations run in the test process.
class ProxyDynamics : public wb::Dynamics {
 public:
  std::int32_t id = -1;

 protected:
  void eval(const wb::Mat2X& x, const wb::Mat2X& v, wb::Mat2X& a) const override {
    Out o;
    put(o, kCallback), put(o, std::int32_t(0)), put(o, id);
    put(o, x), put(o, v), put(o, a);
    worker_channel().send(o);
    In in = wait_callback();
    get(in, a);
  }
};
inline void get(In& in, ProxyDynamics& d) { get(in, d.id); }

class ProxyForce : public wb::Force {
 public:
  ProxyForce(std::int32_t id, std::int64_t k) : id_(id), k_(k) {}
  void add(const wb::Mat2X& x, const wb::Mat2X& v, const wb::VecX& m,
           wb::Mat2X& f) const override {
    Out o = start(1);
    put(o, x), put(o, v), put(o, m), put(o, f);
    worker_channel().send(o);
    In in = wait_callback();
    get(in, f);
  }
  double potential(const wb::Mat2X& x, const wb::VecX& m) const override {
    Out o = start(2);
    put(o, x), put(o, m);
    worker_channel().send(o);
    In in = wait_callback();
    double e = 0;
    get(in, e);
    return e;
  }
  std::string type() const override {
    Out o = start(3);
    worker_channel().send(o);
    In in = wait_callback();
    std::string t;
    get(in, t);
    return t;
  }

 private:
  Out start(std::int32_t what) const {
    Out o;
    put(o, kCallback), put(o, what), put(o, id_), put(o, k_);
    return o;
  }
  std::int32_t id_;
  std::int64_t k_;
};

struct ProxyForces {
  std::vector<std::unique_ptr<wb::Force>> terms;
  operator const std::vector<std::unique_ptr<wb::Force>>&() const { return terms; }
};
inline void get(In& in, ProxyForces& f) {
  std::int32_t id = 0;
  std::int64_t n = 0;
  get(in, id), get(in, n);
  check_count(in, 0, 0);
  if (n < 0 || n > 4096) throw ProtocolError("too many force terms");
  f.terms.clear();
  for (std::int64_t k = 0; k < n; ++k) f.terms.push_back(std::make_unique<ProxyForce>(id, k));
}

// What the worker holds for a parameter of type A while the call runs.
template <class A>
struct Storage {
  using type = std::remove_cv_t<std::remove_reference_t<A>>;
};
template <>
struct Storage<const wb::Dynamics&> {
  using type = ProxyDynamics;
};
template <>
struct Storage<const std::vector<std::unique_ptr<wb::Force>>&> {
  using type = ProxyForces;
};

template <class A, class V>
void put_output(Out& o, const V& v) {
  if constexpr (is_output_v<A>) put(o, v);
}

// Runs fn on the arguments already read and sends back its outputs and its result. The
// adversary's recording serve (fuzz/adversary/adversary.h) reads and observes the arguments
// first, then answers through this same function.
template <class R, class... A, std::size_t... I>
void answer(R (*fn)(A...), std::tuple<typename Storage<A>::type...>& args,
            std::index_sequence<I...>) {
  Out o;
  put(o, kResult);
  if constexpr (std::is_void_v<R>) {
    fn(std::get<I>(args)...);
    (put_output<A>(o, std::get<I>(args)), ...);
  } else {
    const std::remove_cv_t<R> r = fn(std::get<I>(args)...);
    (put_output<A>(o, std::get<I>(args)), ...);
    put(o, r);
  }
  worker_channel().send(o);
}

template <class R, class... A, std::size_t... I>
void serve_impl(R (*fn)(A...), In& in, std::index_sequence<I...> seq) {
  std::tuple<typename Storage<A>::type...> args;
  (get(in, std::get<I>(args)), ...);
  answer(fn, args, seq);
}

template <class R, class... A>
void serve(R (*fn)(A...), In& in) {
  serve_impl(fn, in, std::index_sequence_for<A...>{});
}

}  // namespace wbrpc
