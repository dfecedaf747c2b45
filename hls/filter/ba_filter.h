// Background-activity filter in hardware form: the rule of golden/filter (an event is kept
// when filter_support of its 8 neighbours fired within the window; its own pixel does not
// count; pixels outside the sensor do not exist), with a per-pixel timestamp memory of the
// Shape's width:
//   32 bits, 1 us units (HostShape): the same decisions as golden, up to the 71-minute wrap;
//   16 bits, 128 us units (DefaultShape): one iCE40 SPRAM word per pixel, so 240x180 fits the
//     UP5K's four SPRAMs; the window is then compared in 128 us units.
// Zero means "never fired" (a time that would store as zero stores as one). Times wrap
// modulo the word; so that a stale time cannot alias into the window a wrap later, a scrubber
// clears every entry once it is half the wrap period old (4.2 s at 16 bits). Its pointer
// advances by events and by time:
//   - before an event's neighbours are read, one entry for each 2^kSweepLog2 us boundary the
//     event time crossed since the last judged event, at most the whole memory, so that a whole
//     sweep takes at most an eighth of the wrap (16 us an entry at 240x180, 64 us at 128x128);
//   - after a gap of more than a quarter of the wrap (2.1 s at 16 bits: more than 2^(kWrapLog2 - 2
//     - kSweepLog2) boundaries) every entry is that old, past any window, and the whole memory
//     is cleared instead;
//   - after the event's own time is written, two more entries.
// An entry is then visited at most 3/8 of the wrap apart, so it is cleared before its age can
// wrap, however sparse the events (by events alone, a quiet 128x128 sensor under 2,000 events a
// second would keep noise golden drops). The host limits the windows to a quarter of the wrap
// (host/backend/core_config.h), so clearing an entry older than every window changes no
// decision.
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
#include "hls/math/round.h"

namespace evms::hls {

template <class S>
class BackgroundActivityFilter {
 public:
  void reset() {
    clear_stamps();
    scrub_ = 0;
    last_t_ = 0;
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
    if (started_) scrub_for_time(e.t, now);
    last_t_ = e.t;
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
    for (int k = 0; k < kScrubPerEvent; ++k) scrub_one(now);
    const std::uint32_t interval = e.t >> S::kNoiseIntervalLog2;
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

  // What the time scrubber owes an event at time t after the last judged event at last_t: the
  // entries it visits (one for each 2^kSweepLog2 us boundary crossed, with the 32-bit time's
  // wrap; at most the whole memory), or a clear of the whole memory after a gap of more than a
  // quarter of the wrap. The cycle model (hls/core/schedule.h) counts its clocks from it.
  struct TimeScrub {
    bool clear_all;
    int entries;
  };
  static TimeScrub time_scrub(std::uint32_t last_t, std::uint32_t t) {
    const std::uint32_t crossed = ((t >> kSweepLog2) - (last_t >> kSweepLog2)) & kSweepMask;
    if (crossed > kClearCrossings) return {true, kPixels};
    return {false, crossed >= static_cast<std::uint32_t>(kPixels) ? kPixels : static_cast<int>(crossed)};
  }
  static constexpr int kPixels = S::kMaxWidth * S::kMaxHeight;

 private:
  static_assert(S::kTimestampBits == 16 || S::kTimestampBits == 32, "timestamp memory words are 16 or 32 bits");
  using Stamp = std::conditional_t<S::kTimestampBits == 16, std::uint16_t, std::uint32_t>;
  static constexpr Stamp kHalfWrap = static_cast<Stamp>(Stamp{1} << (S::kTimestampBits - 1));
  static constexpr int kScrubPerEvent = 2;
  static constexpr std::uint32_t kIntervalMask = (std::uint32_t{1} << (32 - S::kNoiseIntervalLog2)) - 1;
  static constexpr std::uint32_t kCountMax = (std::uint32_t{1} << 24) - 1;
  // The time scrubber's pace: one entry each 2^kSweepLog2 us sweeps the memory within an eighth
  // of the wrap; more than kClearCrossings of them (a gap of more than a quarter of the wrap)
  // clear it whole.
  static constexpr int kWrapLog2 = S::kTimestampBits + S::kTimestampShift;
  static constexpr int kSweepLog2 = kWrapLog2 - 3 - ceil_log2(kPixels);
  static_assert(kSweepLog2 >= 0 && kWrapLog2 <= 32, "the memory is too large to sweep within an eighth of the wrap");
  static constexpr std::uint32_t kClearCrossings = std::uint32_t{1} << (kWrapLog2 - 2 - kSweepLog2);
  static constexpr std::uint32_t kSweepMask = static_cast<std::uint32_t>((std::uint64_t{1} << (32 - kSweepLog2)) - 1);

  // Scrubbing owed for the time since the last judged event, before this event's neighbours are
  // read.
  void scrub_for_time(std::uint32_t t, Stamp now) {
    const TimeScrub owed = time_scrub(last_t_, t);
    if (owed.clear_all) {
      clear_stamps();
      return;
    }
  sweep:
    for (int k = 0; k < kPixels; ++k) {
      if (k >= owed.entries) break;
      scrub_one(now);
    }
  }

  // Every pixel "never fired": at reset, and after a gap longer than every window.
  void clear_stamps() {
  clear:
    for (int i = 0; i < kPixels; ++i) {
#pragma HLS PIPELINE II = 1
      stamp_[i] = 0;
    }
  }

  // Clears the entry at the scrub pointer when it is half the wrap period old, and moves on.
  void scrub_one(Stamp now) {
    const Stamp then = stamp_[scrub_];
    if (then != 0 && static_cast<Stamp>(now - then) >= kHalfWrap) stamp_[scrub_] = 0;
    scrub_ = scrub_ + 1 == kPixels ? 0 : scrub_ + 1;
  }

  bool started_ = false, warming_ = false, noisy_ = false, quiet_ = false;
  std::uint32_t interval_ = 0, unsupported_ = 0, warm_start_ = 0, last_t_ = 0;
  Stamp stamp_[kPixels] = {};
  int scrub_ = 0;
};

}  // namespace evms::hls
