// Two objects that one cluster holds where their tracks meet, parted by where each track's own
// events fell.
//
// Each pixel remembers, for each polarity, the track whose event last fell there and when
// (remember(), after the packet's labels). A cluster of at least 128 events whose bounding box,
// grown by 2 px, holds the predictions of two or more confirmed tracks (at the packet's middle
// event) is looked at. Each of its events goes to the track one of whose remembered pixels of
// the event's polarity, no older than outline_split_us at the cluster's first event and moved on
// by the track's velocity (to that time, to the nearest pixel, and then to the event's), lies
// nearest the event, within 3 px; an event that no remembered pixel reaches goes to
// the track that took the most. The cluster becomes one cluster per track that took at least 64
// events (the events of the others go to the track that took the most) when the parts move
// apart: the velocities fitted to each part's time-surface slopes (golden/cluster/
// time_surface_slopes.h) leave at most 0.8 times the residual of one velocity fitted to all of
// them, and two of those velocities differ by at least 0.3 times the faster one's speed (as in
// golden/cluster/motion_split.h). Each part takes the mean of its events' features as its mode.
//
// Why: where two objects cross, their outlines overlap and touch, and no rule on one packet's
// positions parts them (the polarity split, the links). Cut by the nearest predicted centre
// instead, a large outline loses its far edge to the shape it passes over. Each track's own
// outline over the last tens of milliseconds, moved with it, says which edge is whose. The test
// on the parts' motions keeps two tracks on one object (a fragmented outline, whose parts move
// alike) from holding its halves apart for good. docs/sweep.md ("Parting a merge by the tracks'
// outlines") has the measurements. Golden only: the fixed-point core refuses it
// (host/backend/core_config.h).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "golden/cluster/clustering.h"
#include "golden/cluster/features.h"
#include "golden/cluster/time_surface_slopes.h"
#include "golden/track/tracker.h"
#include "types/event.h"
#include "types/params.h"

namespace evms::golden {

class OutlineSplit {
 public:
  OutlineSplit(const Params& params, SensorSize sensor);

  // Splits the clusters of `clusters` (of `events`, whose features are `features`) where two or
  // more of `tracks` meet, appending a cluster, its mode and its spread for each further part.
  void split(std::span<const Event> events, const FeatureMatrix& features, std::span<const TrackPrediction> tracks,
             PacketClusters& clusters);

  // Records where the packet's events fell and which track each went to (`labels`, per event: a
  // track ID, or negative for none).
  void remember(std::span<const Event> events, std::span<const std::int32_t> labels);

 private:
  static constexpr int kLeastClusterEvents = 128;
  static constexpr int kBoxMarginPx = 2;
  static constexpr int kMeetingTracks = 2;
  static constexpr double kReachPx = 3;        // an event and a remembered pixel, moved on, this near are one outline
  static constexpr int kMostSearchPx = 16;     // how far outside a cluster's box its tracks' remembered pixels are looked for
  static constexpr int kLeastPartEvents = 64;
  static constexpr double kMotionShare = 0.8;  // of one velocity's residual, which the parts' velocities may leave
  static constexpr double kLeastVelocityDifference = 0.3;  // between two parts' velocities, times the faster one's speed

  struct Remembered {
    TimeUs t = 0;
    std::int32_t track = -1;
  };
  struct Box {
    int x0, y0, x1, y1;  // inclusive, px
  };
  // The tracks of `near` (indices into the caller's tracks) each of `members` (whose pixels span
  // `box`) goes to, by index into `near`, or false when the cluster stays whole.
  bool parts_of(std::span<const Event> events, std::span<const int> members, const Box& box, std::span<const TrackPrediction* const> near,
                std::vector<int>& part);
  // Whether the parts move apart: their velocities, one a part, explain the sloped events with at
  // most kMotionShare of the residual of one velocity, and two of them differ by at least
  // kLeastVelocityDifference times the faster one's speed.
  bool parts_move_apart(std::span<const Event> events, std::span<const int> members, std::span<const int> part, int parts);
  Remembered& at(int polarity, int x, int y) {
    return memory_[(static_cast<size_t>(polarity != 0) * static_cast<size_t>(height_) + static_cast<size_t>(y)) * static_cast<size_t>(width_) +
                   static_cast<size_t>(x)];
  }

  TimeUs history_us_;
  int width_, height_;
  std::vector<Remembered> memory_;  // per polarity and pixel
  TimeSurfaceSlopes slopes_;
  bool slopes_added_ = false;  // this packet's events are in slopes_
  std::vector<Eigen::Vector2d> slope_;  // per event of the cluster looked at
  std::vector<std::uint8_t> moved_on_;  // parts_of's maps of the near tracks' remembered pixels, moved on
  int max_clusters_;
};

}  // namespace evms::golden
