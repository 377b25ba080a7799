// Correct alternative: resize only when needed, then zero, then a loop by index.
#include "accumulate_forces.h"

void accumulate_forces(const std::vector<std::unique_ptr<wb::Force>>& forces, const wb::Mat2X& x,
                       const wb::Mat2X& v, const wb::VecX& m, wb::Mat2X& f) {
  if (f.cols() != x.cols()) f.resize(2, x.cols());
  f.fill(0.0);
  for (std::size_t k = 0; k < forces.size(); ++k) forces[k]->add(x, v, m, f);
}
