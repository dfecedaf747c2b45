// The least density on each set of linked modes (Config::density_after_links,
// golden/cluster/clustering.cpp): after the links a set is noise when none of its modes is
// dense, or when it holds fewer events than a dense mode's ball (n * min_density), so that a
// sparse arc that touches a dense mode stays in its cluster while a few scattered events that
// reach a dense ball of others' events do not become one. The climbs keep each mode's support
// and leave the test to this pass (hls/cluster/seeded_climbs.h); the links have replaced each
// event's mode by its set's oldest mode (hls/cluster/link.h).
#pragma once

#include <cstdint>

#include "hls/cluster/link.h"
#include "hls/cluster/seeded_climbs.h"
#include "hls/core/config.h"
#include "hls/core/shape.h"

namespace evms::hls {

template <class S>
void drop_sparse_sets(const SeededClimbs<S>& climbs, ModeLinks<S>& links, int n, int mode_count, const Config& cfg,
                      std::int16_t mode_of[S::kPacketMax]) {
  bool dense_set[S::kModesMax];
  std::uint16_t set_events[S::kModesMax];
clear:
  for (int c = 0; c < S::kModesMax; ++c) {
#pragma HLS PIPELINE II = 1
    dense_set[c] = false;
    set_events[c] = 0;
  }
count:
  for (int j = 0; j < S::kPacketMax; ++j) {
#pragma HLS PIPELINE II = 1
    if (j >= n) break;
    if (mode_of[j] >= 0) ++set_events[mode_of[j]];
  }
  const std::uint64_t least = climbs.least(n, cfg);
dense_modes:
  for (int c = 0; c < S::kModesMax; ++c) {
#pragma HLS PIPELINE II = 1
    if (c >= mode_count) break;
    const int root = links.root(c);
    if (!climbs.sparse(c, n, cfg) && (static_cast<std::uint64_t>(set_events[root]) << kDensityFrac) >= least) dense_set[root] = true;
  }
sparse_sets:
  for (int j = 0; j < S::kPacketMax; ++j) {
#pragma HLS PIPELINE II = 1
    if (j >= n) break;
    if (mode_of[j] >= 0 && !dense_set[mode_of[j]]) mode_of[j] = -1;
  }
}

}  // namespace evms::hls
