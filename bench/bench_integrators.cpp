// Integrator throughput: every step function driven through the scene machinery
// (wb::ParticleDynamics over the forces lab's solution), against hand-written
// loops on plain arrays and a STREAM-style memory-bandwidth bound measured in
// the same run. bench/summarize.py turns the JSON output into ratios;
// docs/benchmarks.md explains every number.
//
// The system: n particles under uniform gravity g and viscous damping b, so
//   a_i = (m_i g - b v_i) / m_i.
// Three ways to take one step of each integrator:
//   scene/<integrator>/<n>        the integrator's wb::StepFn on wb::ParticleDynamics
//   hand_passes/<integrator>/<n>  the same passes over memory on std::vector<double>
//                                 (zero f, f += m g, f -= b v, a = f / m, then the
//                                 integrator's updates): the ratio scene / hand_passes
//                                 is the cost of the machinery and nothing else
//   hand_fused/<integrator>/<n>   one pass per step, everything in registers
//                                 (a = g - (b/m) v): the best one can do
// A scene's whole run and what its loop adds (docs/benchmarks.md, "The run loop"):
//   run/<integrator>/<n>          wb::simulate: the run contract's loop, timed by the
//                                 run's own step-loop clock (counter step_loop_cpu_s)
//   loop_check[_separate]/<n>     the loop's per-step bookkeeping alone (one pass, or
//                                 as before issue 34)
//   blocks_nosums/rk4/<n>         rk4 by blocks without the bookkeeping's sums
//   bookkeeping/rk4/<n>           steps without the sums and steps with them and the
//                                 loop's check, alternately: their paired share
//   odeint_fused/rk4/<n>          a plain Boost.Odeint runge_kutta4_classic program
//                                 with a fused right-hand side
// and two bandwidth measurements (a[i] = b[i] + s c[i]):
//   triad_dram/<len>   arrays far larger than the caches: the bound's bandwidth
//   triad_fit/<len>    arrays of 3n doubles, the footprint of one step at n
//                      particles: what that footprint streams at when it fits
//                      in a cache level
//
// Layout of the plain arrays: interleaved [x0 y0 x1 y1 ...], exactly Eigen's
// column-major 2 x n, so the baselines move the same bytes in the same order
// as the machinery and the ratio does not mix in a layout change (SoA would).
//
// Every heap allocation in the process is counted (malloc and friends, and
// operator new): after one warm-up step a step must allocate nothing, which
// is checked on every timed loop and fails the run with a clear message.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <new>
#include <string>
#include <vector>

#include "forces_world.h"
#include "wb/dynamics.h"
#include "wb/run.h"
#include "wb/scene.h"
#include "wb/semi_implicit.h"
#ifdef WB_BENCH_HAS_EULER
#include "explicit_euler.h"
#include "symplectic_euler.h"
#endif
#ifdef WB_BENCH_HAS_MIDPOINT
#include "midpoint.h"
#include "trapezoid.h"
#endif
#ifdef WB_BENCH_HAS_RK4
#include <boost/numeric/odeint/algebra/default_operations.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta4.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta4_classic.hpp>
#include <boost/numeric/odeint/util/is_resizeable.hpp>
#include <boost/numeric/odeint/util/resize.hpp>
#include <boost/numeric/odeint/util/same_size.hpp>

#include "wb/rk4.h"

// Boost.Odeint's runge_kutta4 on the same particles and forces (odeint/rk4/<n>).
// Its state is the machinery's: positions and velocities, two 2 x n Eigen
// arrays, and its system calls the same wb::Dynamics. The algebra applies each
// of odeint's operations (default_operations' scale_sum2..scale_sum5) to the
// positions and to the velocities: one Eigen loop each, as odeint's
// vector_space_algebra would on one Eigen vector.
namespace odebench {
struct State {
  wb::Mat2X x, v;
};
struct Algebra {
  template <class Op, class... S>
  static void apply(Op op, S&... s) {
    op(s.x...);
    op(s.v...);
  }
  template <class S1, class S2, class Op>
  static void for_each2(S1& a, S2& b, Op op) {
    apply(op, a, b);
  }
  template <class S1, class S2, class S3, class Op>
  static void for_each3(S1& a, S2& b, S3& c, Op op) {
    apply(op, a, b, c);
  }
  template <class S1, class S2, class S3, class S4, class Op>
  static void for_each4(S1& a, S2& b, S3& c, S4& d, Op op) {
    apply(op, a, b, c, d);
  }
  template <class S1, class S2, class S3, class S4, class S5, class Op>
  static void for_each5(S1& a, S2& b, S3& c, S4& d, S5& e, Op op) {
    apply(op, a, b, c, d, e);
  }
  template <class S1, class S2, class S3, class S4, class S5, class S6, class Op>
  static void for_each6(S1& a, S2& b, S3& c, S4& d, S5& e, S6& f, Op op) {
    apply(op, a, b, c, d, e, f);
  }
};
using Stepper = boost::numeric::odeint::runge_kutta4<State, double, State, double, Algebra,
                                                     boost::numeric::odeint::default_operations>;
}  // namespace odebench

namespace boost::numeric::odeint {
template <>
struct is_resizeable<odebench::State> : boost::true_type {};
template <>
struct same_size_impl<odebench::State, odebench::State> {
  static bool same_size(const odebench::State& a, const odebench::State& b) {
    return a.x.cols() == b.x.cols() && a.v.cols() == b.v.cols();
  }
};
template <>
struct resize_impl<odebench::State, odebench::State> {
  static void resize(odebench::State& a, const odebench::State& b) {
    a.x.resize(2, b.x.cols());
    a.v.resize(2, b.v.cols());
  }
};
}  // namespace boost::numeric::odeint
#endif

// ---------------------------------------------------------------------------
// Allocation counting.
//
// Eigen allocates through std::malloc, not operator new, so counting only
// operator new would miss an Eigen temporary. With glibc the binary replaces
// malloc, calloc, realloc, free and the aligned variants (glibc supports this,
// and exports __libc_malloc & co. for the replacements to call); operator new
// is replaced too and forwards to malloc, so each allocation counts once.
// Elsewhere only operator new is counted (the program says which in its
// context line "wb_allocation_counting").
namespace {
std::atomic<long> g_allocs{0};  // heap allocations since program start
void count_alloc() { g_allocs.fetch_add(1, std::memory_order_relaxed); }
}  // namespace

// Not under AddressSanitizer, which supplies its own malloc.
#if defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__)
#define WB_COUNT_MALLOC 1
extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* __libc_memalign(std::size_t, std::size_t);
void __libc_free(void*);

void* malloc(std::size_t size) noexcept {
  count_alloc();
  return __libc_malloc(size);
}
void* calloc(std::size_t count, std::size_t size) noexcept {
  count_alloc();
  return __libc_calloc(count, size);
}
void* realloc(void* p, std::size_t size) noexcept {
  count_alloc();
  return __libc_realloc(p, size);
}
void* memalign(std::size_t alignment, std::size_t size) noexcept {
  count_alloc();
  return __libc_memalign(alignment, size);
}
void* aligned_alloc(std::size_t alignment, std::size_t size) noexcept {
  count_alloc();
  return __libc_memalign(alignment, size);
}
int posix_memalign(void** out, std::size_t alignment, std::size_t size) noexcept {
  if (alignment % sizeof(void*) != 0 || (alignment & (alignment - 1)) != 0) return EINVAL;
  count_alloc();
  void* p = __libc_memalign(alignment, size);
  if (!p) return ENOMEM;
  *out = p;
  return 0;
}
void free(void* p) noexcept { __libc_free(p); }
}  // extern "C"
#else
#define WB_COUNT_MALLOC 0
#endif

namespace {
void* counted_new(std::size_t size, std::size_t alignment) {
  if (!WB_COUNT_MALLOC) count_alloc();
  if (size == 0) size = 1;
  void* p = nullptr;
  if (alignment <= alignof(std::max_align_t)) {
    p = std::malloc(size);
  } else if (posix_memalign(&p, alignment, size) != 0) {
    p = nullptr;
  }
  if (!p) throw std::bad_alloc();
  return p;
}
void* counted_new_nothrow(std::size_t size, std::size_t alignment) noexcept {
  try {
    return counted_new(size, alignment);
  } catch (const std::bad_alloc&) {
    return nullptr;
  }
}
}  // namespace

void* operator new(std::size_t n) { return counted_new(n, 0); }
void* operator new[](std::size_t n) { return counted_new(n, 0); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  return counted_new_nothrow(n, 0);
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept {
  return counted_new_nothrow(n, 0);
}
void* operator new(std::size_t n, std::align_val_t a) { return counted_new(n, std::size_t(a)); }
void* operator new[](std::size_t n, std::align_val_t a) { return counted_new(n, std::size_t(a)); }
void* operator new(std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return counted_new_nothrow(n, std::size_t(a));
}
void* operator new[](std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return counted_new_nothrow(n, std::size_t(a));
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept {
  std::free(p);
}

namespace {

long allocations() { return g_allocs.load(std::memory_order_relaxed); }

// ---------------------------------------------------------------------------
// The system being stepped.

constexpr double kGx = 0.0, kGy = -9.81;  // gravity (m/s^2)
constexpr double kB = 0.1;                // damping (kg/s)
constexpr double kH = 1e-3;               // step (s)
// Bytes one step must move at the least, per particle: read x, v (2 doubles
// each) and one per-particle mass term, write x and v back.
constexpr double kBoundBytesPerParticle = 8.0 * (2 + 2 + 1 + 2 + 2);

const char* const kForcesJson =
    R"({"forces":[{"type":"gravity","g":[0,-9.81]},{"type":"damping","b":0.1}]})";

// A deterministic stream of doubles in [0, 1) (splitmix64).
struct Rng {
  std::uint64_t s;
  double next() {
    std::uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return wb::unit_double(z ^ (z >> 31));
  }
};

// n particles scattered over a 100 m square, speeds up to 5 m/s, masses 0.5..1.5 kg.
wb::Scene make_scene(Eigen::Index n) {
  wb::Scene s;
  s.file = "<bench_integrators>";
  s.name = "bench";
  s.x.resize(2, n);
  s.v.resize(2, n);
  s.m.resize(n);
  s.radius = wb::VecX::Zero(n);
  Rng rng{12345};
  for (Eigen::Index i = 0; i < n; ++i) {
    s.x.col(i) = wb::Vec2(100 * rng.next(), 100 * rng.next());
    s.v.col(i) = wb::Vec2(10 * rng.next() - 5, 10 * rng.next() - 5);
    s.m[i] = 0.5 + rng.next();
  }
  s.doc = wb::json::parse(kForcesJson);
  return s;
}

// The same particles on plain arrays, interleaved like Eigen's 2 x n, with
// work arrays that mirror wb::Scratch.
struct Arrays {
  long n = 0;
  std::vector<double> x, v;            // 2n: positions, velocities
  std::vector<double> m, inv_m;        // n: masses and their inverses
  std::vector<double> f;               // 2n: force accumulator (ParticleDynamics::f_)
  std::vector<double> a0, a1, a2, a3;  // 2n: accelerations
  std::vector<double> x1, v1, xs, vs;  // 2n: intermediate state, running sums
  explicit Arrays(const wb::Scene& s) : n(long(s.n())) {
    x.assign(s.x.data(), s.x.data() + 2 * n);
    v.assign(s.v.data(), s.v.data() + 2 * n);
    m.assign(s.m.data(), s.m.data() + n);
    for (double mi : m) inv_m.push_back(1.0 / mi);
    for (auto* w : {&f, &a0, &a1, &a2, &a3, &x1, &v1, &xs, &vs}) w->assign(2 * n, 0.0);
  }
};

// ---------------------------------------------------------------------------
// Hand-written passes. Each is one loop over memory, kept out of line so the
// compiler cannot fuse neighbouring passes: one function here is one Eigen
// statement in the machinery. Their arrays never overlap, and __restrict says
// so, as Eigen assumes for these expressions (no runtime overlap checks).
#define WB_PASS __attribute__((noinline))

WB_PASS void pass_zero(double* __restrict f, long len) {
  for (long k = 0; k < len; ++k) f[k] = 0.0;
}
// f_i += m_i g   (add_uniform_gravity)
WB_PASS void pass_add_gravity(double* __restrict f, const double* __restrict m, long n) {
  for (long i = 0; i < n; ++i) {
    f[2 * i] += kGx * m[i];
    f[2 * i + 1] += kGy * m[i];
  }
}
// f -= b v   (add_damping)
WB_PASS void pass_add_damping(double* __restrict f, const double* __restrict v, long len) {
  for (long k = 0; k < len; ++k) f[k] -= kB * v[k];
}
// a_i = f_i / m_i, as ParticleDynamics does it: times the stored inverse mass
WB_PASS void pass_divide_by_mass(double* __restrict a, const double* __restrict f,
                                 const double* __restrict inv_m, long n) {
  for (long i = 0; i < n; ++i) {
    a[2 * i] = f[2 * i] * inv_m[i];
    a[2 * i + 1] = f[2 * i + 1] * inv_m[i];
  }
}
// y += s u
WB_PASS void pass_axpy(double* __restrict y, double s, const double* __restrict u, long len) {
  for (long k = 0; k < len; ++k) y[k] += s * u[k];
}
// out = y + s u
WB_PASS void pass_waxpy(double* __restrict out, const double* __restrict y, double s,
                        const double* __restrict u, long len) {
  for (long k = 0; k < len; ++k) out[k] = y[k] + s * u[k];
}

// One force evaluation, pass by pass: ParticleDynamics::eval with the
// solution's accumulate_forces, add_uniform_gravity and add_damping.
void hand_acceleration(Arrays& A, const double* v, double* a) {
  pass_zero(A.f.data(), 2 * A.n);
  pass_add_gravity(A.f.data(), A.m.data(), A.n);
  pass_add_damping(A.f.data(), v, 2 * A.n);
  pass_divide_by_mass(a, A.f.data(), A.inv_m.data(), A.n);
}

// out = 0.5 (p + q)
WB_PASS void pass_average(double* __restrict out, const double* __restrict p,
                          const double* __restrict q, long len) {
  for (long k = 0; k < len; ++k) out[k] = 0.5 * (p[k] + q[k]);
}

// The fused loops: particle i's two coordinates are independent under gravity
// and damping (a = g - c v with c = b / m_i), so one pass can take the whole
// step of every coordinate in registers. `step(g, c, x, v)` advances one.
template <class Step>
void fused_loop(Arrays& A, Step step) {
  double* x = A.x.data();
  double* v = A.v.data();
  const double* inv_m = A.inv_m.data();
  for (long i = 0; i < A.n; ++i) {
    const double c = kB * inv_m[i];  // damping rate b/m (1/s)
    step(kGx, c, x[2 * i], v[2 * i]);
    step(kGy, c, x[2 * i + 1], v[2 * i + 1]);
  }
}

// ---------------------------------------------------------------------------
// The integrators. For each: the step through the machinery, the same passes
// on arrays (one per Eigen statement of the step function, in its order), and
// the fused loop. check_baselines() keeps the passes honest: a step function
// that changes without its passes here fails the run.

// symplectic Euler: v += h a(x, v); x += h v (the new v)
#ifdef WB_BENCH_HAS_EULER
const wb::StepFn kSymplecticEuler = symplectic_euler_step;
const char* const kSymplecticEulerSource = "solutions/euler";
#else
const wb::StepFn kSymplecticEuler = wb::semi_implicit_euler_step;
const char* const kSymplecticEulerSource = "framework/src/semi_implicit.cpp";
#endif

void symplectic_passes(Arrays& A, double h) {
  const long len = 2 * A.n;
  hand_acceleration(A, A.v.data(), A.a0.data());
  pass_axpy(A.v.data(), h, A.a0.data(), len);
  pass_axpy(A.x.data(), h, A.v.data(), len);
}
WB_PASS void symplectic_fused(Arrays& A, double h) {
  fused_loop(A, [h](double g, double c, double& x, double& v) {
    v += h * (g - c * v);
    x += h * v;
  });
}

#ifdef WB_BENCH_HAS_EULER
// explicit Euler: a0 = a(x, v); x += h v (the old v); v += h a0
void explicit_passes(Arrays& A, double h) {
  const long len = 2 * A.n;
  hand_acceleration(A, A.v.data(), A.a0.data());
  pass_axpy(A.x.data(), h, A.v.data(), len);
  pass_axpy(A.v.data(), h, A.a0.data(), len);
}
WB_PASS void explicit_fused(Arrays& A, double h) {
  fused_loop(A, [h](double g, double c, double& x, double& v) {
    const double a0 = g - c * v;
    x += h * v;
    v += h * a0;
  });
}
#endif

#ifdef WB_BENCH_HAS_MIDPOINT
// midpoint: a0 = a(x, v); x1 = x + h/2 v; v1 = v + h/2 a0; a1 = a(x1, v1);
// x += h v1; v += h a1
void midpoint_passes(Arrays& A, double h) {
  const long len = 2 * A.n;
  hand_acceleration(A, A.v.data(), A.a0.data());
  pass_waxpy(A.x1.data(), A.x.data(), 0.5 * h, A.v.data(), len);
  pass_waxpy(A.v1.data(), A.v.data(), 0.5 * h, A.a0.data(), len);
  hand_acceleration(A, A.v1.data(), A.a1.data());
  pass_axpy(A.x.data(), h, A.v1.data(), len);
  pass_axpy(A.v.data(), h, A.a1.data(), len);
}
WB_PASS void midpoint_fused(Arrays& A, double h) {
  fused_loop(A, [h](double g, double c, double& x, double& v) {
    const double v1 = v + 0.5 * h * (g - c * v);
    x += h * v1;
    v += h * (g - c * v1);
  });
}

// trapezoid: a0 = a(x, v); (x1, v1) = (x, v) + h (v, a0); a1 = a(x1, v1);
// (xs, vs) = (x, v) + h (v1, a1); (x, v) = average of (x1, v1) and (xs, vs)
void trapezoid_passes(Arrays& A, double h) {
  const long len = 2 * A.n;
  hand_acceleration(A, A.v.data(), A.a0.data());
  pass_waxpy(A.x1.data(), A.x.data(), h, A.v.data(), len);
  pass_waxpy(A.v1.data(), A.v.data(), h, A.a0.data(), len);
  hand_acceleration(A, A.v1.data(), A.a1.data());
  pass_waxpy(A.xs.data(), A.x.data(), h, A.v1.data(), len);
  pass_waxpy(A.vs.data(), A.v.data(), h, A.a1.data(), len);
  pass_average(A.x.data(), A.x1.data(), A.xs.data(), len);
  pass_average(A.v.data(), A.v1.data(), A.vs.data(), len);
}
WB_PASS void trapezoid_fused(Arrays& A, double h) {
  fused_loop(A, [h](double g, double c, double& x, double& v) {
    const double xa = x + h * v, va = v + h * (g - c * v);
    const double xb = x + h * va, vb = v + h * (g - c * va);
    x = 0.5 * (xa + xb);
    v = 0.5 * (va + vb);
  });
}
#endif

#ifdef WB_BENCH_HAS_RK4
// out = (y + s u) + t w
WB_PASS void pass_waxpy2(double* __restrict out, const double* __restrict y, double s,
                         const double* __restrict u, double t, const double* __restrict w,
                         long len) {
  for (long k = 0; k < len; ++k) out[k] = y[k] + s * u[k] + t * w[k];
}
// x += h v + c ((a0 + a1) + a2)   (rk4's position update)
WB_PASS void pass_rk4_x(double* __restrict x, double h, const double* __restrict v, double c,
                        const double* __restrict a0, const double* __restrict a1,
                        const double* __restrict a2, long len) {
  for (long k = 0; k < len; ++k) x[k] += h * v[k] + c * (a0[k] + a1[k] + a2[k]);
}
// v += c (((a0 + 2 a1) + 2 a2) + a3)   (rk4's velocity update)
WB_PASS void pass_rk4_v(double* __restrict v, double c, const double* __restrict a0,
                        const double* __restrict a1, const double* __restrict a2,
                        const double* __restrict a3, long len) {
  for (long k = 0; k < len; ++k) v[k] += c * (a0[k] + 2.0 * a1[k] + 2.0 * a2[k] + a3[k]);
}
// classic RK4 as wb::rk4_step writes it: stage points from x, v and the
// accelerations (the position slopes are velocities), one pass per statement
void rk4_passes(Arrays& A, double h) {
  const long len = 2 * A.n;
  const double h2 = 0.5 * h, hh4 = 0.25 * h * h, hh2 = 0.5 * h * h;
  double *x = A.x.data(), *v = A.v.data(), *x1 = A.x1.data(), *v1 = A.v1.data();
  double *a0 = A.a0.data(), *a1 = A.a1.data(), *a2 = A.a2.data(), *a3 = A.a3.data();
  hand_acceleration(A, v, a0);
  pass_waxpy(x1, x, h2, v, len);
  pass_waxpy(v1, v, h2, a0, len);
  hand_acceleration(A, v1, a1);
  pass_waxpy2(x1, x, h2, v, hh4, a0, len);
  pass_waxpy(v1, v, h2, a1, len);
  hand_acceleration(A, v1, a2);
  pass_waxpy2(x1, x, h, v, hh2, a1, len);
  pass_waxpy(v1, v, h, a2, len);
  hand_acceleration(A, v1, a3);
  pass_rk4_x(x, h, v, h * h / 6.0, a0, a1, a2, len);
  pass_rk4_v(v, h / 6.0, a0, a1, a2, a3, len);
}
WB_PASS void rk4_fused(Arrays& A, double h) {
  fused_loop(A, [h](double g, double c, double& x, double& v) {
    const double a1 = g - c * v;
    const double v2 = v + 0.5 * h * a1, a2 = g - c * v2;
    const double v3 = v + 0.5 * h * a2, a3 = g - c * v3;
    const double v4 = v + h * a3, a4 = g - c * v4;
    x += (h / 6.0) * (v + 2.0 * v2 + 2.0 * v3 + v4);
    v += (h / 6.0) * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
  });
}
#endif

// ---------------------------------------------------------------------------
// The table of integrators timed in this build, in teaching order.

using HandFn = void (*)(Arrays& A, double h);

struct Method {
  const char* name;    // as given to --integrator
  const char* source;  // where its step function comes from
  wb::StepFn step;     // through the machinery
  HandFn passes;       // the same passes on plain arrays
  HandFn fused;        // one fused pass
};

std::vector<Method> methods() {
  std::vector<Method> out;
#ifdef WB_BENCH_HAS_EULER
  out.push_back({"explicit-euler", "solutions/euler", explicit_euler_step, explicit_passes,
                 explicit_fused});
#endif
  out.push_back({"symplectic-euler", kSymplecticEulerSource, kSymplecticEuler, symplectic_passes,
                 symplectic_fused});
#ifdef WB_BENCH_HAS_MIDPOINT
  out.push_back(
      {"midpoint", "solutions/midpoint", midpoint_step, midpoint_passes, midpoint_fused});
  out.push_back(
      {"trapezoid", "solutions/midpoint", trapezoid_step, trapezoid_passes, trapezoid_fused});
#endif
#ifdef WB_BENCH_HAS_RK4
  out.push_back({"rk4", "framework/src/rk4.cpp", wb::rk4_step, rk4_passes, rk4_fused});
#endif
  return out;
}

// ---------------------------------------------------------------------------
// Benchmarks.

bool g_alloc_failure = false;  // some step allocated after its warm-up step

// evals < 0: not counted (the hand loops).
void report(benchmark::State& st, const std::string& what, long n, long allocs, long evals) {
  const double steps = double(st.iterations());
  st.SetItemsProcessed(st.iterations() * n);  // particle-steps
  st.counters["n"] = double(n);
  st.counters["allocs_per_step"] = steps > 0 ? allocs / steps : 0.0;
  if (evals >= 0) st.counters["evals_per_step"] = steps > 0 ? evals / steps : 0.0;
  st.counters["bound_bytes"] = kBoundBytesPerParticle * double(n);
  if (allocs != 0) {
    g_alloc_failure = true;
    std::fprintf(stderr,
                 "FAIL: %s made %ld heap allocations in %lld timed steps after the warm-up step; "
                 "a step must allocate nothing (use the wb::Scratch arrays)\n",
                 (what + "/" + std::to_string(n)).c_str(), allocs,
                 static_cast<long long>(st.iterations()));
    st.SkipWithError("heap allocation inside a step (see stderr)");
  }
}

void bm_scene(benchmark::State& st, const Method& method) {
  const long n = long(st.range(0));
  const wb::Scene scene = make_scene(n);
  const wb::ForceList forces = wb::build_forces(scene);
  const wb::ParticleDynamics dyn(forces, scene.m);
  wb::Mat2X x = scene.x, v = scene.v;
  wb::Scratch s;
  s.resize(n);
  method.step(dyn, kH, x, v, s);  // warm-up: the first step may allocate
  dyn.reset_evals();
  const long before = allocations();
  for (auto _ : st) {
    method.step(dyn, kH, x, v, s);
    benchmark::DoNotOptimize(x.data());
    benchmark::ClobberMemory();
  }
  report(st, std::string("scene/") + method.name, n, allocations() - before, dyn.evals());
  st.SetLabel(method.source);
}

#ifdef WB_BENCH_HAS_RK4
// rk4 by blocks without the bookkeeping's sums (blocks_nosums/rk4/<n>): the same
// blocks and evaluations as scene/rk4, through a Dynamics that forwards them but
// does not sum the state as each block ends. scene/rk4 over this is what the
// sums cost inside the step; run/rk4 over this, the whole loop's bookkeeping.
struct BlocksNoSums : wb::Dynamics {
  const wb::Dynamics& inner;
  explicit BlocksNoSums(const wb::Dynamics& d) : inner(d) {}
  bool per_particle() const override { return inner.per_particle(); }
  bool reads_positions() const override { return inner.reads_positions(); }
  void eval(const wb::Mat2X& x, const wb::Mat2X& v, wb::Mat2X& a) const override {
    inner.acceleration(x, v, a);
  }
  void eval_block(Eigen::Index first, const wb::Mat2X& x, const wb::Mat2X& v,
                  wb::Mat2X& a) const override {
    inner.block_acceleration(first, x, v, a);
  }
};

void bm_blocks_nosums(benchmark::State& st) {
  const long n = long(st.range(0));
  const wb::Scene scene = make_scene(n);
  const wb::ForceList forces = wb::build_forces(scene);
  const wb::ParticleDynamics inner(forces, scene.m);
  const BlocksNoSums dyn(inner);
  wb::Mat2X x = scene.x, v = scene.v;
  wb::Scratch s;
  s.resize(n);
  wb::rk4_step(dyn, kH, x, v, s);  // warm-up: the first step may allocate
  dyn.reset_evals();
  const long before = allocations();
  for (auto _ : st) {
    wb::rk4_step(dyn, kH, x, v, s);
    benchmark::DoNotOptimize(x.data());
    benchmark::ClobberMemory();
  }
  report(st, "blocks_nosums/rk4", n, allocations() - before, dyn.evals());
  st.SetLabel("framework/src/rk4.cpp, no bookkeeping sums");
}

// The bookkeeping's share, paired (bookkeeping/rk4/<n>): every timed iteration
// takes one rk4 step through BlocksNoSums (no sums), then one through the
// world's own dynamics followed by the run loop's per-step check
// (World::checked_energy, which takes the step's sums), on the same arrays, each
// timed by the steady clock. Taken alternately, both see the same caches and
// clock speed, so the difference is not the noise of two benchmarks timed apart
// (run/ and blocks_nosums/ move by +-3 % from one to the other). Counters: the
// median over iterations of (with - without) / with (`share`), and the mean
// times of both steps.
void bm_bookkeeping(benchmark::State& st) {
  using Clock = std::chrono::steady_clock;
  const long n = long(st.range(0));
  const wb::Scene scene = make_scene(n);
  const wb::ForceWorld world(scene);
  const BlocksNoSums nosums(world.dynamics());
  wb::Mat2X x = scene.x, v = scene.v;
  wb::Scratch s;
  s.resize(n);
  bool finite = true;
  wb::rk4_step(nosums, kH, x, v, s);  // warm-up: the first steps may allocate
  wb::rk4_step(world.dynamics(), kH, x, v, s);
  benchmark::DoNotOptimize(world.checked_energy(x, v, finite));
  std::vector<double> shares;
  shares.reserve(100000);
  double without = 0, with = 0;
  const long before = allocations();
  for (auto _ : st) {
    const Clock::time_point t0 = Clock::now();
    wb::rk4_step(nosums, kH, x, v, s);
    benchmark::ClobberMemory();
    const Clock::time_point t1 = Clock::now();
    wb::rk4_step(world.dynamics(), kH, x, v, s);
    benchmark::DoNotOptimize(world.checked_energy(x, v, finite));
    benchmark::ClobberMemory();
    const Clock::time_point t2 = Clock::now();
    const double a = std::chrono::duration<double>(t1 - t0).count();
    const double b = std::chrono::duration<double>(t2 - t1).count();
    without += a;
    with += b;
    if (shares.size() < shares.capacity()) shares.push_back((b - a) / b);
    st.SetIterationTime(a + b);
  }
  const long allocs = allocations() - before;
  if (!finite) st.SkipWithError("the state is not finite");
  std::sort(shares.begin(), shares.end());
  const double iters = double(std::max<benchmark::IterationCount>(1, st.iterations()));
  st.counters["share"] = shares.empty() ? 0.0 : shares[shares.size() / 2];
  st.counters["share_of_sums"] = with > 0 ? (with - without) / with : 0.0;
  st.counters["step_s"] = without / iters;
  st.counters["step_and_check_s"] = with / iters;
  report(st, "bookkeeping/rk4", n, allocs, -1);
  st.SetLabel("rk4 by blocks: + sums + World::checked_energy, against without");
}

// One step of odeint's runge_kutta4 (see odebench above).
void odeint_step(odebench::Stepper& stepper, const wb::Dynamics& dyn, odebench::State& state,
                 double h) {
  auto system = [&dyn](const odebench::State& s, odebench::State& dsdt, double) {
    dsdt.x = s.v;
    dyn.acceleration(s.x, s.v, dsdt.v);
  };
  stepper.do_step(system, state, 0.0, h);
}

void bm_odeint(benchmark::State& st) {
  const long n = long(st.range(0));
  const wb::Scene scene = make_scene(n);
  const wb::ForceList forces = wb::build_forces(scene);
  const wb::ParticleDynamics dyn(forces, scene.m);
  odebench::State state{scene.x, scene.v};
  odebench::Stepper stepper;
  odeint_step(stepper, dyn, state, kH);  // warm-up: odeint sizes its stage arrays
  dyn.reset_evals();
  const long before = allocations();
  for (auto _ : st) {
    odeint_step(stepper, dyn, state, kH);
    benchmark::DoNotOptimize(state.x.data());
    benchmark::ClobberMemory();
  }
  report(st, "odeint/rk4", n, allocations() - before, dyn.evals());
  st.SetLabel("boost::numeric::odeint::runge_kutta4");
}

// A plain Boost.Odeint program (odeint_fused/rk4/<n>): runge_kutta4_classic on
// one std::vector<double> (positions as Eigen lays them out, then velocities)
// with odeint's default range algebra, and a fused right-hand side, one loop
// over the particles: dx/dt = v, dv/dt = g - (b/m) v. What a scene's rk4 run
// (run/rk4/<n>) is held against (issue 34): the same particles, the same build
// flags.
struct FusedSystem {
  const std::vector<double>* rate;  // b / m_i per particle (1/s)
  void operator()(const std::vector<double>& s, std::vector<double>& dsdt, double) const {
    const std::size_t n = rate->size(), v0 = 2 * n;
    const double* c = rate->data();
    for (std::size_t i = 0; i < n; ++i) {
      const double vx = s[v0 + 2 * i], vy = s[v0 + 2 * i + 1];
      dsdt[2 * i] = vx;
      dsdt[2 * i + 1] = vy;
      dsdt[v0 + 2 * i] = kGx - c[i] * vx;
      dsdt[v0 + 2 * i + 1] = kGy - c[i] * vy;
    }
  }
};
using FusedStepper = boost::numeric::odeint::runge_kutta4_classic<std::vector<double>>;

std::vector<double> fused_state(const wb::Scene& scene) {
  const Eigen::Index n = scene.n();
  std::vector<double> s(std::size_t(4 * n));
  std::copy(scene.x.data(), scene.x.data() + 2 * n, s.begin());
  std::copy(scene.v.data(), scene.v.data() + 2 * n, s.begin() + 2 * n);
  return s;
}

std::vector<double> fused_rates(const wb::Scene& scene) {
  std::vector<double> c(std::size_t(scene.n()));
  for (Eigen::Index i = 0; i < scene.n(); ++i) c[std::size_t(i)] = kB / scene.m[i];
  return c;
}

void bm_odeint_fused(benchmark::State& st) {
  const long n = long(st.range(0));
  const wb::Scene scene = make_scene(n);
  const std::vector<double> rate = fused_rates(scene);
  std::vector<double> state = fused_state(scene);
  FusedStepper stepper;
  const FusedSystem system{&rate};
  stepper.do_step(system, state, 0.0, kH);  // warm-up: odeint sizes its stage arrays
  const long before = allocations();
  for (auto _ : st) {
    stepper.do_step(system, state, 0.0, kH);
    benchmark::DoNotOptimize(state.data());
    benchmark::ClobberMemory();
  }
  report(st, "odeint_fused/rk4", n, allocations() - before, -1);
  st.SetLabel("boost::numeric::odeint::runge_kutta4_classic, fused right-hand side");
}
#endif

// A scene's whole run (run/<integrator>/<n>): wb::simulate, the run contract's
// loop (docs/run-contract.md) with its bookkeeping after every step (is the
// state finite, its energy for the divergence rule, the records; no output
// file), on a ForceWorld built from the scene as the executables build it.
// Timed by the run's own clock (the summary's cpu_s: the step loop's CPU time,
// without loading and setting up), per step: the counter step_loop_cpu_s,
// which bench/summarize.py reads for these rows. run/ over scene/ is what the
// loop adds to the bare step.
constexpr double kRunParticleSteps = 2e7;  // per simulate() call: 20 steps at n = 10^6

// The loop's bookkeeping alone, on a state of the run: loop_check/<n> is what
// the loop asks after every step (World::checked_energy: the state's
// finiteness and its energy, one pass); loop_check_separate/<n> the same
// answers as the loop asked them before issue 34 (x.allFinite(),
// v.allFinite(), then World::energy: four passes).
void bm_loop_check(benchmark::State& st, bool separate) {
  const long n = long(st.range(0));
  const wb::Scene scene = make_scene(n);
  const wb::ForceWorld world(scene);
  const wb::Mat2X x = scene.x, v = scene.v;
  double sum = 0;
  for (auto _ : st) {
    bool finite = false;
    double e = 0;
    if (separate) {
      finite = x.allFinite() && v.allFinite();
      e = finite ? world.energy(x, v).total() : NAN;
    } else {
      e = world.checked_energy(x, v, finite);
    }
    sum += finite ? e : 0.0;
    benchmark::DoNotOptimize(sum);
  }
  st.counters["n"] = double(n);
  st.SetLabel(separate ? "allFinite x2, World::energy" : "World::checked_energy");
}

void bm_run(benchmark::State& st, const Method& method) {
  const long n = long(st.range(0));
  const wb::Scene scene = make_scene(n);
  const wb::ForceWorld world(scene);
  const wb::Integrator integ{method.name, method.step, 1, 1, ""};
  wb::RunOptions opt;
  opt.integrator = &integ;
  opt.dt = kH;
  opt.steps = std::max(20L, long(kRunParticleSteps / double(n)));
  double cpu = 0, wall = 0;
  long steps = 0;
  for (auto _ : st) {
    const wb::RunResult r = wb::simulate(scene, world, opt);
    if (r.steps != opt.steps || !r.diverged.empty()) {
      st.SkipWithError("the run stopped early (diverged)");
      break;
    }
    cpu += r.cpu_s;
    wall += r.wall_s;
    steps += r.steps;
    benchmark::DoNotOptimize(r.x.data());
  }
  st.counters["step_loop_cpu_s"] = steps > 0 ? cpu / double(steps) : 0.0;
  st.counters["step_loop_wall_s"] = steps > 0 ? wall / double(steps) : 0.0;
  st.counters["steps_per_run"] = double(opt.steps);
  st.counters["n"] = double(n);
  st.SetLabel("wb::simulate");
}

void bm_hand(benchmark::State& st, const Method& method, bool fused) {
  const HandFn fn = fused ? method.fused : method.passes;
  const long n = long(st.range(0));
  Arrays A(make_scene(n));
  fn(A, kH);  // warm-up, as for the scene
  const long before = allocations();
  for (auto _ : st) {
    fn(A, kH);
    benchmark::DoNotOptimize(A.x.data());
    benchmark::ClobberMemory();
  }
  report(st, std::string(fused ? "hand_fused/" : "hand_passes/") + method.name, n,
         allocations() - before, -1);
}

WB_PASS void triad(double* __restrict a, const double* __restrict b, const double* __restrict c,
                   double s, long len) {
  for (long k = 0; k < len; ++k) a[k] = b[k] + s * c[k];
}

// a[i] = b[i] + s c[i] over arrays of `len` doubles: 24 bytes per element
// counted as STREAM counts them (two reads, one write; the write-allocate
// read of a is not counted).
void bm_triad(benchmark::State& st) {
  const long len = long(st.range(0));
  std::vector<double> a(len, 0.0), b(len, 1.0), c(len, 2.0);
  triad(a.data(), b.data(), c.data(), 3.0, len);  // warm-up, and every page touched
  for (auto _ : st) {
    triad(a.data(), b.data(), c.data(), 3.0, len);
    benchmark::DoNotOptimize(a.data());
    benchmark::ClobberMemory();
  }
  st.SetBytesProcessed(st.iterations() * 24 * len);
  st.counters["len"] = double(len);
}

// ---------------------------------------------------------------------------
// Before timing anything: the baselines must compute what the machinery
// computes, or their ratios mean nothing.

constexpr long kCheckParticles = 1001;
constexpr int kCheckSteps = 20;
// The same passes do the same floating-point operations in the same order as
// the Eigen expressions: they must agree to the last bit.
constexpr double kPassesTol = 0.0;
// The fused loop computes a = g - (b/m) v instead of (m g - b v)/m: a few
// rounding errors (~1e-16 relative) per step, over 20 steps.
constexpr double kFusedTol = 1e-13;

// Largest |p - q| / max(1, |p|) over every coordinate of x and v.
double rel_diff(const wb::Mat2X& x, const wb::Mat2X& v, const Arrays& A) {
  double worst = 0;
  for (long k = 0; k < 2 * A.n; ++k) {
    worst = std::max(worst, std::abs(x.data()[k] - A.x[k]) / std::max(1.0, std::abs(A.x[k])));
    worst = std::max(worst, std::abs(v.data()[k] - A.v[k]) / std::max(1.0, std::abs(A.v[k])));
  }
  return worst;
}

bool check_baselines(const std::vector<Method>& all) {
  bool ok = true;
  for (const Method& method : all) {
    const wb::Scene scene = make_scene(kCheckParticles);
    const wb::ForceList forces = wb::build_forces(scene);
    const wb::ParticleDynamics dyn(forces, scene.m);
    wb::Mat2X x = scene.x, v = scene.v;
    wb::Scratch s;
    s.resize(kCheckParticles);
    Arrays passes(scene), fused(scene);
    for (int k = 0; k < kCheckSteps; ++k) {
      method.step(dyn, kH, x, v, s);
      method.passes(passes, kH);
      method.fused(fused, kH);
    }
    const double dp = rel_diff(x, v, passes), df = rel_diff(x, v, fused);
    if (dp > kPassesTol) {
      std::fprintf(stderr,
                   "FAIL: hand_passes/%s differs from scene/%s by %.3g (relative) after %d "
                   "steps; expected bit-identical results: the baseline no longer does the "
                   "same arithmetic as the step function\n",
                   method.name, method.name, dp, kCheckSteps);
      ok = false;
    }
    if (df > kFusedTol) {
      std::fprintf(stderr,
                   "FAIL: hand_fused/%s differs from scene/%s by %.3g (relative) after %d "
                   "steps; expected at most %.3g: the fused loop is a different integrator\n",
                   method.name, method.name, df, kCheckSteps, kFusedTol);
      ok = false;
    }
  }
  return ok;
}

#ifdef WB_BENCH_HAS_RK4
// odeint sums the stages in another order (h/6 k1 + h/3 k2 + ... in one
// expression; wb::rk4_step folds the position slopes into v and the
// accelerations): a few roundings (~1e-16 relative) per step, over 20 steps.
constexpr double kOdeintTol = 1e-13;

// wb::rk4_step and odeint's runge_kutta4 must take the same steps.
bool check_odeint() {
  const wb::Scene scene = make_scene(kCheckParticles);
  const wb::ForceList forces = wb::build_forces(scene);
  const wb::ParticleDynamics dyn(forces, scene.m);
  wb::Mat2X x = scene.x, v = scene.v;
  wb::Scratch s;
  s.resize(kCheckParticles);
  odebench::State state{scene.x, scene.v};
  odebench::Stepper stepper;
  for (int k = 0; k < kCheckSteps; ++k) {
    wb::rk4_step(dyn, kH, x, v, s);
    odeint_step(stepper, dyn, state, kH);
  }
  double worst = 0;
  for (Eigen::Index k = 0; k < x.size(); ++k) {
    const double* p[2] = {x.data(), v.data()};
    const double* q[2] = {state.x.data(), state.v.data()};
    for (int c = 0; c < 2; ++c)
      worst = std::max(worst, std::abs(p[c][k] - q[c][k]) / std::max(1.0, std::abs(q[c][k])));
  }
  bool ok = worst <= kOdeintTol;
  if (!ok) {
    std::fprintf(stderr,
                 "FAIL: odeint/rk4 differs from scene/rk4 by %.3g (relative) after %d steps; "
                 "expected at most %.3g: the two do not compute the same trajectory\n",
                 worst, kCheckSteps, kOdeintTol);
  }
  // The plain program: its right-hand side computes a = g - (b/m) v, not (m g - b v)/m,
  // and odeint sums the stages in its order: roundings only, as for the fused loop.
  const std::vector<double> rate = fused_rates(scene);
  std::vector<double> fs = fused_state(scene);
  FusedStepper fused;
  for (int k = 0; k < kCheckSteps; ++k) fused.do_step(FusedSystem{&rate}, fs, 0.0, kH);
  double fworst = 0;
  for (Eigen::Index k = 0; k < x.size(); ++k) {
    const double q[2] = {fs[std::size_t(k)], fs[std::size_t(x.size() + k)]};
    const double p[2] = {x.data()[k], v.data()[k]};
    for (int c = 0; c < 2; ++c)
      fworst = std::max(fworst, std::abs(p[c] - q[c]) / std::max(1.0, std::abs(q[c])));
  }
  if (fworst > kFusedTol) {
    std::fprintf(stderr,
                 "FAIL: odeint_fused/rk4 differs from scene/rk4 by %.3g (relative) after %d "
                 "steps; expected at most %.3g: the plain program is another integrator\n",
                 fworst, kCheckSteps, kFusedTol);
    ok = false;
  }
  return ok;
}
#endif

constexpr long kTriadDramLen = 1L << 25;  // 3 arrays of 256 MiB: far beyond any cache

void register_all(const std::vector<Method>& all) {
  benchmark::RegisterBenchmark("triad_dram", bm_triad)->Arg(kTriadDramLen);
  for (long n = 1000; n <= 1000000; n *= 10) {
    for (const Method& method : all) {
      const std::string tail = std::string(method.name);
      benchmark::RegisterBenchmark(("scene/" + tail).c_str(), bm_scene, method)->Arg(n);
      benchmark::RegisterBenchmark(("hand_passes/" + tail).c_str(), bm_hand, method, false)
          ->Arg(n);
      benchmark::RegisterBenchmark(("hand_fused/" + tail).c_str(), bm_hand, method, true)->Arg(n);
    }
#ifdef WB_BENCH_HAS_RK4
    benchmark::RegisterBenchmark("odeint/rk4", bm_odeint)->Arg(n);
    benchmark::RegisterBenchmark("odeint_fused/rk4", bm_odeint_fused)->Arg(n);
    benchmark::RegisterBenchmark("blocks_nosums/rk4", bm_blocks_nosums)->Arg(n);
    benchmark::RegisterBenchmark("bookkeeping/rk4", bm_bookkeeping)->Arg(n)->UseManualTime();
#endif
    for (const Method& method : all) {
      benchmark::RegisterBenchmark(("run/" + std::string(method.name)).c_str(), bm_run, method)
          ->Arg(n)
          ->Iterations(2);
    }
    benchmark::RegisterBenchmark("loop_check", bm_loop_check, false)->Arg(n);
    benchmark::RegisterBenchmark("loop_check_separate", bm_loop_check, true)->Arg(n);
    benchmark::RegisterBenchmark("triad_fit", bm_triad)->Arg(3 * n);
  }
}

// The counter must see the allocations a careless step would make: an Eigen
// temporary (through std::malloc) and a std::vector (through operator new).
bool check_counter() {
  const long before = allocations();
  {
    wb::Mat2X tmp(2, 16);
    std::vector<double> w(16);
    benchmark::DoNotOptimize(tmp.data());
    benchmark::DoNotOptimize(w.data());
  }
  if (allocations() - before >= 2) return true;
  std::fprintf(stderr,
               "FAIL: the allocation counter saw %ld of 2 allocations (an Eigen matrix "
               "and a std::vector); allocations per step cannot be trusted\n",
               allocations() - before);
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 2;
  if (!check_counter()) return 1;
  const std::vector<Method> all = methods();
  if (!check_baselines(all)) return 1;
#ifdef WB_BENCH_HAS_RK4
  if (!check_odeint()) return 1;
#endif
  register_all(all);
  benchmark::AddCustomContext("wb_integrators", [&] {
    std::string names;
    for (const Method& m : all) names += (names.empty() ? "" : ",") + std::string(m.name);
    return names;
  }());
  benchmark::AddCustomContext("wb_bound_bytes_per_particle",
                              std::to_string(int(kBoundBytesPerParticle)));
  benchmark::AddCustomContext("wb_allocation_counting", WB_COUNT_MALLOC
                                                            ? "malloc family and operator new"
                                                            : "operator new only");
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  if (g_alloc_failure) {
    std::fprintf(stderr,
                 "FAIL: some step allocated on the heap after its warm-up step (above)\n");
    return 1;
  }
  return 0;
}
