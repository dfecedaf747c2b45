// The method's parameters (golden/params.h, doubles in physical units) as the core's
// registers (hls/core/config.h, integers in the Shape's formats). Every backend built on the
// core (fixed, rtl, board) and the RTL generator use this one conversion.
#pragma once

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "golden/params.h"
#include "hls/core/config.h"

namespace evms::backend {

// The method the RTL core implements (the "gaussian" preset) with the packet size, cluster and
// track counts cut to what build S holds: the register values a board of that build starts
// with.
template <class S>
Params build_default_params() {
  Params p = preset("gaussian");
  p.packet_size = std::min(p.packet_size, S::kPacketMax);
  p.max_clusters = std::min(p.max_clusters, S::kClustersMax);
  p.max_tracks = std::min(p.max_tracks, S::kTracksMax);
  return p;
}

// The first setting of `p` that the core does not implement, as the one-line message a backend
// built on it refuses it with; empty when the core implements every setting.
inline std::string core_unsupported(const Params& p) {
  const Params core = preset("gaussian");
  for (const char* name : {"kernel", "seeding", "xy-scale", "filter-support", "packet-support", "link-px", "join-boxes",
                           "min-density", "measure", "association", "gate-spread", "coast-packets", "evict-stale"}) {
    const ParamInfo& info = *find_param(name);
    if (param_value(p, info) != param_value(core, info)) {
      return "the fixed-point core does not implement --" + std::string(name) + " " + param_text(p, info) + " (it implements --" +
             name + " " + param_text(core, info) + "; --preset gaussian gives every setting it implements)";
    }
  }
  return {};
}

template <class S>
hls::Config core_config(const Params& p, SensorSize sensor) {
  auto need = [](bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument(what);
  };
  if (std::string unsupported = core_unsupported(p); !unsupported.empty()) throw std::invalid_argument(unsupported);
  need(sensor.width <= S::kMaxWidth && sensor.height <= S::kMaxHeight,
       "the core is built for sensors up to " + std::to_string(S::kMaxWidth) + "x" + std::to_string(S::kMaxHeight) + ", not " +
           std::to_string(sensor.width) + "x" + std::to_string(sensor.height));
  need(p.packet_size <= S::kPacketMax, "the core holds packets of at most " + std::to_string(S::kPacketMax) + " events (--packet-size)");
  need(p.max_iterations <= S::kIterationsMax, "the core runs at most " + std::to_string(S::kIterationsMax) + " iterations (--max-iterations)");
  need(p.max_clusters <= S::kClustersMax, "the core holds at most " + std::to_string(S::kClustersMax) + " clusters (--max-clusters)");
  need(p.max_tracks <= S::kTracksMax, "the core holds at most " + std::to_string(S::kTracksMax) + " tracks (--max-tracks)");
  need(p.coast_us <= (1 << 18), "the core predicts at most 262 ms ahead (--coast-us)");
  need(p.confirm_hits <= 255 && p.min_cluster_size <= 65535, "confirm-hits or min-cluster-size too large for the core");

  const double unit = p.bandwidth * std::sqrt(2.0);  // one phi unit in normalized feature space
  const double feat = std::ldexp(1.0, S::kFeatFrac);
  const double tick_s = std::ldexp(1.0, S::kTickLog2) * 1e-6;
  auto rnd = [](double v) { return static_cast<std::int64_t>(std::llround(v)); };

  hls::Config c;
  c.sensor_width = static_cast<std::uint16_t>(sensor.width);
  c.sensor_height = static_cast<std::uint16_t>(sensor.height);
  c.filter_enabled = p.filter_window_us > 0;
  c.filter_window = static_cast<std::uint32_t>(p.filter_window_us >> S::kTimestampShift);
  c.packet_size = static_cast<std::uint16_t>(p.packet_size);
  c.packet_max_span_us = static_cast<std::uint32_t>(std::min<TimeUs>(p.packet_max_span_us, 0xFFFFFFFF));
  c.scale_x = static_cast<std::uint32_t>(rnd(p.scale_xy / (sensor.width * unit) * std::ldexp(1.0, S::kCoordScaleFrac)));
  c.scale_y = static_cast<std::uint32_t>(rnd(p.scale_xy / (sensor.height * unit) * std::ldexp(1.0, S::kCoordScaleFrac)));
  c.phi_on = static_cast<std::uint32_t>(rnd(p.scale_p / unit * feat));
  c.phi_t_max = static_cast<std::uint32_t>(rnd(p.scale_t / unit * feat));
  c.inv_tau = static_cast<std::uint64_t>(rnd(std::ldexp(1.0, S::kDecayFrac) / p.tau_us));
  c.max_iterations = static_cast<std::uint8_t>(p.max_iterations);
  c.tolerance = static_cast<std::uint32_t>(rnd(p.tolerance / unit * feat));
  c.merge_radius2 = static_cast<std::uint64_t>(rnd(std::pow(p.merge_radius / unit * feat, 2)));
  c.min_cluster_size = static_cast<std::uint16_t>(p.min_cluster_size);
  c.max_clusters = static_cast<std::uint8_t>(p.max_clusters);
  c.gate2 = static_cast<std::uint64_t>(rnd(std::pow(std::ldexp(p.gate_px, S::kPosFrac), 2)));
  c.confirm_hits = static_cast<std::uint8_t>(p.confirm_hits);
  c.coast_us = static_cast<std::uint32_t>(p.coast_us);
  c.max_tracks = static_cast<std::uint8_t>(p.max_tracks);
  const double q_tick = p.accel_psd * tick_s * tick_s * tick_s;  // px^2 / tick^3
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
  need(c.q < (std::int64_t{1} << 31), "--accel-psd is too large for the core (at most 1e5 px^2/s^3)");
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
  return core_px<S>(raw) / (static_cast<double>(std::int64_t{1} << S::kTickLog2) * 1e-6);
}

}  // namespace evms::backend
