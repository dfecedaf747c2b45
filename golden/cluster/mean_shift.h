// The paper's hybrid mean shift on one packet.
//
// Every point i carries a position y_i (features x, y) and an appearance q_i (features p,
// time). All points move together (a Jacobi sweep). In iteration k:
//
//   d2_ij  = |y_i^k - y_j^0|^2 + |q_i^k - q_j^k|^2
//   w_ij   = k(d2_ij / h^2)                               (kernel profile, golden/cluster/kernel.h)
//   y_i^k+1 = sum_j w_ij y_j^0 / sum_j w_ij               (position against the original,
//                                                          unmoved positions: Fukunaga)
//   q_i^k+1 = sum_j w_ij q_j^k / sum_j w_ij               (polarity and time against the
//                                                          previous iteration: blurring)
//
// The sweep stops when no coordinate of any point moved more than the tolerance, or at the
// iteration cap. The converged points are the modes. There is no randomness.
#pragma once

#include <vector>

#include "golden/cluster/features.h"

namespace evms::golden {

struct MeanShiftResult {
  FeatureMatrix modes;
  int iterations = 0;       // sweeps performed
  std::int64_t kernel_evaluations = 0;
};

MeanShiftResult hybrid_mean_shift(const FeatureMatrix& features, const Params& params);

// Groups modes into clusters: each mode, in input order, joins the nearest existing
// cluster whose first mode (its seed) lies within the merge radius (ties: the older cluster);
// otherwise it opens a new cluster, unless max_clusters are open, in which case it is noise.
// Clusters with fewer than min_cluster_size members then become noise. The surviving clusters
// are numbered 0.. in order of their seeds. Returns one cluster index (or -1) per mode.
struct ModeClusters {
  std::vector<int> cluster_of;   // per point
  int count = 0;
};

ModeClusters merge_modes(const FeatureMatrix& modes, const Params& params);

}  // namespace evms::golden
