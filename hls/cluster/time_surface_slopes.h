// Whether a velocity explains the slope of a packet's time surface under an event: the
// fixed-point form of golden/cluster/time_surface_slopes.h and its misfit(), exact in integers.
//
// Per polarity and pixel the packet's events there are summed: their count and their times after
// the packet's first event. The plane t = a x + b y + c fitted by least squares to the sums on
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

namespace evms::hls {

template <class S>
class TimeSurfaceSlopes {
  static_assert(S::kPacketMax <= 4096, "the sums' widths hold packets of at most 2^12 events");

 public:
  using Wide = __int128;
  static constexpr int kNeighbourPx = 2;      // the plane: 5x5 pixels
  static constexpr int kLeastNeighbours = 6;  // events on the plane, the event's own among them
  // A sensor's pixels twice (both polarities) in a build that holds the motion measure, else one
  // word: the memories cost nothing where the core never reads them.
  static constexpr int kWords = S::kHasMotionMeasure ? 2 * S::kMaxWidth * S::kMaxHeight : 1;

  // Every pixel's sums are zero after reset(), and again after clear() with a packet's events.
  void reset() {
  zero:
    for (int i = 0; i < kWords; ++i) count_[i] = 0, time_sum_[i] = 0;
  }

  void add(const PacketEvents<S>& ev, int n) {
  sum:
    for (int i = 0; i < S::kPacketMax; ++i) {
#pragma HLS PIPELINE II = 1
      if (i >= n) break;
      const int w = word(ev.p[i], ev.x[i], ev.y[i]);
      ++count_[w];
      time_sum_[w] += ev.t[i] - ev.t[0];
    }
  }

  void clear(const PacketEvents<S>& ev, int n) {
  unsum:
    for (int i = 0; i < S::kPacketMax; ++i) {
#pragma HLS PIPELINE II = 1
      if (i >= n) break;
      const int w = word(ev.p[i], ev.x[i], ev.y[i]);
      count_[w] = 0, time_sum_[w] = 0;
    }
  }

  // Whether velocity (vx, vy) explains the slope under an event of polarity p at (x0, y0); false
  // when its neighbours give no slope.
  bool explains(std::uint8_t p, int x0, int y0, std::int32_t vx, std::int32_t vy, const Config& cfg) const {
    std::int64_t m = 0, sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0, st = 0, sxt = 0, syt = 0;
  rows:
    for (int dy = -kNeighbourPx; dy <= kNeighbourPx; ++dy) {
    columns:
      for (int dx = -kNeighbourPx; dx <= kNeighbourPx; ++dx) {
#pragma HLS PIPELINE II = 1
        const int x = x0 + dx, y = y0 + dy;
        if (x < 0 || y < 0 || x >= cfg.sensor_width || y >= cfg.sensor_height) continue;
        const int w = word(p, x, y);
        const std::int64_t count = count_[w], times = static_cast<std::int64_t>(time_sum_[w]);
        m += count, sx += dx * count, sy += dy * count;
        sxx += dx * dx * count, syy += dy * dy * count, sxy += dx * dy * count;
        st += times, sxt += dx * times, syt += dy * times;
      }
    }
    if (m < kLeastNeighbours) return false;
    const Wide cxx = Wide{m} * sxx - Wide{sx} * sx, cyy = Wide{m} * syy - Wide{sy} * sy, cxy = Wide{m} * sxy - Wide{sx} * sy;
    const Wide tx = Wide{m} * sxt - Wide{sx} * st, ty = Wide{m} * syt - Wide{sy} * st;
    const Wide d = cxx * cyy - cxy * cxy;
    if (d <= 0 || d * 1000000 < (cxx + cyy) * (cxx + cyy)) return false;
    const Wide nv = (cyy * tx - cxy * ty) * vx + (cxx * ty - cxy * tx) * vy;
    constexpr int kHalfOneLog2 = S::kPosFrac + S::kTickLog2 - 1;  // 1/2 in the units of N . v / D
    const Wide half = d * (Wide{1} << kHalfOneLog2);
    return nv >= half && nv <= 3 * half;
  }

 private:
  static int word(std::uint8_t p, int x, int y) {
    return S::kHasMotionMeasure ? ((p != 0 ? S::kMaxHeight : 0) + y) * S::kMaxWidth + x : 0;
  }

  std::uint16_t count_[kWords];
  std::uint64_t time_sum_[kWords];  // us after the packet's first event, summed
};

}  // namespace evms::hls
