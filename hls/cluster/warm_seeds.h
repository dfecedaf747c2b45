// The seeded path after the climbs and the links: which modes become clusters, and the warm
// seeds they give the next packet (hls/cluster/seeded_climbs.h climbs from them first).
#pragma once

#include <cstdint>

#include "hls/cluster/centroid.h"
#include "hls/cluster/features.h"
#include "hls/cluster/seeded_climbs.h"
#include "hls/core/config.h"

namespace evms::hls {

// Modes (after linking) with at least min_cluster_size events become clusters, the first
// max_clusters of them in the order they opened; their positions become the warm seeds
// (warm.x, warm.y, warm.p, warm.t and warm.count; the balls are warm_balls'). Returns the
// cluster count.
template <class S>
int keep_clusters(const std::int16_t mode_of[S::kPacketMax], int n, const Modes<S>& modes, const Config& cfg,
                  std::int8_t cluster_of[S::kPacketMax], Modes<S>& warm) {
  int size[S::kModesMax];
count:
  for (int c = 0; c < S::kModesMax; ++c) {
    if (c >= modes.count) break;
    size[c] = 0;
  }
sizes:
  for (int j = 0; j < S::kPacketMax; ++j) {
    if (j >= n) break;
    if (mode_of[j] >= 0) ++size[mode_of[j]];
  }
  std::int16_t renumber[S::kModesMax];
  int kept = 0;
survivors:
  for (int c = 0; c < S::kModesMax; ++c) {
    if (c >= modes.count) break;
    renumber[c] = -1;
    if (size[c] >= cfg.min_cluster_size && kept < cfg.max_clusters && kept < S::kClustersMax) {
      renumber[c] = static_cast<std::int16_t>(kept);
      warm.x[kept] = modes.x[c], warm.y[kept] = modes.y[c], warm.p[kept] = modes.p[c], warm.t[kept] = modes.t[c];
      ++kept;
    }
  }
  warm.count = kept;
relabel:
  for (int j = 0; j < S::kPacketMax; ++j) {
    if (j >= n) break;
    cluster_of[j] = static_cast<std::int8_t>(mode_of[j] < 0 ? -1 : renumber[mode_of[j]]);
  }
  return kept;
}

// The ball each warm seed climbs with in the next packet: radius^2 = warm_scale2 times the
// variance of its cluster's features, clamped to [h^2, warm_ball2_max]. The sums run about the
// seed, so that they stay within 64 bits; var = S2 / n - (S1 / n)^2, each quotient rounded.
template <class S>
void warm_balls(const Features<S>& phi, int n, const std::int8_t cluster_of[S::kPacketMax], const Config& cfg, Modes<S>& warm) {
  std::int64_t s1[4][S::kClustersMax], count[S::kClustersMax];
  std::uint64_t s2[4][S::kClustersMax];  // a cluster across a 1280 px sensor reaches 2^63
clear:
  for (int c = 0; c < S::kClustersMax; ++c) {
    count[c] = 0;
    for (int d = 0; d < 4; ++d) s1[d][c] = s2[d][c] = 0;
  }
accumulate:
  for (int j = 0; j < S::kPacketMax; ++j) {
#pragma HLS PIPELINE II = 1
    if (j >= n) break;
    const int c = cluster_of[j];
    if (c < 0) continue;
    const std::int64_t v[4] = {phi.x[j] - warm.x[c], phi.y[j] - warm.y[c], phi.p[j] - warm.p[c], phi.t[j] - warm.t[c]};
    for (int d = 0; d < 4; ++d) s1[d][c] += v[d], s2[d][c] += static_cast<std::uint64_t>(v[d] * v[d]);
    ++count[c];
  }
  constexpr std::uint64_t kOne = SeededClimbs<S>::kOne;
  const std::uint64_t top = cfg.warm_ball2_max > kOne ? cfg.warm_ball2_max : kOne;
balls:
  for (int c = 0; c < S::kClustersMax; ++c) {
    if (c >= warm.count) break;
    std::int64_t var = 0;
    for (int d = 0; d < 4; ++d) {
      const std::int64_t mean = s1[d][c] >= 0 ? (2 * s1[d][c] + count[c]) / (2 * count[c]) : -((-2 * s1[d][c] + count[c]) / (2 * count[c]));
      const auto m = static_cast<std::uint64_t>(count[c]);
      var += static_cast<std::int64_t>(s2[d][c] / m + (s2[d][c] % m >= (m + 1) / 2 ? 1 : 0)) - mean * mean;
    }
    const auto v = static_cast<std::uint64_t>(var > 0 ? var : 0);
    const std::uint64_t ball2 = (std::uint64_t{cfg.warm_scale2} * v + (std::uint64_t{1} << (kSpreadFrac - 1))) >> kSpreadFrac;
    warm.ball2[c] = ball2 < kOne ? kOne : (ball2 > top ? top : ball2);
  }
}

}  // namespace evms::hls
