#include "golden/cluster/clustering.h"

#include <algorithm>
#include <cmath>

#include "golden/cluster/edge_join.h"
#include "golden/cluster/kernel.h"
#include "golden/cluster/mean_shift.h"

namespace evms::golden {
namespace {

PacketClusters every_event(const FeatureMatrix& features, const Params& params) {
  const MeanShiftResult shifted = hybrid_mean_shift(features, params);
  const ModeClusters merged = merge_modes(shifted.modes, params);
  PacketClusters out;
  out.cluster_of = merged.cluster_of;
  out.count = merged.count;
  out.iterations = shifted.iterations;
  out.kernel_evaluations = shifted.kernel_evaluations;
  // A cluster's mode: the mode of its seed, the first event that opened it.
  out.modes.assign(static_cast<size_t>(merged.count), Eigen::Vector4d::Zero());
  std::vector<bool> set(static_cast<size_t>(merged.count), false);
  for (size_t i = 0; i < merged.cluster_of.size(); ++i) {
    const int c = merged.cluster_of[i];
    if (c >= 0 && !set[static_cast<size_t>(c)]) set[static_cast<size_t>(c)] = true, out.modes[static_cast<size_t>(c)] = shifted.modes.col(static_cast<Eigen::Index>(i));
  }
  return out;
}

}  // namespace

PacketClusterer::PacketClusterer(const Params& params, SensorSize sensor)
    : params_(params), sensor_(sensor), least_support_per_event_(least_support_per_event(params, sensor)), links_(sensor), split_(params, sensor), motion_split_(params, sensor), edge_(edge_rule(params, sensor)) {}

PacketClusters PacketClusterer::cluster(std::span<const Event> events, const FeatureMatrix& features,
                                        const std::vector<Eigen::Vector4d>& warm_modes, const std::vector<double>& warm_spreads,
                                        std::span<const Eigen::Vector2d> meeting_points) {
  if (params_.seeding == Seeding::kEvery) return every_event(features, params_);
  const bool finite = kernel_is_finite(params_.kernel);
  // Cells of half a bandwidth: a climb's ball then visits little more than its own area.
  grid_.build(features, events, params_.bandwidth, finite);
  climbs_.start(grid_, params_, sensor_);
  if (params_.warm_start) {
    const double most = std::max(params_.bandwidth, params_.warm_max_bandwidth);
    for (size_t k = 0; k < warm_modes.size(); ++k) {
      const double spread = k < warm_spreads.size() ? warm_spreads[k] : 0.0;
      // The ball finds the centre of a large outline; the events the climb takes are those
      // within its reach, so that the ball's margin does not take a neighbour's (0: the ball).
      const double reach = params_.warm_reach > 0 ? std::max(params_.bandwidth, params_.warm_reach * spread) : 0.0;
      climbs_.climb(warm_modes[k], std::clamp(params_.warm_scale * spread, params_.bandwidth, most), reach);
    }
  }
  if (params_.seeding == Seeding::kGrid) {
    cells_.build(features, events, params_.bandwidth, true);
    climbs_.seed_from_grid(cells_);
  }
  climbs_.seed_from_events();  // after grid seeds: only events no climb reached, if any
  return finish(events, features, meeting_points, climbs_.labels());
}

PacketClusters PacketClusterer::finish(std::span<const Event> events, const FeatureMatrix& features, std::span<const Eigen::Vector2d> meeting_points,
                                       std::vector<int> raw) {
  std::vector<Eigen::Vector4d> modes = climbs_.modes();
  const auto n = raw.size();
  PacketClusters result;
  result.iterations = climbs_.iterations();
  result.kernel_evaluations = climbs_.kernel_evaluations();
  // A mode no denser than a uniform spread of the packet, times min_density, is noise; with
  // density_after_links, a set of linked modes none of which is that dense, or that holds fewer
  // events than such a mode's ball.
  const double least = static_cast<double>(n) * least_support_per_event_;
  const auto sparse = [&](int mode) { return climbs_.support()[static_cast<size_t>(mode)] < least; };
  const std::vector<int> mode_of = params_.density_after_links ? raw : std::vector<int>{};
  if (!params_.density_after_links) {
    for (int& c : raw) {
      if (c >= 0 && sparse(c)) c = -1;
    }
  }
  if (params_.link_px > 0) links_.join(events, link_px_at(params_, sensor_), static_cast<int>(modes.size()), raw);
  if (params_.density_after_links) {
    std::vector<char> dense_set(modes.size(), 0);
    std::vector<int> set_events(modes.size(), 0);
    for (size_t j = 0; j < n; ++j) {
      if (raw[j] < 0) continue;
      if (!sparse(mode_of[j])) dense_set[static_cast<size_t>(raw[j])] = 1;
      ++set_events[static_cast<size_t>(raw[j])];
    }
    for (int& c : raw) {
      if (c >= 0 && !(dense_set[static_cast<size_t>(c)] && set_events[static_cast<size_t>(c)] >= least)) c = -1;
    }
  }
  if (params_.join_boxes) join_overlapping_boxes(events, raw);
  if (params_.split_balance > 0) split_.split(events, features, modes, raw);
  if (params_.motion_split > 0) motion_split_.split(events, features, meeting_points, modes, raw);
  join_edges(events, edge_, static_cast<int>(modes.size()), raw);
  std::vector<int> size(modes.size(), 0);
  for (int c : raw) {
    if (c >= 0) ++size[static_cast<size_t>(c)];
  }
  std::vector<int> renumber(modes.size(), -1);
  for (size_t c = 0; c < modes.size(); ++c) {
    if (size[c] >= params_.min_cluster_size && result.count < params_.max_clusters) {
      renumber[c] = result.count++;
      result.modes.push_back(modes[c]);
    }
  }
  result.cluster_of.resize(n);
  for (size_t j = 0; j < n; ++j) result.cluster_of[j] = raw[j] < 0 ? -1 : renumber[static_cast<size_t>(raw[j])];
  // Each cluster's spread: the RMS distance of its events from their mean, in feature units.
  std::vector<Eigen::Vector4d> mean(static_cast<size_t>(result.count), Eigen::Vector4d::Zero());
  std::vector<double> sq(static_cast<size_t>(result.count), 0.0), count(static_cast<size_t>(result.count), 0.0);
  for (size_t j = 0; j < n; ++j) {
    const int c = result.cluster_of[j];
    if (c < 0) continue;
    mean[static_cast<size_t>(c)] += features.col(static_cast<Eigen::Index>(j));
    sq[static_cast<size_t>(c)] += features.col(static_cast<Eigen::Index>(j)).squaredNorm();
    count[static_cast<size_t>(c)] += 1;
  }
  for (size_t c = 0; c < mean.size(); ++c) {
    const Eigen::Vector4d m = mean[c] / count[c];
    result.spreads.push_back(std::sqrt(std::max(0.0, sq[c] / count[c] - m.squaredNorm())));
  }
  return result;
}

// Clusters whose bounding boxes overlap become one, until no two overlap.
void PacketClusterer::join_overlapping_boxes(std::span<const Event> events, std::vector<int>& raw) const {
  struct Box {
    int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1;
    bool empty() const { return x1 < 0; }
  };
  const size_t modes = climbs_.modes().size();
  std::vector<Box> box(modes);
  for (size_t j = 0; j < raw.size(); ++j) {
    if (raw[j] < 0) continue;
    Box& b = box[static_cast<size_t>(raw[j])];
    b.x0 = std::min<int>(b.x0, events[j].x), b.x1 = std::max<int>(b.x1, events[j].x);
    b.y0 = std::min<int>(b.y0, events[j].y), b.y1 = std::max<int>(b.y1, events[j].y);
  }
  std::vector<int> into(modes);
  for (size_t c = 0; c < into.size(); ++c) into[c] = static_cast<int>(c);
  for (bool changed = true; changed;) {
    changed = false;
    for (size_t a = 0; a < box.size(); ++a) {
      for (size_t b = a + 1; b < box.size(); ++b) {
        if (box[a].empty() || box[b].empty()) continue;
        if (box[a].x0 > box[b].x1 || box[b].x0 > box[a].x1 || box[a].y0 > box[b].y1 || box[b].y0 > box[a].y1) continue;
        box[a] = {std::min(box[a].x0, box[b].x0), std::min(box[a].y0, box[b].y0), std::max(box[a].x1, box[b].x1), std::max(box[a].y1, box[b].y1)};
        box[b] = {};
        for (int& c : into) c = c == static_cast<int>(b) ? static_cast<int>(a) : c;
        changed = true;
      }
    }
  }
  for (int& c : raw) {
    if (c >= 0) c = into[static_cast<size_t>(c)];
  }
}

PacketClusters cluster_packet(std::span<const Event> events, const FeatureMatrix& features, const Params& params,
                              const std::vector<Eigen::Vector4d>& warm_modes, const std::vector<double>& warm_spreads, SensorSize sensor) {
  PacketClusterer clusterer(params, sensor);
  return clusterer.cluster(events, features, warm_modes, warm_spreads);
}

}  // namespace evms::golden
