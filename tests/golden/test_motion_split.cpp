// Splitting a cluster where two tracks meet by its events' motion (golden/cluster/motion_split.h):
// straight edges swept at known velocities, so each event's slope is known exactly.
#include <gtest/gtest.h>

#include <algorithm>

#include "golden/cluster/motion_split.h"
#include "tests/support/scenes.h"

namespace evms::golden {
namespace {

using test::kSensor;
using test::swept_edge;
using test::swept_packet;
using test::SweptPacket;

Params motion_splitting() {
  Params p;
  p.motion_split = 0.6;
  return p;
}

struct MotionParts {
  std::vector<int> cluster_of;
  std::vector<Eigen::Vector4d> modes;
};

// Every event in cluster 0 of one mode, then split with `meeting_points`.
MotionParts split_by_motion(const std::vector<Event>& events, const std::vector<Eigen::Vector2d>& meeting_points, const Params& p = motion_splitting()) {
  const FeatureMatrix features = packet_features(events, kSensor, p);
  MotionParts s{std::vector<int>(events.size(), 0), {Eigen::Vector4d::Zero()}};
  MotionSplit(p, kSensor).split(events, features, meeting_points, s.modes, s.cluster_of);
  return s;
}

// A fast edge sweeping right beside a slow one, in one cluster, two tracks in its box. (Edges
// at right angles would not do: one velocity explains both, as each edge fixes only the
// velocity across it.)
const SweptPacket kTwoMotions = swept_packet({swept_edge(10, 30, 20, 50, 1000, 0), swept_edge(32, 42, 20, 50, 200, 0)});
const std::vector<Eigen::Vector2d> kTwoTracks = {{20, 35}, {37, 35}};

TEST(MotionSplit, TwoMotionsWhereTwoTracksMeetBecomeTwoClusters) {
  const MotionParts s = split_by_motion(kTwoMotions.events, kTwoTracks);
  ASSERT_EQ(s.modes.size(), 2u);
  // Each cluster holds one edge's events: the two labellings agree up to the clusters' order.
  const int first_edge_cluster = s.cluster_of[static_cast<size_t>(std::find(kTwoMotions.object.begin(), kTwoMotions.object.end(), 0) - kTwoMotions.object.begin())];
  for (size_t i = 0; i < s.cluster_of.size(); ++i) EXPECT_EQ(s.cluster_of[i] == first_edge_cluster, kTwoMotions.object[i] == 0) << "event " << i;
  // Each cluster's mode is the mean of its events' features: the fast edge's pixels span x 10-29.
  EXPECT_NEAR(s.modes[static_cast<size_t>(first_edge_cluster)](0), 19.5 / 240, 1e-12);
  EXPECT_NEAR(s.modes[static_cast<size_t>(1 - first_edge_cluster)](0), 36.5 / 240, 1e-12);
}

TEST(MotionSplit, AClusterStaysWholeWithoutTwoTracksInItsBox) {
  const MotionParts one_track = split_by_motion(kTwoMotions.events, {kTwoTracks[0]});
  EXPECT_EQ(one_track.modes.size(), 1u);
  const MotionParts far_track = split_by_motion(kTwoMotions.events, {kTwoTracks[0], {150, 150}});
  EXPECT_EQ(far_track.modes.size(), 1u);
  EXPECT_TRUE(std::all_of(far_track.cluster_of.begin(), far_track.cluster_of.end(), [](int c) { return c == 0; }));
}

TEST(MotionSplit, OneMotionStaysOneCluster) {
  // Two edges moving together: two tracks in the box, but one velocity explains every event.
  const SweptPacket together = swept_packet({swept_edge(10, 30, 20, 50, 1000, 0), swept_edge(34, 54, 20, 50, 1000, 0)});
  EXPECT_EQ(split_by_motion(together.events, {{20, 35}, {44, 35}}).modes.size(), 1u);
}

TEST(MotionSplit, TheGainBoundsTheSplit) {
  // Noise in the slopes: every other column of the slow edge fires a fifth of a pixel's time
  // late, so two velocities no longer explain the events exactly; a gain near 0 asks that they do.
  SweptPacket rough = kTwoMotions;
  for (size_t i = 0; i < rough.events.size(); ++i) {
    if (rough.object[i] == 1 && rough.events[i].x % 2) rough.events[i].t += 1000;
  }
  Params strict = motion_splitting();
  strict.motion_split = 1e-9;
  EXPECT_EQ(split_by_motion(rough.events, kTwoTracks, strict).modes.size(), 1u);
  EXPECT_EQ(split_by_motion(rough.events, kTwoTracks).modes.size(), 2u);
}

TEST(MotionSplit, ASmallClusterStaysWhole) {
  // Fewer than 200 events: too few slopes to tell two motions from one.
  const SweptPacket small = swept_packet({swept_edge(10, 20, 20, 30, 1000, 0), swept_edge(22, 27, 20, 30, 200, 0)});
  ASSERT_LT(small.events.size(), 200u);
  EXPECT_EQ(split_by_motion(small.events, {{15, 25}, {24, 25}}).modes.size(), 1u);
}

}  // namespace
}  // namespace evms::golden
