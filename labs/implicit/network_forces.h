// The network's force at (x, v): every spring (through spring_derivatives, I2)
// and the drag. Provided, not a task.
#pragma once
#include "spring_derivatives.h"
#include "spring_network.h"

// Inputs: net (n particles), x, v (2 x n; m, m/s). Output: f (2 x n, N),
// resized and overwritten. Pinned particles get their force too.
inline void network_forces(const SpringNetwork& net, const wb::Mat2X& x, const wb::Mat2X& v,
                           wb::Mat2X& f) {
  f = -net.drag * v;
  wb::Vec2 fi;
  wb::Mat2 K, D;
  for (const NetworkSpring& s : net.springs) {
    const bool anchored = s.j < 0;
    const wb::Vec2 xj = anchored ? s.anchor : wb::Vec2(x.col(s.j));
    const wb::Vec2 vj = anchored ? wb::Vec2::Zero() : wb::Vec2(v.col(s.j));
    spring_derivatives(x.col(s.i), xj, v.col(s.i), vj, s.k, s.rest, s.kd, false, fi, K, D);
    f.col(s.i) += fi;
    if (!anchored) f.col(s.j) -= fi;
  }
}
