// The spring network the implicit lab's steps solve for (provided, not a task).
#pragma once
#include <vector>

#include "wb/types.h"

// One damped spring, as in the forces lab (F5): the force on end i is
//   f_i = -( k (L - rest) + kd (v_i - v_j) . u ) u,   d = x_i - x_j, L = |d|, u = d / L
// and f_j = -f_i. A spring with j < 0 joins particle i to the fixed point `anchor`.
struct NetworkSpring {
  Eigen::Index i = 0, j = -1;          // particle indices; j < 0: anchored
  wb::Vec2 anchor = wb::Vec2::Zero();  // fixed end (m) when j < 0
  double k = 0;                        // stiffness (N/m), >= 0
  double rest = 0;                     // rest length (m), >= 0
  double kd = 0;                       // damping along the spring (N s/m), >= 0
};

// Every particle's mass, the springs between them, an optional viscous drag
// -drag v_i on every particle, and the pinned particles. A pinned particle has
// infinite mass: it never moves (its velocity is 0 and stays 0), and springs
// attached to it act on their other end only.
struct SpringNetwork {
  std::vector<NetworkSpring> springs;
  wb::VecX m;                // masses (kg), one per particle, > 0
  double drag = 0;           // viscous drag b (N s/m): force -b v_i on every particle
  std::vector<char> pinned;  // one flag per particle (empty: none pinned)

  Eigen::Index n() const { return m.size(); }
  bool is_pinned(Eigen::Index i) const { return !pinned.empty() && pinned[std::size_t(i)] != 0; }
};
