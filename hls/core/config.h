// The core's runtime settings, as registers. The host computes them from the method's
// parameters (host/backend/core_config.cpp); the board top has them as reset values.
#pragma once

#include <cstdint>

namespace evms::hls {

struct Config {
  std::uint16_t sensor_width = 240;
  std::uint16_t sensor_height = 180;
  // Background-activity filter.
  bool filter_enabled = true;
  std::uint32_t filter_window = 78;        // in stored time units (2^kTimestampShift us)
  std::uint8_t filter_support = 1;         // neighbours that must have fired within the window
  // Packets.
  std::uint16_t packet_size = 256;         // <= kPacketMax
  std::uint32_t packet_max_span_us = 0;    // 0: only full packets close
  // Features, in bandwidth units: phi_x = x * scale_x, phi_y = y * scale_y (kCoordScaleFrac),
  // phi_p = p ? phi_on : 0, phi_t = phi_t_max * exp(-dt * inv_tau) (kFeatFrac; kDecayFrac).
  std::uint32_t scale_x = 0, scale_y = 0;
  std::uint32_t phi_on = 0;
  std::uint32_t phi_t_max = 0;
  std::uint64_t inv_tau = 0;
  // Mean shift. seeded: climbs from seeds with a flat kernel, features in h units
  // (hls/cluster/seeded_climbs.h); otherwise every event climbs with the Gaussian kernel,
  // features in h sqrt(2) units (hls/cluster/mean_shift.h), as the RTL does.
  bool seeded = false;
  std::uint64_t climb_scale_x = 0, climb_scale_y = 0;  // seeded: phi = x * scale (kClimbScaleFrac)
  bool warm_start = false;                 // seeded: the previous packet's modes climb first
  std::uint32_t warm_scale2 = 0;           // ... each with a ball of radius^2 warm_scale2 * its cluster's
                                           //     variance (kSpreadFrac fraction bits), clamped to
  std::uint64_t warm_ball2_max = 0;        //     [h^2, warm_ball2_max] (phi^2 raw)
  // (seeded: phi has kFeatFrac + kClimbFrac fraction bits, hls/cluster/seeded_climbs.h)
  std::uint32_t link2 = 0;                 // seeded: clusters with events within sqrt(link2) px join; 0 = off
  std::uint8_t max_iterations = 8;         // <= kIterationsMax
  std::uint32_t tolerance = 0;             // largest move that counts as converged, phi raw units
  std::uint64_t merge_radius2 = 0;         // squared merge radius, phi^2 raw units
  std::uint16_t min_cluster_size = 8;
  std::uint8_t max_clusters = 16;          // <= kClustersMax
  // Tracker.
  std::uint64_t gate2 = 0;                 // squared gate, px^2 with 2 * kPosFrac fraction bits
  std::uint8_t confirm_hits = 3;
  std::uint32_t coast_us = 100000;
  std::uint8_t max_tracks = 16;            // <= kTracksMax
  std::int64_t q_third = 0, q_half = 0, q = 0;  // process noise per tick^3 (kNoiseFrac)
  std::int64_t r = 0;                      // measurement variance, px^2 (kCovFrac)
  std::int64_t p0_pos = 0, p0_vel = 0;     // initial variances, px^2 and (px/tick)^2 (kCovFrac)
  bool associate_last = false;             // gate against the last measurement, not the prediction
  std::uint32_t gate_spread2 = 0;          // the gate's widening by the cluster's spread, squared (kSpreadFrac)
  std::uint32_t coast_packets = 0;         // a confirmed track also ends after missing this many; 0 = never
  bool evict_stale = false;                // with no free slot, take the unmatched slot measured longest ago
  bool report_tentative = false;           // tentative tracks report their updates too
};

}  // namespace evms::hls
