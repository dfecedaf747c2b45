// Multi-target tracking in fixed point: the rules of golden/track/tracker.h with slots in a
// register file. Per packet:
//  1. confirmed tracks not measured for more than coast_us, or that missed coast_packets
//     packets in a row (when set), end;
//  2. (track, measurement) pairs within the gate of the track's prediction (or, with
//     associate_last, of its last measurement) are candidates; the gate is gate2, widened to
//     gate_spread2 times the measurement's spread squared when that is larger. The nearest pair
//     is taken, then the nearest among the rest, and so on (ties: lower slot, then lower
//     measurement), so association is one-to-one; with size_ratio_log2, pairs whose event counts
//     (the measurement's and the track's last) differ by more than 2^size_ratio_log2 times come
//     after every other pair (the "far" bit of the pair table, above the distance); with
//     gate_boxes, a pair beyond the gate is a candidate too when the track's last measurement
//     lies in the measurement's bounding box or the measurement in the last one's box, and it
//     comes after every pair within the gate (the "beyond" bit, above "far");
//  3. matched tracks predict to their measurement's time and update; they report (tentative
//     ones only with report_tentative);
//  4. unmatched tentative tracks end; unmatched confirmed ones coast;
//  5. unmatched measurements start tracks in the lowest free slots with new IDs (31-bit
//     counter, never reused) and report as in 3; with no slot free they take the slot of the
//     unmatched track measured longest ago (evict_stale), or leave their events as noise.
#pragma once

#include <cstdint>

#include "hls/cluster/centroid.h"
#include "hls/core/words.h"
#include "hls/fixed/stream.h"
#include "hls/track/kalman_axis.h"
#include "hls/track/measurement_variance.h"

namespace evms::hls {

// What one step did, for the cycle model (hls/core/schedule.h).
struct TrackerTrace {
  int scans = 0;        // passes over the (track, measurement) pairs, one per round
  int slot_steps = 0;   // measurements visited by those passes, over live unmatched tracks
  int distances = 0;    // distances taken, once per (live track, measurement) pair
  int matches = 0;
  bool rounds_capped = false;  // every round matched, up to kClustersMax
  int births = 0;
  int evict_scans = 0;  // births that found no free slot and looked for one to evict
};

// A track's predicted position (kPosFrac fraction bits, px), its velocity (kPosFrac fraction
// bits, px per tick), and whether it was matched in the last step.
struct TrackPoint {
  std::int32_t x = 0, y = 0, vx = 0, vy = 0;
  bool matched = false;
};

// Whether track point q lies in the box [x_min, x_max] x [y_min, y_max] px grown by margin px on
// every side, compared in PosFrac fraction bits: where the motion measure and the split by motion
// look for the tracks a cluster holds.
template <int PosFrac>
bool in_grown_box(const TrackPoint& q, int x_min, int y_min, int x_max, int y_max, int margin) {
  const std::int64_t unit = std::int64_t{1} << PosFrac;
  return q.x >= (std::int64_t{x_min} - margin) * unit && q.x <= (std::int64_t{x_max} + margin) * unit &&
         q.y >= (std::int64_t{y_min} - margin) * unit && q.y <= (std::int64_t{y_max} + margin) * unit;
}

// A measurement's bounding box, px (inclusive).
struct Box {
  std::uint16_t x_min = 0, y_min = 0, x_max = 0, y_max = 0;
  // Whether the pixel the point (x, y) (kPosFrac fraction bits) falls in, its coordinates'
  // whole parts, is one of the box's: compares of the whole parts' 16 bits, not of the
  // fractions. A centre is a mean of 16-bit pixel coordinates, so its whole part fits 16 bits.
  template <int PosFrac>
  bool holds(std::int32_t x, std::int32_t y) const {
    const auto px = static_cast<std::uint16_t>(x >> PosFrac), py = static_cast<std::uint16_t>(y >> PosFrac);
    return px >= x_min && px <= x_max && py >= y_min && py <= y_max;
  }
};

template <class S>
class Tracker {
  static_assert(S::kPacketMax < 65536, "a slot keeps its last cluster's event count in 16 bits");

 public:
  using Axis = KalmanAxis<S>;

  void reset() {
    for (int s = 0; s < S::kTracksMax; ++s) slot_[s].valid = false;
    next_id_ = 0;
    unassigned_ = 0;
  }

  // Assigns a track ID (or -1) to each measurement and writes the updates to report to
  // `updates`.
  template <int Depth>
  void step(std::uint32_t packet_time, const Measurement z[S::kClustersMax], int m, const Config& cfg, std::int32_t ids[S::kClustersMax],
            Stream<TrackWord, Depth>& updates) {
    trace_ = {};
  expire:
    for (int s = 0; s < S::kTracksMax; ++s) {
#pragma HLS UNROLL
      const bool too_old = static_cast<std::int32_t>(packet_time - slot_[s].t_last) > static_cast<std::int32_t>(cfg.coast_us);
      const bool too_many_missed = cfg.coast_packets != 0 && slot_[s].missed >= cfg.coast_packets;
      if (slot_[s].valid && (too_old || too_many_missed)) slot_[s].valid = false;
    }
    bool slot_matched[S::kTracksMax] = {};
    bool meas_matched[S::kClustersMax] = {};
    std::uint64_t gate2[S::kClustersMax];
    for (int c = 0; c < S::kClustersMax; ++c) {
      ids[c] = -1;
      if (c < m) gate2[c] = gate_of(z[c], cfg);
    }

    // Every pair's distance, once: a track's distance to a measurement changes only when the
    // track is matched, and a matched track takes part in no later round. The rounds then scan
    // the table, a pair a clock, instead of predicting and squaring again.
    // One memory of {within, d2} words in the RTL (rtl/track/evms_tracker.sv, the pair table):
    // written by the distance pass, read by the scans, never both in one clock.
    std::uint64_t pair_d2[S::kTracksMax][S::kClustersMax];
    bool pair_within[S::kTracksMax][S::kClustersMax] = {};  // a candidate
    bool pair_beyond[S::kTracksMax][S::kClustersMax] = {};  // ... by the boxes, beyond the gate
    bool pair_far[S::kTracksMax][S::kClustersMax] = {};
#pragma HLS BIND_STORAGE variable = pair_d2 type = ram_s2p
#pragma HLS BIND_STORAGE variable = pair_within type = ram_s2p
#pragma HLS BIND_STORAGE variable = pair_beyond type = ram_s2p
#pragma HLS BIND_STORAGE variable = pair_far type = ram_s2p
  distances:
    for (int s = 0; s < S::kTracksMax; ++s) {
      if (!slot_[s].valid || s >= cfg.max_tracks) continue;
      for (int k = 0; k < S::kClustersMax; ++k) {
        if (k >= m) break;
        ++trace_.distances;
        pair_d2[s][k] = cfg.associate_last ? last_distance2(slot_[s], z[k]) : distance2(slot_[s], z[k]);
        pair_beyond[s][k] = pair_d2[s][k] > gate2[k];
        pair_within[s][k] = !pair_beyond[s][k] || (cfg.gate_boxes && boxes_cover(slot_[s], z[k]));
        pair_far[s][k] = sizes_differ(slot_[s].last_events, z[k].events, cfg.size_ratio_log2);
      }
    }

    trace_.rounds_capped = true;
  rounds:
    for (int round = 0; round < S::kClustersMax; ++round) {
      int best_s = -1, best_m = -1;
      std::uint64_t best_d2 = 0;
      int best_rank = 0;  // beyond the gate (2) and sizes far apart (1): lower ranks first
      ++trace_.scans;
    pairs:
      for (int s = 0; s < S::kTracksMax; ++s) {
        if (!slot_[s].valid || slot_matched[s] || s >= cfg.max_tracks) continue;
        trace_.slot_steps += m;
        for (int k = 0; k < S::kClustersMax; ++k) {
#pragma HLS PIPELINE II = 1
          if (k >= m) break;
          if (meas_matched[k] || !pair_within[s][k]) continue;
          const int rank = 2 * pair_beyond[s][k] + pair_far[s][k];
          if (best_s < 0 || rank < best_rank || (rank == best_rank && pair_d2[s][k] < best_d2)) {
            best_s = s, best_m = k, best_d2 = pair_d2[s][k], best_rank = rank;
          }
        }
      }
      if (best_s < 0) {
        trace_.rounds_capped = false;
        break;
      }
      ++trace_.matches;
      slot_matched[best_s] = meas_matched[best_m] = true;
      Slot& t = slot_[best_s];
      const std::uint32_t dt = z[best_m].t - t.t_last;
      Axis::predict(t.ax, dt, cfg);
      Axis::predict(t.ay, dt, cfg);
      t.t_last = z[best_m].t;
      const std::int64_t r = measurement_variance<S>(z[best_m], cfg);
      Axis::update(t.ax, z[best_m].x, r);
      Axis::update(t.ay, z[best_m].y, r);
      if (!t.confirmed) t.confirmed = ++t.hits >= cfg.confirm_hits;
      t.missed = 0;
      t.zx = z[best_m].x, t.zy = z[best_m].y;
      t.last_events = z[best_m].events;
      t.last_box = box_of(z[best_m]);
      ids[best_m] = t.id;
      report(t, z[best_m], cfg, updates);
    }

  end_or_coast:
    for (int s = 0; s < S::kTracksMax; ++s) {
      if (!slot_[s].valid || slot_matched[s]) continue;
      if (slot_[s].confirmed) ++slot_[s].missed;
      else slot_[s].valid = false;
    }

  births:
    for (int k = 0; k < S::kClustersMax; ++k) {
      if (k >= m) break;
      if (meas_matched[k]) continue;
      const int slot = slot_for_new_track(cfg, slot_matched);
      if (slot < 0) {
        ++unassigned_;
        continue;
      }
      ++trace_.births;
      Slot& t = slot_[slot];
      slot_matched[slot] = true;
      t.valid = true;
      t.id = next_id_;
      next_id_ = (next_id_ + 1) & 0x7FFFFFFF;
      t.hits = 1;
      t.confirmed = cfg.confirm_hits <= 1;
      t.missed = 0;
      t.t_last = z[k].t;
      t.zx = z[k].x, t.zy = z[k].y;
      t.last_events = z[k].events;
      t.last_box = box_of(z[k]);
      t.ax = {z[k].x, 0, cfg.p0_pos, 0, cfg.p0_vel};
      t.ay = {z[k].y, 0, cfg.p0_pos, 0, cfg.p0_vel};
      ids[k] = t.id;
      report(t, z[k], cfg, updates);
    }
  }

  // The confirmed tracks, coasting ones too, in slot order, predicted to time t: golden's
  // confirmed_predictions(t). Returns how many it wrote.
  int confirmed_tracks(std::uint32_t t, const Config& cfg, TrackPoint out[S::kTracksMax]) const {
    int count = 0;
  confirmed:
    for (int s = 0; s < S::kTracksMax; ++s) {
#pragma HLS PIPELINE II = 1
      const Slot& slot = slot_[s];
      if (!slot.valid || !slot.confirmed || s >= cfg.max_tracks) continue;
      const std::int32_t dt_raw = static_cast<std::int32_t>(t - slot.t_last);
      const std::uint32_t dt = dt_raw > 0 ? static_cast<std::uint32_t>(dt_raw) : 0;
      out[count++] = {Axis::predicted(slot.ax, dt), Axis::predicted(slot.ay, dt), slot.ax.vel, slot.ay.vel, slot.missed == 0};
    }
    return count;
  }

  std::int32_t tracks_started() const { return next_id_; }
  const TrackerTrace& last_step() const { return trace_; }
  std::int64_t unassigned_clusters() const { return unassigned_; }
  // The covariance of a live slot, for tests.
  bool slot_state(int s, AxisState& ax, AxisState& ay) const {
    if (!slot_[s].valid) return false;
    ax = slot_[s].ax, ay = slot_[s].ay;
    return true;
  }

 private:
  struct Slot {
    bool valid = false, confirmed = false;
    std::int32_t id = 0;
    std::uint8_t hits = 0;
    std::uint32_t missed = 0;        // packets in a row without a measurement
    std::uint32_t t_last = 0;
    std::int32_t zx = 0, zy = 0;     // the last measurement, kPosFrac
    std::uint16_t last_events = 0;   // ... its event count (at most kPacketMax)
    Box last_box;                    // ... and its bounding box
    AxisState ax, ay;
  };

  static Box box_of(const Measurement& z) { return {z.x_min, z.y_min, z.x_max, z.y_max}; }

  // gate_boxes' test: the track's last measurement lies in z's box, or z in the last one's box.
  static bool boxes_cover(const Slot& t, const Measurement& z) {
    return box_of(z).template holds<S::kPosFrac>(t.zx, t.zy) || t.last_box.template holds<S::kPosFrac>(z.x, z.y);
  }

  // The pair's event counts differ by more than 2^log2 times (never when log2 is 0).
  static bool sizes_differ(std::uint32_t track_events, std::uint32_t measurement_events, std::uint8_t log2) {
    if (log2 == 0) return false;
    const std::uint32_t hi = track_events > measurement_events ? track_events : measurement_events;
    const std::uint32_t lo = track_events > measurement_events ? measurement_events : track_events;
    return hi > (lo << log2);
  }

  // gate2, or gate_spread2 times the spread squared when that is larger (both 2 kPosFrac
  // fraction bits).
  static std::uint64_t gate_of(const Measurement& z, const Config& cfg) {
    constexpr int kShift = 2 * S::kPosFrac - 2 * kSpreadFrac;
    const std::uint64_t product = std::uint64_t{cfg.gate_spread2} * z.spread2;
    std::uint64_t spread_gate = product;
    if constexpr (kShift >= 0) spread_gate = product << kShift;
    else spread_gate = product >> -kShift;
    return spread_gate > cfg.gate2 ? spread_gate : cfg.gate2;
  }

  // The lowest free slot; with none, the unmatched slot measured longest ago (evict_stale,
  // ties to the lower slot); -1 when neither.
  int slot_for_new_track(const Config& cfg, const bool slot_matched[S::kTracksMax]) {
    int free = -1;
    for (int s = S::kTracksMax - 1; s >= 0; --s) {
      if (!slot_[s].valid && s < cfg.max_tracks) free = s;
    }
    if (free >= 0 || !cfg.evict_stale) return free;
    ++trace_.evict_scans;
    int stalest = -1;
    for (int s = 0; s < S::kTracksMax; ++s) {
      if (s >= cfg.max_tracks || slot_matched[s]) continue;
      if (stalest < 0 || static_cast<std::int32_t>(slot_[s].t_last - slot_[stalest].t_last) < 0) stalest = s;
    }
    return stalest;
  }

  template <int Depth>
  static void report(const Slot& t, const Measurement& z, const Config& cfg, Stream<TrackWord, Depth>& updates) {
    if (!t.confirmed && !cfg.report_tentative) return;
    TrackWord w;
    w.t = z.t;
    w.id = t.id;
    w.x = t.ax.pos, w.y = t.ay.pos, w.vx = t.ax.vel, w.vy = t.ay.vel;
    w.zx = z.x, w.zy = z.y;
    w.confirmed = t.confirmed;
    w.events = z.events;
    w.x_min = z.x_min, w.y_min = z.y_min, w.x_max = z.x_max, w.y_max = z.y_max;
    w.var_x = t.ax.p00, w.var_y = t.ay.p00;
    updates.write(w);
  }

  static std::uint64_t distance2(const Slot& t, const Measurement& z) {
    const std::int32_t dt_raw = static_cast<std::int32_t>(z.t - t.t_last);
    const std::uint32_t dt = dt_raw > 0 ? static_cast<std::uint32_t>(dt_raw) : 0;
    constexpr std::int64_t kLimit = std::int64_t{1} << S::kGateDistLog2;
    const std::int64_t dx = clamp_sym(std::int64_t{z.x} - Axis::predicted(t.ax, dt), kLimit);
    const std::int64_t dy = clamp_sym(std::int64_t{z.y} - Axis::predicted(t.ay, dt), kLimit);
    return static_cast<std::uint64_t>(dx * dx + dy * dy);
  }

  static std::uint64_t last_distance2(const Slot& t, const Measurement& z) {
    const std::int64_t dx = std::int64_t{z.x} - t.zx, dy = std::int64_t{z.y} - t.zy;
    return static_cast<std::uint64_t>(dx * dx + dy * dy);
  }

  Slot slot_[S::kTracksMax];
  std::int32_t next_id_ = 0;
  std::int64_t unassigned_ = 0;
  TrackerTrace trace_;
};

}  // namespace evms::hls
