// Seeded climbs (golden/cluster/clustering.h): kernels, seeds, labels, links, and the warm
// seeds' own bandwidths, each on a packet small enough to work out by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "golden/cluster/clustering.h"
#include "golden/cluster/kernel.h"
#include "tests/support/scenes.h"

namespace evms::golden {
namespace {

using test::kSensor;
using test::concat;

// A packet of events and its features (x/W, y/H, no polarity or time).
struct Packet {
  std::vector<Event> events;
  FeatureMatrix features;
  Packet(std::vector<Event> e, const Params& p) : events(std::move(e)), features(packet_features(events, kSensor, p)) {}
  PacketClusters cluster(const Params& p, const std::vector<Eigen::Vector4d>& warm = {}, const std::vector<double>& spreads = {}) const {
    return cluster_packet(events, features, p, warm, spreads, kSensor);
  }
};

// Events on a ring of `radius` px around (cx, cy), one every `step` degrees.
std::vector<Event> ring(double cx, double cy, double radius, double step = 6) {
  std::vector<Event> e;
  for (double a = 0; a < 360; a += step) {
    e.push_back({static_cast<TimeUs>(e.size()), static_cast<std::uint16_t>(std::lround(cx + radius * std::cos(a * M_PI / 180))),
                 static_cast<std::uint16_t>(std::lround(cy + radius * std::sin(a * M_PI / 180))), 1});
  }
  return e;
}

Params seeded() {
  Params p;  // the defaults: flat kernel, seeds from events, first-reach labels, links
  p.min_cluster_size = 2;
  p.warm_start = false;
  return p;
}

TEST(Kernel, ProfilesAndReach) {
  EXPECT_DOUBLE_EQ(kernel_profile(Kernel::kGaussian, 2.0), std::exp(-1.0));
  EXPECT_EQ(kernel_profile(Kernel::kFlat, 0.999), 1.0);
  EXPECT_EQ(kernel_profile(Kernel::kFlat, 1.0), 0.0) << "the ball is open";
  EXPECT_DOUBLE_EQ(kernel_profile(Kernel::kEpanechnikov, 0.25), 0.75);
  EXPECT_EQ(kernel_profile(Kernel::kEpanechnikov, 1.5), 0.0);
  EXPECT_FALSE(kernel_is_finite(Kernel::kGaussian));
  EXPECT_TRUE(kernel_is_finite(Kernel::kFlat));
}

TEST(SeededClimbs, TwoBlobsFarApartAreTwoClustersInTheOrderTheyOpened) {
  Params p = seeded();
  p.link_px = 0;
  std::vector<Event> e;
  for (int i = 0; i < 20; ++i) e.push_back({i, static_cast<std::uint16_t>(150 + i % 3), static_cast<std::uint16_t>(40 + i % 4), 1});
  for (int i = 0; i < 20; ++i) e.push_back({20 + i, static_cast<std::uint16_t>(30 + i % 4), static_cast<std::uint16_t>(120 + i % 3), 1});
  const Packet packet(e, p);
  const PacketClusters c = packet.cluster(p);
  ASSERT_EQ(c.count, 2);
  for (int i = 0; i < 20; ++i) EXPECT_EQ(c.cluster_of[static_cast<size_t>(i)], 0);
  for (int i = 20; i < 40; ++i) EXPECT_EQ(c.cluster_of[static_cast<size_t>(i)], 1);
  // The mode of a blob is its centre of mass (a flat ball holds all of it): x is 150, 151 and
  // 152 seven, seven and six times.
  EXPECT_NEAR(c.modes[0].x() * 240, 150.95, 1e-9);
  EXPECT_GT(c.kernel_evaluations, 0);
}

TEST(SeededClimbs, AnEventIsLabelledByTheFirstClimbThatReachedIt) {
  // Two blobs 12 px apart with a bridge event between them, within h (9.6 px at 240) of both
  // blob centres' first climbs: the first climb (from the left blob) reaches it first.
  Params p = seeded();
  p.link_px = 0;
  p.merge_radius = 0.001;
  std::vector<Event> e;
  for (int i = 0; i < 10; ++i) e.push_back({i, 100, static_cast<std::uint16_t>(90 + i % 2), 1});
  for (int i = 0; i < 10; ++i) e.push_back({10 + i, 112, static_cast<std::uint16_t>(90 + i % 2), 1});
  e.push_back({30, 106, 90, 1});
  const Packet packet(e, p);
  const PacketClusters c = packet.cluster(p);
  ASSERT_EQ(c.count, 2);
  EXPECT_EQ(c.cluster_of.back(), c.cluster_of.front());
  p.labelling = Labelling::kNearest;  // equidistant: nearest ties go to the older mode too
  EXPECT_EQ(packet.cluster(p).cluster_of.back(), 0);
}

TEST(SeededClimbs, ARingLargerThanTheKernelSplitsAndTheLinkJoinsIt) {
  // A ring of radius 30 px (a 60 px shape) with h = 9.6 px: many climbs, many modes.
  Params p = seeded();
  const Packet packet(ring(120, 90, 30, 3), p);
  p.link_px = 0;
  const PacketClusters split = packet.cluster(p);
  EXPECT_GT(split.count, 2);
  p.link_px = 6;
  const PacketClusters joined = packet.cluster(p);
  EXPECT_EQ(joined.count, 1) << "neighbouring ring events are 1-2 px apart";
  EXPECT_EQ(std::set<int>(joined.cluster_of.begin(), joined.cluster_of.end()), std::set<int>{0});
}

TEST(SeededClimbs, TheLinkDoesNotJoinShapesAGapApart) {
  Params p = seeded();
  p.link_px = 6;
  // Two rings whose nearest events are 10 px apart.
  const Packet packet(concat(ring(60, 90, 20, 3), ring(110, 90, 20, 3)), p);
  EXPECT_EQ(packet.cluster(p).count, 2);
}

// The link distance holds up to link_px_width and grows with a wider sensor, to twice link_px.
TEST(SeededClimbs, TheLinkDistanceGrowsWithTheSensorWidthUpToTwice) {
  const Params p;
  ASSERT_EQ(p.link_px_width, 320);
  EXPECT_DOUBLE_EQ(link_px_at(p, {128, 128}), p.link_px);
  EXPECT_DOUBLE_EQ(link_px_at(p, {320, 240}), p.link_px);
  EXPECT_DOUBLE_EQ(link_px_at(p, {480, 360}), 1.5 * p.link_px);
  EXPECT_DOUBLE_EQ(link_px_at(p, {640, 480}), 2 * p.link_px);
  EXPECT_DOUBLE_EQ(link_px_at(p, {1280, 720}), 2 * p.link_px) << "no wider sensor was measured";
  Params unscaled = p;
  unscaled.link_px_width = 0;
  EXPECT_DOUBLE_EQ(link_px_at(unscaled, {1280, 720}), p.link_px) << "width 0: the same on every sensor";
}

// A ring of radius 120 px on a 640x480 sensor with events 6-7 px apart: the kernel (h = 25.6
// px there) splits it into arcs, 4 px links leave them apart, and the defaults' 8 px on that
// sensor join them.
TEST(SeededClimbs, OnAWideSensorTheLinkBridgesTheWiderGapsOfAnOutline) {
  const SensorSize wide{640, 480};
  Params p = seeded();
  const std::vector<Event> events = ring(320, 240, 120, 3);
  const FeatureMatrix features = packet_features(events, wide, p);
  ASSERT_DOUBLE_EQ(link_px_at(p, wide), 8);
  EXPECT_EQ(cluster_packet(events, features, p, {}, {}, wide).count, 1);
  p.link_px_width = 0;
  EXPECT_GT(cluster_packet(events, features, p, {}, {}, wide).count, 2);
}

TEST(SeededClimbs, AWarmSeedClimbsWithItsClustersSize) {
  // A ring of radius 30 px and a warm seed 10 px inside its right edge. With h (9.6 px) the
  // seed's ball holds nothing; with its own bandwidth (1.5 times its cluster's spread of 30 px,
  // capped at 0.14, 33.6 px at 240 wide) it reaches a wide arc of the ring first.
  Params p = seeded();
  p.link_px = 0;
  p.warm_start = true;
  p.min_cluster_size = 1;
  const Packet packet(ring(120, 90, 30, 3), p);
  const Eigen::Vector4d seed(140.0 / 240, 90.0 / 180, 0, 0);
  p.warm_scale = 0;
  const PacketClusters small = packet.cluster(p, {seed}, {30.0 / 240});
  p.warm_scale = 1.5;
  const PacketClusters own = packet.cluster(p, {seed}, {30.0 / 240});
  // Cluster 0 is the warm seed's: its own, larger ball reaches more of the ring first.
  const auto count0 = [](const PacketClusters& c) { return std::count(c.cluster_of.begin(), c.cluster_of.end(), 0); };
  EXPECT_GT(count0(own), 2 * count0(small));
}

TEST(SeededClimbs, AWarmSeedsReachLeavesANeighbourInItsBallsMarginToItsOwnCluster) {
  // A ring of radius 20 px (spread 20 px) and, 16 px outside it, a small square of events. The
  // warm seed at the ring's centre climbs with a ball of 2 spreads (40 px), which holds the
  // square (and moves 4 px towards it); with a reach of 1.5 spreads (30 px) the ring is taken and
  // the square is not.
  Params p = seeded();
  p.link_px = 0;
  p.warm_start = true;
  p.min_cluster_size = 1;
  p.warm_max_bandwidth = 0.2;
  std::vector<Event> e = ring(120, 90, 20, 3);
  const size_t square = e.size();
  for (int i = 0; i < 16; ++i) {
    e.push_back({static_cast<TimeUs>(e.size()), static_cast<std::uint16_t>(156 + i % 4), static_cast<std::uint16_t>(88 + i / 4), 1});
  }
  const Packet packet(e, p);
  const Eigen::Vector4d seed(120.0 / 240, 90.0 / 180, 0, 0);
  const std::vector<double> spread{20.0 / 240};
  const auto square_in_ring_cluster = [&](const PacketClusters& c) {
    return std::count(c.cluster_of.begin() + static_cast<std::ptrdiff_t>(square), c.cluster_of.end(), c.cluster_of.front());
  };

  p.warm_reach = 0;
  const PacketClusters ball = packet.cluster(p, {seed}, spread);
  EXPECT_EQ(square_in_ring_cluster(ball), 16) << "the whole ball takes the square with the ring";

  p.warm_reach = 1.5;
  const PacketClusters reach = packet.cluster(p, {seed}, spread);
  EXPECT_EQ(square_in_ring_cluster(reach), 0) << "beyond the reach, the square climbs on its own";
  EXPECT_TRUE(std::all_of(reach.cluster_of.begin(), reach.cluster_of.begin() + static_cast<std::ptrdiff_t>(square),
                          [&](int c) { return c == reach.cluster_of.front() && c >= 0; }))
      << "the ring stays one cluster";
}

// A dense blob, a sparse arc that touches it, and a sparse arc alone: lines of events 4 px apart
// (within the link distance), whose climbs hold three events each, against the least density of
// 816 events (2 x 816 x pi h^2 = 8.2). The arcs come first in the packet, the far end first, so
// that their climbs open modes of their own before the blob's. Tested on each mode before the
// links, both arcs are noise; tested on the linked sets (the default), the arc that touches the
// blob stays in its cluster and the lone arc is still noise.
TEST(SeededClimbs, ASparseArcTouchingADenseModeStaysWithItWhenTheDensityIsTestedAfterTheLinks) {
  Params p = seeded();
  p.min_density = 2;
  p.density_after_links = false;
  std::vector<Event> e;
  for (int k = 7; k >= 0; --k) e.push_back({static_cast<TimeUs>(e.size()), 61, static_cast<std::uint16_t>(97 + 4 * k), 1});
  const size_t alone = e.size();
  for (int k = 7; k >= 0; --k) e.push_back({static_cast<TimeUs>(e.size()), 200, static_cast<std::uint16_t>(20 + 4 * k), 1});
  const size_t blob = e.size();
  for (int i = 0; i < 800; ++i) {
    e.push_back({static_cast<TimeUs>(e.size()), static_cast<std::uint16_t>(60 + i % 4), static_cast<std::uint16_t>(90 + i / 4 % 4), 1});
  }
  const Packet packet(e, p);
  const auto noise_in = [](const PacketClusters& c, size_t from, size_t to) {
    return std::count(c.cluster_of.begin() + static_cast<std::ptrdiff_t>(from), c.cluster_of.begin() + static_cast<std::ptrdiff_t>(to), -1);
  };

  const PacketClusters before = packet.cluster(p);
  EXPECT_GT(noise_in(before, 0, alone), 0) << "the touching arc's sparse modes are noise";
  EXPECT_EQ(noise_in(before, alone, blob), 8);
  EXPECT_EQ(noise_in(before, blob, e.size()), 0);

  p.density_after_links = true;
  const PacketClusters after = packet.cluster(p);
  ASSERT_EQ(after.count, 1);
  EXPECT_EQ(noise_in(after, 0, alone), 0) << "linked to the blob, the touching arc is in its cluster";
  EXPECT_EQ(noise_in(after, alone, blob), 8) << "a set of sparse modes is noise";
  EXPECT_EQ(noise_in(after, blob, e.size()), 0);
  EXPECT_EQ(after.cluster_of.front(), after.cluster_of.back());
}

TEST(SeededClimbs, ModesTheRunCannotKeepAreNoise) {
  Params p = seeded();
  p.link_px = 0;
  p.max_clusters = 1;
  std::vector<Event> e;
  for (int i = 0; i < 20; ++i) e.push_back({i, static_cast<std::uint16_t>(150 + i % 3), 40, 1});
  for (int i = 0; i < 20; ++i) e.push_back({20 + i, 30, static_cast<std::uint16_t>(120 + i % 3), 1});
  e.push_back({50, 200, 170, 1});  // a lone event: a cluster of one
  const Packet packet(e, p);
  const PacketClusters c = packet.cluster(p);
  EXPECT_EQ(c.count, 1);
  EXPECT_EQ(c.cluster_of[25], -1) << "beyond max-clusters";
  EXPECT_EQ(c.cluster_of.back(), -1) << "below min-cluster-size";
}

TEST(Presets, NameEveryChoiceAndRefuseUnknownNames) {
  const Params paper = preset("paper", {240, 180});
  EXPECT_EQ(paper.kernel, Kernel::kFlat);
  EXPECT_EQ(paper.seeding, Seeding::kEvents);
  EXPECT_EQ(paper.labelling, Labelling::kVotes);
  EXPECT_EQ(paper.association, Association::kNearestCentre);
  EXPECT_DOUBLE_EQ(paper.bandwidth, 0.15);
  EXPECT_EQ(paper.packet_size, 1800);
  EXPECT_EQ(preset("paper", {128, 128}).packet_size, 1500);
  EXPECT_EQ(preset("gaussian").kernel, Kernel::kGaussian);
  EXPECT_EQ(preset("gaussian").seeding, Seeding::kEvery);
  EXPECT_EQ(preset("evms"), Params{});
  EXPECT_THROW(preset("fast"), std::invalid_argument);
}

TEST(Method, SettingsOverrideThePresetWhateverTheirOrder) {
  Method m{"paper", {{"bandwidth", "0.1"}, {"kernel", "epanechnikov"}}};
  const Params p = m.resolve({240, 180});
  EXPECT_DOUBLE_EQ(p.bandwidth, 0.1);
  EXPECT_EQ(p.kernel, Kernel::kEpanechnikov);
  EXPECT_EQ(p.packet_size, 1800) << "the rest is the preset's";
  EXPECT_EQ(m.describe(), "--preset paper --bandwidth 0.1 --kernel epanechnikov");
  EXPECT_THROW((Method{"evms", {{"kernel", "box"}}}.resolve({240, 180})), std::invalid_argument);
}

}  // namespace
}  // namespace evms::golden
