// libFuzzer target: the trusted side of the grader's worker (fuzz/README.md, "fuzz_worker_wire").
//
// In the grader every value that comes back from the worker (the process with the student's
// code) is hostile. This target plays the worker: the fuzzer's bytes are the messages it
// sends, results, errors and callback requests in any order and of any contents, while the
// trusted side (the generated stubs of tools/grader/stubs.py for the forces, euler, implicit
// and collisions labs, and tools/grader/cpp/client.cpp) makes one call, as a test would, and
// serves the callbacks with callbacks written the way the tests write them (a Dynamics that
// indexes a captured per-particle array, force terms that index m[i] for every column of x).
//
// Input: byte 0 picks the call; the rest is cut into messages, each a 2-byte length and that
// many bytes (the 4-byte length the wire puts in front is added here, so that every input is
// a sequence of whole messages; a message of length 0xffff says "make it the 64 MiB limit + 1"
// to reach the size check). The trusted side reads them from a file descriptor; what it writes
// goes to /dev/null.
//
// A finding is a crash or a sanitizer report (heap overflow, use after free, integer overflow
// in a size, a misaligned or out-of-range index). Every exception is expected: the test fails.
#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "accumulate_forces.h"
#include "assemble_system.h"
#include "attractor.h"
#include "backward_euler.h"
#include "boids.h"
#include "collide_particles.h"
#include "contact_solver.h"
#include "curl_noise.h"
#include "explicit_euler.h"
#include "grid_pairs.h"
#include "spring_derivatives.h"
#include "wb/dynamics.h"
#include "wb/force.h"

namespace {

constexpr int kIn = 900, kOut = 901;  // WB_WORKER_FDS: the "worker"'s messages, /dev/null

// A Dynamics as the tests write them: a per-particle array captured by the test, indexed by
// the columns of the x the callback gets (client.cpp pins them to the call's particle count).
wb::LambdaDynamics test_dynamics(std::vector<double> w) {
  return wb::LambdaDynamics([w](const wb::Mat2X& x, const wb::Mat2X& v, wb::Mat2X& a) {
    for (Eigen::Index i = 0; i < x.cols(); ++i)
      a.col(i) = -w[std::size_t(i)] * x.col(i) - 0.1 * v.col(i);
  });
}

// Force terms as F6's tests write them.
class MassTerm : public wb::Force {
 public:
  void add(const wb::Mat2X& x, const wb::Mat2X&, const wb::VecX& m, wb::Mat2X& f) const override {
    for (Eigen::Index i = 0; i < x.cols(); ++i) f.col(i) += m[i] * wb::Vec2(1, -2);
  }
  double potential(const wb::Mat2X& x, const wb::VecX& m) const override {
    double e = 0;
    for (Eigen::Index i = 0; i < x.cols(); ++i) e += m[i] * x(1, i);
    return e;
  }
  std::string type() const override { return "test-mass"; }
};
class VelocityTerm : public wb::Force {
 public:
  void add(const wb::Mat2X& x, const wb::Mat2X& v, const wb::VecX&, wb::Mat2X& f) const override {
    for (Eigen::Index i = 0; i < x.cols(); ++i) f.col(i) += -0.5 * v.col(i);
  }
  std::string type() const override { return "test-velocity"; }
};

void call(int which) {
  const Eigen::Index n = 4;
  wb::Mat2X x = wb::Mat2X::Random(2, n), v = wb::Mat2X::Random(2, n);
  wb::VecX m = wb::VecX::Constant(n, 1.5);
  wb::Mat2X f = wb::Mat2X::Zero(2, n);
  switch (which % 9) {
    case 0:
      add_attractor(x, m, wb::Vec2(0.5, -1), 2.0, f);
      break;
    case 1: {
      std::vector<std::unique_ptr<wb::Force>> terms;
      terms.push_back(std::make_unique<MassTerm>());
      terms.push_back(std::make_unique<VelocityTerm>());
      accumulate_forces(terms, x, v, m, f);
      break;
    }
    case 2: {
      const wb::LambdaDynamics dyn = test_dynamics({1.0, 2.0, 3.0, 4.0});
      wb::Scratch s;
      s.resize(n);
      explicit_euler_step(dyn, 0.01, x, v, s);
      break;
    }
    case 3: {
      CurlNoiseParams p;
      p.psi = [](const wb::Vec2& y) { return y.x() * y.y(); };
      p.obstacles = {{wb::Vec2(0, 0), 0.5}};
      add_curl_noise(x, v, p, f);
      (void)curl_noise_flow(wb::Vec2(0.3, 0.2), p);
      break;
    }
    case 4: {
      std::vector<std::pair<int, int>> pairs = {{0, 1}};
      grid_pairs(x, wb::VecX::Constant(n, 0.3), pairs);
      break;
    }
    case 5: {
      SpringNetwork net;
      net.m = m;
      net.springs.push_back(NetworkSpring{0, 1, wb::Vec2::Zero(), 10.0, 0.5, 0.1});
      net.pinned = {0, 1, 0, 0};
      SparseSystem sys;
      assemble_system(net, x, v, x, v, f, 0.01, true, sys);
      break;
    }
    case 6: {
      SpringNetwork net;
      net.m = m;
      net.springs.push_back(NetworkSpring{0, -1, wb::Vec2(1, 1), 10.0, 0.5, 0.1});
      NewtonOptions o;
      NewtonWorkspace ws;
      const NewtonReport r = backward_euler_step(net, f, 0.01, o, x, v, ws);
      (void)r;
      break;
    }
    case 7: {
      Contact c;
      c.a = 0, c.b = 1;
      (void)solve_contact(m, c, v);
      wb::Vec2 x1(0, 0), v1(1, 0), x2(0.5, 0), v2(-1, 0);
      (void)collide_particles(1, 0.3, 2, 0.3, 0.5, x1, v1, x2, v2);
      break;
    }
    default: {
      BoidsParams p;
      p.separation = {0.5, 1.0};
      add_boids(x, v, m, p, f);
      wb::Vec2 fi;
      wb::Mat2 K, D;
      spring_derivatives(x.col(0), x.col(1), v.col(0), v.col(1), 5, 1, 0.2, false, fi, K, D);
      break;
    }
  }
  // What a test does next with the values: compare them (reading every entry).
  volatile double sink = f.sum() + x.sum() + v.sum();
  (void)sink;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  const int out = open("/dev/null", O_WRONLY);
  if (out < 0 || dup2(out, kOut) < 0) std::abort();
  const int in = memfd_create("wb-worker-messages", 0);
  if (in < 0 || dup2(in, kIn) < 0) std::abort();
  setenv("WB_WORKER_FDS", (std::to_string(kIn) + "," + std::to_string(kOut)).c_str(), 1);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1 || size > 1 << 16) return 0;
  // The messages, each with the wire's 4-byte length in front.
  std::string stream;
  std::size_t k = 1;
  while (k + 2 <= size) {
    const std::size_t len = std::size_t(data[k]) | std::size_t(data[k + 1]) << 8;
    k += 2;
    if (len == 0xffff) {  // a length over the limit: refused before anything is read
      const std::uint32_t huge = (64u << 20) + 1;
      stream.append(reinterpret_cast<const char*>(&huge), 4);
      break;
    }
    const std::size_t take = std::min(len, size - k);
    const std::uint32_t n = std::uint32_t(take);
    stream.append(reinterpret_cast<const char*>(&n), 4);
    stream.append(reinterpret_cast<const char*>(data + k), take);
    k += take;
  }
  if (ftruncate(kIn, 0) != 0 || lseek(kIn, 0, SEEK_SET) != 0) std::abort();
  if (!stream.empty() && write(kIn, stream.data(), stream.size()) != ssize_t(stream.size()))
    std::abort();
  if (lseek(kIn, 0, SEEK_SET) != 0) std::abort();
  try {
    call(data[0]);
  } catch (const std::exception&) {
    // the call failed: what a test reports as a failure of the lab's code
  }
  return 0;
}
