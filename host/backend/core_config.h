// The method's parameters (types/params.h, doubles in physical units) as the core's
// registers (hls/core/config.h, integers in the Shape's formats). Every backend built on the
// core (fixed, rtl, board) and the RTL generator use this one conversion.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cmath>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <string_view>

#include "types/params.h"
#include "hls/cluster/centroid.h"
#include "hls/cluster/edge_join.h"
#include "hls/cluster/seeded_climbs.h"
#include "hls/core/config.h"
#include "hls/core/configs.h"
#include "hls/track/kalman_axis.h"

namespace evms::backend {

// The board a core build is for (EVMS_BOARD_BUILDS, hls/core/configs.h): its clock, its UART's
// clocks a bit and its link queue's depth in events; all 0 for a build without a board.
struct BoardOfBuild {
  long long clock_hz = 0, clocks_per_bit = 0, link_fifo_depth = 0;
  // Where the board's core stops; a cut core returns verdicts (and its climbs), and the host
  // runs the rest.
  hls::CoreCut core_cut = hls::CoreCut::kWhole;
  constexpr bool cut() const { return core_cut != hls::CoreCut::kWhole; }
  // Its UART's line rate, which the host's serial port must match: 6 Mbaud on the iCEBreaker,
  // 2 Mbaud on the Arty.
  constexpr long long baud() const { return clocks_per_bit > 0 ? clock_hz / clocks_per_bit : 0; }
};
constexpr BoardOfBuild board_of(std::string_view build) {
#define EVMS_BOARD_OF(name, clock_hz, clocks_per_bit, link_fifo_depth, cut, cut_shape) \
  if (build == #name) return {clock_hz, clocks_per_bit, link_fifo_depth, static_cast<hls::CoreCut>(cut)};
  EVMS_BOARD_BUILDS(EVMS_BOARD_OF)
#undef EVMS_BOARD_OF
  return {};
}

// The method `p` within build S: the packet size, cluster and track counts cut to what S holds,
// and without the polarity split, the polarity midpoint or the pixel centre, the edge join, the
// measurement noise from the spread, the gate's boxes and the least density on the linked sets
// where S does not hold them (Shape::kHasPolaritySplit, kHasPolarityMidpoint, kHasPixelCentre,
// kHasEdgeJoin, kHasSpreadNoise, kHasGateBoxes, kHasDensityAfterLinks: the board builds),
// without the dropped events' labels, the motion measure, the split by motion and the polarity
// split's concentric groups where S does not hold them (kHasRescue, kHasMotionMeasure,
// kHasPixelTime, kHasConcentricGroups: every RTL build), and without warm seeds where S starts without them (kHasWarmSeeds), each
// unless `kept(name)` says the command line set it, for the backend to refuse what S cannot run.
template <class S, class Kept>
Params within_build(Params p, Kept kept) {
  auto cut = [&](int& value, const char* name, int build_max) {
    if (!kept(name)) value = std::min(value, build_max);
  };
  cut(p.packet_size, "packet-size", S::kPacketMax);
  cut(p.max_clusters, "max-clusters", S::kClustersMax);
  cut(p.max_tracks, "max-tracks", S::kTracksMax);
  if (!S::kHasPolaritySplit && !kept("split-balance")) p.split_balance = 0;
  const bool measure_held = p.measure == Measure::kPolarityMidpoint ? S::kHasPolarityMidpoint != 0
                            : p.measure == Measure::kPixelCentre    ? S::kHasPixelCentre != 0
                                                                    : true;
  if (!measure_held && !kept("measure")) p.measure = Measure::kCentroid;
  if (!S::kHasEdgeJoin && !kept("edge-join")) p.edge_join = 0;
  if (!S::kHasSpreadNoise && !kept("meas-noise-from-spread")) p.meas_noise_from_spread = false;
  if (!S::kHasGateBoxes && !kept("gate-boxes")) p.gate_boxes = false;
  if (!S::kHasDensityAfterLinks && !kept("density-after-links")) p.density_after_links = false;
  if (!S::kHasWarmSeeds && !kept("warm-start")) p.warm_start = false;
  if (!S::kHasRescue && !kept("rescue-px")) p.rescue_px = 0;
  if (!S::kHasMotionMeasure && !kept("motion-measure")) p.motion_measure = 0;
  if (!S::kHasMotionMeasure && !kept("motion-split")) p.motion_split = 0;
  if (!S::kHasConcentricGroups && !kept("split-concentric")) p.split_concentric = false;
  if (!S::kHasPixelTime && !kept("time-by-pixels")) p.time_by_pixels = false;
  return p;
}

// The method every build starts with: the default method (the "evms" preset, which every
// build's seeded path holds) within build S: the register values a board of that build starts
// with (a board's C++ core stands for its board). The host build's Gaussian path is
// --preset gaussian.
inline constexpr const char* kBuildResetPreset = "evms";
template <class S>
Params build_default_params() {
  return within_build<S>(preset(kBuildResetPreset), [](const char*) { return false; });
}

namespace detail {

// "--name value": how a refusal names a setting.
inline std::string setting(const Params& p, const char* name) { return std::string("--") + name + " " + param_text(p, *find_param(name)); }

// The first of `names` on which `p` differs from `reference`, or nullptr.
inline const char* first_difference(const Params& p, const Params& reference, std::initializer_list<const char*> names) {
  for (const char* name : names) {
    const ParamInfo& info = *find_param(name);
    if (param_value(p, info) != param_value(reference, info)) return name;
  }
  return nullptr;
}

// The size_ratio_log2 register for p.size_ratio: 0 when the rule is off, k when the ratio is
// 2^k with k from 1 to 15, and -1 for any other ratio (the core compares a count with the
// other shifted left).
inline int size_ratio_log2(const Params& p) {
  if (p.size_ratio == 0) return 0;
  const long k = std::lround(std::log2(p.size_ratio));
  return k >= 1 && k <= 15 && std::exp2(static_cast<double>(k)) == p.size_ratio ? static_cast<int>(k) : -1;
}

}  // namespace detail

// The first of the settings the filter's registers come from (core_config below) on which `p`
// differs from `board`, or nullptr: with the sensor's size, all that a board whose core stops at
// the filter holds of the method.
inline const char* first_filter_difference(const Params& p, const Params& board) {
  return detail::first_difference(p, board, {"filter-window-us", "filter-support", "filter-warm-up-us", "filter-noise-hz", "filter-noise-pixels",
                                              "filter-quiet-hz", "filter-quiet-window-us"});
}

// The same for a board whose core stops after its climbs (rtl/core/evms_climbs_core.sv): the
// filter's settings, then those its packets and climbs' registers come from, and the warm seeds
// its climbs do not have.
inline const char* first_climbs_difference(const Params& p, const Params& board) {
  if (const char* name = first_filter_difference(p, board)) return name;
  return detail::first_difference(p, board, {"packet-size", "packet-max-span-us", "bandwidth", "scale-xy", "max-iterations", "tolerance",
                                              "merge-radius", "warm-start"});
}

// The first setting of `p` that the C++ core (hls/) does not implement, as the one line a
// backend built on it refuses it with; empty when it implements every setting. It implements
// both mean shifts: every event with the Gaussian kernel, and seeded climbs with the flat kernel
// labelled by the first climb to reach an event.
inline std::string core_unsupported(const Params& p) {
  const bool seeded = p.seeding != Seeding::kEvery;
  if (seeded && p.kernel != Kernel::kFlat) return "the fixed-point core climbs from seeds with the flat kernel only, not " + detail::setting(p, "kernel");
  if (!seeded && p.kernel != Kernel::kGaussian) return "the fixed-point core shifts every event with the Gaussian kernel only, not " + detail::setting(p, "kernel");
  if (p.seeding == Seeding::kGrid) return "the fixed-point core seeds from events, not " + detail::setting(p, "seeding");
  if (seeded && p.labelling != Labelling::kFirst) return "the fixed-point core labels an event by the first climb that reached it, not " + detail::setting(p, "labelling");
  const Params off = preset("gaussian");
  if (const char* name = detail::first_difference(p, off, {"filter-look-ahead-us", "packet-support", "join-boxes", "warm-reach",
                                                               "packet-span-edge-px", "outline-split-us"})) {
    return "the fixed-point core does not implement " + detail::setting(p, name) + " (only " + detail::setting(off, name) + ")";
  }
  if (p.measure == Measure::kBoxCentre || (!seeded && p.measure != Measure::kCentroid)) {
    return "the fixed-point core measures a cluster by its centroid, or with seeded climbs by the polarity midpoint or the pixel centre, not " +
           detail::setting(p, "measure");
  }
  if (p.association == Association::kNearestCentre) return "the fixed-point core does not implement " + detail::setting(p, "association");
  if (detail::size_ratio_log2(p) < 0) {
    return "the fixed-point core compares sizes by a power of two from 2 to 32768, not " + detail::setting(p, "size-ratio");
  }
  if (!seeded && (p.link_px > 0 || p.warm_start)) return "the fixed-point core links clusters and warm-starts only with seeded climbs (--seeding events)";
  if (seeded && (p.scale_p != 0 || p.scale_t != 0)) return "the fixed-point core's seeded climbs use position only (--scale-p 0 --scale-t 0)";
  if (seeded && (p.bandwidth < 0.01 || p.scale_xy != 1)) return "the fixed-point core's seeded climbs need --bandwidth 0.01 or more and --scale-xy 1";
  return {};
}

// The first setting of `p` that RTL build `build` (hls/core/configs.h, and a board built from
// it) does not implement. Every build implements the numbers of its clustering paths (the
// Gaussian mean shift of every event, the seeded climbs, or both: Shape::kHasGaussianPath,
// kHasSeededPath), the polarity split, the edge join, the polarity midpoint and the measurement
// noise from the spread where it holds them (kHasPolaritySplit, kHasEdgeJoin,
// kHasPolarityMidpoint, kHasSpreadNoise), the pixel centre (kHasPixelCentre), the gate's boxes
// and the least density on the linked sets where it holds them (kHasGateBoxes, kHasDensityAfterLinks)
// and the tracker's other policies but the gate's widening by
// the spread and coasting by packets. No build labels the events the filter dropped (--rescue-px),
// measures a fast track's cluster by its motion (--motion-measure) or splits a cluster by its
// events' motions (--motion-split), and every build times the pixel centre by all its events
// (--time-by-pixels false).
inline std::string rtl_unsupported(const Params& p, const std::string& build) {
  if (std::string unsupported = core_unsupported(p); !unsupported.empty()) return unsupported;
  bool gaussian_path = false, seeded_path = false, polarity_split = false, edge_join = false, polarity_midpoint = false,
       spread_noise = false, gate_boxes = false, pixel_centre = false, density_after_links = false;
#define EVMS_PATHS_OF_BUILD(name, fixed, rtl, width, height, description)                                             \
  if (build == #name) {                                                                                               \
    gaussian_path = hls::rtl::kHasGaussianPath != 0, seeded_path = hls::rtl::kHasSeededPath != 0;                     \
    polarity_split = hls::rtl::kHasPolaritySplit != 0, edge_join = hls::rtl::kHasEdgeJoin != 0;                       \
    polarity_midpoint = hls::rtl::kHasPolarityMidpoint != 0, spread_noise = hls::rtl::kHasSpreadNoise != 0;           \
    gate_boxes = hls::rtl::kHasGateBoxes != 0, pixel_centre = hls::rtl::kHasPixelCentre != 0;                         \
    density_after_links = hls::rtl::kHasDensityAfterLinks != 0;                                                       \
  }
  EVMS_CORE_BUILDS(EVMS_PATHS_OF_BUILD)
#undef EVMS_PATHS_OF_BUILD
  const bool seeded = p.seeding != Seeding::kEvery;
  if (seeded && !seeded_path) {
    return "the RTL build '" + build + "' clusters by the Gaussian mean shift only, not " + detail::setting(p, "seeding") +
           " (add --preset gaussian, or use --core host)";
  }
  if (!seeded && !gaussian_path) return "the RTL build '" + build + "' clusters by seeded climbs only, not " + detail::setting(p, "seeding");
  const Params rtl = preset("gaussian");
  if (const char* name = detail::first_difference(p, rtl, {"filter-support", "gate-spread", "coast-packets", "rescue-px", "motion-measure"})) {
    return "the RTL core does not implement " + detail::setting(p, name) + " (add --" + name + " " + param_text(rtl, *find_param(name)) + ")";
  }
  if (p.measure == Measure::kPixelCentre && p.time_by_pixels) {
    return "the RTL core times the pixel centre by all its events, not " + detail::setting(p, "time-by-pixels") + " (add --time-by-pixels false)";
  }
  if (!polarity_split && seeded && p.split_balance != 0) {
    return "the RTL build '" + build + "' does not hold the polarity split, not " + detail::setting(p, "split-balance") + " (add --split-balance 0)";
  }
  if (!edge_join && seeded && p.edge_join != 0) {
    return "the RTL build '" + build + "' does not hold the edge join, not " + detail::setting(p, "edge-join") + " (add --edge-join 0)";
  }
  if (!polarity_midpoint && p.measure == Measure::kPolarityMidpoint) {
    return "the RTL build '" + build + "' does not hold the polarity midpoint, not " + detail::setting(p, "measure") + " (add --measure centroid)";
  }
  if (!pixel_centre && p.measure == Measure::kPixelCentre) {
    return "the RTL build '" + build + "' does not hold the pixel centre, not " + detail::setting(p, "measure") + " (add --measure centroid)";
  }
  if (!spread_noise && p.meas_noise_from_spread) {
    return "the RTL build '" + build + "' does not hold the measurement noise from the spread, not " +
           detail::setting(p, "meas-noise-from-spread") + " (add --meas-noise-from-spread false)";
  }
  if (!gate_boxes && p.gate_boxes && p.association != Association::kNearestCentre) {
    return "the RTL build '" + build + "' does not hold the gate's boxes, not " + detail::setting(p, "gate-boxes") + " (add --gate-boxes false)";
  }
  if (!density_after_links && seeded && p.min_density != 0 && p.density_after_links) {
    return "the RTL build '" + build + "' does not hold the least density on the linked sets, not " +
           detail::setting(p, "density-after-links") + " (add --density-after-links false)";
  }
  return {};
}

// The core's unit of time for velocities and covariances, in seconds (2^kTickLog2 us).
template <class S>
constexpr double tick_seconds() {
  return static_cast<double>(std::int64_t{1} << S::kTickLog2) * 1e-6;
}

// The largest process noise the core's filter takes, px^2/s^3: q/3 (kNoiseFrac fraction bits, per
// tick^3) times dt^3 of the longest step (kMaxDt, kCovFrac fraction bits), plus the half that
// rounds its shift, must be a signed 64-bit number (hls/track/kalman_axis.h).
template <class S>
double max_accel_psd() {
  const int longest_step_log2 = S::kMaxDtLog2 - S::kTickLog2;  // ticks
  const int dt3_bits = 3 * longest_step_log2 + S::kCovFrac;
  const std::int64_t q_third_max = (INT64_MAX - (std::int64_t{1} << (S::kNoiseFrac - 1))) >> dt3_bits;
  const double tick_s = tick_seconds<S>();
  // rnd(q_tick / 3 * 2^kNoiseFrac) <= q_third_max, with a margin of one part in 2^20 for the rounding
  return 3 * std::ldexp(static_cast<double>(q_third_max) * (1 - 0x1p-20), -S::kNoiseFrac) / (tick_s * tick_s * tick_s);
}

template <class S>
hls::Config core_config(const Params& p, SensorSize sensor) {
  auto need = [](bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument(what);
  };
  static_assert(S::kNoiseIntervalLog2 == kFilterNoiseIntervalLog2, "the core's filter counts in the method's intervals");
  if (std::string unsupported = core_unsupported(p); !unsupported.empty()) throw std::invalid_argument(unsupported);
  need(sensor.width <= S::kMaxWidth && sensor.height <= S::kMaxHeight,
       "the core is built for sensors up to " + std::to_string(S::kMaxWidth) + "x" + std::to_string(S::kMaxHeight) + ", not " +
           std::to_string(sensor.width) + "x" + std::to_string(sensor.height));
  need(p.packet_size <= S::kPacketMax, "the core holds packets of at most " + std::to_string(S::kPacketMax) + " events (--packet-size)");
  need(p.max_iterations <= S::kIterationsMax, "the core runs at most " + std::to_string(S::kIterationsMax) + " iterations (--max-iterations)");
  need(p.max_clusters <= S::kClustersMax, "the core holds at most " + std::to_string(S::kClustersMax) + " clusters (--max-clusters)");
  need(p.max_tracks <= S::kTracksMax, "the core holds at most " + std::to_string(S::kTracksMax) + " tracks (--max-tracks)");
  need(p.coast_us <= (1 << S::kMaxDtLog2),
       "the core predicts at most " + std::to_string((1 << S::kMaxDtLog2) / 1000) + " ms ahead (--coast-us)");
  need(p.confirm_hits <= 255 && p.min_cluster_size <= 65535, "confirm-hits or min-cluster-size too large for the core");

  const double link_px = link_px_at(p, sensor);
  need(link_px < S::kLinkMax + 1, "the core links clusters at most " + std::to_string(S::kLinkMax) +
                                      " px apart (--link-px, scaled on this sensor by --link-px-width)");
  need(p.measure != Measure::kPixelCentre || link_px >= 1,
       "the core marks each pixel of a cluster in the links' pixel map, so --measure pixel-centre needs --link-px 1 or more "
       "(scaled on this sensor by --link-px-width)");
  need(p.seeding == Seeding::kEvery || p.warm_max_bandwidth <= S::kReachMax * p.bandwidth,
       "the core's warm balls reach at most " + std::to_string(S::kReachMax) + " bandwidths (--warm-max-bandwidth)");
  need(p.filter_support <= 8, "--filter-support is at most 8");
  need(p.rescue_px == 0 || S::kHasRescue, "this build's core does not label the events its filter dropped, not " + detail::setting(p, "rescue-px") + " (add --rescue-px 0)");
  need(p.rescue_px <= S::kRescueMax, "the core labels dropped events from at most " + std::to_string(S::kRescueMax) + " px away (--rescue-px)");
  need(p.measure != Measure::kPixelCentre || !p.time_by_pixels || S::kHasPixelTime,
       "this build's core times the pixel centre by all its events, not " + detail::setting(p, "time-by-pixels") + " (add --time-by-pixels false)");
  need(p.motion_measure == 0 || S::kHasMotionMeasure,
       "this build's core does not measure a fast track's cluster by its motion, not " + detail::setting(p, "motion-measure") + " (add --motion-measure 0)");
  need(p.motion_split == 0 || S::kHasMotionMeasure,
       "this build's core does not split a cluster by its events' motions, not " + detail::setting(p, "motion-split") + " (add --motion-split 0)");
  need(!p.split_concentric || p.split_balance == 0 || S::kHasConcentricGroups,
       "this build's core splits a cluster's concentric groups of parts, not " + detail::setting(p, "split-concentric") + " (add --split-concentric false)");
  need(filter_noise_count(p, sensor) < (std::int64_t{1} << 24), "--filter-noise-hz is too large for the core's 24-bit count");
  need(filter_quiet_count(p, sensor) < (std::int64_t{1} << 24), "--filter-quiet-hz is too large for the core's 24-bit count");
  // hls/filter/ba_filter.h clears every pixel's time after a gap of a quarter of the timestamps'
  // wrap, so no window may reach that far.
  constexpr TimeUs kFilterWindowMax = (TimeUs{1} << (S::kTimestampBits - 2 + S::kTimestampShift)) - 1;
  need(p.filter_window_us <= kFilterWindowMax && p.filter_quiet_window_us <= kFilterWindowMax,
       "the core's filter windows reach at most " + std::to_string(kFilterWindowMax) + " us (--filter-window-us, --filter-quiet-window-us)");
  const bool seeded = p.seeding != Seeding::kEvery;
  // One phi unit in normalized feature space: h for the flat ball (|dphi|^2 < 1), h sqrt(2)
  // for the Gaussian (exp(-|dphi|^2)).
  const double unit = seeded ? p.bandwidth : p.bandwidth * std::sqrt(2.0);
  const FeatureSides side = feature_sides(p, sensor);
  const double feat = std::ldexp(1.0, S::kFeatFrac);
  const double tick_s = tick_seconds<S>();
  auto rnd = [](double v) { return static_cast<std::int64_t>(std::llround(v)); };

  hls::Config c;
  c.sensor_width = static_cast<std::uint16_t>(sensor.width);
  c.sensor_height = static_cast<std::uint16_t>(sensor.height);
  // The filter's registers, from the settings first_filter_difference names.
  c.filter_enabled = p.filter_window_us > 0;
  c.filter_window = static_cast<std::uint32_t>(p.filter_window_us >> S::kTimestampShift);
  c.filter_support = static_cast<std::uint8_t>(p.filter_support);
  c.filter_noise_count = static_cast<std::uint32_t>(filter_noise_count(p, sensor));
  c.filter_quiet_count = static_cast<std::uint32_t>(filter_quiet_count(p, sensor));
  c.filter_quiet_window = static_cast<std::uint32_t>(p.filter_quiet_window_us >> S::kTimestampShift);
  c.filter_warm_up = static_cast<std::uint32_t>(p.filter_warm_up_us);  // at most 1e9 (types/params.cpp)
  c.packet_size = static_cast<std::uint16_t>(p.packet_size);
  c.packet_max_span_us = static_cast<std::uint32_t>(std::min<TimeUs>(p.packet_max_span_us, 0xFFFFFFFF));
  c.scale_x = static_cast<std::uint32_t>(rnd(p.scale_xy / (side.x * unit) * std::ldexp(1.0, S::kCoordScaleFrac)));
  c.scale_y = static_cast<std::uint32_t>(rnd(p.scale_xy / (side.y * unit) * std::ldexp(1.0, S::kCoordScaleFrac)));
  c.phi_on = static_cast<std::uint32_t>(rnd(p.scale_p / unit * feat));
  c.phi_t_max = static_cast<std::uint32_t>(rnd(p.scale_t / unit * feat));
  c.inv_tau = static_cast<std::uint64_t>(rnd(std::ldexp(1.0, S::kDecayFrac) / p.tau_us));
  // Seeded climbs' features and positions carry kClimbFrac more fraction bits.
  const double climb = seeded ? feat * std::ldexp(1.0, hls::kClimbFrac) : feat;
  if (seeded) {
    c.climb_scale_x = static_cast<std::uint64_t>(rnd(p.scale_xy / (side.x * unit) * std::ldexp(1.0, hls::kClimbScaleFrac)));
    c.climb_scale_y = static_cast<std::uint64_t>(rnd(p.scale_xy / (side.y * unit) * std::ldexp(1.0, hls::kClimbScaleFrac)));
  }
  c.seeded = seeded;
  c.warm_start = p.warm_start;
  c.warm_scale2 = static_cast<std::uint32_t>(rnd(p.warm_scale * p.warm_scale * std::ldexp(1.0, hls::kSpreadFrac)));
  c.warm_ball2_max = static_cast<std::uint64_t>(rnd(std::pow(std::max(p.bandwidth, p.warm_max_bandwidth) / unit * climb, 2)));
  c.link2 = static_cast<std::uint32_t>(std::floor(link_px * link_px));
  c.max_iterations = static_cast<std::uint8_t>(p.max_iterations);
  c.tolerance = static_cast<std::uint32_t>(rnd(p.tolerance / unit * climb));
  c.merge_radius2 = static_cast<std::uint64_t>(rnd(std::pow(p.merge_radius / unit * climb, 2)));
  c.min_cluster_size = static_cast<std::uint16_t>(p.min_cluster_size);
  c.max_clusters = static_cast<std::uint8_t>(p.max_clusters);
  c.gate2 = static_cast<std::uint64_t>(rnd(std::pow(std::ldexp(p.gate_px, S::kPosFrac), 2)));
  c.confirm_hits = static_cast<std::uint8_t>(p.confirm_hits);
  c.coast_us = static_cast<std::uint32_t>(p.coast_us);
  c.max_tracks = static_cast<std::uint8_t>(p.max_tracks);
  c.associate_last = p.association == Association::kLastMeasurement;
  c.gate_boxes = p.gate_boxes;
  c.gate_spread2 = static_cast<std::uint32_t>(rnd(p.gate_spread * p.gate_spread * std::ldexp(1.0, hls::kSpreadFrac)));
  c.size_ratio_log2 = static_cast<std::uint8_t>(detail::size_ratio_log2(p));
  c.coast_packets = static_cast<std::uint32_t>(p.coast_packets);
  c.rescue_reach = static_cast<std::uint8_t>(p.rescue_px);
  // px/s to the tracker's velocity word (px per tick, kPosFrac bits); at least 1 when on, which
  // it is with the pixel centre only, as golden's (golden/pipeline.cpp).
  const double motion_speed = p.motion_measure * tick_s * std::ldexp(1.0, S::kPosFrac);
  need(motion_speed < 4294967295.0, "--motion-measure is too large for the core's 32-bit speed");
  c.pixel_time = p.time_by_pixels && p.measure == Measure::kPixelCentre && S::kHasPixelTime ? 1 : 0;
  c.motion_speed = p.motion_measure > 0 && p.measure == Measure::kPixelCentre ? static_cast<std::uint32_t>(std::max<std::int64_t>(1, rnd(motion_speed))) : 0;
  // Golden's gain (types/params.h); on with seeded climbs only, as golden's.
  static_assert(hls::kMotionGainFrac == kMotionGainFrac);
  c.motion_split_gain = seeded ? static_cast<std::uint16_t>(motion_split_gain(p)) : 0;
  const double least_per_event = least_support_per_event(p, sensor);
  need(!seeded || least_per_event < 256, "--min-density is too large for the core's 32-bit density");
  c.min_density = seeded ? static_cast<std::uint32_t>(rnd(least_per_event * std::ldexp(1.0, hls::kDensityFrac))) : 0;
  c.density_after_links = seeded && p.density_after_links;
  c.meas_from_spread = p.meas_noise_from_spread;
  static_assert(hls::kSplitCellFrac == kSplitCellFrac && hls::kSplitFractionFrac == kSplitFractionFrac);
  const SplitRule split = seeded ? split_rule(p, sensor) : SplitRule{};  // golden splits the seeded path's clusters only
  c.split_balance = static_cast<std::uint16_t>(split.balance);
  c.split_share = static_cast<std::uint16_t>(split.share);
  c.split_min_events = static_cast<std::uint16_t>(split.min_events);
  c.split_cell_scale_x = split.cell_scale_x;
  c.split_cell_scale_y = split.cell_scale_y;
  c.split_partial = split.partial;
  c.split_concentric = split.concentric && S::kHasConcentricGroups;
  static_assert(hls::kEdgeSizeRatio == kEdgeSizeRatio);
  const EdgeRule edge = seeded ? edge_rule(p, sensor) : EdgeRule{};  // golden joins the seeded path's clusters only
  c.edge_radius2 = edge.radius2;
  c.edge_balance = static_cast<std::uint16_t>(edge.balance);
  c.edge_min_events = static_cast<std::uint16_t>(edge.min_events);
  c.midpoint_min = seeded && p.measure == Measure::kPolarityMidpoint ? static_cast<std::uint16_t>(p.midpoint_min_events) : 0;
  c.pixel_centre = seeded && p.measure == Measure::kPixelCentre;
  c.evict_stale = p.evict_stale;
  c.report_tentative = p.report_tentative;
  const double accel_psd = accel_psd_at(p, sensor);
  const double q_tick = accel_psd * tick_s * tick_s * tick_s;  // px^2 / tick^3
  c.q_third = rnd(q_tick / 3 * std::ldexp(1.0, S::kNoiseFrac));
  c.q_half = rnd(q_tick / 2 * std::ldexp(1.0, S::kNoiseFrac));
  c.q = rnd(q_tick * std::ldexp(1.0, S::kNoiseFrac));
  c.r = rnd(p.meas_sigma_px * p.meas_sigma_px * std::ldexp(1.0, S::kCovFrac));
  c.p0_pos = rnd(p.init_sigma_px * p.init_sigma_px * std::ldexp(1.0, S::kCovFrac));
  c.p0_vel = rnd(std::pow(p.init_sigma_vel * tick_s, 2) * std::ldexp(1.0, S::kCovFrac));
  need(c.r > 0, "--meas-sigma-px is too small for the core's covariance words");
  // The core's 64-bit products stay exact only below these (docs/hls.md, "Formats").
  need(c.r < (std::int64_t{1} << 35) && c.p0_pos < (std::int64_t{1} << 35) && c.p0_vel < (std::int64_t{1} << 35),
       "--meas-sigma-px, --init-sigma-px or --init-sigma-vel is too large for the core's covariance words");
  const double accel_psd_max = max_accel_psd<S>();
  need(accel_psd <= accel_psd_max,
       "--accel-psd is too large for the core: at most " + std::to_string(static_cast<long long>(accel_psd_max)) +
           " px^2/s^3 on this sensor, --accel-psd-width included");
  need(c.inv_tau <= (std::uint64_t{1} << 32), "--tau-us must be at least 1 us for the core");
  return c;
}

// Physical units of the core's track words.
template <class S>
constexpr double core_px(std::int32_t raw) {
  return raw / static_cast<double>(std::int64_t{1} << S::kPosFrac);
}
template <class S>
constexpr double core_px_per_s(std::int32_t raw) {
  return core_px<S>(raw) / tick_seconds<S>();
}

}  // namespace evms::backend
