// Each cluster's measurement: the centre of mass of its events' pixel positions (kPosFrac
// fraction bits, rounded) timed at the rounded mean of their timestamps.
#pragma once

#include <cstdint>

#include "hls/cluster/features.h"
#include "hls/cluster/tables.h"

namespace evms::hls {

struct Measurement {
  std::uint32_t t = 0;
  std::int32_t x = 0, y = 0;  // kPosFrac fraction bits, px
};

template <class S>
void centroids(const PacketEvents<S>& ev, int n, const std::int8_t cluster_of[S::kPacketMax], int clusters,
               Measurement out[S::kClustersMax]) {
  std::uint32_t sx[S::kClustersMax] = {}, sy[S::kClustersMax] = {}, count[S::kClustersMax] = {};
  std::uint64_t st[S::kClustersMax] = {};
  const std::uint32_t t0 = ev.t[0];
accumulate:
  for (int i = 0; i < S::kPacketMax; ++i) {
#pragma HLS PIPELINE II = 1
    if (i >= n) break;
    const int c = cluster_of[i];
    if (c < 0) continue;
    sx[c] += ev.x[i];
    sy[c] += ev.y[i];
    st[c] += ev.t[i] - t0;
    ++count[c];
  }
divide:
  for (int c = 0; c < S::kClustersMax; ++c) {
    if (c >= clusters) break;
    out[c].x = static_cast<std::int32_t>(Tables<S>::recip.template divide<S::kPosFrac>(sx[c], count[c]));
    out[c].y = static_cast<std::int32_t>(Tables<S>::recip.template divide<S::kPosFrac>(sy[c], count[c]));
    out[c].t = t0 + static_cast<std::uint32_t>(Tables<S>::recip.template divide<0>(st[c], count[c]));
  }
}

}  // namespace evms::hls
