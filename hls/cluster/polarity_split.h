// Two objects that one cluster holds, told from the two edges of one object by their polarities
// (golden/cluster/polarity_split.h states the rule and why): the large parts of a cluster's
// events, 8-connected sets of cells, fall into groups, each part holding both polarities a group
// of its own and the others one group together (with split_partial clear, a cluster with any such
// part keeps one group); a cluster of two or more groups becomes one cluster per group, and each
// small part joins the group of the large part whose centre is nearest.
//
// Integers throughout, the same as golden's (SplitRule in types/params.h):
//   cell of (x, y)    ((x * split_cell_scale_x) >> kSplitCellFrac, likewise y); a scale is at most
//                     2^(kSplitCellFrac - 1), so cells are at least two pixels a side
//   large part        events >= split_min_events and events << kSplitFractionFrac >= split_share * size
//   both polarities   |2 on - events| << kSplitFractionFrac < split_balance * events
//   part centre       1/16 px, (32 sum + events) / (2 events); nearest by squared distance, ties to
//                     the part whose first event came first
//   split mode        the mean of the group's climb features, rounded half up
//   concentric        (Config::split_concentric, a build with HasConcentricGroups) group sums and
//                     boxes over their large parts; a's centre in the middle half of b's box on
//                     an axis: 2 |2 sum_a - events_a (min_b + max_b)| <= events_a (max_b - min_b + 1);
//                     each later group joins the first earlier group concentric with it both ways
// Groups are numbered in the order of their first large parts' first events; the first keeps the
// cluster's mode, the others open modes after the existing ones. A cluster whose groups (or large
// parts) would not fit in the mode table (kModesMax) stays whole, and is counted (golden has no
// such table: a departure, docs/hls.md).
//
// In hardware form: the cluster's events, bucketed by mode, each write the first event of its cell
// into a cell map (or join it); each occupied cell joins its occupied neighbours ahead of it; the
// parts' sums accumulate at their roots; the cells written are cleared from a list, not by a pass
// over the map.
#pragma once

#include <cstdint>

#include "hls/cluster/features.h"
#include "hls/cluster/seeded_climbs.h"
#include "hls/cluster/union_find.h"
#include "hls/core/config.h"
#include "hls/math/round.h"

namespace evms::hls {

template <class S>
class PolaritySplit {
 public:
  static constexpr int kCellsX = S::kMaxWidth / 2 + 1, kCellsY = S::kMaxHeight / 2 + 1;

  void reset() {
  clear:
    for (int c = 0; c < kCellsX * kCellsY; ++c) first_in_cell_[c] = -1;
  }

  // mode_of: per event its mode after the links (-1: none). Returns the clusters left whole because
  // the mode table had no room for their parts.
  int run(const PacketEvents<S>& ev, const Features<S>& phi, int n, const Config& cfg, std::int16_t mode_of[S::kPacketMax],
          Modes<S>& modes) {
    if (cfg.split_balance == 0) return 0;
    bucket(mode_of, n, modes.count);
    const int clusters = modes.count;
    int left_whole = 0;
  clusters_loop:
    for (int c = 0; c < S::kModesMax; ++c) {
      if (c >= clusters) break;
      const int first = start_[c], size = start_[c + 1] - start_[c];
      if (size < 2 * cfg.split_min_events) continue;
      find_parts(ev, first, size, cfg);
      const int large = large_parts(ev, first, size, cfg);
      if (large < 2 || groups_ < 2) continue;
      if (modes.count + groups_ - 1 > S::kModesMax || large > S::kModesMax) {  // the RTL keeps a centre per large part
        ++left_whole;
        continue;
      }
      reassign(phi, first, size, large, c, mode_of, modes);
    }
    return left_whole;
  }

 private:
  // members_[start_[c] .. start_[c + 1]) are mode c's events, in event order.
  void bucket(const std::int16_t mode_of[S::kPacketMax], int n, int count) {
  zero:
    for (int c = 0; c <= S::kModesMax; ++c) {
      if (c > count) break;
      start_[c] = 0;
    }
  sizes:
    for (int j = 0; j < S::kPacketMax; ++j) {
      if (j >= n) break;
      if (mode_of[j] >= 0) ++start_[mode_of[j] + 1];
    }
  prefix:
    for (int c = 0; c < S::kModesMax; ++c) {
      if (c >= count) break;
      start_[c + 1] += start_[c];
      fill_[c] = start_[c];
    }
  place:
    for (int j = 0; j < S::kPacketMax; ++j) {
      if (j >= n) break;
      if (mode_of[j] >= 0) members_[fill_[mode_of[j]]++] = static_cast<std::int16_t>(j);
    }
  }

  static int cell_of(const PacketEvents<S>& ev, int j, const Config& cfg) {
    const int cx = static_cast<int>((std::uint64_t{ev.x[j]} * cfg.split_cell_scale_x) >> kSplitCellFrac);
    const int cy = static_cast<int>((std::uint64_t{ev.y[j]} * cfg.split_cell_scale_y) >> kSplitCellFrac);
    return cy * kCellsX + cx;
  }

  // Afterwards sets_ holds the parts of the cluster's events, each named by its smallest member.
  void find_parts(const PacketEvents<S>& ev, int first, int size, const Config& cfg) {
    int touched = 0;
  cells:
    for (int k = 0; k < S::kPacketMax; ++k) {
#pragma HLS PIPELINE II = 1
      if (k >= size) break;
      const int j = members_[first + k];
      const int cell = cell_of(ev, j, cfg);
      sets_.make_set(j);
      if (first_in_cell_[cell] < 0) {
        first_in_cell_[cell] = static_cast<std::int16_t>(j);
        touched_[touched++] = cell;
      } else {
        sets_.unite(first_in_cell_[cell], j);
      }
    }
    // The four neighbours ahead of a cell; the other four see it.
    static constexpr int kAheadX[4] = {1, -1, 0, 1}, kAheadY[4] = {0, 1, 1, 1};
  neighbours:
    for (int k = 0; k < S::kPacketMax; ++k) {
      if (k >= touched) break;
      const int cx = touched_[k] % kCellsX, cy = touched_[k] / kCellsX;
      for (int a = 0; a < 4; ++a) {
#pragma HLS PIPELINE II = 1
        const int nx = cx + kAheadX[a], ny = cy + kAheadY[a];
        if (nx < 0 || nx >= kCellsX || ny >= kCellsY) continue;
        const int near = first_in_cell_[ny * kCellsX + nx];
        if (near >= 0) sets_.unite(first_in_cell_[touched_[k]], near);
      }
    }
  uncover:
    for (int k = 0; k < S::kPacketMax; ++k) {
#pragma HLS PIPELINE II = 1
      if (k >= touched) break;
      first_in_cell_[touched_[k]] = -1;
    }
  }

  // Sums each part at its root and numbers the large parts (large_of_, in the order of their
  // roots) and their groups (group_of_, groups_). Returns the large parts' count.
  int large_parts(const PacketEvents<S>& ev, int first, int size, const Config& cfg) {
  clear:
    for (int k = 0; k < S::kPacketMax; ++k) {
#pragma HLS PIPELINE II = 1
      if (k >= size) break;
      const int j = members_[first + k];
      events_[j] = on_[j] = 0;
      sum_x_[j] = sum_y_[j] = 0;
      x_min_[j] = y_min_[j] = 0xFFFF;
      x_max_[j] = y_max_[j] = 0;
      large_of_[j] = -1;
    }
  sums:
    for (int k = 0; k < S::kPacketMax; ++k) {
      if (k >= size) break;
      const int j = members_[first + k];
      const int r = sets_.find(j);
      part_of_[j] = static_cast<std::int16_t>(r);
      ++events_[r];
      on_[r] += ev.p[j] != 0;
      sum_x_[r] += ev.x[j];
      sum_y_[r] += ev.y[j];
      if (ev.x[j] < x_min_[r]) x_min_[r] = ev.x[j];
      if (ev.x[j] > x_max_[r]) x_max_[r] = ev.x[j];
      if (ev.y[j] < y_min_[r]) y_min_[r] = ev.y[j];
      if (ev.y[j] > y_max_[r]) y_max_[r] = ev.y[j];
    }
    int large = 0, one_polarity_group = -1;
    bool balanced = true;
    groups_ = 0;
  large_loop:
    for (int k = 0; k < S::kPacketMax; ++k) {
#pragma HLS PIPELINE II = 1
      if (k >= size) break;
      const int j = members_[first + k];
      if (part_of_[j] != j || events_[j] < cfg.split_min_events ||
          (std::int64_t{events_[j]} << kSplitFractionFrac) < std::int64_t{cfg.split_share} * size) {
        continue;
      }
      large_of_[j] = static_cast<std::int16_t>(large);
      large_root_[large++] = static_cast<std::int16_t>(j);
      const std::int64_t imbalance = 2 * on_[j] - events_[j];
      const std::int64_t imbalance_q = (imbalance < 0 ? -imbalance : imbalance) << kSplitFractionFrac;
      const bool both = imbalance_q < std::int64_t{cfg.split_balance} * events_[j];
      balanced = balanced && both;
      if (both || !cfg.split_partial) {
        group_of_[large - 1] = static_cast<std::int16_t>(groups_++);
      } else {
        if (one_polarity_group < 0) one_polarity_group = groups_++;
        group_of_[large - 1] = static_cast<std::int16_t>(one_polarity_group);
      }
    }
    if (!cfg.split_partial && !balanced) groups_ = 1;
    if (S::kHasConcentricGroups && cfg.split_concentric && groups_ >= 2) join_concentric_groups(large);
    return large;
  }

  // a's centre (sum / events) within a quarter of the box [lo, hi]'s side of its middle.
  static bool centre_in_middle_half(std::int64_t sum, std::int64_t events, int lo, int hi) {
    const std::int64_t off = 2 * sum - events * (lo + hi);
    return 2 * (off < 0 ? -off : off) <= events * (hi - lo + 1);
  }

  bool concentric(int a, int b) const {
    return centre_in_middle_half(group_x_[a], group_events_[a], group_x_min_[b], group_x_max_[b]) &&
           centre_in_middle_half(group_y_[a], group_events_[a], group_y_min_[b], group_y_max_[b]) &&
           centre_in_middle_half(group_x_[b], group_events_[b], group_x_min_[a], group_x_max_[a]) &&
           centre_in_middle_half(group_y_[b], group_events_[b], group_y_min_[a], group_y_max_[a]);
  }

  // Each later group joins the first earlier group concentric with it (an earlier group that has
  // not joined another); the groups are numbered again in the order of their first large parts.
  void join_concentric_groups(int large) {
  group_clear:
    for (int g = 0; g < S::kPacketMax; ++g) {
#pragma HLS PIPELINE II = 1
      if (g >= groups_) break;
      group_events_[g] = group_x_[g] = group_y_[g] = 0;
      group_x_min_[g] = group_y_min_[g] = 0xFFFF;
      group_x_max_[g] = group_y_max_[g] = 0;
      number_[g] = -1;
    }
  group_sums:
    for (int l = 0; l < S::kPacketMax; ++l) {
#pragma HLS PIPELINE II = 1
      if (l >= large) break;
      const int r = large_root_[l], g = group_of_[l];
      group_events_[g] += events_[r], group_x_[g] += sum_x_[r], group_y_[g] += sum_y_[r];
      if (x_min_[r] < group_x_min_[g]) group_x_min_[g] = x_min_[r];
      if (x_max_[r] > group_x_max_[g]) group_x_max_[g] = x_max_[r];
      if (y_min_[r] < group_y_min_[g]) group_y_min_[g] = y_min_[r];
      if (y_max_[r] > group_y_max_[g]) group_y_max_[g] = y_max_[r];
    }
  joins:
    for (int k = 0; k < S::kPacketMax; ++k) {
      if (k >= groups_) break;
      joins_[k] = static_cast<std::int16_t>(k);
    earlier:
      for (int j = 0; j < S::kPacketMax; ++j) {
#pragma HLS PIPELINE II = 1
        if (j >= k) break;
        if (joins_[k] == k && joins_[j] == j && concentric(k, j)) joins_[k] = static_cast<std::int16_t>(j);
      }
    }
    int left = 0;
  renumber:
    for (int l = 0; l < S::kPacketMax; ++l) {
#pragma HLS PIPELINE II = 1
      if (l >= large) break;
      const int root = joins_[group_of_[l]];
      if (number_[root] < 0) number_[root] = static_cast<std::int16_t>(left++);
      group_of_[l] = number_[root];
    }
    groups_ = left;
  }

  // Group g takes mode c (g = 0) or mode modes.count + g - 1; a large part its group's, a small
  // part the group of the large part with the nearest centre. Each group's mode is its events' mean.
  void reassign(const Features<S>& phi, int first, int size, int large, int c, std::int16_t mode_of[S::kPacketMax],
                Modes<S>& modes) {
  zero:
    for (int k = 0; k < S::kPacketMax; ++k) {
      if (k >= groups_) break;
      mean_x_[k] = mean_y_[k] = 0;
      count_[k] = 0;
    }
  members_loop:
    for (int m = 0; m < S::kPacketMax; ++m) {
      if (m >= size) break;
      const int j = members_[first + m];
      const int r = part_of_[j];
      int k = large_of_[r];
      if (k < 0) {  // a small part, at its first event: to the large part with the nearest centre
        std::int64_t best = 0;
      nearest:
        for (int l = 0; l < S::kPacketMax; ++l) {
#pragma HLS PIPELINE II = 1
          if (l >= large) break;
          const int q = large_root_[l];
          const std::int64_t dx = mean_sixteenths(sum_x_[r], events_[r]) - mean_sixteenths(sum_x_[q], events_[q]);
          const std::int64_t dy = mean_sixteenths(sum_y_[r], events_[r]) - mean_sixteenths(sum_y_[q], events_[q]);
          if (k < 0 || dx * dx + dy * dy < best) best = dx * dx + dy * dy, k = l;
        }
        large_of_[r] = static_cast<std::int16_t>(k);
      }
      const int g = group_of_[k];
      mode_of[j] = static_cast<std::int16_t>(g == 0 ? c : modes.count + g - 1);
      mean_x_[g] += phi.x[j];
      mean_y_[g] += phi.y[j];
      ++count_[g];
    }
  modes_loop:
    for (int k = 0; k < S::kPacketMax; ++k) {
      if (k >= groups_) break;
      const int m = k == 0 ? c : modes.count + k - 1;
      modes.x[m] = (2 * mean_x_[k] + count_[k]) / (2 * count_[k]);
      modes.y[m] = (2 * mean_y_[k] + count_[k]) / (2 * count_[k]);
      modes.p[m] = modes.t[m] = 0;  // the climbs' features are (x, y) only
    }
    modes.count += groups_ - 1;
  }

  std::int16_t first_in_cell_[kCellsX * kCellsY];  // the first event of the current cluster in a cell, or -1
  std::int32_t touched_[S::kPacketMax];            // the cells the current cluster occupies
  UnionFind<S::kPacketMax> sets_;                  // the current cluster's parts, over the packet's events
  std::int32_t start_[S::kModesMax + 1], fill_[S::kModesMax];
  std::int16_t members_[S::kPacketMax];
  // Per part, at its root: its events, its ON events and the sums of their pixel coordinates.
  std::int32_t events_[S::kPacketMax], on_[S::kPacketMax];
  std::int64_t sum_x_[S::kPacketMax], sum_y_[S::kPacketMax];
  std::int16_t part_of_[S::kPacketMax];   // per member: its part's root
  std::int16_t large_of_[S::kPacketMax];  // per root: the large part its events go to (its own index, or the nearest one's), or -1
  std::uint16_t x_min_[S::kPacketMax], x_max_[S::kPacketMax], y_min_[S::kPacketMax], y_max_[S::kPacketMax];  // per root: its box
  std::int16_t large_root_[S::kPacketMax];
  std::int16_t group_of_[S::kPacketMax];   // per large part: its group
  int groups_ = 0;
  // Per group, while the concentric groups join: its large parts' events, coordinate sums and box,
  // the earlier group it joins (itself if none) and its number after the joins.
  std::int64_t group_events_[S::kPacketMax], group_x_[S::kPacketMax], group_y_[S::kPacketMax];
  std::uint16_t group_x_min_[S::kPacketMax], group_x_max_[S::kPacketMax], group_y_min_[S::kPacketMax], group_y_max_[S::kPacketMax];
  std::int16_t joins_[S::kPacketMax], number_[S::kPacketMax];
  std::int64_t mean_x_[S::kPacketMax], mean_y_[S::kPacketMax];  // per group: its features' sums
  std::int32_t count_[S::kPacketMax];
};

}  // namespace evms::hls
