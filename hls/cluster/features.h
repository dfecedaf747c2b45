// Packet features in bandwidth units (see golden/cluster/features.h for the definition):
//   phi_x = round(x * scale_x), phi_y = round(y * scale_y)     (scale = s_xy / (W h sqrt2))
//   phi_p = p ? phi_on : 0                                    (phi_on = s_p / (h sqrt2))
//   phi_t = round(phi_t_max * exp(-(t_newest - t) / tau))     (phi_t_max = s_t / (h sqrt2))
// each saturated to kFeatBits. The decay uses the kernel's exp table.
#pragma once

#include <cstdint>

#include "hls/cluster/tables.h"
#include "hls/core/config.h"
#include "hls/math/round.h"

namespace evms::hls {

template <class S>
struct PacketEvents {
  std::uint16_t x[S::kPacketMax];
  std::uint16_t y[S::kPacketMax];
  std::uint8_t p[S::kPacketMax];
  std::uint32_t t[S::kPacketMax];
};

template <class S>
struct Features {
  std::uint32_t x[S::kPacketMax], y[S::kPacketMax], p[S::kPacketMax], t[S::kPacketMax];
};

template <class S>
void packet_features(const PacketEvents<S>& ev, int n, const Config& cfg, Features<S>& phi) {
  constexpr std::int64_t kMax = (std::int64_t{1} << S::kFeatBits) - 1;
  const std::uint32_t newest = ev.t[n - 1];
features:
  for (int i = 0; i < S::kPacketMax; ++i) {
#pragma HLS PIPELINE II = 1
    if (i >= n) break;
    phi.x[i] = static_cast<std::uint32_t>(clamp(shr_rnd(std::int64_t{ev.x[i]} * cfg.scale_x, S::kCoordScaleFrac - S::kFeatFrac), 0, kMax));
    phi.y[i] = static_cast<std::uint32_t>(clamp(shr_rnd(std::int64_t{ev.y[i]} * cfg.scale_y, S::kCoordScaleFrac - S::kFeatFrac), 0, kMax));
    phi.p[i] = ev.p[i] ? static_cast<std::uint32_t>(clamp(cfg.phi_on, 0, kMax)) : 0;
    std::uint32_t age = newest - ev.t[i];
    if (age > 0x7FFFFFFFu) age = 0x7FFFFFFFu;
    const std::uint64_t u = std::uint64_t{age} * cfg.inv_tau;  // kDecayFrac fraction bits
    const std::uint32_t decay = Tables<S>::exp.template lookup<S::kDecayFrac>(u);
    phi.t[i] = static_cast<std::uint32_t>(clamp(shr_rnd(std::int64_t{cfg.phi_t_max} * decay, S::kWeightFrac), 0, kMax));
  }
}

// The squared distance of two feature points from their differences per dimension, which every
// kernel, ball and merge test compares.
inline std::uint64_t squared_distance(std::int64_t dx, std::int64_t dy, std::int64_t dp, std::int64_t dt) {
  return static_cast<std::uint64_t>(dx * dx + dy * dy + dp * dp + dt * dt);
}

}  // namespace evms::hls
