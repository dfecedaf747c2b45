// Background-activity filter in hardware form: the rule of golden/filter (an event is kept
// when filter_support of its 8 neighbours fired within the window; its own pixel does not
// count; pixels outside the sensor do not exist), with a per-pixel timestamp memory of the
// Shape's width:
//   32 bits, 1 us units (HostShape): the same decisions as golden, up to the 71-minute wrap;
//   16 bits, 128 us units (DefaultShape): one iCE40 SPRAM word per pixel, so 240x180 fits the
//     UP5K's four SPRAMs; the window is then compared in 128 us units.
// Zero means "never fired" (a time that would store as zero stores as one). Times wrap
// modulo the word; so that a stale time cannot alias into the window a wrap later, every
// event also scrubs the next two memory entries, clearing them once older than half the wrap
// period (4.2 s at 16 bits; at 240x180 a full sweep takes 21,600 events).
//
// The noise check (golden/filter/background_activity_filter.h): in intervals of 2^15 us it
// counts the events no neighbour supported; an interval with filter_noise_count or more of them
// makes the next one noisy, and there an event needs one more supporting neighbour. An interval
// is t >> 15 of the 32-bit time, 17 bits, so that the time's wrap is one interval step, as in
// the RTL (rtl/filter/evms_ba_filter.sv); the count saturates at 2^24 - 1.
//
// The quiet window: an interval with fewer than filter_quiet_count unsupported events (counted
// against filter_window) makes the next one quiet, and there an event is judged by its
// neighbours within filter_quiet_window instead.
//
// The warm-up: every event less than filter_warm_up us after the first event the filter judged
// is kept, because its neighbours' history is shorter than the window. The difference is taken
// of the 32-bit times, and the first event at or past the warm-up ends it for good, so that the
// time's wrap cannot bring it back.
#pragma once

#include <cstdint>
#include <type_traits>

#include "hls/core/config.h"
#include "hls/core/words.h"

namespace evms::hls {

template <class S>
class BackgroundActivityFilter {
 public:
  void reset() {
    for (int i = 0; i < S::kMaxWidth * S::kMaxHeight; ++i) stamp_[i] = 0;
    scrub_ = 0;
    started_ = false;
    warming_ = false;
    warm_start_ = 0;
    noisy_ = false;
    quiet_ = false;
    interval_ = 0;
    unsupported_ = 0;
  }

  bool accept(const EventWord& e, const Config& cfg) {
    if (!cfg.filter_enabled) return true;
    if (e.x >= cfg.sensor_width || e.y >= cfg.sensor_height) return false;
    const Stamp now = static_cast<Stamp>(e.t >> S::kTimestampShift);
    int supporters = 0, quiet_supporters = 0;
  neighbours:
    for (int k = 0; k < 9; ++k) {
#pragma HLS PIPELINE II = 1
      const int nx = e.x + k % 3 - 1, ny = e.y + k / 3 - 1;
      if (k == 4 || nx < 0 || ny < 0 || nx >= cfg.sensor_width || ny >= cfg.sensor_height) continue;
      const Stamp then = stamp_[ny * S::kMaxWidth + nx];
      const Stamp age = static_cast<Stamp>(now - then);
      if (then != 0 && age <= cfg.filter_window) ++supporters;
      if (then != 0 && age <= cfg.filter_quiet_window) ++quiet_supporters;
    }
    stamp_[e.y * S::kMaxWidth + e.x] = now == 0 ? 1 : now;
  scrub:
    for (int k = 0; k < kScrubPerEvent; ++k) {
      // Clears entries older than half the wrap period, so that stale times cannot alias
      // into the window a wrap later.
      const Stamp then = stamp_[scrub_];
      if (then != 0 && static_cast<Stamp>(now - then) >= kHalfWrap) stamp_[scrub_] = 0;
      scrub_ = scrub_ + 1 == S::kMaxWidth * S::kMaxHeight ? 0 : scrub_ + 1;
    }
    const std::uint32_t interval = e.t >> kNoiseIntervalLog2;
    if (!started_) started_ = true, interval_ = interval, warm_start_ = e.t, warming_ = cfg.filter_warm_up != 0;
    bool warm = false;
    if (warming_) {
      warm = static_cast<std::uint32_t>(e.t - warm_start_) < cfg.filter_warm_up;
      warming_ = warm;
    }
    if (interval != interval_) {
      noisy_ = cfg.filter_noise_count != 0 && interval == ((interval_ + 1) & kIntervalMask) && unsupported_ >= cfg.filter_noise_count;
      quiet_ = cfg.filter_quiet_count != 0 && unsupported_ < cfg.filter_quiet_count;
      interval_ = interval, unsupported_ = 0;
    }
    if (supporters == 0 && unsupported_ < kCountMax) ++unsupported_;
    return (quiet_ ? quiet_supporters : supporters) >= cfg.filter_support + (noisy_ ? 1 : 0) || warm;
  }

 private:
  static_assert(S::kTimestampBits == 16 || S::kTimestampBits == 32, "timestamp memory words are 16 or 32 bits");
  using Stamp = std::conditional_t<S::kTimestampBits == 16, std::uint16_t, std::uint32_t>;
  static constexpr Stamp kHalfWrap = static_cast<Stamp>(Stamp{1} << (S::kTimestampBits - 1));
  static constexpr int kScrubPerEvent = 2;
  static constexpr int kNoiseIntervalLog2 = 15;  // types/params.h: kFilterNoiseIntervalLog2
  static constexpr std::uint32_t kIntervalMask = (std::uint32_t{1} << (32 - kNoiseIntervalLog2)) - 1;
  static constexpr std::uint32_t kCountMax = (std::uint32_t{1} << 24) - 1;
  bool started_ = false, warming_ = false, noisy_ = false, quiet_ = false;
  std::uint32_t interval_ = 0, unsupported_ = 0, warm_start_ = 0;
  Stamp stamp_[S::kMaxWidth * S::kMaxHeight] = {};
  int scrub_ = 0;
};

}  // namespace evms::hls
