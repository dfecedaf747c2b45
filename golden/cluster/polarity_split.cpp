#include "golden/cluster/polarity_split.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace evms::golden {

PolaritySplit::PolaritySplit(const Params& params, SensorSize sensor)
    : rule_(split_rule(params, sensor)) {
  if (rule_.balance == 0) return;
  cells_x_ = static_cast<int>((static_cast<std::uint64_t>(sensor.width) * rule_.cell_scale_x) >> kSplitCellFrac) + 1;
  cells_y_ = static_cast<int>((static_cast<std::uint64_t>(sensor.height) * rule_.cell_scale_y) >> kSplitCellFrac) + 1;
  first_in_cell_.assign(static_cast<size_t>(cells_x_) * static_cast<size_t>(cells_y_), -1);
}

void PolaritySplit::find_parts(std::span<const Event> events, std::span<const int> members) {
  touched_.clear();
  for (const int i : members) {
    const Event& e = events[static_cast<size_t>(i)];
    const int cx = std::min(cells_x_ - 1, static_cast<int>((std::uint64_t{e.x} * rule_.cell_scale_x) >> kSplitCellFrac));
    const int cy = std::min(cells_y_ - 1, static_cast<int>((std::uint64_t{e.y} * rule_.cell_scale_y) >> kSplitCellFrac));
    const int c = cy * cells_x_ + cx;
    sets_.make_set(i);
    int& first = first_in_cell_[static_cast<size_t>(c)];
    if (first < 0) {
      first = i;
      touched_.push_back(c);
    } else {
      sets_.unite(first, i);
    }
  }
  // Each occupied cell joins its occupied neighbours ahead of it (the other four see it).
  for (const int c : touched_) {
    const int cx = c % cells_x_, cy = c / cells_x_;
    for (const auto& [dx, dy] : {std::pair{1, 0}, std::pair{-1, 1}, std::pair{0, 1}, std::pair{1, 1}}) {
      const int nx = cx + dx, ny = cy + dy;
      if (nx < 0 || nx >= cells_x_ || ny >= cells_y_) continue;
      const int near = first_in_cell_[static_cast<size_t>(ny * cells_x_ + nx)];
      if (near >= 0) sets_.unite(first_in_cell_[static_cast<size_t>(c)], near);
    }
  }
  for (const int c : touched_) first_in_cell_[static_cast<size_t>(c)] = -1;
  for (const int i : members) part_of_[static_cast<size_t>(i)] = sets_.find(i);
}

void PolaritySplit::split(std::span<const Event> events, const FeatureMatrix& features, std::vector<Eigen::Vector4d>& modes,
                          std::vector<int>& cluster_of) {
  const auto n = cluster_of.size();
  sets_.resize(static_cast<int>(n));
  part_of_.resize(n);
  part_.resize(n);  // every entry is Part{} between clusters: each cluster resets the entries it used
  // The members of each cluster, in event order.
  const size_t clusters = modes.size();
  start_.assign(clusters + 1, 0);
  members_.resize(n);
  for (const int c : cluster_of) {
    if (c >= 0) ++start_[static_cast<size_t>(c) + 1];
  }
  for (size_t c = 0; c < clusters; ++c) start_[c + 1] += start_[c];
  fill_.assign(start_.begin(), start_.end() - 1);
  for (size_t i = 0; i < n; ++i) {
    if (cluster_of[i] >= 0) members_[static_cast<size_t>(fill_[static_cast<size_t>(cluster_of[i])]++)] = static_cast<int>(i);
  }

  for (size_t c = 0; c < clusters; ++c) {
    const std::span<const int> in(members_.data() + start_[c], static_cast<size_t>(start_[c + 1] - start_[c]));
    if (in.size() < 2 * static_cast<size_t>(rule_.min_events)) continue;
    find_parts(events, in);
    for (const int i : in) {
      const Event& e = events[static_cast<size_t>(i)];
      Part& q = part_[static_cast<size_t>(part_of_[static_cast<size_t>(i)])];
      ++q.events, q.on += e.p > 0, q.x += e.x, q.y += e.y;
      q.x_min = std::min<int>(q.x_min, e.x), q.x_max = std::max<int>(q.x_max, e.x);
      q.y_min = std::min<int>(q.y_min, e.y), q.y_max = std::max<int>(q.y_max, e.y);
    }
    const auto size = static_cast<std::int64_t>(in.size());
    large_.clear();
    group_of_large_.clear();
    int groups = 0, one_polarity_group = -1;
    bool every_large_part_balanced = true;
    for (const int i : in) {
      Part& q = part_[static_cast<size_t>(i)];
      const std::int64_t events_q = std::int64_t{q.events} << kSplitFractionFrac;
      if (part_of_[static_cast<size_t>(i)] != i || q.events < static_cast<int>(rule_.min_events) || events_q < rule_.share * size) continue;
      q.large = static_cast<int>(large_.size());
      large_.push_back(i);
      const std::int64_t imbalance_q = std::int64_t{std::abs(2 * q.on - q.events)} << kSplitFractionFrac;
      const bool balanced = imbalance_q < std::int64_t{rule_.balance} * q.events;
      every_large_part_balanced = every_large_part_balanced && balanced;
      if (balanced || !rule_.partial) {
        group_of_large_.push_back(groups++);
      } else {
        if (one_polarity_group < 0) one_polarity_group = groups++;
        group_of_large_.push_back(one_polarity_group);
      }
    }
    if (!rule_.partial && !every_large_part_balanced) groups = 1;
    if (rule_.concentric && groups >= 2) groups = join_concentric_groups(groups);
    if (large_.size() >= 2 && groups >= 2) {
      // Group k becomes cluster c (k = 0) or a new one; each takes its events' mean as its mode.
      std::vector<Eigen::Vector4d> sum(static_cast<size_t>(groups), Eigen::Vector4d::Zero());
      std::vector<int> count(static_cast<size_t>(groups), 0);
      for (const int i : in) {
        Part& q = part_[static_cast<size_t>(part_of_[static_cast<size_t>(i)])];
        if (q.large < 0) {  // a small part, at its first event: to the large part with the nearest centre
          std::int64_t best = std::numeric_limits<std::int64_t>::max();
          int nearest = 0;
          for (const int r : large_) {
            const Part& l = part_[static_cast<size_t>(r)];
            const std::int64_t dx = mean_sixteenths(q.x, q.events) - mean_sixteenths(l.x, l.events);
            const std::int64_t dy = mean_sixteenths(q.y, q.events) - mean_sixteenths(l.y, l.events);
            if (dx * dx + dy * dy < best) best = dx * dx + dy * dy, nearest = l.large;
          }
          q.large = nearest;
        }
        const int k = group_of_large_[static_cast<size_t>(q.large)];
        cluster_of[static_cast<size_t>(i)] = k == 0 ? static_cast<int>(c) : static_cast<int>(modes.size()) + k - 1;
        sum[static_cast<size_t>(k)] += features.col(i);
        ++count[static_cast<size_t>(k)];
      }
      modes[c] = sum[0] / count[0];
      for (int k = 1; k < groups; ++k) modes.push_back(sum[static_cast<size_t>(k)] / count[static_cast<size_t>(k)]);
    }
    for (const int i : in) part_[static_cast<size_t>(i)] = Part{};
  }
}

int PolaritySplit::join_concentric_groups(int groups) {
  struct Group {
    std::int64_t events = 0, x = 0, y = 0;
    int x_min = std::numeric_limits<int>::max(), y_min = std::numeric_limits<int>::max(), x_max = -1, y_max = -1;
  };
  std::vector<Group> group(static_cast<size_t>(groups));
  for (size_t k = 0; k < large_.size(); ++k) {
    const Part& q = part_[static_cast<size_t>(large_[k])];
    Group& g = group[static_cast<size_t>(group_of_large_[k])];
    g.events += q.events, g.x += q.x, g.y += q.y;
    g.x_min = std::min(g.x_min, q.x_min), g.x_max = std::max(g.x_max, q.x_max);
    g.y_min = std::min(g.y_min, q.y_min), g.y_max = std::max(g.y_max, q.y_max);
  }
  // a's centre sum / events within a quarter of b's box's side of its middle (min + max) / 2,
  // on each axis, cleared of the divisions: |2 sum - events (min + max)| <= events (max - min + 1) / 2.
  const auto centre_in_middle_half = [](std::int64_t sum, std::int64_t events, int lo, int hi) {
    return 2 * std::abs(2 * sum - events * (lo + hi)) <= events * (hi - lo + 1);
  };
  const auto concentric = [&](const Group& a, const Group& b) {
    return centre_in_middle_half(a.x, a.events, b.x_min, b.x_max) && centre_in_middle_half(a.y, a.events, b.y_min, b.y_max) &&
           centre_in_middle_half(b.x, b.events, a.x_min, a.x_max) && centre_in_middle_half(b.y, b.events, a.y_min, a.y_max);
  };
  std::vector<int> joins(static_cast<size_t>(groups));
  for (int k = 0; k < groups; ++k) {
    joins[static_cast<size_t>(k)] = k;
    for (int j = 0; j < k; ++j) {
      if (joins[static_cast<size_t>(j)] == j && concentric(group[static_cast<size_t>(k)], group[static_cast<size_t>(j)])) {
        joins[static_cast<size_t>(k)] = j;
        break;
      }
    }
  }
  // Numbered again in the order of their first large parts (a joined group's first large part
  // comes after the one it joined).
  std::vector<int> number(static_cast<size_t>(groups), -1);
  int left = 0;
  for (int& k : group_of_large_) {
    int& n = number[static_cast<size_t>(joins[static_cast<size_t>(k)])];
    if (n < 0) n = left++;
    k = n;
  }
  return left;
}

}  // namespace evms::golden
