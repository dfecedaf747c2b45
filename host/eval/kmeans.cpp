#include "host/eval/kmeans.h"

#include <limits>
#include <set>

#include "golden/cluster/features.h"
#include "golden/filter/background_activity_filter.h"
#include "host/gen/random.h"

namespace evms::eval {

std::vector<int> kmeans(const Eigen::Matrix<double, 4, Eigen::Dynamic>& x, int k, std::uint64_t seed) {
  const Eigen::Index n = x.cols();
  std::vector<int> assign(static_cast<size_t>(n), 0);
  if (n == 0 || k <= 1) return assign;
  k = static_cast<int>(std::min<Eigen::Index>(k, n));
  gen::Random rng(seed);
  Eigen::Matrix<double, 4, Eigen::Dynamic> centres(4, k);
  // k-means++: each next centre is drawn with probability proportional to D(x)^2.
  centres.col(0) = x.col(static_cast<Eigen::Index>(rng.below(static_cast<std::uint64_t>(n))));
  Eigen::VectorXd d2 = (x.colwise() - centres.col(0)).colwise().squaredNorm().transpose();
  for (int c = 1; c < k; ++c) {
    const double total = d2.sum();
    Eigen::Index pick = 0;
    if (total > 0) {
      double r = rng.uniform() * total;
      for (pick = 0; pick < n - 1 && r >= d2(pick); ++pick) r -= d2(pick);
    }
    centres.col(c) = x.col(pick);
    d2 = d2.cwiseMin((x.colwise() - centres.col(c)).colwise().squaredNorm().transpose());
  }
  for (int iteration = 0; iteration < 100; ++iteration) {
    bool changed = iteration == 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      Eigen::Index best = 0;
      (centres.colwise() - x.col(i)).colwise().squaredNorm().minCoeff(&best);
      if (assign[static_cast<size_t>(i)] != static_cast<int>(best)) changed = true;
      assign[static_cast<size_t>(i)] = static_cast<int>(best);
    }
    if (!changed) break;
    Eigen::Matrix<double, 4, Eigen::Dynamic> sum = Eigen::Matrix<double, 4, Eigen::Dynamic>::Zero(4, k);
    Eigen::VectorXd count = Eigen::VectorXd::Zero(k);
    for (Eigen::Index i = 0; i < n; ++i) {
      sum.col(assign[static_cast<size_t>(i)]) += x.col(i);
      count(assign[static_cast<size_t>(i)]) += 1;
    }
    for (int c = 0; c < k; ++c) {
      if (count(c) > 0) centres.col(c) = sum.col(c) / count(c);  // an empty cluster keeps its centre
    }
  }
  return assign;
}

std::vector<std::int32_t> kmeans_labels(std::span<const Event> events, std::span<const std::int32_t> truth,
                                        SensorSize sensor, const Params& params, Chunking chunking, std::uint64_t seed) {
  std::vector<bool> kept(events.size());
  golden::BackgroundActivityFilter filter(sensor, params.filter_window_us);
  for (size_t i = 0; i < events.size(); ++i) kept[i] = filter.accept(events[i]);

  std::vector<std::int32_t> labels(events.size(), kNoiseLabel);
  for (const auto& [begin, end] : chunk_ranges(events, chunking)) {
    std::set<std::int32_t> objects;
    std::vector<Event> chunk;
    std::vector<size_t> index;
    for (size_t i = begin; i < end; ++i) {
      if (truth[i] >= 0) objects.insert(truth[i]);
      if (kept[i]) chunk.push_back(events[i]), index.push_back(i);
    }
    if (chunk.empty() || objects.empty()) continue;
    const auto assign = kmeans(golden::packet_features(chunk, sensor, params), static_cast<int>(objects.size()), seed);
    for (size_t j = 0; j < chunk.size(); ++j) labels[index[j]] = assign[j];
  }
  return labels;
}

}  // namespace evms::eval
