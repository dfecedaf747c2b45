// The evms core: filter -> packets -> features -> hybrid mean shift -> mode merging (or seeded
// climbs -> links -> polarity split -> split by motion where tracks meet -> edge join) ->
// centroids (a fast track's by its motion) ->
// tracking -> labels,
// bit-accurate, for one Shape. rtl/ implements all of it, and sim/ checks every output word
// against it.
//
// Word by word: an event passes the background-activity filter (or is noise), joins the
// pending queue (every event, in input order) and, when kept, the open packet. A packet closes
// when it holds packet_size events, when the next kept event is more than packet_max_span_us
// newer than its first, when the pending queue is full (a hardware bound golden does not
// have: kPendingDepth = 4 N), or on a flush word. Closing clusters and tracks the packet and
// then releases every pending event with its label; in a build with HasRescue, an event the
// filter dropped takes the label of the nearest labelled event of the packet within rescue_reach
// px (golden/pipeline.cpp, rescue_dropped). A noise event that arrives while no packet is open
// leaves at once.
#pragma once

#include <cstdint>

#include "hls/cluster/centroid.h"
#include "hls/cluster/edge_join.h"
#include "hls/cluster/motion_split.h"
#include "hls/cluster/features.h"
#include "hls/cluster/link.h"
#include "hls/cluster/mean_shift.h"
#include "hls/cluster/merge.h"
#include "hls/cluster/polarity_split.h"
#include "hls/cluster/seeded_climbs.h"
#include "hls/cluster/sparse_sets.h"
#include "hls/cluster/warm_seeds.h"
#include "hls/core/config.h"
#include "hls/core/shape.h"
#include "hls/core/words.h"
#include "hls/filter/ba_filter.h"
#include "hls/fixed/stream.h"
#include "hls/track/motion_measure.h"
#include "hls/track/tracker.h"

namespace evms::hls {

// What closing one packet did: the inputs of the cycle model (hls/core/schedule.h).
struct PacketTrace {
  int events = 0;      // released: every pending event, kept or not
  int kept = 0;        // in the packet (0: only noise was released)
  int sweeps = 0;       // Gaussian sweeps, or seeded climb steps
  int clusters = 0;
  int splits_left_whole = 0;  // clusters the polarity split left whole: no room in the mode table
  int edges_joined = 0;       // pairs of one-polarity modes the edge join made one
  MergeTrace merge;
  ClimbTrace climbs;
  TrackerTrace track;
};

// Sees every word (with the filter's answer; false for a flush word) and every packet closing;
// the core's results do not depend on it. The default sees nothing and costs nothing.
struct NoObserver {
  void on_word(const EventWord&, bool /*kept*/) {}
  void on_close(const PacketTrace&) {}
};

template <class S, class Observer = NoObserver>
class Core {
 public:
  static constexpr int kLabelDepth = S::kPendingDepth + 1;
  using LabelStream = Stream<LabelWord, kLabelDepth>;
  using TrackStream = Stream<TrackWord, S::kClustersMax + 1>;
  using PacketStream = Stream<PacketWord, 2>;

  void reset(const Config& cfg) {
    cfg_ = cfg;
    filter_.reset();
    tracker_.reset();
    links_.reset();
    split_.reset();
    if (S::kHasMotionMeasure) motion_.reset(), motion_split_.reset();
    warm_.count = 0;
    n_ = 0;
    pending_n_ = 0;
    if (S::kHasRescue) {
    unlabel:
      for (int i = 0; i < kRescueMapSize; ++i) label_at_pixel_[i] = -1;
    }
  }

  using ClimbsStream = Stream<ClimbsFrame<S>, 2>;

  // Consumes one input word. The output streams must have room for what a packet releases
  // (the host drains them after every word; the RTL holds them in FIFOs of the same depth).
  void process(const EventWord& in, LabelStream& labels, TrackStream& tracks, PacketStream& packets) {
    process_word(in, !in.flush && filter_.accept(in, cfg_), labels, tracks, packets, nullptr, nullptr);
  }

  // The same, with the filter's answer for `in` decided elsewhere: by a cut board
  // (rtl/core/evms_climbs_core.sv), whose packets the host climbs itself with this where it holds
  // no frame of the board's climbs. Given the verdicts of this core's filter, the words out are
  // process()'s.
  void process_decided(const EventWord& in, bool kept, LabelStream& labels, TrackStream& tracks, PacketStream& packets) {
    process_word(in, kept, labels, tracks, packets, nullptr, nullptr);
  }

  // The core cut after its climbs, as a board whose core stops there runs it
  // (rtl/core/evms_climbs_core.sv): process(), which also writes each packet's climbs to
  // `frames` (climbs_needed(in, kept) of them for this word).
  void process_to_climbs(const EventWord& in, LabelStream& labels, TrackStream& tracks, PacketStream& packets, ClimbsStream& frames) {
    process_word(in, !in.flush && filter_.accept(in, cfg_), labels, tracks, packets, nullptr, &frames);
  }

  // process_decided() with each packet's climbs taken from `frames` (climbs_needed(in, kept) of
  // them) instead of run here: how the host completes a board whose core stops at the climbs.
  // Given that board's verdicts and frames, the words out are process()'s when warm_start is
  // off (the board's climbs have no warm seeds).
  void process_climbed(const EventWord& in, bool kept, ClimbsStream& frames, LabelStream& labels, TrackStream& tracks, PacketStream& packets) {
    process_word(in, kept, labels, tracks, packets, &frames, nullptr);
  }

  // How many packets with events the word closes (0-2; each takes one climbs frame).
  int climbs_needed(const EventWord& in, bool kept) const {
    const WordPlan plan = plan_word(in, kept);
    return (plan.close_before && n_ > 0 ? 1 : 0) + (plan.close_after && (plan.into_packet || n_ > 0) ? 1 : 0);
  }

  const Tracker<S>& tracker() const { return tracker_; }
  Observer& observer() { return observer_; }

 private:
  // What a word does: close the open packet before it (a flush word; a kept event beyond the
  // packet's span), join the pending queue and the packet, close the packet after it.
  struct WordPlan {
    bool close_before, pending, into_packet, close_after;
  };
  WordPlan plan_word(const EventWord& in, bool kept) const {
    if (in.flush) return {true, false, false, false};
    if (!kept) return {false, true, false, n_ == 0 || pending_n_ + 1 == S::kPendingDepth};
    const bool span = n_ > 0 && cfg_.packet_max_span_us != 0 && in.t - packet_.t[0] > cfg_.packet_max_span_us;
    const int n_after = (span ? 0 : n_) + 1, pending_after = (span ? 0 : pending_n_) + 1;
    return {span, true, true, n_after >= cfg_.packet_size || n_after >= S::kPacketMax || pending_after == S::kPendingDepth};
  }

  void process_word(const EventWord& in, bool kept, LabelStream& labels, TrackStream& tracks, PacketStream& packets, ClimbsStream* given,
                    ClimbsStream* record) {
    const WordPlan plan = plan_word(in, kept);
    observer_.on_word(in, plan.into_packet);
    if (plan.close_before) close_packet(labels, tracks, packets, given, record);
    if (plan.pending) {
      pending_[pending_n_++] = {in, static_cast<std::int16_t>(plan.into_packet ? n_ : -1)};
    }
    if (plan.into_packet) {
      packet_.x[n_] = in.x, packet_.y[n_] = in.y, packet_.p[n_] = in.p, packet_.t[n_] = in.t;
      ++n_;
    }
    if (plan.close_after) close_packet(labels, tracks, packets, given, record);
  }

  // Clusters and tracks the open packet, by its own climbs or by the next of `given`, and
  // writes its climbs to `record` (when not null).
  void close_packet(LabelStream& labels, TrackStream& tracks, PacketStream& packets, ClimbsStream* given, ClimbsStream* record) {
    std::int32_t label_of[S::kPacketMax];
    PacketTrace trace;
    trace.events = pending_n_;
    trace.kept = n_;
    if (n_ > 0) {
      Features<S> phi;
      std::int8_t cluster_of[S::kPacketMax];
      bool first_on_pixel[S::kPacketMax];  // the seeded path's links set it
      int sweeps = 0, clusters = 0;
      if (cfg_.seeded) {
        climb_features(packet_, n_, cfg_, phi);
        std::int16_t mode_of[S::kPacketMax];
        Modes<S> modes;
        if (given != nullptr) {
          ClimbsFrame<S> frame;
          given->read(frame);
          climbs_.assume(frame, mode_of, modes, trace.climbs);
        } else {
          climbs_.run(phi, n_, cfg_, warm_, mode_of, modes, trace.climbs, false);
        }
        if (record != nullptr) {
          ClimbsFrame<S> frame;
          climbs_.frame(mode_of, n_, modes, trace.climbs, frame);
          record->write(frame);
        }
        // The least density on each mode, unless the links' sets take it: after the climbs, which
        // a board's core cut after them does not test (rtl/core/evms_climbs_core.sv).
        climbs_.drop_sparse_modes(mode_of, n_, cfg_);
        links_.run(packet_, n_, modes.count, cfg_, mode_of, first_on_pixel);
        if (cfg_.min_density != 0 && cfg_.density_after_links) drop_sparse_sets(climbs_, links_, n_, modes.count, cfg_, mode_of);
        trace.splits_left_whole = split_.run(packet_, phi, n_, cfg_, mode_of, modes);
        if (S::kHasMotionMeasure && cfg_.motion_split_gain != 0) motion_split_.run(packet_, phi, n_, cfg_, tracker_, mode_of, modes);
        trace.edges_joined = edges_.run(packet_, n_, cfg_, modes.count, mode_of);
        clusters = keep_clusters<S>(mode_of, n_, modes, cfg_, cluster_of, warm_);
        warm_balls<S>(phi, n_, cluster_of, cfg_, warm_);
        sweeps = trace.climbs.steps;
      } else {
        packet_features(packet_, n_, cfg_, phi);
        sweeps = mean_shift(phi, n_, cfg_);
        clusters = merge_modes(phi, n_, cfg_, cluster_of, trace.merge);
      }
      Measurement z[S::kClustersMax];
      centroids(packet_, n_, cluster_of, clusters, z, cfg_.seeded, cfg_.midpoint_min,
                cfg_.seeded && cfg_.pixel_centre && cfg_.link2 != 0 ? first_on_pixel : nullptr,  // the links mark the pixels
                S::kHasPixelTime && cfg_.pixel_time != 0);
      if (S::kHasMotionMeasure && cfg_.motion_speed != 0) motion_.measure(packet_, n_, cluster_of, clusters, tracker_, cfg_, z);
      std::int32_t ids[S::kClustersMax];
      tracker_.step(packet_.t[n_ - 1], z, clusters, cfg_, ids, tracks);
      trace.sweeps = sweeps;
      trace.clusters = clusters;
      trace.track = tracker_.last_step();
      for (int i = 0; i < S::kPacketMax; ++i) {
        if (i >= n_) break;
        label_of[i] = cluster_of[i] >= 0 ? ids[cluster_of[i]] : -1;
      }
      packets.write({packet_.t[0], packet_.t[n_ - 1], static_cast<std::uint16_t>(n_), static_cast<std::uint8_t>(clusters),
                     static_cast<std::uint16_t>(sweeps < 0xFFFF ? sweeps : 0xFFFF)});
    }
    observer_.on_close(trace);
    const bool rescue = S::kHasRescue && cfg_.rescue_reach > 0 && n_ > 0;
    if (rescue) {
      // The label of the packet's last labelled event on each pixel.
    label_pixels:
      for (int k = 0; k < S::kPendingDepth; ++k) {
#pragma HLS PIPELINE II = 1
        if (k >= pending_n_) break;
        const Pending& p = pending_[k];
        if (p.index >= 0 && label_of[p.index] >= 0) label_at_pixel_[pixel_of(p.e)] = static_cast<std::int16_t>(label_of[p.index]);
      }
    }
  release:
    for (int k = 0; k < S::kPendingDepth; ++k) {
#pragma HLS PIPELINE II = 1
      if (k >= pending_n_) break;
      const Pending& p = pending_[k];
      const std::int32_t label = p.index >= 0 ? label_of[p.index] : rescue ? nearest_label(p.e) : kLabelNoise;
      labels.write({p.e.t, p.e.x, p.e.y, p.e.p, label});
    }
    if (rescue) {
    unlabel_pixels:
      for (int k = 0; k < S::kPendingDepth; ++k) {
#pragma HLS PIPELINE II = 1
        if (k >= pending_n_) break;
        if (pending_[k].index >= 0) label_at_pixel_[pixel_of(pending_[k].e)] = -1;
      }
    }
    n_ = 0;
    pending_n_ = 0;
  }

  static int pixel_of(const EventWord& e) { return (S::kHasRescue ? e.y * S::kMaxWidth + e.x : 0); }

  // The label nearest to e's pixel within rescue_reach px on label_at_pixel_ (squared distance,
  // ties to the first in row order), or kLabelNoise.
  std::int32_t nearest_label(const EventWord& e) const {
    std::int32_t label = kLabelNoise;
    int nearest = 2 * (S::kRescueMax + 1) * (S::kRescueMax + 1);
    const int reach = cfg_.rescue_reach;
  rows:
    for (int dy = -S::kRescueMax; dy <= S::kRescueMax; ++dy) {
    columns:
      for (int dx = -S::kRescueMax; dx <= S::kRescueMax; ++dx) {
#pragma HLS PIPELINE II = 1
        const int x = e.x + dx, y = e.y + dy;
        if (dx < -reach || dx > reach || dy < -reach || dy > reach) continue;
        if (x < 0 || y < 0 || x >= cfg_.sensor_width || y >= cfg_.sensor_height || dx * dx + dy * dy >= nearest) continue;
        const std::int16_t l = label_at_pixel_[S::kHasRescue ? y * S::kMaxWidth + x : 0];
        if (l >= 0) nearest = dx * dx + dy * dy, label = l;
      }
    }
    return label;
  }

  struct Pending {
    EventWord e;
    std::int16_t index;  // in the packet, or -1 for a filtered event
  };

  Config cfg_;
  BackgroundActivityFilter<S> filter_;
  Tracker<S> tracker_;
  SeededClimbs<S> climbs_;
  ModeLinks<S> links_;
  PolaritySplit<S> split_;
  EdgeJoin<S> edges_;
  MotionMeasure<S> motion_;
  MotionSplit<S> motion_split_;
  Modes<S> warm_;                // the previous packet's cluster modes
  PacketEvents<S> packet_;
  int n_ = 0;
  Pending pending_[S::kPendingDepth];
  int pending_n_ = 0;
  static constexpr int kRescueMapSize = S::kHasRescue ? S::kMaxWidth * S::kMaxHeight : 1;
  std::int16_t label_at_pixel_[kRescueMapSize];  // HasRescue: the packet's labels by pixel, -1 elsewhere
  Observer observer_;
};

}  // namespace evms::hls
