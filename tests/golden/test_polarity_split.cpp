// Splitting a cluster into the objects it holds by their polarities (golden/cluster/polarity_split.h):
// each case a packet small enough to work out by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "golden/cluster/clustering.h"
#include "golden/cluster/polarity_split.h"
#include "tests/support/scenes.h"

namespace evms::golden {
namespace {

using test::kSensor;
using test::concat;

Params splitting() {
  Params p;
  p.split_balance = 0.3;  // cells of 0.4 h = 3.84 x 2.88 px on this sensor
  return p;
}

// A filled square of side `side` px at (x0, y0), its pixels' polarity from `polarity(x, y)`.
template <class Polarity>
std::vector<Event> square(int x0, int y0, int side, Polarity polarity) {
  std::vector<Event> e;
  for (int y = y0; y < y0 + side; ++y) {
    for (int x = x0; x < x0 + side; ++x) e.push_back({0, static_cast<std::uint16_t>(x), static_cast<std::uint16_t>(y), polarity(x, y)});
  }
  return e;
}
const auto kChecker = [](int x, int y) { return static_cast<std::uint8_t>((x + y) % 2); };  // both polarities, evenly
const auto kOn = [](int, int) { return std::uint8_t{1}; };
const auto kOff = [](int, int) { return std::uint8_t{0}; };

struct Split {
  std::vector<int> cluster_of;
  std::vector<Eigen::Vector4d> modes;
};

// Every event in cluster 0 of one mode, then split.
Split split_one_cluster(const std::vector<Event>& events, const Params& p) {
  const FeatureMatrix features = packet_features(events, kSensor, p);
  Split s{std::vector<int>(events.size(), 0), {Eigen::Vector4d::Zero()}};
  PolaritySplit(p, kSensor).split(events, features, s.modes, s.cluster_of);
  return s;
}

TEST(PolaritySplit, TwoObjectsOfBothPolaritiesApartBecomeTwoClusters) {
  const auto a = square(20, 20, 10, kChecker), b = square(100, 60, 10, kChecker);
  const Split s = split_one_cluster(concat(a, b), splitting());
  ASSERT_EQ(s.modes.size(), 2u);
  for (size_t i = 0; i < a.size(); ++i) EXPECT_EQ(s.cluster_of[i], 0);
  for (size_t i = a.size(); i < s.cluster_of.size(); ++i) EXPECT_EQ(s.cluster_of[i], 1);
  // Each part's mode is the mean of its events' features: the squares' centres, 24.5 and 104.5 px.
  EXPECT_NEAR(s.modes[0](0), 24.5 / 240, 1e-12);
  EXPECT_NEAR(s.modes[1](0), 104.5 / 240, 1e-12);
  EXPECT_NEAR(s.modes[1](1), 64.5 / 180, 1e-12);
}

TEST(PolaritySplit, TwoEdgesOfOnePolarityEachStayOneCluster) {
  // A square outline translating along x: its leading edge fires ON, its trailing edge OFF.
  std::vector<Event> edges;
  for (int y = 40; y < 70; ++y) {
    for (int x : {60, 61}) edges.push_back({0, static_cast<std::uint16_t>(x), static_cast<std::uint16_t>(y), 1});
    for (int x : {90, 91}) edges.push_back({0, static_cast<std::uint16_t>(x), static_cast<std::uint16_t>(y), 0});
  }
  const Split s = split_one_cluster(edges, splitting());
  EXPECT_EQ(s.modes.size(), 1u);
  EXPECT_EQ(std::set<int>(s.cluster_of.begin(), s.cluster_of.end()), std::set<int>{0});
}

TEST(PolaritySplit, ABalancedPartLeavesAndTheOnePolarityPartsStayTogether) {
  // A translating outline's two edges (ON at x 60-61, OFF at x 90-91) and, apart from them, a
  // small object firing both polarities: the object leaves, and the edges (72 events each, large)
  // stay one cluster.
  std::vector<Event> edges;
  for (int y = 40; y < 76; ++y) {
    for (int x : {60, 61}) edges.push_back({0, static_cast<std::uint16_t>(x), static_cast<std::uint16_t>(y), 1});
    for (int x : {90, 91}) edges.push_back({0, static_cast<std::uint16_t>(x), static_cast<std::uint16_t>(y), 0});
  }
  const auto object = square(20, 20, 10, kChecker);
  const auto events = concat(object, edges);
  const Split s = split_one_cluster(events, splitting());
  ASSERT_EQ(s.modes.size(), 2u);
  for (size_t i = 0; i < object.size(); ++i) EXPECT_EQ(s.cluster_of[i], 0) << "the first large part's group keeps the cluster";
  for (size_t i = object.size(); i < events.size(); ++i) EXPECT_EQ(s.cluster_of[i], 1) << "both edges, one cluster";
  // The edges' mode is the mean of both edges' features: x 75.5 px.
  EXPECT_NEAR(s.modes[1](0), 75.5 / 240, 1e-12);
  // With --split-partial false, one part of one polarity keeps the cluster whole.
  Params whole = splitting();
  whole.split_partial = false;
  EXPECT_EQ(split_one_cluster(events, whole).modes.size(), 1u);
  EXPECT_EQ(split_one_cluster(concat(object, square(100, 60, 10, kOff)), whole).modes.size(), 1u);
  // Parts of one polarity alone never split, whatever their number.
  EXPECT_EQ(split_one_cluster(concat(square(20, 20, 10, kOn), square(100, 60, 10, kOff)), splitting()).modes.size(), 1u);
}

TEST(PolaritySplit, PartsWithinACellOfEachOtherAreOnePart) {
  // 3 px apart: pixels 29 and 33 fall in neighbouring cells of 3.84 px, so one part.
  const Split near = split_one_cluster(concat(square(20, 20, 10, kChecker), square(33, 20, 10, kChecker)), splitting());
  EXPECT_EQ(near.modes.size(), 1u);
  // 30 px apart: separate parts.
  const Split far = split_one_cluster(concat(square(20, 20, 10, kChecker), square(60, 20, 10, kChecker)), splitting());
  EXPECT_EQ(far.modes.size(), 2u);
}

TEST(PolaritySplit, ASmallPartJoinsTheNearestLargePart) {
  const auto a = square(20, 20, 10, kChecker), b = square(100, 20, 10, kChecker);
  const auto speck = square(85, 22, 2, kChecker);  // 4 events: below a tenth of the cluster
  const Split s = split_one_cluster(concat(concat(a, b), speck), splitting());
  ASSERT_EQ(s.modes.size(), 2u);
  for (size_t i = a.size() + b.size(); i < s.cluster_of.size(); ++i) EXPECT_EQ(s.cluster_of[i], 1) << "nearer b than a";
}

TEST(PolaritySplit, ClustersTooSmallForTwoLargePartsAndOtherClustersAreLeftAlone) {
  Params p = splitting();
  const auto a = square(20, 20, 2, kChecker), b = square(100, 60, 2, kChecker);  // 4 + 4 events, under 2 x split_min_events
  const Split s = split_one_cluster(concat(a, b), p);
  EXPECT_EQ(s.modes.size(), 1u);
  // Noise (-1) stays noise, and a second cluster keeps its number.
  std::vector<Event> events = concat(concat(square(20, 20, 10, kChecker), square(100, 60, 10, kChecker)), square(200, 150, 6, kChecker));
  const FeatureMatrix features = packet_features(events, kSensor, p);
  std::vector<int> cluster_of(events.size(), 0);
  for (size_t i = 200; i < events.size(); ++i) cluster_of[i] = 1;
  cluster_of[199] = -1;
  std::vector<Eigen::Vector4d> modes(2, Eigen::Vector4d::Zero());
  PolaritySplit(p, kSensor).split(events, features, modes, cluster_of);
  ASSERT_EQ(modes.size(), 3u);
  EXPECT_EQ(cluster_of[199], -1);
  for (size_t i = 200; i < events.size(); ++i) EXPECT_EQ(cluster_of[i], 1);
  EXPECT_EQ(cluster_of[150], 2) << "the second part of cluster 0 opens after the clusters there were";
}

TEST(PolaritySplit, PartsOfFewerThanSplitMinEventsDoNotCount) {
  // Two parts of 49 events each, both polarities evenly: under the default 64 events a part, so
  // the cluster stays whole (a sparse outline's parts look balanced by chance); counted from 49.
  const auto events = concat(square(20, 20, 7, kChecker), square(100, 60, 7, kChecker));
  Params p = splitting();
  ASSERT_EQ(p.split_min_events, 64);
  EXPECT_EQ(split_one_cluster(events, p).modes.size(), 1u);
  p.split_min_events = 49;
  EXPECT_EQ(split_one_cluster(events, p).modes.size(), 2u);
  p.split_min_events = 50;
  EXPECT_EQ(split_one_cluster(events, p).modes.size(), 1u);
  // min_cluster_size bounds it from below as well.
  p.split_min_events = 1;
  p.min_cluster_size = 50;
  EXPECT_EQ(split_one_cluster(events, p).modes.size(), 1u);
}

TEST(PolaritySplit, CellsAreNoFinerThanTwoPixels) {
  // At h = 1e-4 the cells would be 0.06 px across on this sensor, 2 * 10^8 of them; cells of
  // two pixels along y (3.6 px along x) are 1.3 * 10^5, a solid square is one part, and two
  // squares apart are two.
  constexpr SensorSize kLarge{1280, 720};
  Params p = splitting();
  p.bandwidth = 1e-4;
  const auto events = concat(square(20, 20, 10, kChecker), square(1000, 600, 10, kChecker));
  const FeatureMatrix features = packet_features(events, kLarge, p);
  std::vector<int> cluster_of(events.size(), 0);
  std::vector<Eigen::Vector4d> modes(1, Eigen::Vector4d::Zero());
  PolaritySplit(p, kLarge).split(events, features, modes, cluster_of);
  EXPECT_EQ(modes.size(), 2u);
  EXPECT_NE(cluster_of.front(), cluster_of.back());
}

// Events on the circle of `radius` px about (cx, cy), one a degree from `from` to `to` degrees,
// their polarity from the degree.
template <class Polarity>
std::vector<Event> arc(double cx, double cy, double radius, int from, int to, Polarity polarity) {
  std::vector<Event> e;
  for (int degree = from; degree <= to; ++degree) {
    const double a = degree * M_PI / 180;
    e.push_back({0, static_cast<std::uint16_t>(std::lround(cx + radius * std::cos(a))),
                 static_cast<std::uint16_t>(std::lround(cy + radius * std::sin(a))), polarity(degree, 0)});
  }
  return e;
}

TEST(PolaritySplit, ARingsTwoCirclesAboutOneCentreStayOneCluster) {
  // A ring moving along y: its outer circle fires as two arcs of one polarity each (its sides,
  // along the motion, fire nothing), its inner circle all round in both polarities. The arcs
  // form one group and the inner circle, balanced, another; their centres coincide.
  const auto inner = arc(100, 90, 15, 0, 359, kChecker);
  const auto events = concat(inner, concat(arc(100, 90, 30, 20, 160, kOff), arc(100, 90, 30, 200, 340, kOn)));
  const Split s = split_one_cluster(events, splitting());
  EXPECT_EQ(s.modes.size(), 1u);
  EXPECT_EQ(std::set<int>(s.cluster_of.begin(), s.cluster_of.end()), std::set<int>{0});
  Params apart = splitting();
  apart.split_concentric = false;
  const Split two = split_one_cluster(events, apart);
  ASSERT_EQ(two.modes.size(), 2u);
  for (size_t i = 0; i < inner.size(); ++i) EXPECT_EQ(two.cluster_of[i], 0) << "the inner circle, balanced";
  for (size_t i = inner.size(); i < events.size(); ++i) EXPECT_EQ(two.cluster_of[i], 1) << "the outer arcs, one group";
  // A balanced circle 22 px off the centre of arcs whose box is 81 px wide (a quarter: 20.25 px) is
  // another object, and splits.
  const auto off_centre = concat(arc(122, 90, 10, 0, 359, kChecker), concat(arc(100, 90, 40, 20, 160, kOff), arc(100, 90, 40, 200, 340, kOn)));
  EXPECT_EQ(split_one_cluster(off_centre, splitting()).modes.size(), 2u);
}

TEST(PolaritySplit, TheClustererSplitsWhatTheWarmBallHeldTogether) {
  // One warm mode between two objects 60 px apart whose ball reaches both: without the split
  // they are one cluster, with it two.
  const auto events = concat(square(60, 80, 10, kChecker), square(120, 80, 10, kChecker));
  Params p;
  p.split_balance = 0;
  const FeatureMatrix features = packet_features(events, kSensor, p);
  const std::vector<Eigen::Vector4d> warm{{94.5 / 240, 84.5 / 180, 0, 0}};
  const std::vector<double> spread{0.06};  // a ball of 2 x 0.06 = 0.12, 29 px: reaches both squares
  const PacketClusters whole = cluster_packet(events, features, p, warm, spread, kSensor);
  EXPECT_EQ(whole.count, 1);
  p.split_balance = 0.3;
  const PacketClusters split = cluster_packet(events, features, p, warm, spread, kSensor);
  ASSERT_EQ(split.count, 2);
  EXPECT_NE(split.cluster_of.front(), split.cluster_of.back());
  EXPECT_EQ(split.modes.size(), 2u);
}

}  // namespace
}  // namespace evms::golden
