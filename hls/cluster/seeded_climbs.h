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
// A mode's support is the number of events in the ball at the last step of the climbs that
// joined it (the most of them). With min_density, a mode whose support is below
// n * min_density (golden: the events a uniform spread of the packet's n events over the sensor
// would put in a ball of radius h, times --min-density) is noise, and so are its events; with
// density_after_links the climbs leave the test to drop_sparse_sets, which makes it on each set
// of linked modes after the links (hls/cluster/sparse_sets.h).
//
// Seeds, in order: the previous packet's modes (warm start, each climbing with its own ball,
// Modes::ball2), then the first event no climb has reached yet, with the ball of radius h, until
// every event was reached. An event's cluster is the mode of the first climb
// that reached it. The sums are exact integers, so the order the events are visited in (and the
// number of lanes that visit them) does not change a result.
//
// The events are first sorted into a grid of cells one bandwidth wide (the integer part of their
// features, clamped to kGridSide - 1), cell by cell, row after row: a ball of radius r <= R
// bandwidths around m holds only events of the cells within R of m's cell, which are 2R + 1
// contiguous runs of the sorted events. So a step visits the events near m, not the packet.
#pragma once

#include <cstdint>

#include "hls/cluster/features.h"
#include "hls/core/shape.h"
#include "hls/core/config.h"
#include "hls/math/round.h"

namespace evms::hls {

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

// What one packet's climbs give the rest of the core: every event's mode and every mode's
// position and support, with the counts. A board whose core stops at the climbs
// (rtl/core/evms_climbs_core.sv) returns one a packet, and Core::process_climbed completes the
// packet from it (hls/core/core.h).
template <class S>
struct ClimbsFrame {
  int n = 0;                                  // events in the packet
  int mode_count = 0;
  std::uint32_t x[S::kModesMax], y[S::kModesMax];
  std::uint16_t support[S::kModesMax];
  std::int16_t first_mode[S::kPacketMax];     // -1: no mode
  ClimbTrace trace;
};

namespace detail {

// round(num / den) for num >= 0, den > 0, half up.
constexpr std::int64_t divide_rounded(std::int64_t num, std::int64_t den) { return (2 * num + den) / (2 * den); }

}  // namespace detail

template <class S>
class SeededClimbs {
 public:
  static constexpr std::uint64_t kOne = std::uint64_t{1} << (2 * (S::kFeatFrac + kClimbFrac));  // h^2
  static constexpr int kUnitShift = S::kFeatFrac + kClimbFrac;                                  // one bandwidth
  static constexpr int kCells = S::kGridSide * S::kGridSide;

  // Writes each event's mode (or -1) to first_mode and the modes to `modes`. Warm balls must be
  // at most kReachMax bandwidths (the backends refuse larger, host/backend/core_config.h).
  // Without `drop_sparse`, the modes below the least density keep their events (the caller
  // drops them later with drop_sparse_modes, as the core does to record the climbs first).
  void run(const Features<S>& phi, int n, const Config& cfg, const Modes<S>& warm, std::int16_t first_mode[S::kPacketMax], Modes<S>& modes,
           ClimbTrace& trace, bool drop_sparse = true) {
    trace = {};
    modes.count = 0;
    sort_into_cells(phi, n);
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
      climb(cfg, warm.x[k], warm.y[k], warm.ball2[k], first_mode, modes, trace);
    }
  event_seeds:
    for (int i = 0; i < S::kPacketMax; ++i) {
      if (i >= n) break;
      if (!reached_[i]) climb(cfg, phi.x[i], phi.y[i], kOne, first_mode, modes, trace);
    }
    if (drop_sparse) drop_sparse_modes(first_mode, n, cfg);
  }

  // Without density_after_links, the events of a mode below the least density go without one
  // (run() does it; a run taken from elsewhere by assume() needs it done).
  void drop_sparse_modes(std::int16_t first_mode[S::kPacketMax], int n, const Config& cfg) const {
    if (cfg.min_density == 0 || cfg.density_after_links) return;
  sparse_modes:
    for (int j = 0; j < S::kPacketMax; ++j) {
#pragma HLS PIPELINE II = 1
      if (j >= n) break;
      const int c = first_mode[j];
      if (c >= 0 && sparse(c, n, cfg)) first_mode[j] = -1;
    }
  }

  // The least events a mode (or, with density_after_links, a set of linked modes) of a packet
  // of n events holds to be kept: n * min_density, kDensityFrac fraction bits.
  static std::uint64_t least(int n, const Config& cfg) { return static_cast<std::uint64_t>(n) * cfg.min_density; }

  // Mode c's support in the last run: the most events a climb that joined it held at its last step.
  int support(int c) const { return support_[c]; }

  // The last run's result, as a board whose core stops at the climbs returns it.
  void frame(const std::int16_t first_mode[S::kPacketMax], int n, const Modes<S>& modes, const ClimbTrace& trace, ClimbsFrame<S>& out) const {
    out.n = n, out.mode_count = modes.count, out.trace = trace;
  modes_out:
    for (int c = 0; c < S::kModesMax; ++c) {
      if (c >= modes.count) break;
      out.x[c] = static_cast<std::uint32_t>(modes.x[c]), out.y[c] = static_cast<std::uint32_t>(modes.y[c]), out.support[c] = support_[c];
    }
  events_out:
    for (int j = 0; j < S::kPacketMax; ++j) {
      if (j >= n) break;
      out.first_mode[j] = first_mode[j];
    }
  }

  // Takes a run's result from elsewhere (a board's climbs, of a run without warm seeds) as if
  // this had run it: run()'s outputs, and the supports support() and sparse() read.
  void assume(const ClimbsFrame<S>& in, std::int16_t first_mode[S::kPacketMax], Modes<S>& modes, ClimbTrace& trace) {
    modes.count = in.mode_count, trace = in.trace;
  modes_in:
    for (int c = 0; c < S::kModesMax; ++c) {
      if (c >= in.mode_count) break;
      modes.x[c] = in.x[c], modes.y[c] = in.y[c], modes.p[c] = 0, modes.t[c] = 0, modes.ball2[c] = 0;
      support_[c] = in.support[c];
    }
  events_in:
    for (int j = 0; j < S::kPacketMax; ++j) {
      if (j >= in.n) break;
      first_mode[j] = in.first_mode[j];
    }
  }

  // Whether mode c of the last run's packet of n events is below the least density.
  bool sparse(int c, int n, const Config& cfg) const {
    return (static_cast<std::uint64_t>(support_[c]) << kDensityFrac) < least(n, cfg);
  }

 private:
  static int cell_of(std::int64_t v) {
    const std::int64_t c = v >> kUnitShift;
    return c < 0 ? 0 : (c >= S::kGridSide ? S::kGridSide - 1 : static_cast<int>(c));
  }

  // Counting sort of the events by cell: start_[c] .. start_[c + 1] are cell c's events in
  // sorted order, in packet order within the cell.
  void sort_into_cells(const Features<S>& phi, int n) {
  clear_counts:
    for (int c = 0; c <= kCells; ++c) {
#pragma HLS PIPELINE II = 1
      start_[c] = 0;
    }
  count:
    for (int j = 0; j < S::kPacketMax; ++j) {
#pragma HLS PIPELINE II = 1
      if (j >= n) break;
      cell_[j] = static_cast<std::uint16_t>(cell_of(phi.y[j]) * S::kGridSide + cell_of(phi.x[j]));
      ++start_[cell_[j] + 1];
    }
  prefix:
    for (int c = 0; c < kCells; ++c) {
#pragma HLS PIPELINE II = 1
      start_[c + 1] += start_[c];
      next_[c] = start_[c];
    }
  place:
    for (int j = 0; j < S::kPacketMax; ++j) {
#pragma HLS PIPELINE II = 1
      if (j >= n) break;
      const int k = next_[cell_[j]]++;
      sorted_x_[k] = phi.x[j], sorted_y_[k] = phi.y[j], event_[k] = static_cast<std::uint16_t>(j);
    }
  }

  void climb(const Config& cfg, std::int64_t mx, std::int64_t my, std::uint64_t ball2, std::int16_t first_mode[S::kPacketMax], Modes<S>& modes,
             ClimbTrace& trace) {
    ++trace.climbs;
    // The ball's reach in cells: the least r with (r bandwidths)^2 >= ball2.
    int reach = 1;
  reach_of_ball:
    for (int r = 1; r < S::kReachMax; ++r) {
      if ((static_cast<std::uint64_t>(r * r) << (2 * kUnitShift)) >= ball2) break;
      reach = r + 1;
    }
    int touched = 0;
    int inside = 0;  // events in the ball at the last step
  steps:
    for (int step = 0; step < S::kIterationsMax; ++step) {
      if (step >= cfg.max_iterations) break;
      std::int64_t sx = 0, sy = 0, count = 0;
      const int cx = cell_of(mx), cy = cell_of(my);
      const int x0 = cx - reach < 0 ? 0 : cx - reach, x1 = cx + reach >= S::kGridSide ? S::kGridSide - 1 : cx + reach;
    rows:
      for (int dy = -S::kReachMax; dy <= S::kReachMax; ++dy) {
        const int row = cy + dy;
        if (dy < -reach || dy > reach || row < 0 || row >= S::kGridSide) continue;
      kernel:
        for (int k = start_[row * S::kGridSide + x0]; k < start_[row * S::kGridSide + x1 + 1]; ++k) {
#pragma HLS PIPELINE II = 1
#pragma HLS UNROLL factor = S::kLanes
          const std::int64_t dx = mx - sorted_x_[k], dyf = my - sorted_y_[k];
          if (squared_distance(dx, dyf, 0, 0) < ball2) {
            const int j = event_[k];
            reached_[j] = true;
            if (!in_climb_[j]) in_climb_[j] = true, touched_[touched++] = static_cast<std::uint16_t>(j);
            sx += sorted_x_[k], sy += sorted_y_[k];
            ++count;
          }
        }
      }
      ++trace.steps;
      inside = static_cast<int>(count);
      if (count == 0) break;  // nothing in reach: the climb stays where it is
      const std::int64_t nx = detail::divide_rounded(sx, count), ny = detail::divide_rounded(sy, count);
      const std::int64_t move_x = nx > mx ? nx - mx : mx - nx, move_y = ny > my ? ny - my : my - ny;
      mx = nx, my = ny;
      if ((move_x > move_y ? move_x : move_y) <= cfg.tolerance) break;
    }
    const int mode = join_or_open(cfg, mx, my, 0, 0, inside, modes, trace);
  label:
    for (int t = 0; t < S::kPacketMax; ++t) {
#pragma HLS PIPELINE II = 1
      if (t >= touched) break;
      const int j = touched_[t];
      if (first_mode[j] < 0) first_mode[j] = static_cast<std::int16_t>(mode);
      in_climb_[j] = false;
    }
  }

  // The nearest mode within the merge radius (ties: the older), else a new one; -1 when the
  // table is full. The mode's support becomes the climb's `inside` if that is more.
  int join_or_open(const Config& cfg, std::int64_t mx, std::int64_t my, std::int64_t mp, std::int64_t mt, int inside, Modes<S>& modes,
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
    if (best >= 0) {
      if (inside > support_[best]) support_[best] = static_cast<std::uint16_t>(inside);
      return best;
    }
    if (modes.count == S::kModesMax) {
      ++trace.modes_lost;
      return -1;
    }
    const int c = modes.count++;
    modes.x[c] = mx, modes.y[c] = my, modes.p[c] = mp, modes.t[c] = mt;
    support_[c] = static_cast<std::uint16_t>(inside);
    return c;
  }

  std::uint16_t support_[S::kModesMax];  // each mode's support (above)
  bool reached_[S::kPacketMax];
  bool in_climb_[S::kPacketMax];
  std::uint16_t touched_[S::kPacketMax];   // the current climb's events, in the order it reached them
  // The grid: the events sorted by cell, their packet index, and where each cell's run starts.
  std::uint16_t cell_[S::kPacketMax];
  std::uint32_t sorted_x_[S::kPacketMax], sorted_y_[S::kPacketMax];
  std::uint16_t event_[S::kPacketMax];
  int start_[kCells + 1];
  int next_[kCells];
};

}  // namespace evms::hls
