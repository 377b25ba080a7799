// Shared by the implicit lab's probes (tests/common/wb_probe.h): small spring networks.
#pragma once
#include <vector>

#include "backward_euler.h"
#include "spring_network.h"
#include "wb_probe.h"

namespace improbe {

using wb::Mat2X;
using wb::Vec2;

inline NetworkSpring spring(Eigen::Index i, Eigen::Index j, double k, double rest, double kd = 0,
                            const Vec2& anchor = Vec2::Zero()) {
  NetworkSpring s;
  s.i = i, s.j = j, s.k = k, s.rest = rest, s.kd = kd, s.anchor = anchor;
  return s;
}

// The network as inputs: masses, drag, pinned flags, and each spring.
inline void network_in(wbprobe::Probe& P, const SpringNetwork& net) {
  P.in("net.m", net.m), P.in("net.drag", net.drag);
  if (!net.pinned.empty()) {
    Eigen::VectorXd pinned(Eigen::Index(net.pinned.size()));
    for (std::size_t p = 0; p < net.pinned.size(); ++p) pinned[Eigen::Index(p)] = net.pinned[p];
    P.in("net.pinned", pinned);
  }
  for (const NetworkSpring& s : net.springs) {
    Eigen::VectorXd row(5);
    row << double(s.i), double(s.j), s.k, s.rest, s.kd;
    P.in("spring (i, j, k, rest, kd)", row);
    if (s.j < 0) P.in("  its anchor", s.anchor);
  }
}

// The report as one output: (iterations, converged, solver_failed, scale[, residual]). The
// residual of a converged step is rounding: recorded only where it is not.
inline Eigen::VectorXd report(const NewtonReport& r, bool residual) {
  Eigen::VectorXd out(residual ? 5 : 4);
  out.head<4>() << r.iterations, r.converged, r.solver_failed, r.scale;
  if (residual) out[4] = r.residual;
  return out;
}
inline void report_out(wbprobe::Probe& P, const NewtonReport& r, bool residual) {
  P.out(residual ? "report (iterations, converged, solver_failed, scale, residual)"
                 : "report (iterations, converged, solver_failed, scale)",
        report(r, residual));
}

// A small nonlinear network: a triangle with a tail to an anchor, every spring stretched or
// compressed, every particle moving, drag 0.3, some damping.
inline void small_network(SpringNetwork& net, Mat2X& x, Mat2X& v) {
  net = SpringNetwork{};
  net.m = Eigen::Vector4d(1.0, 2.0, 0.5, 1.5);
  net.drag = 0.3;
  net.springs = {spring(0, 1, 40.0, 0.8, 0.5), spring(1, 2, 25.0, 1.4, 0.2),
                 spring(2, 0, 60.0, 0.7, 0.1), spring(2, 3, 30.0, 0.5, 0.3),
                 spring(3, -1, 50.0, 0.6, 0.4, Vec2(2.5, -1.0))};
  x = wbprobe::cols({{0.0, 0.0}, {1.1, 0.2}, {0.4, 1.0}, {1.3, 0.1}});
  v = wbprobe::cols({{0.3, -0.7}, {-0.5, 0.4}, {0.8, -0.1}, {-0.2, 0.6}});
}

}  // namespace improbe
