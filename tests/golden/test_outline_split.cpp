// Parting a cluster where two tracks meet by where each track's own events fell
// (golden/track/outline_split.h): straight edges swept at known velocities, remembered as they
// were a few milliseconds before.
#include <gtest/gtest.h>

#include <algorithm>

#include "golden/cluster/features.h"
#include "golden/track/outline_split.h"
#include "tests/support/scenes.h"

namespace evms::golden {
namespace {

using test::kSensor;
using test::swept_edge;

constexpr TimeUs kHistoryUs = 30000;
constexpr int kRow0 = 20, kRow1 = 80;  // the rows the edges sweep

Params outline_splitting(TimeUs history_us = kHistoryUs) {
  Params p;
  p.outline_split_us = static_cast<double>(history_us);
  return p;
}

// The sweep an edge made just before it swept [x0, x1): over the pixels [x0 - (x1 - x0), x0), up to
// one pixel's time before its first event in the packet.
std::vector<Event> sweep_before(int x0, int x1, double vx) {
  const int width = x1 - x0;
  std::vector<Event> was = swept_edge(x0 - width, x0, kRow0, kRow1, vx, 0);
  for (Event& e : was) e.t -= static_cast<TimeUs>(std::lround(width / vx * 1e6));
  return was;
}

struct Edge {
  int x0, x1;
  double vx;
  std::int32_t track;
};

struct Parted {
  test::SweptPacket packet;
  PacketClusters clusters;
};

// Two edges sweeping right over rows kRow0 to kRow1 - 1 in one cluster, each one's track predicted in its box;
// each edge's sweep just before remembered under its track when `remember` is set.
Parted split_edges(const Edge& a, const Edge& b, bool remember, const Params& p = outline_splitting()) {
  Parted s{test::swept_packet({swept_edge(a.x0, a.x1, kRow0, kRow1, a.vx, 0), swept_edge(b.x0, b.x1, kRow0, kRow1, b.vx, 0)}), {}};
  OutlineSplit split(p, kSensor);
  if (remember) {
    for (const Edge& edge : {a, b}) {
      const std::vector<Event> was = sweep_before(edge.x0, edge.x1, edge.vx);
      split.remember(was, std::vector<std::int32_t>(was.size(), edge.track));
    }
  }
  s.clusters.cluster_of.assign(s.packet.events.size(), 0);
  s.clusters.count = 1;
  s.clusters.modes = {Eigen::Vector4d::Zero()};
  s.clusters.spreads = {0.0};
  const std::vector<TrackPrediction> tracks = {{{(a.x0 + a.x1) / 2.0, (kRow0 + kRow1) / 2.0}, {a.vx, 0}, true, a.track},
                                               {{(b.x0 + b.x1) / 2.0, (kRow0 + kRow1) / 2.0}, {b.vx, 0}, true, b.track}};
  split.split(s.packet.events, packet_features(s.packet.events, kSensor, p), tracks, s.clusters);
  return s;
}

// A fast edge beside a slow one (the edges of two shapes that cross, where they touch).
const Edge kFast{40, 48, 1000, 7}, kSlow{50, 54, 200, 9};

TEST(OutlineSplit, EachTrackTakesTheEventsItsOwnOutlineExplains) {
  const Parted s = split_edges(kFast, kSlow, true);
  ASSERT_EQ(s.clusters.count, 2);
  ASSERT_EQ(s.clusters.modes.size(), 2u);
  ASSERT_EQ(s.clusters.spreads.size(), 2u);
  // Each cluster holds one edge's events, the first track's edge keeping the cluster's index.
  for (size_t i = 0; i < s.clusters.cluster_of.size(); ++i) EXPECT_EQ(s.clusters.cluster_of[i], s.packet.object[i]) << "event " << i;
  // Each part's mode is the mean of its events' features: the fast edge's pixels span x 40-47.
  EXPECT_NEAR(s.clusters.modes[0](0), 43.5 / 240, 1e-12);
  EXPECT_NEAR(s.clusters.modes[1](0), 51.5 / 240, 1e-12);
  EXPECT_GT(s.clusters.spreads[1], 0);
}

TEST(OutlineSplit, AClusterStaysWholeWithoutRememberedOutlines) {
  const Parted s = split_edges(kFast, kSlow, false);
  EXPECT_EQ(s.clusters.count, 1);
  for (int c : s.clusters.cluster_of) EXPECT_EQ(c, 0);
}

TEST(OutlineSplit, OutlinesOlderThanTheHistoryAreForgotten) {
  const Parted s = split_edges(kFast, kSlow, true, outline_splitting(500));
  EXPECT_EQ(s.clusters.count, 1);
}

TEST(OutlineSplit, TwoTracksThatMoveAlikeKeepOneCluster) {
  // Two tracks on one outline, each remembering its half: their events' motions do not differ,
  // so the cluster stays whole (a fragmented object is not held apart).
  const Parted s = split_edges({40, 48, 1000, 7}, {50, 54, 1000, 9}, true);
  EXPECT_EQ(s.clusters.count, 1);
}

TEST(OutlineSplit, NoClusterIsSplitPastTheClusterLimit) {
  Params p = outline_splitting();
  p.max_clusters = 1;
  const Parted s = split_edges(kFast, kSlow, true, p);
  EXPECT_EQ(s.clusters.count, 1);
}

}  // namespace
}  // namespace evms::golden
