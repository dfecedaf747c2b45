// The leading and trailing edges of one outline, joined into one cluster (golden/cluster/edge_join.h
// states the rule and why): a mostly-ON and a mostly-OFF cluster whose centres lie within the
// radius, neither holding more than kEdgeSizeRatio times the other's events, and each the other's
// nearest such, become one.
//
// Integers throughout, the same as golden's (EdgeRule in types/params.h):
//   looked at        events >= edge_min_events
//   mostly ON        (2 on - events) << kSplitFractionFrac >= edge_balance * events (OFF: events - 2 on)
//   centre           1/16 px, (32 sum + events) / (2 events)
//   within reach     dx^2 + dy^2 <= edge_radius2
//   nearest          the least such distance; ties to the lower mode
// The later mode's events take the earlier mode, which keeps its position.
//
// In hardware form (rtl/cluster/evms_edge_join.sv): one pass over the packet accumulates each
// mode's sums, then each leaning mode scans the modes of the other lean (listed once) for its
// nearest, and a table from mode to mode relabels.
#pragma once

#include <cstdint>

#include "hls/cluster/features.h"
#include "hls/core/config.h"
#include "hls/core/shape.h"
#include "hls/math/round.h"

namespace evms::hls {

template <class S>
class EdgeJoin {
 public:
  // `mode_of`: per event, a mode in 0 .. modes - 1, or -1. Returns the pairs joined.
  int run(const PacketEvents<S>& ev, int n, const Config& cfg, int modes, std::int16_t mode_of[S::kPacketMax]) {
    if (cfg.edge_radius2 == 0) return 0;
  clear:
    for (int c = 0; c < S::kModesMax; ++c) {
#pragma HLS PIPELINE II = 1
      if (c >= modes) break;
      events_[c] = on_[c] = 0;
      sum_x_[c] = sum_y_[c] = 0;
    }
  accumulate:
    for (int j = 0; j < S::kPacketMax; ++j) {
#pragma HLS PIPELINE II = 1
      if (j >= n) break;
      const int c = mode_of[j];
      if (c < 0) continue;
      ++events_[c], on_[c] += ev.p[j], sum_x_[c] += ev.x[j], sum_y_[c] += ev.y[j];
    }
    // The leaning modes, each lean listed once, with their centres.
    int leaning = 0;
  lean:
    for (int c = 0; c < S::kModesMax; ++c) {
#pragma HLS PIPELINE II = 1
      if (c >= modes) break;
      nearest_[c] = -1;
      if (events_[c] == 0 || events_[c] < cfg.edge_min_events) continue;  // an empty mode has no centre, whatever the register
      const std::int64_t surplus = 2 * std::int64_t{on_[c]} - events_[c];
      const std::int64_t needed = std::int64_t{cfg.edge_balance} * events_[c];
      const std::int64_t scaled = surplus * (1 << kSplitFractionFrac);
      const int lean = scaled >= needed ? 1 : (-scaled >= needed ? -1 : 0);
      if (lean == 0) continue;
      list_[leaning] = static_cast<std::int16_t>(c);
      lean_[leaning] = static_cast<std::int8_t>(lean);
      centre_x_[leaning] = mean_sixteenths(sum_x_[c], events_[c]);
      centre_y_[leaning] = mean_sixteenths(sum_y_[c], events_[c]);
      ++leaning;
    }
  pairs:
    for (int a = 0; a < kLeaningMax; ++a) {
      if (a >= leaning) break;
      std::uint64_t best = 0;
      int with = -1;
    partners:
      for (int b = 0; b < kLeaningMax; ++b) {
#pragma HLS PIPELINE II = 1
        if (b >= leaning) break;
        if (lean_[b] != -lean_[a]) continue;
        const int na = events_[list_[a]], nb = events_[list_[b]];
        if (na > kEdgeSizeRatio * nb || nb > kEdgeSizeRatio * na) continue;
        const std::int64_t dx = centre_x_[a] - centre_x_[b], dy = centre_y_[a] - centre_y_[b];
        const auto d2 = static_cast<std::uint64_t>(dx * dx + dy * dy);
        // The list is in mode order, so the first of equal distances is the lower mode.
        if (d2 <= cfg.edge_radius2 && (with < 0 || d2 < best)) with = list_[b], best = d2;
      }
      nearest_[list_[a]] = static_cast<std::int16_t>(with);
    }
    int joined = 0;
  into:
    for (int c = 0; c < S::kModesMax; ++c) {
#pragma HLS PIPELINE II = 1
      if (c >= modes) break;
      const int b = nearest_[c];
      const bool mutual = b >= 0 && b < c && nearest_[b] == c;
      into_[c] = static_cast<std::int16_t>(mutual ? b : c);
      joined += mutual ? 1 : 0;
    }
  relabel:
    for (int j = 0; j < S::kPacketMax; ++j) {
#pragma HLS PIPELINE II = 1
      if (j >= n) break;
      if (mode_of[j] >= 0) mode_of[j] = into_[mode_of[j]];
    }
    return joined;
  }

 private:
  // A leaning mode holds at least min_cluster_size events (at least 1), so at most the packet's
  // events lean.
  static constexpr int kLeaningMax = S::kModesMax < S::kPacketMax ? S::kModesMax : S::kPacketMax;
  int events_[S::kModesMax], on_[S::kModesMax];
  std::int64_t sum_x_[S::kModesMax], sum_y_[S::kModesMax];
  std::int16_t nearest_[S::kModesMax], into_[S::kModesMax];
  std::int16_t list_[kLeaningMax];
  std::int8_t lean_[kLeaningMax];
  std::int64_t centre_x_[kLeaningMax], centre_y_[kLeaningMax];
};

}  // namespace evms::hls
