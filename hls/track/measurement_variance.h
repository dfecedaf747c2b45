// The variance of a cluster's measured position, for the Kalman update (hls/track/kalman_axis.h).
//
// Config::r, or with Config::meas_from_spread r (spread^2 + 1/6) / events: the scatter of the
// cluster's centre of mass, its events' squared RMS distance from it (both axes, kSpreadFrac
// fraction bits) plus a pixel's own width (1/12 px^2 an axis) over their count, as golden's
// MultiTargetTracker::measurement_variance (golden/track/tracker.cpp). In px^2 with kCovFrac
// fraction bits, as r.
//
// The scatter per event is one exact division rounded half up, to S::kPerEventFrac fraction
// bits and at most 2^S::kPerEventLog2 - 1 (2^12 px^2), so that r (below 2^S::kCovLog2) times it
// fits 63 bits; the result is clamped to [1, kCovMax], as the update needs 0 < r.
//
// Bound (tests/hls/test_tracker.cpp, dense over spreads from 0 to 1,000 px, 1 to 4,096 events
// and r from 0.01 to 100 px^2): within r (2^-17 + 1 / (768 events)) + 1/2 units of
// r (spread2 / 2^kSpreadFrac + 1/6) / events in double precision (capped as above): the
// division's rounding, and 1/6 px^2 rounded to kSpreadFrac bits (43 / 256 at 8).
#pragma once

#include <cstdint>

#include "hls/cluster/centroid.h"
#include "hls/core/config.h"
#include "hls/math/round.h"
#include "hls/track/kalman_axis.h"

namespace evms::hls {

template <class S>
std::int64_t measurement_variance(const Measurement& z, const Config& cfg) {
  if (!cfg.meas_from_spread || z.events == 0) return cfg.r;
  constexpr std::uint64_t kPerEventMax = (std::uint64_t{1} << S::kPerEventLog2) - 1;
  const std::uint64_t scatter = (z.spread2 + S::kPixelWidth2) << (S::kPerEventFrac - S::kSpreadFrac);
  std::uint64_t per_event = (2 * scatter + z.events) / (2 * std::uint64_t{z.events});
  if (per_event > kPerEventMax) per_event = kPerEventMax;
  const std::int64_t r = shr_rnd(cfg.r * static_cast<std::int64_t>(per_event), S::kPerEventFrac);
  return r < 1 ? 1 : r > KalmanAxis<S>::kCovMax ? KalmanAxis<S>::kCovMax : r;
}

}  // namespace evms::hls
