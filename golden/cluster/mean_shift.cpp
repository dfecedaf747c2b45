#include "golden/cluster/mean_shift.h"

#include <limits>

namespace evms::golden {

MeanShiftResult hybrid_mean_shift(const FeatureMatrix& features, const Params& params) {
  const Eigen::Index n = features.cols();
  const double inv_h2 = 1.0 / (params.bandwidth * params.bandwidth);
  // The reference set: original positions, and the appearance of the previous iteration.
  const Eigen::ArrayXd x0 = features.row(0).transpose().array();
  const Eigen::ArrayXd y0 = features.row(1).transpose().array();
  Eigen::ArrayXd p = features.row(2).transpose().array();
  Eigen::ArrayXd f = features.row(3).transpose().array();

  FeatureMatrix current = features;
  FeatureMatrix next(4, n);
  Eigen::ArrayXd w(n);
  MeanShiftResult result;
  for (int k = 0; k < params.max_iterations && n > 0; ++k) {
    for (Eigen::Index i = 0; i < n; ++i) {
      const auto c = current.col(i);
      const Eigen::ArrayXd u =
          inv_h2 * ((x0 - c(0)).square() + (y0 - c(1)).square() + (p - c(2)).square() + (f - c(3)).square());
      switch (params.kernel) {
        case Kernel::kGaussian: w = (-0.5 * u).exp(); break;
        case Kernel::kFlat: w = (u < 1.0).cast<double>(); break;
        case Kernel::kEpanechnikov: w = (1.0 - u).max(0.0); break;
      }
      const double norm = w.sum();
      if (norm > 0) {
        next.col(i) << (w * x0).sum() / norm, (w * y0).sum() / norm, (w * p).sum() / norm,
            (w * f).sum() / norm;
      } else {
        next.col(i) = c;  // no neighbour in reach: the point stays
      }
    }
    const double shift = (next - current).cwiseAbs().maxCoeff();
    current.swap(next);
    p = current.row(2).transpose().array();
    f = current.row(3).transpose().array();
    result.iterations = k + 1;
    result.kernel_evaluations += static_cast<std::int64_t>(n) * n;
    if (shift <= params.tolerance) break;
  }
  result.modes = std::move(current);
  return result;
}

ModeClusters merge_modes(const FeatureMatrix& modes, const Params& params) {
  const Eigen::Index n = modes.cols();
  std::vector<Eigen::Index> seeds;  // point index of each cluster's first mode
  std::vector<int> raw(static_cast<size_t>(n), -1);
  const double r2 = params.merge_radius * params.merge_radius;
  for (Eigen::Index i = 0; i < n; ++i) {
    int best = -1;
    double best_d2 = std::numeric_limits<double>::infinity();
    for (size_t c = 0; c < seeds.size(); ++c) {
      const double d2 = (modes.col(i) - modes.col(seeds[c])).squaredNorm();
      if (d2 <= r2 && d2 < best_d2) {
        best = static_cast<int>(c);
        best_d2 = d2;
      }
    }
    if (best < 0 && static_cast<int>(seeds.size()) < params.max_clusters) {
      best = static_cast<int>(seeds.size());
      seeds.push_back(i);
    }
    raw[static_cast<size_t>(i)] = best;
  }

  std::vector<int> size(seeds.size(), 0);
  for (int c : raw) {
    if (c >= 0) ++size[static_cast<size_t>(c)];
  }
  std::vector<int> renumber(seeds.size(), -1);
  ModeClusters out;
  for (size_t c = 0; c < seeds.size(); ++c) {
    if (size[c] >= params.min_cluster_size) renumber[c] = out.count++;
  }
  out.cluster_of.resize(static_cast<size_t>(n));
  for (size_t i = 0; i < raw.size(); ++i) {
    out.cluster_of[i] = raw[i] < 0 ? -1 : renumber[static_cast<size_t>(raw[i])];
  }
  return out;
}

}  // namespace evms::golden
