// Correct alternative: column by column.
#include "damping.h"

void add_damping(const wb::Mat2X& v, double b, wb::Mat2X& f) {
  for (Eigen::Index i = 0; i < v.cols(); ++i) f.col(i) += -b * v.col(i);
}
