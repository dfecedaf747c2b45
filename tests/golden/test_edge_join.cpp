// Joining the leading and trailing edges of one outline (golden/cluster/edge_join.h): each case a
// packet of a few one-polarity bars, small enough to work out by hand, on a 240x180 sensor whose
// default reach is 5 h = 5 x 0.04 x 240 = 48 px.
#include <gtest/gtest.h>

#include <vector>

#include "golden/cluster/edge_join.h"
#include "tests/support/scenes.h"

namespace evms::golden {
namespace {

using test::kSensor;  // 240x180

struct Packet {
  std::vector<Event> events;
  std::vector<int> cluster_of;
  std::vector<size_t> first;  // each bar's first event
};

// A vertical bar of `n` events at column x (rows 60 to 99), in a cluster of its own; the first
// `on` of its events are ON.
void bar(Packet& k, int x, int n, int on) {
  k.first.push_back(k.events.size());
  const int cluster = static_cast<int>(k.first.size()) - 1;
  for (int i = 0; i < n; ++i) {
    k.events.push_back({0, static_cast<std::uint16_t>(x), static_cast<std::uint16_t>(60 + i % 40), static_cast<std::uint8_t>(i < on)});
    k.cluster_of.push_back(cluster);
  }
}

// The cluster each bar's events end in (all of a bar's events end in the same one).
std::vector<int> joined(Packet k, const Params& p = Params{}) {
  join_edges(k.events, edge_rule(p, kSensor), static_cast<int>(k.first.size()), k.cluster_of);
  std::vector<int> of_bar;
  for (size_t b = 0; b < k.first.size(); ++b) {
    const size_t end = b + 1 < k.first.size() ? k.first[b + 1] : k.events.size();
    for (size_t j = k.first[b]; j < end; ++j) EXPECT_EQ(k.cluster_of[j], k.cluster_of[k.first[b]]) << "bar " << b;
    of_bar.push_back(k.cluster_of[k.first[b]]);
  }
  return of_bar;
}

TEST(EdgeJoin, AnOnEdgeAndAnOffEdgeWithinReachBecomeTheEarlierCluster) {
  Packet k;
  bar(k, 60, 40, 40), bar(k, 100, 40, 0);
  EXPECT_EQ(joined(k), (std::vector<int>{0, 0}));
  Params off;
  off.edge_join = 0;
  EXPECT_EQ(joined(k, off), (std::vector<int>{0, 1})) << "--edge-join 0";
}

TEST(EdgeJoin, EdgesOfOnePolarityBeyondReachOrOfDifferentSizesStayApart) {
  Packet same;
  bar(same, 60, 40, 40), bar(same, 100, 40, 40);
  EXPECT_EQ(joined(same), (std::vector<int>{0, 1})) << "both ON";
  Packet far;
  bar(far, 60, 40, 40), bar(far, 109, 40, 0);  // 49 px apart, beyond 48
  EXPECT_EQ(joined(far), (std::vector<int>{0, 1}));
  Packet reach;
  bar(reach, 60, 40, 40), bar(reach, 108, 40, 0);  // 48 px: within
  EXPECT_EQ(joined(reach), (std::vector<int>{0, 0}));
  Packet sizes;
  bar(sizes, 60, 40, 40), bar(sizes, 100, 161, 0);  // more than four times the other's events
  EXPECT_EQ(joined(sizes), (std::vector<int>{0, 1}));
  Packet four;
  bar(four, 60, 40, 40), bar(four, 100, 160, 0);  // four times: joined
  EXPECT_EQ(joined(four), (std::vector<int>{0, 0}));
}

TEST(EdgeJoin, OnlyClustersMostlyOfOnePolarityAndLargeEnoughAreLookedAt) {
  // edge_balance 0.5: ON - OFF at least half the events, 30 of 40 ON.
  Packet mostly;
  bar(mostly, 60, 40, 30), bar(mostly, 100, 40, 10);
  EXPECT_EQ(joined(mostly), (std::vector<int>{0, 0}));
  Packet mixed;
  bar(mixed, 60, 40, 29), bar(mixed, 100, 40, 0);
  EXPECT_EQ(joined(mixed), (std::vector<int>{0, 1})) << "29 of 40 ON holds both polarities";
  Packet small;
  bar(small, 60, 15, 15), bar(small, 100, 40, 0);
  EXPECT_EQ(joined(small), (std::vector<int>{0, 1})) << "15 events, below edge_min_events";
}

TEST(EdgeJoin, EachClusterJoinsItsNearestAndOnlyWhenThatOneChoosesItToo) {
  Packet k;
  // ON at 60; OFF at 90 and at 100; ON at 125. The OFF at 90 and the ON at 60 are each other's
  // nearest (30 px); the OFF at 100 is nearest to the ON at 125 (25 px), whose nearest it is.
  bar(k, 60, 40, 40), bar(k, 90, 40, 0), bar(k, 100, 40, 0), bar(k, 125, 40, 40);
  EXPECT_EQ(joined(k), (std::vector<int>{0, 0, 2, 2}));
  Packet lonely;
  // The OFF at 100's nearest ON is at 60 (40 px), whose nearest OFF is at 90: no pair for it.
  bar(lonely, 60, 40, 40), bar(lonely, 90, 40, 0), bar(lonely, 100, 40, 0);
  EXPECT_EQ(joined(lonely), (std::vector<int>{0, 0, 2}));
}

TEST(EdgeJoin, OfTwoPartnersAtTheSameDistanceTheLowerClusterIsTaken) {
  Packet k;
  bar(k, 100, 40, 40), bar(k, 70, 40, 0), bar(k, 130, 40, 0);
  EXPECT_EQ(joined(k), (std::vector<int>{0, 0, 2}));
}

}  // namespace
}  // namespace evms::golden
