#include "golden/cluster/polarity_split.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace evms::golden {

PolaritySplit::PolaritySplit(const Params& params, SensorSize sensor) : params_(params) {
  if (params.split_balance <= 0) return;
  const Eigen::Vector2d px = feature_pixels(sensor, params);
  // Cells of at least two pixels (along the axis where pixels are larger): neighbouring pixels
  // then always fall in the same or neighbouring cells, whatever the rounding of their features,
  // so a solid object is one part; finer cells would tell no more and only grow the grid.
  cell_ = std::max(params.split_cell * params.bandwidth, 2 * params.scale_xy / std::min(px.x(), px.y()));
  // Features run from 0 to scale_xy * (sensor side - 1) / px; one cell more for the edge.
  cells_x_ = static_cast<int>(params.scale_xy * sensor.width / px.x() / cell_) + 2;
  cells_y_ = static_cast<int>(params.scale_xy * sensor.height / px.y() / cell_) + 2;
  first_in_cell_.assign(static_cast<size_t>(cells_x_) * static_cast<size_t>(cells_y_), -1);
}

int PolaritySplit::find(int a) {
  while (root_[static_cast<size_t>(a)] != a) a = root_[static_cast<size_t>(a)] = root_[static_cast<size_t>(root_[static_cast<size_t>(a)])];
  return a;
}

void PolaritySplit::unite(int a, int b) {
  a = find(a), b = find(b);
  if (a != b) root_[static_cast<size_t>(std::max(a, b))] = std::min(a, b);
}

void PolaritySplit::find_parts(std::span<const int> members, const FeatureMatrix& features) {
  touched_.clear();
  for (const int i : members) {
    const auto cx = std::clamp(static_cast<int>(features(0, i) / cell_), 0, cells_x_ - 1);
    const auto cy = std::clamp(static_cast<int>(features(1, i) / cell_), 0, cells_y_ - 1);
    const int c = cy * cells_x_ + cx;
    root_[static_cast<size_t>(i)] = i;
    int& first = first_in_cell_[static_cast<size_t>(c)];
    if (first < 0) {
      first = i;
      touched_.push_back(c);
    } else {
      unite(first, i);
    }
  }
  // Each occupied cell joins its occupied neighbours ahead of it (the other four see it).
  for (const int c : touched_) {
    const int cx = c % cells_x_, cy = c / cells_x_;
    for (const auto& [dx, dy] : {std::pair{1, 0}, std::pair{-1, 1}, std::pair{0, 1}, std::pair{1, 1}}) {
      const int nx = cx + dx, ny = cy + dy;
      if (nx < 0 || nx >= cells_x_ || ny >= cells_y_) continue;
      const int near = first_in_cell_[static_cast<size_t>(ny * cells_x_ + nx)];
      if (near >= 0) unite(first_in_cell_[static_cast<size_t>(c)], near);
    }
  }
  for (const int c : touched_) first_in_cell_[static_cast<size_t>(c)] = -1;
  for (const int i : members) root_[static_cast<size_t>(i)] = find(i);
}

void PolaritySplit::split(std::span<const Event> events, const FeatureMatrix& features, std::vector<Eigen::Vector4d>& modes,
                          std::vector<int>& cluster_of) {
  const auto n = cluster_of.size();
  root_.resize(n);
  // The members of each cluster, in event order.
  const size_t clusters = modes.size();
  std::vector<int>& start = start_;
  std::vector<int>& members = members_;
  start.assign(clusters + 1, 0);
  members.resize(n);
  for (const int c : cluster_of) {
    if (c >= 0) ++start[static_cast<size_t>(c) + 1];
  }
  for (size_t c = 0; c < clusters; ++c) start[c + 1] += start[c];
  fill_.assign(start.begin(), start.end() - 1);
  std::vector<int>& fill = fill_;
  for (size_t i = 0; i < n; ++i) {
    if (cluster_of[i] >= 0) members[static_cast<size_t>(fill[static_cast<size_t>(cluster_of[i])]++)] = static_cast<int>(i);
  }

  std::vector<Part>& part = part_;
  part.resize(n);  // every entry is Part{} between clusters: each cluster resets the entries it used
  std::vector<int> remade;  // the clusters of split clusters' parts
  for (size_t c = 0; c < clusters; ++c) {
    const std::span<const int> in(members.data() + start[c], static_cast<size_t>(start[c + 1] - start[c]));
    if (in.size() < 2 * static_cast<size_t>(params_.min_cluster_size)) continue;
    find_parts(in, features);
    for (const int i : in) {
      Part& q = part[static_cast<size_t>(root_[static_cast<size_t>(i)])];
      ++q.events, q.on += events[static_cast<size_t>(i)].p > 0, q.x += events[static_cast<size_t>(i)].x, q.y += events[static_cast<size_t>(i)].y;
    }
    const double least = std::max<double>(params_.min_cluster_size, params_.split_share * static_cast<double>(in.size()));
    std::vector<int> large;
    bool every_large_part_balanced = true;
    for (const int i : in) {
      if (root_[static_cast<size_t>(i)] != i || part[static_cast<size_t>(i)].events < least) continue;
      const Part& q = part[static_cast<size_t>(i)];
      large.push_back(i);
      every_large_part_balanced = every_large_part_balanced && std::abs(2 * q.on - q.events) < params_.split_balance * q.events;
    }
    if (large.size() >= 2 && every_large_part_balanced) {
      for (size_t k = 0; k < large.size(); ++k) {
        part[static_cast<size_t>(large[k])].cluster = k == 0 ? static_cast<int>(c) : static_cast<int>(modes.size());
        remade.push_back(part[static_cast<size_t>(large[k])].cluster);
        if (k > 0) modes.emplace_back(Eigen::Vector4d::Zero());
      }
      for (const int i : in) {
        const Part& q = part[static_cast<size_t>(root_[static_cast<size_t>(i)])];
        int to = q.cluster;
        if (to < 0) {  // a small part: to the large part with the nearest centre
          double best = std::numeric_limits<double>::infinity();
          for (const int r : large) {
            const Part& l = part[static_cast<size_t>(r)];
            const double dx = q.x / q.events - l.x / l.events, dy = q.y / q.events - l.y / l.events;
            if (dx * dx + dy * dy < best) best = dx * dx + dy * dy, to = l.cluster;
          }
        }
        cluster_of[static_cast<size_t>(i)] = to;
      }
    }
    for (const int i : in) part[static_cast<size_t>(i)] = Part{};
  }
  if (remade.empty()) return;
  std::vector<Eigen::Vector4d> sum(modes.size(), Eigen::Vector4d::Zero());
  std::vector<int> count(modes.size(), 0);
  for (size_t i = 0; i < n; ++i) {
    if (cluster_of[i] < 0) continue;
    sum[static_cast<size_t>(cluster_of[i])] += features.col(static_cast<Eigen::Index>(i));
    ++count[static_cast<size_t>(cluster_of[i])];
  }
  for (const int c : remade) modes[static_cast<size_t>(c)] = sum[static_cast<size_t>(c)] / count[static_cast<size_t>(c)];
}

}  // namespace evms::golden
