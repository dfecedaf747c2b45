// Two objects that one cluster holds where their tracks meet, told apart by their motions.
//
// An edge moving at velocity v fires so that the slope of the time surface under its events
// (time_surface_slopes.h) satisfies slope · v = 1, so a velocity explains an event by
// |slope · v - 1| (capped at 1), and the velocity that explains a set of events best is the
// least-squares solution of slope · v = 1 over them.
//
// A cluster is looked at when it holds at least 200 events, at least a third of them with a
// slope, and its bounding box grown by 2 px holds two or more of the positions the caller passes
// (the tracker's predictions of its confirmed tracks matched in the packet before, at the
// packet's middle event): the only place where two objects can share a cluster and be tracked
// apart. Its events are cut in two across the principal axis of their pixels, then each event
// goes to the part whose velocity explains it better, plus 0.5 times its Chebyshev distance from
// the part's centre over the events' mean Chebyshev distance from the cluster's centre (an event
// without a slope counts 0.5 for the velocity); up to 8 such rounds, each part's velocity and
// centre fitted anew, until no event changes part, and the round whose parts the velocities
// explain with the least summed residual is kept. The cluster splits when the two velocities
// explain its sloped events with at most motion_split times the residual of one velocity fitted
// to them all (the share in the core's steps of 1/256: types/params.h, motion_split_gain), the
// velocities differ by at least 0.3 times the faster one's speed, and each part holds a fifth of
// the sloped events and 64 events. The second part becomes a new cluster, appended to the modes;
// each part takes the mean of its events' features as its mode.
//
// Why: a fast object crossing a slow one joins it in one cluster for as long as their outlines
// touch, and no rule on positions alone (polarity_split.h, the links' distance) can part them.
// docs/sweep.md ("Splitting a cluster by its events' motion") has the measurements. The distances
// are Chebyshev and the axis is found without an angle so that the fixed-point core
// (hls/cluster/motion_split.h) needs no square root but one and no trigonometry; the rounds
// need not settle, and keeping the best of them keeps the core's parts golden's where a rounding
// moves a later round.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "golden/cluster/features.h"
#include "golden/cluster/time_surface_slopes.h"
#include "types/event.h"
#include "types/params.h"

namespace evms::golden {

class MotionSplit {
 public:
  MotionSplit(const Params& params, SensorSize sensor);

  // `cluster_of`: per event, a cluster in 0 .. modes.size() - 1, or -1. `meeting_points`: the
  // positions (px) of which a cluster's box must hold two. Each split appends a cluster to
  // `modes` and relabels the events of its second part.
  void split(std::span<const Event> events, const FeatureMatrix& features, std::span<const Eigen::Vector2d> meeting_points,
             std::vector<Eigen::Vector4d>& modes, std::vector<int>& cluster_of);

 private:
  // The part (0 or 1) of each of `members`, or false when the cluster stays whole.
  bool parts_of(std::span<const Event> events, std::span<const int> members, std::vector<int>& part) const;

  std::uint32_t gain_;  // motion_split_gain (types/params.h): the share to kMotionGainFrac fraction bits
  int width_, height_;
  std::optional<TimeSurfaceSlopes> slopes_;  // none with the split off
  std::vector<Eigen::Vector2d> slope_;  // per event of the clusters looked at
  std::vector<char> has_slope_;
};

}  // namespace evms::golden
