// Two objects that one cluster holds where their tracks meet, told apart by their motions: the
// fixed-point form of golden/cluster/motion_split.h, which states the rule and why
// (Config::motion_split_gain; a build with HasMotionMeasure, whose time-surface slopes it reads).
//
// The rule is golden's; the numbers are integers:
//   slope g           hls/cluster/time_surface_slopes.h's gradient, rounded to kSlopeFrac
//                     fraction bits of us/px and held within kSlopeMax; golden's flattest
//                     slope, 0.1 us/px, is dropped the same way
//   velocity v        least squares on g . v = 1 over a part's slopes: v = A^-1 b with
//                     A = sum g g^T and b = sum g, exact in 128 bits, kVelocityFrac fraction
//                     bits of px/us; A singular (all slopes along one line): A b / trace(A)^2,
//                     its pseudo-inverse's answer
//   residual          min(1, |g . v - 1|), exact (kResidualFrac fraction bits); 1/2 for an
//                     event without a slope
//   first cut         across the principal axis of the cluster's pixels: with the second
//                     moments times m^2 (cxx = m sum x^2 - (sum x)^2, ...), d = cxx - cyy and
//                     r = isqrt(d^2 + 4 cxy^2), the axis runs along (r + d, 2 cxy), or along y
//                     when that vanishes
//   distance          Chebyshev, from the part's centre over the cluster's events' mean
//                     Chebyshev distance from its centre; an event's cost fit + distance /
//                     (2 radius) is compared exactly, as fractions cleared of their denominators
//   rounds            up to kRounds, until no event changes part; the round of the least summed
//                     residual is kept (the first of equals)
//   the split         two parts' summed residual <= gain times one velocity's
//                     (kMotionGainFrac fraction bits, the share golden compares with too:
//                     types/params.h, motion_split_gain); each part a fifth of the sloped events and
//                     kLeastPartEvents events; |v0 - v1|^2 >= 0.09 max(|v0|, |v1|)^2
// The second part opens a mode after the existing ones (a cluster stays whole when the mode table
// is full); each part's mode is the mean of its climb features, rounded half up. Golden computes
// in doubles from the slopes it rounds less, so the two differ where a cost or a test is within
// rounding of a tie (the slope and velocity words' bounds: tests/hls/test_motion_measure.cpp; the
// core's labels against golden's: CoreAgreesWithGolden.TheSplitByMotionWhereTracksMeet in
// tests/hls/test_core.cpp).
#pragma once

#include <cstdint>

#include "hls/cluster/features.h"
#include "hls/cluster/seeded_climbs.h"
#include "hls/cluster/time_surface_slopes.h"
#include "hls/core/config.h"
#include "hls/math/isqrt.h"
#include "hls/math/round.h"
#include "hls/track/tracker.h"

namespace evms::hls {

template <class S>
class MotionSplit {
 public:
  using Wide = __int128;
  static constexpr int kLeastClusterEvents = 200;
  static constexpr int kBoxMarginPx = 2;
  static constexpr int kMeetingPoints = 2;
  static constexpr int kRounds = 8;
  static constexpr int kLeastPartEvents = 64;
  static constexpr int kSlopeFrac = 4;
  static constexpr std::int64_t kSlopeMax = std::int64_t{1} << 24;  // 2^20 us/px: slower than any edge a packet holds
  static constexpr int kVelocityFrac = 24;
  static constexpr std::int64_t kVelocityMax = std::int64_t{1} << 40;  // 65,536 px/us: a near-singular A's answer, held
  static constexpr int kResidualFrac = kSlopeFrac + kVelocityFrac;  // exact: g . v's own units
  static constexpr std::int64_t kOne = std::int64_t{1} << kResidualFrac;

  void reset() { slopes_.reset(); }

  // The normal equations of least squares on g . v = 1 over slopes g (kSlopeFrac bits of us/px,
  // at most kSlopeMax, at most kPacketMax of them): A = sum g g^T, b = sum g.
  struct SlopeSums {
    Wide a11 = 0, a12 = 0, a22 = 0, b1 = 0, b2 = 0;
    void add(std::int64_t gx, std::int64_t gy) { a11 += Wide{gx} * gx, a12 += Wide{gx} * gy, a22 += Wide{gy} * gy, b1 += gx, b2 += gy; }
  };

  // Their solution, v = 2^kSlopeFrac A^-1 b px/us, to kVelocityFrac bits rounded half away from
  // zero and held within kVelocityMax: exact in 128 bits, as |A| < 2^60 and |b| < 2^36. A
  // singular A (every slope along one line) gives A b / trace(A)^2, its pseudo-inverse's answer;
  // no slopes give 0.
  static void velocity(const SlopeSums& s, std::int64_t& vx, std::int64_t& vy) {
    constexpr int kScale = kSlopeFrac + kVelocityFrac;
    const Wide det = s.a11 * s.a22 - s.a12 * s.a12;
    if (det != 0) {
      vx = clamp_velocity(divide_signed((s.a22 * s.b1 - s.a12 * s.b2) * (Wide{1} << kScale), det));
      vy = clamp_velocity(divide_signed((s.a11 * s.b2 - s.a12 * s.b1) * (Wide{1} << kScale), det));
      return;
    }
    const Wide trace = s.a11 + s.a22;
    if (trace == 0) {
      vx = vy = 0;
      return;
    }
    // Rank one, A = t u u^T with t its trace: its pseudo-inverse is A / t^2.
    vx = clamp_velocity(divide_signed((s.a11 * s.b1 + s.a12 * s.b2) * (Wide{1} << kScale), trace * trace));
    vy = clamp_velocity(divide_signed((s.a12 * s.b1 + s.a22 * s.b2) * (Wide{1} << kScale), trace * trace));
  }

  // The slope (nx, ny) / d us/px of hls/cluster/time_surface_slopes.h's gradient() to kSlopeFrac
  // bits, rounded half away from zero and held within kSlopeMax; false for one flatter than golden's
  // least, 0.1 us/px (|g|^2 < 0.01 (us/px)^2).
  static bool slope_words(Wide nx, Wide ny, Wide d, std::int64_t& gx, std::int64_t& gy) {
    gx = clamp_slope(divide_rounded(nx * (Wide{1} << kSlopeFrac), d));
    gy = clamp_slope(divide_rounded(ny * (Wide{1} << kSlopeFrac), d));
    return 100 * (gx * gx + gy * gy) >= (std::int64_t{1} << (2 * kSlopeFrac));
  }

  // How badly velocity v explains slope g: min(1, |g . v - 1|), kResidualFrac bits, exact.
  static std::int64_t misfit(std::int64_t gx, std::int64_t gy, std::int64_t vx, std::int64_t vy) {
    constexpr int kScale = kSlopeFrac + kVelocityFrac;
    Wide off = Wide{gx} * vx + Wide{gy} * vy - (Wide{1} << kScale);
    if (off < 0) off = -off;
    return off > kOne ? kOne : static_cast<std::int64_t>(off);
  }

  // mode_of: per event of the packet ev[0..n), its mode after the links and the polarity split
  // (-1: none). Splits each cluster of `modes` the rule holds for; returns how many split.
  int run(const PacketEvents<S>& ev, const Features<S>& phi, int n, const Config& cfg, const Tracker<S>& tracker,
          std::int16_t mode_of[S::kPacketMax], Modes<S>& modes) {
    if (cfg.motion_split_gain == 0 || n == 0) return 0;
    TrackPoint confirmed[S::kTracksMax];
    const int tracks = tracker.confirmed_tracks(ev.t[n / 2], cfg, confirmed);
    int matched = 0;
  count_matched:
    for (int k = 0; k < S::kTracksMax; ++k) {
      if (k >= tracks) break;
      matched += confirmed[k].matched;
    }
    if (matched < kMeetingPoints) return 0;
    const int clusters = modes.count;
    boxes(ev, n, mode_of, clusters);
    bool looked_at[S::kModesMax];
    bool any = false;
  meeting:
    for (int c = 0; c < S::kModesMax; ++c) {
      if (c >= clusters) break;
      looked_at[c] = false;
      if (events_[c] < kLeastClusterEvents) continue;
      int held = 0;
    points:
      for (int k = 0; k < S::kTracksMax; ++k) {
#pragma HLS PIPELINE II = 1
        if (k >= tracks) break;
        held += confirmed[k].matched && in_grown_box<S::kPosFrac>(confirmed[k], x_min_[c], y_min_[c], x_max_[c], y_max_[c], kBoxMarginPx);
      }
      looked_at[c] = held >= kMeetingPoints;
      any = any || looked_at[c];
    }
    if (!any) return 0;
    slopes_.add(ev, n);
  slopes:
    for (int i = 0; i < S::kPacketMax; ++i) {
      if (i >= n) break;
      has_slope_[i] = mode_of[i] >= 0 && looked_at[mode_of[i]] && slope_of(ev, i, cfg);
    }
    slopes_.clear(n);
    int splits = 0;
  split_clusters:
    for (int c = 0; c < S::kModesMax; ++c) {
      if (c >= clusters) break;
      if (!looked_at[c] || modes.count >= S::kModesMax || !parts_of(ev, n, c, cfg.motion_split_gain, mode_of)) continue;
      relabel(phi, n, c, mode_of, modes);
      ++splits;
    }
    return splits;
  }

 private:
  // Each mode's event count and bounding box.
  void boxes(const PacketEvents<S>& ev, int n, const std::int16_t mode_of[S::kPacketMax], int clusters) {
  empty:
    for (int c = 0; c < S::kModesMax; ++c) {
#pragma HLS PIPELINE II = 1
      if (c >= clusters) break;
      events_[c] = 0;
      x_min_[c] = y_min_[c] = 0xFFFF;
      x_max_[c] = y_max_[c] = 0;
    }
  grow:
    for (int i = 0; i < S::kPacketMax; ++i) {
#pragma HLS PIPELINE II = 1
      if (i >= n) break;
      const int c = mode_of[i];
      if (c < 0) continue;
      ++events_[c];
      if (ev.x[i] < x_min_[c]) x_min_[c] = ev.x[i];
      if (ev.x[i] > x_max_[c]) x_max_[c] = ev.x[i];
      if (ev.y[i] < y_min_[c]) y_min_[c] = ev.y[i];
      if (ev.y[i] > y_max_[c]) y_max_[c] = ev.y[i];
    }
  }

  // Event i's slope in slope_x_/slope_y_; false when it has none.
  bool slope_of(const PacketEvents<S>& ev, int i, const Config& cfg) {
    Wide nx = 0, ny = 0, d = 0;
    std::int64_t gx = 0, gy = 0;
    if (!slopes_.gradient(ev.p[i], ev.x[i], ev.y[i], cfg, nx, ny, d) || !slope_words(nx, ny, d, gx, gy)) return false;
    slope_x_[i] = static_cast<std::int32_t>(gx), slope_y_[i] = static_cast<std::int32_t>(gy);
    return true;
  }

  static std::int64_t clamp_slope(Wide g) {
    return static_cast<std::int64_t>(g > kSlopeMax ? Wide{kSlopeMax} : g < -kSlopeMax ? Wide{-kSlopeMax} : g);
  }

  // a / b rounded half away from zero, b > 0.
  static Wide divide_rounded(Wide a, Wide b) { return a >= 0 ? (2 * a + b) / (2 * b) : -((-2 * a + b) / (2 * b)); }
  static Wide divide_signed(Wide a, Wide b) { return b > 0 ? divide_rounded(a, b) : divide_rounded(-a, -b); }
  static std::int64_t clamp_velocity(Wide v) {
    return static_cast<std::int64_t>(v > kVelocityMax ? Wide{kVelocityMax} : v < -kVelocityMax ? Wide{-kVelocityMax} : v);
  }

  // The velocity (kVelocityFrac bits of px/us) that explains the slopes of cluster c's sloped
  // events in `part` (-1: all of them) best.
  void fit_velocity(int n, int c, int part, const std::int16_t mode_of[S::kPacketMax], std::int64_t& vx, std::int64_t& vy) const {
    SlopeSums sums;
  normal_equations:
    for (int i = 0; i < S::kPacketMax; ++i) {
#pragma HLS PIPELINE II = 1
      if (i >= n) break;
      if (mode_of[i] != c || !has_slope_[i] || (part >= 0 && part_[i] != part)) continue;
      sums.add(slope_x_[i], slope_y_[i]);
    }
    velocity(sums, vx, vy);
  }

  // min(1, |g . v - 1|) of event i's slope, kResidualFrac bits.
  std::int64_t residual(int i, std::int64_t vx, std::int64_t vy) const { return misfit(slope_x_[i], slope_y_[i], vx, vy); }

  // Whether cluster c holds two motions; its events' parts in part_.
  bool parts_of(const PacketEvents<S>& ev, int n, int c, std::uint32_t gain, const std::int16_t mode_of[S::kPacketMax]) {
    std::int64_t m = 0, sloped = 0, sum_x = 0, sum_y = 0, sum_xx = 0, sum_yy = 0, sum_xy = 0;
  moments:
    for (int i = 0; i < S::kPacketMax; ++i) {
#pragma HLS PIPELINE II = 1
      if (i >= n) break;
      if (mode_of[i] != c) continue;
      const std::int64_t x = ev.x[i], y = ev.y[i];
      ++m, sloped += has_slope_[i], sum_x += x, sum_y += y, sum_xx += x * x, sum_yy += y * y, sum_xy += x * y;
    }
    if (3 * sloped < m) return false;
    std::int64_t one_vx = 0, one_vy = 0;
    fit_velocity(n, c, -1, mode_of, one_vx, one_vy);
    // The first cut, and the events' mean Chebyshev distance from their centre (1/16 px).
    const Wide cxx = Wide{m} * sum_xx - Wide{sum_x} * sum_x, cyy = Wide{m} * sum_yy - Wide{sum_y} * sum_y;
    const Wide cxy = Wide{m} * sum_xy - Wide{sum_x} * sum_y;
    const Wide d = cxx - cyy, r = isqrt(d * d + 4 * cxy * cxy);
    const bool along_y = cxy == 0 && d < 0;
    const Wide ax = along_y ? Wide{0} : r == 0 ? Wide{1} : r + d, ay = along_y ? Wide{1} : 2 * cxy;
    std::int64_t one_residual = 0, spread = 0;
  first_cut:
    for (int i = 0; i < S::kPacketMax; ++i) {
#pragma HLS PIPELINE II = 1
      if (i >= n) break;
      if (mode_of[i] != c) continue;
      const Wide along = (Wide{m} * ev.x[i] - sum_x) * ax + (Wide{m} * ev.y[i] - sum_y) * ay;
      part_[i] = along > 0;
      spread += chebyshev(m * ev.x[i] - sum_x, m * ev.y[i] - sum_y);  // m^2 times the distance
      if (has_slope_[i]) one_residual += residual(i, one_vx, one_vy);
    }
    // The radius is spread / m^2 px, and part q's centre (part_x[q], part_y[q]) / count[q].
    std::int64_t vx[2] = {0, 0}, vy[2] = {0, 0}, two_residual = 0, count[2] = {0, 0}, sloped_in[2] = {0, 0};
    // The rounds need not settle, and their residual need not fall each round: the round of the
    // least residual is kept (the first of equals), its parts and the velocities that gave them.
    std::int64_t best_vx[2] = {0, 0}, best_vy[2] = {0, 0}, best_residual = 0, best_count[2] = {0, 0}, best_sloped_in[2] = {0, 0};
  rounds:
    for (int round = 0; round < kRounds; ++round) {
      std::int64_t part_x[2] = {0, 0}, part_y[2] = {0, 0};
      count[0] = count[1] = sloped_in[0] = sloped_in[1] = 0;
    centres:
      for (int i = 0; i < S::kPacketMax; ++i) {
#pragma HLS PIPELINE II = 1
        if (i >= n) break;
        if (mode_of[i] != c) continue;
        const int q = part_[i];
        part_x[q] += ev.x[i], part_y[q] += ev.y[i], ++count[q], sloped_in[q] += has_slope_[i];
      }
      if (count[0] == 0 || count[1] == 0 || sloped_in[0] < 3 || sloped_in[1] < 3) return false;
    fits:
      for (int q = 0; q < 2; ++q) fit_velocity(n, c, q, mode_of, vx[q], vy[q]);
      two_residual = 0;
      std::int64_t centre_x[2] = {part_x[0], part_x[1]}, centre_y[2] = {part_y[0], part_y[1]}, in_part[2] = {count[0], count[1]};
      count[0] = count[1] = sloped_in[0] = sloped_in[1] = 0;
      bool moved = false;
    assign:
      for (int i = 0; i < S::kPacketMax; ++i) {
#pragma HLS PIPELINE II = 1
        if (i >= n) break;
        if (mode_of[i] != c) continue;
        // An event's cost in part q, fit_q + d_q / (2 radius) with d_q = away_q / in_part[q], times
        // 2 spread in_part[0] in_part[1] (all positive): exact in 128 bits.
        std::int64_t fit[2];
        Wide cost[2];
        for (int q = 0; q < 2; ++q) {
          fit[q] = has_slope_[i] ? residual(i, vx[q], vy[q]) : kOne / 2;
          const std::int64_t away = chebyshev(in_part[q] * ev.x[i] - centre_x[q], in_part[q] * ev.y[i] - centre_y[q]);
          cost[q] = 2 * Wide{spread} * in_part[0] * in_part[1] * fit[q] + Wide{away} * m * m * in_part[1 - q] * kOne;
        }
        const std::uint8_t q = cost[1] < cost[0] ? 1 : 0;
        moved = moved || q != part_[i];
        part_[i] = q;
        ++count[q];
        if (has_slope_[i]) two_residual += fit[q], ++sloped_in[q];
      }
      if (round == 0 || two_residual < best_residual) {
        best_residual = two_residual;
      keep:
        for (int i = 0; i < S::kPacketMax; ++i) {
#pragma HLS PIPELINE II = 1
          if (i >= n) break;
          if (mode_of[i] == c) best_part_[i] = part_[i];
        }
        for (int q = 0; q < 2; ++q) best_vx[q] = vx[q], best_vy[q] = vy[q], best_count[q] = count[q], best_sloped_in[q] = sloped_in[q];
      }
      if (!moved) break;  // the next round would fit the same parts again
    }
  restore:
    for (int i = 0; i < S::kPacketMax; ++i) {
#pragma HLS PIPELINE II = 1
      if (i >= n) break;
      if (mode_of[i] == c) part_[i] = best_part_[i];
    }
    two_residual = best_residual;
    for (int q = 0; q < 2; ++q) vx[q] = best_vx[q], vy[q] = best_vy[q], count[q] = best_count[q], sloped_in[q] = best_sloped_in[q];
    if ((two_residual << kMotionGainFrac) > std::int64_t{gain} * one_residual) return false;
    if (5 * (sloped_in[0] < sloped_in[1] ? sloped_in[0] : sloped_in[1]) < sloped) return false;
    const Wide dvx = Wide{vx[0]} - vx[1], dvy = Wide{vy[0]} - vy[1];
    const Wide speed0 = Wide{vx[0]} * vx[0] + Wide{vy[0]} * vy[0], speed1 = Wide{vx[1]} * vx[1] + Wide{vy[1]} * vy[1];
    if (100 * (dvx * dvx + dvy * dvy) < 9 * (speed0 > speed1 ? speed0 : speed1)) return false;
    return (count[0] < count[1] ? count[0] : count[1]) >= kLeastPartEvents;
  }

  static std::int64_t chebyshev(std::int64_t dx, std::int64_t dy) {
    const std::int64_t ax = dx < 0 ? -dx : dx, ay = dy < 0 ? -dy : dy;
    return ax > ay ? ax : ay;
  }

  // Cluster c's second part opens a mode; each part's mode is its climb features' mean.
  void relabel(const Features<S>& phi, int n, int c, std::int16_t mode_of[S::kPacketMax], Modes<S>& modes) {
    const int second = modes.count;
    std::int64_t sum_x[2] = {0, 0}, sum_y[2] = {0, 0}, count[2] = {0, 0};
  parts:
    for (int i = 0; i < S::kPacketMax; ++i) {
#pragma HLS PIPELINE II = 1
      if (i >= n) break;
      if (mode_of[i] != c) continue;
      const int q = part_[i];
      sum_x[q] += phi.x[i], sum_y[q] += phi.y[i], ++count[q];
      if (q == 1) mode_of[i] = static_cast<std::int16_t>(second);
    }
    for (int q = 0; q < 2; ++q) {
      const int mode = q == 0 ? c : second;
      modes.x[mode] = (2 * sum_x[q] + count[q]) / (2 * count[q]);
      modes.y[mode] = (2 * sum_y[q] + count[q]) / (2 * count[q]);
      modes.p[mode] = modes.t[mode] = 0;  // the climbs' features are (x, y) only
      modes.ball2[mode] = modes.ball2[c];
    }
    ++modes.count;
  }

  TimeSurfaceSlopes<S> slopes_;
  std::int32_t events_[S::kModesMax];
  std::uint16_t x_min_[S::kModesMax], y_min_[S::kModesMax], x_max_[S::kModesMax], y_max_[S::kModesMax];
  bool has_slope_[S::kPacketMax];
  std::int32_t slope_x_[S::kPacketMax], slope_y_[S::kPacketMax];  // kSlopeFrac bits of us/px
  std::uint8_t part_[S::kPacketMax], best_part_[S::kPacketMax];
};

}  // namespace evms::hls
