// Seeded mean-shift climbs with a flat kernel, as golden/cluster/clustering.h states them, in
// fixed point. Features are the pixel coordinates in bandwidth units (phi = (x / W) / h, and
// y likewise), with kFeatFrac + kClimbFrac fraction bits (climb_features): close enough to
// golden's doubles that a kernel boundary decides the same way but for events within 2^-21 h
// of it. The kernel's ball is |m - phi_j|^2 < 1.
//
// A climb from m: sum the events in the ball and count them; move m to their mean, rounded to
// the nearest unit of m (exact integer division, half up); stop when no coordinate moved more
// than the tolerance, when the ball is empty, or after max_iterations steps. Every event that
// was in the ball at any step is reached. The converged climb joins the nearest earlier mode
// within the merge radius or opens a mode (while fewer than kModesMax are open; otherwise it
// is lost and its events stay unlabelled unless a later climb reaches them first).
//
// Seeds, in order: the previous packet's modes (warm start, each climbing with its own ball,
// Modes::ball2), then the first event no climb has reached yet, with the ball of radius h, until
// every event was reached. An event's cluster is the mode of the first climb
// that reached it. The sums are exact integers, so the order the events are visited in (and the
// number of lanes that visit them) does not change a result.
#pragma once

#include <cstdint>

#include "hls/cluster/features.h"
#include "hls/core/config.h"
#include "hls/math/round.h"

namespace evms::hls {

// Fraction bits of the climbs' features and positions beyond kFeatFrac, and of the scale
// registers that make them.
inline constexpr int kClimbFrac = 8;
inline constexpr int kClimbScaleFrac = 40;

// (x, y) in bandwidth units with kFeatFrac + kClimbFrac fraction bits, rounded; polarity and
// time are not features of the climbs (the core refuses their scales).
template <class S>
void climb_features(const PacketEvents<S>& ev, int n, const Config& cfg, Features<S>& phi) {
  constexpr int kShift = kClimbScaleFrac - S::kFeatFrac - kClimbFrac;
features:
  for (int i = 0; i < S::kPacketMax; ++i) {
#pragma HLS PIPELINE II = 1
    if (i >= n) break;
    phi.x[i] = static_cast<std::uint32_t>(shr_rnd(static_cast<std::int64_t>(ev.x[i] * cfg.climb_scale_x), kShift));
    phi.y[i] = static_cast<std::uint32_t>(shr_rnd(static_cast<std::int64_t>(ev.y[i] * cfg.climb_scale_y), kShift));
    phi.p[i] = 0;
    phi.t[i] = 0;
  }
}

// Modes, in the climbs' feature units.
template <class S>
struct Modes {
  std::int64_t x[S::kModesMax], y[S::kModesMax], p[S::kModesMax], t[S::kModesMax];
  std::uint64_t ball2[S::kModesMax];  // warm seeds: the squared radius of their climb's ball
  int count = 0;
};

// What the climbs did, for the cycle model and the statistics.
struct ClimbTrace {
  int climbs = 0;
  int steps = 0;              // kernel sweeps over the packet, summed over climbs
  int modes_lost = 0;         // climbs that found the mode table full
};

namespace detail {

// round(num / den) for num >= 0, den > 0, half up.
constexpr std::int64_t divide_rounded(std::int64_t num, std::int64_t den) { return (2 * num + den) / (2 * den); }

}  // namespace detail

template <class S>
class SeededClimbs {
 public:
  // Writes each event's mode (or -1) to first_mode and the modes to `modes`.
  void run(const Features<S>& phi, int n, const Config& cfg, const Modes<S>& warm, std::int16_t first_mode[S::kPacketMax], Modes<S>& modes,
           ClimbTrace& trace) {
    trace = {};
    modes.count = 0;
  clear:
    for (int j = 0; j < S::kPacketMax; ++j) {
#pragma HLS PIPELINE II = 1
      if (j >= n) break;
      first_mode[j] = -1;
      reached_[j] = false;
      in_climb_[j] = false;
    }
  warm_seeds:
    for (int k = 0; k < S::kModesMax; ++k) {
      if (!cfg.warm_start || k >= warm.count) break;
      climb(phi, n, cfg, warm.x[k], warm.y[k], warm.p[k], warm.t[k], warm.ball2[k], first_mode, modes, trace);
    }
  event_seeds:
    for (int i = 0; i < S::kPacketMax; ++i) {
      if (i >= n) break;
      if (!reached_[i]) climb(phi, n, cfg, phi.x[i], phi.y[i], phi.p[i], phi.t[i], kOne, first_mode, modes, trace);
    }
  }

 private:
 public:
  static constexpr std::uint64_t kOne = std::uint64_t{1} << (2 * (S::kFeatFrac + kClimbFrac));  // h^2

 private:
  void climb(const Features<S>& phi, int n, const Config& cfg, std::int64_t mx, std::int64_t my, std::int64_t mp, std::int64_t mt,
             std::uint64_t ball2, std::int16_t first_mode[S::kPacketMax], Modes<S>& modes, ClimbTrace& trace) {
    ++trace.climbs;
  steps:
    for (int step = 0; step < S::kIterationsMax; ++step) {
      if (step >= cfg.max_iterations) break;
      std::int64_t sx = 0, sy = 0, sp = 0, st = 0, count = 0;
    kernel:
      for (int j = 0; j < S::kPacketMax; ++j) {
#pragma HLS PIPELINE II = 1
#pragma HLS UNROLL factor = S::kLanes
        if (j >= n) break;
        const std::int64_t dx = mx - phi.x[j], dy = my - phi.y[j], dp = mp - phi.p[j], dt = mt - phi.t[j];
        if (squared_distance(dx, dy, dp, dt) < ball2) {
          reached_[j] = true;
          in_climb_[j] = true;
          sx += phi.x[j], sy += phi.y[j], sp += phi.p[j], st += phi.t[j];
          ++count;
        }
      }
      ++trace.steps;
      if (count == 0) break;  // nothing in reach: the climb stays where it is
      const std::int64_t nx = detail::divide_rounded(sx, count), ny = detail::divide_rounded(sy, count);
      const std::int64_t np = detail::divide_rounded(sp, count), nt = detail::divide_rounded(st, count);
      std::int64_t move = nx > mx ? nx - mx : mx - nx;
      const std::int64_t moves[3] = {ny > my ? ny - my : my - ny, np > mp ? np - mp : mp - np, nt > mt ? nt - mt : mt - nt};
      for (std::int64_t m : moves) move = m > move ? m : move;
      mx = nx, my = ny, mp = np, mt = nt;
      if (move <= cfg.tolerance) break;
    }
    const int mode = join_or_open(cfg, mx, my, mp, mt, modes, trace);
  label:
    for (int j = 0; j < S::kPacketMax; ++j) {
#pragma HLS PIPELINE II = 1
      if (j >= n) break;
      if (in_climb_[j] && first_mode[j] < 0) first_mode[j] = static_cast<std::int16_t>(mode);
      in_climb_[j] = false;
    }
  }

  // The nearest mode within the merge radius (ties: the older), else a new one; -1 when the
  // table is full.
  static int join_or_open(const Config& cfg, std::int64_t mx, std::int64_t my, std::int64_t mp, std::int64_t mt, Modes<S>& modes,
                          ClimbTrace& trace) {
    int best = -1;
    std::uint64_t best_d2 = 0;
  modes_loop:
    for (int c = 0; c < S::kModesMax; ++c) {
#pragma HLS PIPELINE II = 1
      if (c >= modes.count) break;
      const std::int64_t dx = mx - modes.x[c], dy = my - modes.y[c], dp = mp - modes.p[c], dt = mt - modes.t[c];
      const std::uint64_t d2 = squared_distance(dx, dy, dp, dt);
      if (d2 <= cfg.merge_radius2 && (best < 0 || d2 < best_d2)) best = c, best_d2 = d2;
    }
    if (best >= 0) return best;
    if (modes.count == S::kModesMax) {
      ++trace.modes_lost;
      return -1;
    }
    const int c = modes.count++;
    modes.x[c] = mx, modes.y[c] = my, modes.p[c] = mp, modes.t[c] = mt;
    return c;
  }

  bool reached_[S::kPacketMax];
  bool in_climb_[S::kPacketMax];
};

}  // namespace evms::hls
