// One axis of the constant-velocity Kalman filter, in fixed point.
//
// The tracker's 4-state filter (golden/track/kalman_filter.h) has A = [[I, dt I], [0, I]],
// H = [I 0], and diagonal R, P0 and white-noise-acceleration Q; so x and y never couple and
// it splits exactly into two 2-state filters, one per axis (tests/hls/test_tracker.cpp
// checks the split against the golden filter in double precision). Each holds
//   pos (px), vel (px/tick), and the symmetric covariance as p00, p01, p11,
// so symmetry holds by construction. Per axis:
//   predict: pos += vel dt; p00 += 2 dt p01 + dt^2 p11 + q/3 dt^3;
//            p01 += dt p11 + q/2 dt^2;  p11 += q dt
//   update:  s = p00 + r; k0 = p00 / s; k1 = p01 / s; e = z - pos;
//            pos += k0 e; vel += k1 e; p00 = r k0; p01 = r k1; p11 -= k1 p01
// (the last three are (I - K H) P written so that p00 stays positive). Times: dt in ticks
// with kTickLog2 fraction bits, i.e. the raw value is microseconds. Every right shift rounds
// half up; covariances saturate at +-kCovMax, gains at +-kGainMax.
#pragma once

#include <cstdint>

#include "hls/cluster/tables.h"
#include "hls/core/config.h"
#include "hls/math/round.h"

namespace evms::hls {

struct AxisState {
  std::int32_t pos = 0, vel = 0;
  std::int64_t p00 = 0, p01 = 0, p11 = 0;
};

template <class S>
struct KalmanAxis {
  static constexpr std::int64_t kCovMax = (std::int64_t{1} << S::kCovLog2) - 1;
  static constexpr std::int64_t kGainMax = (std::int64_t{1} << S::kGainLog2) - 1;
  static constexpr std::int64_t kPosMax = (std::int64_t{1} << S::kPosLog2) - 1;
  static constexpr std::uint32_t kMaxDt = (1u << S::kMaxDtLog2);  // longer steps are clamped

  static std::int64_t cov(std::int64_t v) { return clamp_sym(v, kCovMax); }
  static std::int32_t word(std::int64_t v) { return static_cast<std::int32_t>(clamp_sym(v, kPosMax)); }

  // Position at dt (microseconds) from now, without changing the state.
  static std::int32_t predicted(const AxisState& a, std::uint32_t dt_us) {
    const std::int64_t dt = dt_us > kMaxDt ? kMaxDt : dt_us;
    return word(a.pos + shr_rnd(std::int64_t{a.vel} * dt, S::kTickLog2));
  }

  static void predict(AxisState& a, std::uint32_t dt_us, const Config& cfg) {
    const std::int64_t dt = dt_us > kMaxDt ? kMaxDt : dt_us;               // kTickLog2 frac
    const std::int64_t dt2 = shr_rnd(dt * dt, 2 * S::kTickLog2 - S::kCovFrac);   // kCovFrac
    const std::int64_t dt3 = shr_rnd(dt2 * dt, S::kTickLog2);                      // kCovFrac
    a.pos = word(a.pos + shr_rnd(std::int64_t{a.vel} * dt, S::kTickLog2));
    const std::int64_t p01 = a.p01, p11 = a.p11;
    a.p00 = cov(a.p00 + shr_rnd(2 * dt * p01, S::kTickLog2) + shr_rnd(dt2 * p11, S::kCovFrac) +
                shr_rnd(cfg.q_third * dt3, S::kNoiseFrac));
    a.p01 = cov(p01 + shr_rnd(dt * p11, S::kTickLog2) + shr_rnd(cfg.q_half * dt2, S::kNoiseFrac));
    a.p11 = cov(p11 + shr_rnd(cfg.q * dt, S::kNoiseFrac + S::kTickLog2 - S::kCovFrac));
  }

  // With the measurement variance r (px^2, kCovFrac fraction bits, 0 < r <= kCovMax).
  static void update(AxisState& a, std::int32_t z, std::int64_t r) {
    const std::int64_t s = a.p00 + r;  // > 0: r > 0 and p00 >= 0
    const auto k0 = static_cast<std::int64_t>(Tables<S>::recip.template divide<S::kGainFrac>(static_cast<std::uint64_t>(a.p00), static_cast<std::uint64_t>(s)));
    const std::int64_t k1_mag = static_cast<std::int64_t>(
        Tables<S>::recip.template divide<S::kGainFrac>(static_cast<std::uint64_t>(a.p01 < 0 ? -a.p01 : a.p01), static_cast<std::uint64_t>(s)));
    const std::int64_t k1 = clamp_sym(a.p01 < 0 ? -k1_mag : k1_mag, kGainMax);
    const std::int64_t e = std::int64_t{z} - a.pos;
    a.pos = word(a.pos + shr_rnd(k0 * e, S::kGainFrac));
    a.vel = word(a.vel + shr_rnd(k1 * clamp_sym(e, kGainMax), S::kGainFrac));
    const std::int64_t p01 = a.p01;
    a.p00 = cov(shr_rnd(r * k0, S::kGainFrac));
    a.p01 = cov(shr_rnd(r * k1, S::kGainFrac));
    a.p11 = cov(a.p11 - shr_rnd(k1 * p01, S::kGainFrac));
  }
};

}  // namespace evms::hls
