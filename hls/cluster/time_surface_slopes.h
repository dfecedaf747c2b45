// Whether a velocity explains the slope of a packet's time surface under an event: the
// fixed-point form of golden/cluster/time_surface_slopes.h and its misfit(), exact in integers.
//
// Per polarity and pixel the packet's events there are summed: their count and their times after
// the packet's first event, in a table of the packet's own pixels (twice as many slots as a packet
// holds events, open addressing by a multiplicative hash of the pixel, each event's slot kept so
// that clear() empties exactly the slots the packet took) rather than one word per pixel of the
// largest sensor: a packet touches at most kPacketMax of a 1280x720 sensor's 1.8 M pixel words.
// The plane t = a x + b y + c fitted by least squares to the sums on
// the 5x5 pixels around an event (at least 6 events, the fit not degenerate) has the gradient
//   g = (Cyy Tx - Cxy Ty, Cxx Ty - Cxy Tx) / D  us/px,   D = Cxx Cyy - Cxy^2,
// with m the events, Cxx = m Sxx - Sx^2, Cxy = m Sxy - Sx Sy, Tx = m Sxt - Sx St (the offsets'
// and times' sums): golden's covariances times m, whose m^2 cancels in g. A velocity v (the
// tracker's word: kPosFrac fraction bits, px per tick of 2^kTickLog2 us) explains it when
// |g . v - 1| <= 1/2, that is, with F = kPosFrac + kTickLog2 and N = D g,
//   2^(F-1) D <= N . v <= 3 2^(F-1) D,
// compared in 128 bits: |N| < 2^85 and |v| < 2^31 for packets of at most 2^12 events that span
// at most 2^32 us. The degenerate test is golden's, det < 10^-6 (cxx + cyy)^2, times m^2:
// 10^6 D < (Cxx + Cyy)^2. Golden also drops a slope flatter than 10^-7 s/px; no velocity under
// 5 10^6 px/s explains one, so the verdict needs no such test. Golden computes in doubles from
// the same integer sums: the two verdicts differ only where |g . v - 1| is within rounding of
// 1/2 (tests/hls/test_motion_measure.cpp).
#pragma once

#include <cstdint>

#include "hls/cluster/features.h"
#include "hls/core/config.h"
#include "hls/math/round.h"

namespace evms::hls {

template <class S>
class TimeSurfaceSlopes {
  static_assert(S::kPacketMax <= 4096, "the sums' widths hold packets of at most 2^12 events");

 public:
  using Wide = __int128;
  static constexpr int kNeighbourPx = 2;      // the plane: 5x5 pixels
  static constexpr int kLeastNeighbours = 6;  // events on the plane, the event's own among them
  // The table's slots: at least twice a packet's events (a power of two), so that a probe finds
  // its pixel or an empty slot within a few steps; one slot in a build without the measure, whose
  // memories the core never reads.
  static constexpr int kSlotsLog2 = S::kHasMotionMeasure ? ceil_log2(S::kPacketMax) + 1 : 0;
  static constexpr int kSlots = 1 << kSlotsLog2;

  // Every slot is empty after reset(), and again after clear() with the packet's event count.
  void reset() {
  empty:
    for (int i = 0; i < kSlots; ++i) {
#pragma HLS PIPELINE II = 1
      key_[i] = kEmpty, count_[i] = 0, time_sum_[i] = 0;
    }
  }

  void add(const PacketEvents<S>& ev, int n) {
  sum:
    for (int i = 0; i < S::kPacketMax; ++i) {
      if (i >= n) break;
      const std::int32_t w = word(ev.p[i], ev.x[i], ev.y[i]);
      const int slot = find(w);
      key_[slot] = w;
      ++count_[slot];
      time_sum_[slot] += ev.t[i] - ev.t[0];
      slot_of_[i] = static_cast<std::uint16_t>(slot);
    }
  }

  // Empties the slots the packet's n events took in add().
  void clear(int n) {
  unsum:
    for (int i = 0; i < S::kPacketMax; ++i) {
#pragma HLS PIPELINE II = 1
      if (i >= n) break;
      const int slot = slot_of_[i];
      key_[slot] = kEmpty, count_[slot] = 0, time_sum_[slot] = 0;
    }
  }

  // The slope under an event of polarity p at (x0, y0) as g = (nx, ny) / d us/px, d > 0; false
  // when its neighbours give no slope (fewer than kLeastNeighbours events, or all along a line).
  bool gradient(std::uint8_t p, int x0, int y0, const Config& cfg, Wide& nx, Wide& ny, Wide& d) const {
    std::int64_t m = 0, sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0, st = 0, sxt = 0, syt = 0;
  rows:
    for (int dy = -kNeighbourPx; dy <= kNeighbourPx; ++dy) {
    columns:
      for (int dx = -kNeighbourPx; dx <= kNeighbourPx; ++dx) {
#pragma HLS PIPELINE II = 1
        const int x = x0 + dx, y = y0 + dy;
        if (x < 0 || y < 0 || x >= cfg.sensor_width || y >= cfg.sensor_height) continue;
        const int slot = find(word(p, x, y));  // an empty slot: no events there, zero sums
        const std::int64_t count = count_[slot], times = static_cast<std::int64_t>(time_sum_[slot]);
        m += count, sx += dx * count, sy += dy * count;
        sxx += dx * dx * count, syy += dy * dy * count, sxy += dx * dy * count;
        st += times, sxt += dx * times, syt += dy * times;
      }
    }
    if (m < kLeastNeighbours) return false;
    const Wide cxx = Wide{m} * sxx - Wide{sx} * sx, cyy = Wide{m} * syy - Wide{sy} * sy, cxy = Wide{m} * sxy - Wide{sx} * sy;
    const Wide tx = Wide{m} * sxt - Wide{sx} * st, ty = Wide{m} * syt - Wide{sy} * st;
    d = cxx * cyy - cxy * cxy;
    if (d <= 0 || d * 1000000 < (cxx + cyy) * (cxx + cyy)) return false;
    nx = cyy * tx - cxy * ty, ny = cxx * ty - cxy * tx;
    return true;
  }

  // Whether velocity (vx, vy) explains the slope under an event of polarity p at (x0, y0); false
  // when its neighbours give no slope.
  bool explains(std::uint8_t p, int x0, int y0, std::int32_t vx, std::int32_t vy, const Config& cfg) const {
    Wide nx = 0, ny = 0, d = 0;
    if (!gradient(p, x0, y0, cfg, nx, ny, d)) return false;
    const Wide nv = nx * vx + ny * vy;
    constexpr int kHalfOneLog2 = S::kPosFrac + S::kTickLog2 - 1;  // 1/2 in the units of N . v / D
    const Wide half = d * (Wide{1} << kHalfOneLog2);
    return nv >= half && nv <= 3 * half;
  }

 private:
  static constexpr std::int32_t kEmpty = -1;

  static std::int32_t word(std::uint8_t p, int x, int y) { return ((p != 0 ? S::kMaxHeight : 0) + y) * S::kMaxWidth + x; }

  // The slot that holds word w, or the empty slot where it would go: the probe starts at the
  // hash's top kSlotsLog2 bits (Fibonacci hashing) and steps by one. The table is never more than
  // half full, so the probe ends.
  int find(std::int32_t w) const {
    if constexpr (kSlotsLog2 == 0) {
      return 0;
    } else {
      int slot = static_cast<int>((static_cast<std::uint32_t>(w) * 2654435769u) >> (32 - kSlotsLog2));
    probe:
      for (int step = 0; step < kSlots; ++step) {
        if (key_[slot] == w || key_[slot] == kEmpty) break;
        slot = (slot + 1) & (kSlots - 1);
      }
      return slot;
    }
  }

  std::int32_t key_[kSlots];        // the slot's polarity and pixel word, or kEmpty
  std::uint16_t count_[kSlots];
  std::uint64_t time_sum_[kSlots];  // us after the packet's first event, summed
  std::uint16_t slot_of_[S::kPacketMax];  // each event's slot, for clear()
};

}  // namespace evms::hls
