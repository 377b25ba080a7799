// The adversarial worker (fuzz/README.md, "adversary"): it takes the place of the grader's worker
// (tools/grader/cpp/worker_main.cpp, the process that holds the student's code) and answers every
// call of every graded test with values it chooses, of the right types: every output a lab
// function writes and every value it returns, the states a kernel returns, field by field.
// Nothing of a lab's code is linked. What the trusted test process does with the answers is the
// target: it must end every test passed or failed with a reason, never crash.
//
// The choice comes from WB_ADVERSARY="<mode>:<seed>" (the harness, tools/wbtools/adversary.py,
// sets it; the grader never runs this binary):
//   inf    every floating-point number +inf and -inf in turn; integers, booleans, sizes kept
//   nan    every floating-point number NaN; the rest kept
//   mixed  each number drawn from a menu (+-inf, NaN, -0, denormals, +-2^51 and 2^52, 1e300,
//          the value it had, that value one ulp off, a small random number), integers from
//          theirs (0, -1, the largest and smallest, one off), a dynamic size now and then
//          changed (0, one less, one more, 2^16), quaternions that are not rotations; and the
//          callbacks a call passes (a wb::Dynamics, force terms) called with such values
// A generated <lab>_adversary.cpp (tools/wbtools/adversary.py) supplies dispatch() and the
// labs' structs' poison() overloads, field by field.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "worker.h"

namespace wbrpc {

class Adversary {
 public:
  enum Mode { kInf, kNan, kMixed };

  static Adversary& get() {
    static Adversary a;
    return a;
  }
  Mode mode() const { return mode_; }
  std::uint64_t draw() { return gen_(); }
  bool chance(int one_in) { return gen_() % std::uint64_t(one_in) == 0; }

  double number(double old) {
    constexpr double inf = std::numeric_limits<double>::infinity();
    if (mode_ == kInf) return (flip_ = !flip_) ? inf : -inf;
    if (mode_ == kNan) return std::numeric_limits<double>::quiet_NaN();
    switch (gen_() % 16) {
      case 0:
        return inf;
      case 1:
        return -inf;
      case 2:
        return std::numeric_limits<double>::quiet_NaN();
      case 3:
        return -0.0;
      case 4:
        return std::numeric_limits<double>::denorm_min() * double(gen_() % 1000 + 1);
      case 5:
        return -std::numeric_limits<double>::min() / 3;
      case 6:
        return 0x1p51;
      case 7:
        return -0x1p51 - 0.5;
      case 8:
        return 0x1p52 + 1;
      case 9:
        return (gen_() & 1) ? 1e300 : -1e300;
      case 10:
        return std::nextafter(old, inf);
      case 11:
        return double(std::int64_t(gen_() % 2001) - 1000) / 128;
      case 12:
        return -old;
      default:
        return old;
    }
  }
  template <class I>
  I integer(I old) {
    if (mode_ != kMixed) return old;
    switch (gen_() % 10) {
      case 0:
        return I(0);
      case 1:
        return std::numeric_limits<I>::max();
      case 2:
        return std::numeric_limits<I>::min();
      case 3:
        return I(old + 1);
      case 4:
        return I(old - 1);
      case 5:
        return I(-1);
      default:
        return old;
    }
  }
  // A dynamic size: kept, or (mixed, one time in five) another one, up to 2^16.
  std::int64_t size(std::int64_t old) {
    if (mode_ != kMixed || !chance(5)) return old;
    switch (gen_() % 4) {
      case 0:
        return 0;
      case 1:
        return old > 0 ? old - 1 : 1;
      case 2:
        return old + 1;
      default:
        return 1 << 16;
    }
  }

 private:
  Adversary() {
    const char* e = std::getenv("WB_ADVERSARY");
    const std::string s = e ? e : "mixed:1";
    const std::size_t colon = s.find(':');
    const std::string m = s.substr(0, colon);
    mode_ = m == "inf" ? kInf : m == "nan" ? kNan : kMixed;
    gen_.seed(colon == std::string::npos ? 1 : std::strtoull(s.c_str() + colon + 1, nullptr, 0));
  }
  Mode mode_ = kMixed;
  bool flip_ = false;
  std::mt19937_64 gen_;
};

// ---- poison(a, v): v replaced by values the adversary chooses, of v's type.
template <class T>
void poison(Adversary&, T&) {}  // callbacks, caches, functions: nothing to send
inline void poison(Adversary& a, double& v) { v = a.number(v); }
inline void poison(Adversary& a, float& v) { v = float(a.number(v)); }
inline void poison(Adversary& a, bool& v) {
  if (a.mode() == Adversary::kMixed) v = a.draw() & 1;
}
inline void poison(Adversary& a, int& v) { v = a.integer(v); }
inline void poison(Adversary& a, long& v) { v = a.integer(v); }
inline void poison(Adversary& a, long long& v) { v = a.integer(v); }
inline void poison(Adversary& a, unsigned long& v) { v = a.integer(v); }
template <class S, int R, int C, int O, int MR, int MC>
void poison(Adversary& a, Eigen::Matrix<S, R, C, O, MR, MC>& m) {
  if constexpr (R == Eigen::Dynamic || C == Eigen::Dynamic) {
    Eigen::Index r = m.rows(), c = m.cols();
    if (R == Eigen::Dynamic) r = Eigen::Index(a.size(r));
    if (C == Eigen::Dynamic) c = Eigen::Index(a.size(c));
    if (r * c > (1 << 20)) (R == Eigen::Dynamic ? r : c) = 1;  // at most 8 MiB of doubles
    if (r != m.rows() || c != m.cols()) m.conservativeResize(r, c);
  }
  for (Eigen::Index k = 0; k < m.size(); ++k) {
    double v = double(m.data()[k]);
    poison(a, v);
    m.data()[k] = S(v);
  }
}
inline void poison(Adversary& a, Eigen::Quaterniond& q) {
  Eigen::Vector4d c = q.coeffs();
  poison(a, c);
  if (a.mode() == Adversary::kMixed && a.chance(3)) c *= 1.5;  // not a rotation
  q.coeffs() = c;
}
inline void poison(Adversary& a, Eigen::SparseMatrix<double>& m) {
  m.makeCompressed();
  if (a.mode() == Adversary::kMixed && a.chance(5)) {  // another shape, a few entries
    const Eigen::Index r = Eigen::Index(a.size(m.rows())), c = Eigen::Index(a.size(m.cols()));
    Eigen::SparseMatrix<double> n(r, c);
    for (int k = 0; k < 8 && r > 0 && c > 0; ++k)
      n.coeffRef(Eigen::Index(a.draw() % std::uint64_t(r)),
                 Eigen::Index(a.draw() % std::uint64_t(c))) = 1.0;
    n.makeCompressed();
    m = n;
  }
  for (Eigen::Index k = 0; k < m.nonZeros(); ++k) poison(a, m.valuePtr()[k]);
}
inline void poison(Adversary& a, std::string& s) {
  if (a.mode() != Adversary::kMixed) return;
  s.assign(std::size_t(a.draw() % 64), char(a.draw() % 256));
}
template <class A, class B>
void poison(Adversary& a, std::pair<A, B>& p) {
  poison(a, p.first);
  poison(a, p.second);
}
template <class T, class Al>
void poison(Adversary& a, std::vector<T, Al>& v) {
  const std::int64_t n = a.size(std::int64_t(v.size()));
  v.resize(std::size_t(std::min<std::int64_t>(n, 1 << 14)));
  for (auto& e : v) {
    T x = e;
    poison(a, x);
    e = std::move(x);
  }
}

// A callback the call passed (mixed only, now and then): called with values the adversary
// chooses, of the sizes the call has (the trusted side refuses any other) or not.
inline Eigen::Index call_particles(Adversary& a, Eigen::Index n) {
  return a.chance(4) ? Eigen::Index(a.size(n) % 70000) : n;
}
inline void provoke(Adversary& a, const ProxyDynamics& d, Eigen::Index n) {
  const Eigen::Index k = call_particles(a, n);
  wb::Mat2X x = wb::Mat2X::Zero(2, k), v = wb::Mat2X::Zero(2, k), acc = wb::Mat2X::Zero(2, k);
  poison(a, x), poison(a, v);
  x.conservativeResize(2, k), v.conservativeResize(2, k);
  try {
    d.acceleration(x, v, acc);
  } catch (const CallbackFailed&) {
  }
}
inline void provoke(Adversary& a, const ProxyForces& f, Eigen::Index n) {
  for (const auto& t : f.terms) {
    const Eigen::Index k = call_particles(a, n);
    wb::Mat2X x = wb::Mat2X::Zero(2, k), v = wb::Mat2X::Zero(2, k), out = wb::Mat2X::Zero(2, k);
    wb::VecX m = wb::VecX::Ones(k);
    poison(a, x), poison(a, v), poison(a, m);
    x.conservativeResize(2, k), v.conservativeResize(2, k), m.conservativeResize(k);
    try {
      t->add(x, v, m, out);
      (void)t->potential(x, m);
      (void)t->type();
    } catch (const CallbackFailed&) {
    }
  }
}
template <class T>
void provoke(Adversary&, const T&, Eigen::Index) {}

template <class T>
struct is_vector : std::false_type {};
template <class T, class Al>
struct is_vector<std::vector<T, Al>> : std::true_type {};

// A kernel's outputs (tests/<lab>/kernels) come empty and leave with one entry per checkpoint:
// n / every + 1 of them (its two `long` inputs), times the particles for a matrix. An empty
// output is given that shape, so that the trusted side's checks of a run's states see values
// of the right shape, not only a size it refuses.
struct Shape {
  std::vector<long> longs;
  Eigen::Index particles = -1;
  long checkpoints() const {
    return longs.size() >= 2 && longs[1] > 0 && longs[0] >= 0 && longs[0] / longs[1] < (1 << 16)
               ? longs[0] / longs[1] + 1
               : -1;
  }
};
template <class T>
void note(Shape& s, const T& v) {
  if constexpr (std::is_same_v<T, long>) s.longs.push_back(v);
  if constexpr (std::is_same_v<T, wb::Mat2X>)
    if (s.particles < 0) s.particles = v.cols();
}
template <class T>
void shape_output(const Shape& s, T& v) {
  const long k = s.checkpoints();
  if (k < 0) return;
  if constexpr (std::is_same_v<T, wb::Mat2X>) {
    if (v.cols() == 0 && s.particles > 0) v = wb::Mat2X::Zero(2, k * s.particles);
  } else if constexpr (is_vector<T>::value) {
    if (v.empty()) v.resize(std::size_t(k));
  }
}

template <class R, class... A, std::size_t... I>
void serve_adversary_impl(In& in, std::index_sequence<I...>) {
  Adversary& a = Adversary::get();
  std::tuple<typename Storage<A>::type...> args;
  (get(in, std::get<I>(args)), ...);
  Shape shape;
  (note(shape, std::get<I>(args)), ...);
  if (a.mode() == Adversary::kMixed && a.chance(3)) {
    const Eigen::Index n = shape.particles;
    (provoke(a, std::get<I>(args), n < 0 ? 3 : n), ...);
  }
  Out o;
  put(o, kResult);
  (
      [&](auto& v) {
        if constexpr (is_output_v<A>) {
          shape_output(shape, v);
          poison(a, v);
          put(o, v);
        }
      }(std::get<I>(args)),
      ...);
  if constexpr (!std::is_void_v<R>) {
    std::remove_cv_t<std::remove_reference_t<R>> r{};
    poison(a, r);
    put(o, r);
  }
  worker_channel().send(o);
}

// One call of a function of signature R(A...): read its arguments, answer with chosen outputs.
template <class Sig>
struct ServeAdversary;
template <class R, class... A>
struct ServeAdversary<R(A...)> {
  static void serve(In& in) {
    serve_adversary_impl<R, A...>(in, std::index_sequence_for<A...>{});
  }
};

}  // namespace wbrpc

// ---- The recorder (tools/adversary --inputs): a worker with the lab's own code (the
// solution's, in that scratch build) that writes, for every call, what its inputs look like
// to a file named by WB_RECORD, then serves the call as the grader's worker does. What is
// recorded: how many numbers the call carried, how many of them are short decimals (at most
// 6 significant digits), the largest magnitude, the particles (columns of its first 2 x n
// argument), and the significant digits of its short decimals, summed (a public test writes
// 0.5 and 9.81; a held-out draw must not always write 0.517). tools/wbtools/adversary.py's
// classifier asks whether these tell a public test's call from a held-out one.
namespace wbrpc {

struct Observed {
  long numbers = 0, short_decimals = 0, digits = 0;
  double largest = 0;
  Eigen::Index particles = -1;
};
// The fewest significant digits (1 to 6) that write v exactly, or 0: not a short decimal. Zero
// counts as one digit.
inline int significant_digits(double v) {
  if (!std::isfinite(v)) return 0;
  for (int d = 1; d <= 6; ++d) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.*g", d, v);
    if (std::strtod(buf, nullptr) == v) return d;
  }
  return 0;
}
template <class T>
void observe(Observed&, const T&) {}
inline void observe(Observed& o, const double& v) {
  ++o.numbers;
  const int d = significant_digits(v);
  o.short_decimals += d > 0;
  o.digits += d;
  if (std::isfinite(v)) o.largest = std::max(o.largest, std::abs(v));
}
template <class S, int R, int C, int O, int MR, int MC>
void observe(Observed& o, const Eigen::Matrix<S, R, C, O, MR, MC>& m) {
  if constexpr (std::is_same_v<Eigen::Matrix<S, R, C, O, MR, MC>, wb::Mat2X>)
    if (o.particles < 0) o.particles = m.cols();
  for (Eigen::Index k = 0; k < m.size() && k < 4096; ++k) observe(o, double(m.data()[k]));
}
inline void observe(Observed& o, const Eigen::Quaterniond& q) { observe(o, q.coeffs()); }
inline void observe(Observed& o, const Eigen::SparseMatrix<double>& m) {
  for (Eigen::Index k = 0; k < m.nonZeros() && k < 4096; ++k) observe(o, m.valuePtr()[k]);
}
template <class A, class B>
void observe(Observed& o, const std::pair<A, B>& p) {
  observe(o, p.first);
  observe(o, p.second);
}
template <class T, class Al>
void observe(Observed& o, const std::vector<T, Al>& v) {
  for (std::size_t k = 0; k < v.size() && k < 256; ++k) observe(o, v[k]);
}

template <class R, class... A, std::size_t... I>
void serve_recorded_impl(R (*fn)(A...), std::int32_t id, In& in, std::index_sequence<I...> seq) {
  std::tuple<typename Storage<A>::type...> args;
  (get(in, std::get<I>(args)), ...);
  Observed seen;
  (observe(seen, std::get<I>(args)), ...);
  if (const char* path = std::getenv("WB_RECORD")) {
    if (std::FILE* f = std::fopen(path, "a")) {
      std::fprintf(f, "%d %ld %ld %.17g %ld %ld\n", int(id), seen.numbers, seen.short_decimals,
                   seen.largest, long(seen.particles), seen.digits);
      std::fclose(f);
    }
  }
  answer(fn, args, seq);  // as the worker answers (worker.h)
}
template <class R, class... A>
void serve_recorded(R (*fn)(A...), std::int32_t id, In& in) {
  serve_recorded_impl(fn, id, in, std::index_sequence_for<A...>{});
}

}  // namespace wbrpc
