// Two objects that one cluster holds, told from the two edges of one object by their polarities.
//
// A cluster's parts are the 8-connected sets of the cells its events occupy, cells of
// split_cell bandwidths a side on the (x, y) features (at least two pixels). A part is large
// when it holds at least split_share of the cluster's events and at least split_min_events (and
// min_cluster_size): a part of a few events may look balanced by chance, and a sparse outline,
// such as a shape spinning slowly near the centre of a rotation, falls into such parts. A large
// part is balanced when it holds both polarities (|ON - OFF| below split_balance times its
// events). The large parts fall into groups: each balanced part is a group of its own, and
// every large part that is not balanced is one group together (with split_partial false, a
// cluster with any such part keeps one group). A cluster of two or more groups becomes one
// cluster per group, numbered in the order of their first large parts; each small part joins
// the group of the large part whose centre is nearest (centres in 1/16 px, rounded; ties: the
// part whose first event came first). With split_concentric, before that, two groups stay one
// group when each one's centre (the mean of its large parts' events) lies in the middle half of
// the other's bounding box (the box of its large parts' events), along x and along y: each later
// group joins the first earlier group it is concentric with, and the groups are numbered again in
// the order of their first large parts. The cells and thresholds are integers (SplitRule,
// types/params.h), so the fixed-point core (hls/cluster/polarity_split.h) finds the same parts.
//
// Why polarity: an object moving over its background fires its leading edge in one polarity and
// its trailing edge in the other, and its edges parallel to the motion do not fire, so a
// translating outline falls apart into two parts of one polarity each, which the warm ball and
// the links rightly keep as one cluster. Two objects that the warm ball holds together after
// they touched are two parts of both polarities each. A warm ball that holds a translating
// outline's two edges can hold a small object beside them too: the object, balanced, leaves, and
// the edges stay together. Concentric groups: a ring moving across its width fires each of its
// two circles as a part (or the outer as two arcs of one polarity each, which form a group, and
// the inner, whose sides fire too, as a balanced part), and those parts share one centre, which
// two objects side by side do not. docs/sweep.md ("Splitting two objects by their polarities",
// "A ring's two circles about one centre") has the measurements.
#pragma once

#include <limits>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "golden/cluster/features.h"
#include "golden/cluster/union_find.h"
#include "types/event.h"
#include "types/params.h"

namespace evms::golden {

class PolaritySplit {
 public:
  PolaritySplit(const Params& params, SensorSize sensor);

  // `cluster_of`: per event, a cluster in 0 .. modes.size() - 1, or -1. Each cluster split gives
  // its parts' events new clusters, appended to `modes`; every part of a split cluster takes the
  // mean of its events' features as its mode.
  void split(std::span<const Event> events, const FeatureMatrix& features, std::vector<Eigen::Vector4d>& modes,
             std::vector<int>& cluster_of);

 private:
  // The parts of one cluster's events `members`: afterwards part_of_[i] is the smallest member of
  // i's part, for each member i.
  void find_parts(std::span<const Event> events, std::span<const int> members);
  // Joins concentric groups (split_concentric) in group_of_large_; returns the groups left.
  int join_concentric_groups(int groups);

  SplitRule rule_;
  int cells_x_ = 0, cells_y_ = 0;
  std::vector<int> first_in_cell_;  // per cell: the first member of the current cluster in it, or -1
  std::vector<int> touched_;        // the cells the current cluster occupies
  UnionFind sets_;                  // over the events: the current cluster's parts
  std::vector<int> part_of_;        // per event of the current cluster: its part's smallest member
  struct Part {
    int events = 0, on = 0;
    std::int64_t x = 0, y = 0;  // sums of the events' pixel coordinates
    int x_min = std::numeric_limits<int>::max(), y_min = std::numeric_limits<int>::max(), x_max = -1, y_max = -1;
    int large = -1;  // the large part its events go to: its own index among them, or the nearest one's
  };
  std::vector<Part> part_;          // per event: the sums of the part it is the smallest member of
  std::vector<int> start_, members_, fill_;  // each cluster's events, in event order
  std::vector<int> large_;          // the current cluster's large parts (their smallest members)
  std::vector<int> group_of_large_;  // per large part: its group, the cluster it becomes
};

}  // namespace evms::golden
