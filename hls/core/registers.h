// The core's registers, described once. Every copy is made from these two lists:
//   - hls/core/config.h (the Config struct), through the lists below;
//   - the RTL's cfg_* ports (the core's, and the filter's sensor_* and filter_* alone for the
//     intake and a core cut after its filter), the board's Cfg* parameters and their
//     connections, the per-build reset values, and docs/registers.md, written by
//     host/tools/rtl_gen into rtl/generated/;
//   - the Verilated and SystemC testbenches' port assignments (sim/rtl_core.h,
//     sim/systemc/sc_core_tb.cpp), through the lists below.
//
// X(name, type, bits, reset, description):
//   name         the Config member; the RTL port is cfg_<name>, the board parameter Cfg<Name>
//   type         its C++ type
//   bits         its width in the RTL (unsigned there; a signed value travels as its bits)
//   reset        its value in a default-constructed Config
//   description  what it holds and in what format (formats: hls/core/shape.h)
#pragma once

// Registers of both the C++ core and the RTL core (rtl/core/evms_core.sv).
#define EVMS_CORE_RTL_REGISTERS(X)                                                                                      \
  X(sensor_width, std::uint16_t, 16, 240, "sensor width, px")                                                           \
  X(sensor_height, std::uint16_t, 16, 180, "sensor height, px")                                                         \
  X(filter_enabled, bool, 1, true, "background-activity filter on")                                                     \
  X(filter_window, std::uint32_t, 32, 78, "filter window, stored time units (2^kTimestampShift us)")                    \
  X(filter_noise_count, std::uint32_t, 24, 0, "unsupported events in 2^15 us that make the next 2^15 us ask one more neighbour; 0: off") \
  X(filter_quiet_count, std::uint32_t, 24, 0, "unsupported events in 2^15 us below which the next 2^15 us judge by filter_quiet_window; 0: off") \
  X(filter_quiet_window, std::uint32_t, 32, 0, "filter window after a quiet interval, stored time units (2^kTimestampShift us)") \
  X(filter_warm_up, std::uint32_t, 32, 0, "keep every event of the stream's first this many us (from the first event the filter judges); 0: off") \
  X(packet_size, std::uint16_t, 16, 256, "kept events that close a packet (at most kPacketMax)")                        \
  X(packet_max_span_us, std::uint32_t, 32, 0, "a packet also closes when it would span more than this, us; 0: never")   \
  X(scale_x, std::uint32_t, 32, 0, "Gaussian feature: phi_x = x * scale_x, kCoordScaleFrac fraction bits")              \
  X(scale_y, std::uint32_t, 32, 0, "Gaussian feature: phi_y = y * scale_y, kCoordScaleFrac fraction bits")              \
  X(phi_on, std::uint32_t, 32, 0, "Gaussian feature: phi_p of an ON event (OFF: 0), kFeatFrac fraction bits")           \
  X(phi_t_max, std::uint32_t, 32, 0, "Gaussian feature: phi_t = phi_t_max * exp(-dt * inv_tau), kFeatFrac bits")        \
  X(inv_tau, std::uint64_t, 64, 0, "1 / tau per us, kDecayFrac fraction bits")                                          \
  X(max_iterations, std::uint8_t, 8, 8, "mean-shift iterations at most (at most kIterationsMax)")                       \
  X(tolerance, std::uint32_t, 32, 0, "largest move that counts as converged, phi raw units")                            \
  X(merge_radius2, std::uint64_t, 64, 0, "squared merge radius of modes, phi^2 raw units")                              \
  X(min_cluster_size, std::uint16_t, 16, 8, "events a cluster needs, or its events are noise")                          \
  X(max_clusters, std::uint8_t, 8, 16, "clusters a packet keeps, largest first (at most kClustersMax)")                 \
  X(gate2, std::uint64_t, 64, 0, "squared association gate, px^2 with 2 * kPosFrac fraction bits")                      \
  X(confirm_hits, std::uint8_t, 8, 3, "updates that confirm a track")                                                   \
  X(coast_us, std::uint32_t, 32, 100000, "a track unmatched this long ends, us")                                        \
  X(max_tracks, std::uint8_t, 8, 16, "track slots (at most kTracksMax)")                                                \
  X(q_third, std::int64_t, 64, 0, "process noise q / 3 per tick^3, kNoiseFrac fraction bits")                           \
  X(q_half, std::int64_t, 64, 0, "process noise q / 2 per tick^3, kNoiseFrac fraction bits")                            \
  X(q, std::int64_t, 64, 0, "process noise q per tick^3, kNoiseFrac fraction bits")                                     \
  X(r, std::int64_t, 64, 0, "measurement variance, px^2, kCovFrac fraction bits")                                       \
  X(p0_pos, std::int64_t, 64, 0, "position variance a track starts with, px^2, kCovFrac fraction bits")                      \
  X(p0_vel, std::int64_t, 64, 0, "velocity variance a track starts with, (px/tick)^2, kCovFrac bits")                   \
  X(seeded, bool, 1, false, "climbs from seeds with the flat kernel (hls/cluster/seeded_climbs.h), not every event")    \
  X(climb_scale_x, std::uint64_t, 64, 0, "seeded: phi_x = x * climb_scale_x, kClimbScaleFrac fraction bits")            \
  X(climb_scale_y, std::uint64_t, 64, 0, "seeded: phi_y = y * climb_scale_y, kClimbScaleFrac fraction bits")            \
  X(warm_start, bool, 1, false, "seeded: the modes of the previous packet climb first")                                 \
  X(warm_scale2, std::uint32_t, 32, 0, "seeded: radius^2 of a warm ball per variance of its cluster, kSpreadFrac bits") \
  X(warm_ball2_max, std::uint64_t, 64, 0, "seeded: radius^2 of the largest warm ball, phi^2 raw units (at least h^2)")  \
  X(link2, std::uint32_t, 32, 0, "seeded: clusters with events within sqrt(link2) px join; 0: off")                     \
  X(associate_last, bool, 1, false, "gate against the last measurement of a track, not its prediction")                 \
  X(evict_stale, bool, 1, false, "with no free slot, take the unmatched slot measured longest ago")                     \
  X(size_ratio_log2, std::uint8_t, 4, 0, "pairs whose event counts differ by more than 2^this are taken last; 0: off")  \
  X(report_tentative, bool, 1, false, "tentative tracks report their updates too")                                     \
  X(split_balance, std::uint16_t, 16, 0, "seeded: parts hold both polarities when |2 ON - events| < this * events, kSplitFractionFrac bits; 0: no split (the only setting of a build without HasPolaritySplit)") \
  X(split_share, std::uint16_t, 16, 0, "seeded: a part is large with at least this share of its cluster, kSplitFractionFrac bits") \
  X(split_min_events, std::uint16_t, 16, 0, "seeded: a part is large with at least this many events too; a cluster of fewer than twice this is not looked at") \
  X(split_cell_scale_x, std::uint32_t, 32, 0, "seeded: a split cell's column is (x * this) >> kSplitCellFrac (at most 2^15)") \
  X(split_cell_scale_y, std::uint32_t, 32, 0, "seeded: a split cell's row is (y * this) >> kSplitCellFrac (at most 2^15)") \
  X(split_partial, bool, 1, false, "seeded: each large part that holds both polarities becomes a cluster and the other large parts one more; false: a cluster splits only when every large part holds both") \
  X(midpoint_min, std::uint16_t, 16, 0, "seeded: a cluster whose ON and OFF events number at least this each is measured at the midpoint of their centres of mass; 0: at the centre of mass (the only setting of a build without HasPolarityMidpoint)") \
  X(edge_radius2, std::uint64_t, 64, 0, "seeded: a mostly-ON and a mostly-OFF mode whose centres lie within sqrt(this) / 16 px join (hls/cluster/edge_join.h); 0: off (the only setting of a build without HasEdgeJoin)") \
  X(edge_balance, std::uint16_t, 16, 0, "seeded: a mode is mostly one polarity when |2 ON - events| >= this * events, kSplitFractionFrac bits") \
  X(edge_min_events, std::uint16_t, 16, 0, "seeded: the edge join looks at modes of at least this many events")        \
  X(meas_from_spread, bool, 1, false, "the measurement variance is r (spread^2 + 1/6 px^2) / events instead of r (hls/track/measurement_variance.h); false: r (the only setting of a build without HasSpreadNoise)") \
  X(min_density, std::uint32_t, 32, 0, "seeded: a mode whose climbs' last balls held fewer than n * this events (n the packet's) is noise, kDensityFrac fraction bits; 0: off") \
  X(density_after_links, bool, 1, false, "seeded: min_density is tested on each set of linked modes after the links (noise when none of its modes is dense or it holds fewer than n * min_density events), not on each mode before them (false: the only setting of a build without HasDensityAfterLinks)") \
  X(gate_boxes, bool, 1, false, "a pair beyond the gate is a candidate after every pair within it when the track's last measurement lies in the measurement's box or the measurement in the last one's") \
  X(pixel_centre, bool, 1, false, "seeded: a cluster is measured at the mean of the pixels its events fall on, each pixel once (marked by the links, so link2 != 0); false: at the centre of mass or midpoint (the only setting of a build without HasPixelCentre)")

// Registers of the C++ core only: the filter's support count, the gate's widening by a
// cluster's spread, coasting by packets, the labels of the filter's dropped events, the
// measurement of a fast track's cluster by its motion, the split of a cluster by its events'
// motions and the polarity split's concentric groups. The RTL refuses a setting that needs them
// (host/backend/core_config.h).
#define EVMS_CORE_HLS_REGISTERS(X)                                                                                      \
  X(filter_support, std::uint8_t, 8, 1, "neighbours that must have fired within the filter window")                     \
  X(gate_spread2, std::uint32_t, 32, 0, "widening of the gate by the spread of the cluster, squared, kSpreadFrac bits") \
  X(coast_packets, std::uint32_t, 32, 0, "a confirmed track also ends after missing this many packets; 0: never") \
  X(rescue_reach, std::uint8_t, 8, 0, "an event the filter dropped takes the label of the nearest labelled event of its packet within this many px (at most kRescueMax; a build with HasRescue); 0: off") \
  X(pixel_time, std::uint8_t, 1, 0, "the pixel centre is timed at the mean timestamp of its pixels' first events, not of all its events (hls/cluster/centroid.h; a build with HasPixelTime)") \
  X(motion_speed, std::uint32_t, 32, 0, "a cluster that holds a confirmed track at least this fast (px per tick, kPosFrac bits) and another confirmed track is measured from the pixels whose time-surface slopes the fast one's velocity explains (hls/track/motion_measure.h; a build with HasMotionMeasure; the host sets it with pixel_centre only); 0: off") \
  X(motion_split_gain, std::uint16_t, 16, 0, "seeded: a cluster of 200 events or more whose box holds the predictions of two matched confirmed tracks splits in two when two velocities leave at most this share of one velocity's residual of its time-surface slopes (hls/cluster/motion_split.h, kMotionGainFrac fraction bits; a build with HasMotionMeasure); 0: off") \
  X(split_concentric, bool, 1, false, "seeded, with the polarity split: two groups of a cluster's parts stay one cluster when each one's centre lies in the middle half of the other's bounding box (hls/cluster/polarity_split.h; a build with HasConcentricGroups)")
