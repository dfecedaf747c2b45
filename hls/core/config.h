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
  // Packets.
  std::uint16_t packet_size = 256;         // <= kPacketMax
  std::uint32_t packet_max_span_us = 0;    // 0: only full packets close
  // Features, in bandwidth units: phi_x = x * scale_x, phi_y = y * scale_y (kCoordScaleFrac),
  // phi_p = p ? phi_on : 0, phi_t = phi_t_max * exp(-dt * inv_tau) (kFeatFrac; kDecayFrac).
  std::uint32_t scale_x = 0, scale_y = 0;
  std::uint32_t phi_on = 0;
  std::uint32_t phi_t_max = 0;
  std::uint64_t inv_tau = 0;
  // Mean shift.
  std::uint8_t max_iterations = 8;         // <= kIterationsMax
  std::uint32_t tolerance = 0;             // largest move that counts as converged, phi raw units
  std::uint64_t merge_radius2 = 0;         // squared merge radius, 2 * kFeatFrac fraction bits
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
};

}  // namespace evms::hls
