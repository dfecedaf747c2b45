// The mean-shift kernel's profile k(u), u = |f_i - f_j|^2 / h^2, and its reach. A point's new
// position is sum_j k(u_ij) f_j / sum_j k(u_ij); the constant factor of each kernel cancels.
//   gaussian      exp(-u / 2)        every point has weight
//   flat          1      for u < 1   the mean of the points in the ball of radius h
//   epanechnikov  1 - u  for u < 1   the mean weighted down towards the ball's rim
#pragma once

#include <cmath>

#include "types/params.h"

namespace evms::golden {

inline double kernel_profile(Kernel k, double u) {
  switch (k) {
    case Kernel::kGaussian: return std::exp(-0.5 * u);
    case Kernel::kFlat: return u < 1.0 ? 1.0 : 0.0;
    case Kernel::kEpanechnikov: return u < 1.0 ? 1.0 - u : 0.0;
  }
  return 0.0;
}

// A finite kernel gives no weight at u >= 1, so a point only needs the points within h.
inline bool kernel_is_finite(Kernel k) { return k != Kernel::kGaussian; }

}  // namespace evms::golden
