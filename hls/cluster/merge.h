// Modes to clusters, as golden/cluster/mean_shift.h states it: each mode in input order joins
// the nearest seed (a cluster's first mode) within the merge radius (ties: the older
// cluster), or opens a new cluster while fewer than max_clusters are open, or is noise.
// Clusters smaller than min_cluster_size become noise; the rest are numbered in seed order.
#pragma once

#include <cstdint>

#include "hls/cluster/features.h"

namespace evms::hls {

// What the merging did, for the cycle model (hls/core/schedule.h).
struct MergeTrace {
  int seeds = 0;        // clusters opened, before small ones became noise
  int seed_visits = 0;  // (mode, seed) distances taken
};

// Writes each point's cluster (or -1) and returns the number of clusters.
template <class S>
int merge_modes(const Features<S>& m, int n, const Config& cfg, std::int8_t cluster_of[S::kPacketMax], MergeTrace& trace) {
  int seed[S::kClustersMax];
  int size[S::kClustersMax];
  int seeds = 0;
  trace.seed_visits = 0;
points:
  for (int i = 0; i < S::kPacketMax; ++i) {
    if (i >= n) break;
    int best = -1;
    std::uint64_t best_d2 = ~std::uint64_t{0};
    trace.seed_visits += seeds;
  seeds_loop:
    for (int c = 0; c < S::kClustersMax; ++c) {
#pragma HLS PIPELINE II = 1
      if (c >= seeds) break;
      const int s = seed[c];
      const std::int64_t dx = std::int64_t{m.x[i]} - m.x[s], dy = std::int64_t{m.y[i]} - m.y[s];
      const std::int64_t dp = std::int64_t{m.p[i]} - m.p[s], dt = std::int64_t{m.t[i]} - m.t[s];
      const std::uint64_t d2 = squared_distance(dx, dy, dp, dt);
      if (d2 <= cfg.merge_radius2 && d2 < best_d2) best = c, best_d2 = d2;
    }
    if (best < 0 && seeds < cfg.max_clusters && seeds < S::kClustersMax) {
      best = seeds;
      seed[seeds] = i;
      size[seeds] = 0;
      ++seeds;
    }
    if (best >= 0) ++size[best];
    cluster_of[i] = static_cast<std::int8_t>(best);
  }
  trace.seeds = seeds;
  std::int8_t renumber[S::kClustersMax];
  int count = 0;
  for (int c = 0; c < S::kClustersMax; ++c) {
    if (c >= seeds) break;
    renumber[c] = static_cast<std::int8_t>(size[c] >= cfg.min_cluster_size ? count++ : -1);
  }
relabel:
  for (int i = 0; i < S::kPacketMax; ++i) {
    if (i >= n) break;
    if (cluster_of[i] >= 0) cluster_of[i] = renumber[cluster_of[i]];
  }
  return count;
}

}  // namespace evms::hls
