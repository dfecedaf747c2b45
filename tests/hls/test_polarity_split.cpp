// The core's polarity split (hls/cluster/polarity_split.h) against golden's
// (golden/cluster/polarity_split.h): the same events in the same clusters, numbered the same, on
// dense random packets over the rule's settings and sensors (blobs about one centre among them, for
// the concentric groups), and the split modes within a unit of
// the climbs' features of golden's means.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "golden/cluster/polarity_split.h"
#include "hls/cluster/polarity_split.h"
#include "hls/core/shape.h"
#include "host/backend/core_config.h"
#include "host/gen/random.h"

namespace evms::hls {
namespace {

using S = HostShape;

struct Case {
  SensorSize sensor;
  Params params;
  std::vector<Event> events;
  std::vector<int> cluster_of;  // the clusters before the split
  int modes = 0;
};

// Blobs (filled discs or rings) each of both polarities or mostly one, dealt to a few clusters, and
// scattered events of no cluster.
Case random_case(gen::Random& rng) {
  static constexpr SensorSize kSensors[] = {{128, 128}, {240, 180}, {346, 260}, {640, 480}};
  Case c;
  c.sensor = kSensors[rng.below(4)];
  c.params.split_balance = std::array{0.1, 0.3, 0.5, 1.0}[rng.below(4)];
  c.params.split_share = std::array{0.05, 0.1, 0.2}[rng.below(3)];
  c.params.split_cell = std::array{0.3, 0.5, 1.0}[rng.below(3)];
  c.params.bandwidth = std::array{0.02, 0.04, 0.08}[rng.below(3)];
  c.params.min_cluster_size = static_cast<int>(std::array{4, 8, 16}[rng.below(3)]);
  c.params.split_min_events = static_cast<int>(std::array{1, 8, 32, 64, 128}[rng.below(5)]);
  c.params.split_partial = rng.below(3) != 0;
  c.params.split_concentric = rng.below(3) != 0;
  c.modes = 1 + static_cast<int>(rng.below(4));
  const int blobs = 2 + static_cast<int>(rng.below(6));
  double centre_x = 0, centre_y = 0, last_radius = 0;
  int last_cluster = 0;
  for (int b = 0; b < blobs; ++b) {
    // Half of the later blobs are rings about the previous blob's centre, wider than it, in its
    // cluster: a ring's circles.
    const bool concentric = b > 0 && rng.uniform() < 0.5;
    const double cx = concentric ? centre_x : rng.uniform(5, c.sensor.width - 5), cy = concentric ? centre_y : rng.uniform(5, c.sensor.height - 5);
    const double radius = concentric ? last_radius + rng.uniform(4, 20) : rng.uniform(1, 25);
    const double on_share = std::array{0.5, 0.45, 0.9, 0.05}[rng.below(4)];
    const bool ring = concentric || rng.uniform() < 0.3;
    const int cluster = concentric ? last_cluster : static_cast<int>(rng.below(static_cast<std::uint64_t>(c.modes)));
    centre_x = cx, centre_y = cy, last_radius = radius, last_cluster = cluster;
    const int n = 5 + static_cast<int>(rng.below(300));
    for (int i = 0; i < n; ++i) {
      const double r = ring ? radius : rng.uniform(0, radius), a = rng.uniform(0, 2 * M_PI);
      const auto x = static_cast<std::uint16_t>(std::clamp(std::lround(cx + r * std::cos(a)), 0L, static_cast<long>(c.sensor.width - 1)));
      const auto y = static_cast<std::uint16_t>(std::clamp(std::lround(cy + r * std::sin(a)), 0L, static_cast<long>(c.sensor.height - 1)));
      c.events.push_back({static_cast<TimeUs>(c.events.size()), x, y, static_cast<std::uint8_t>(rng.uniform() < on_share)});
      c.cluster_of.push_back(cluster);
    }
  }
  for (int i = 0; i < 40; ++i) {
    c.events.push_back({static_cast<TimeUs>(c.events.size()), static_cast<std::uint16_t>(rng.below(static_cast<std::uint64_t>(c.sensor.width))),
                        static_cast<std::uint16_t>(rng.below(static_cast<std::uint64_t>(c.sensor.height))), 1});
    c.cluster_of.push_back(-1);
  }
  // Shuffled, so that a part's first event is anywhere in the packet.
  for (size_t i = c.events.size() - 1; i > 0; --i) {
    const size_t j = rng.below(i + 1);
    std::swap(c.events[i], c.events[j]);
    std::swap(c.cluster_of[i], c.cluster_of[j]);
  }
  return c;
}

struct Packet {
  std::unique_ptr<PacketEvents<S>> events = std::make_unique<PacketEvents<S>>();
  std::unique_ptr<Features<S>> phi = std::make_unique<Features<S>>();
  std::unique_ptr<Modes<S>> modes = std::make_unique<Modes<S>>();
  std::vector<std::int16_t> mode_of = std::vector<std::int16_t>(S::kPacketMax, -1);
};

Packet core_packet(const Case& c, const Config& cfg) {
  Packet k;
  for (size_t i = 0; i < c.events.size(); ++i) {
    k.events->x[i] = c.events[i].x, k.events->y[i] = c.events[i].y, k.events->p[i] = c.events[i].p;
    k.events->t[i] = static_cast<std::uint32_t>(c.events[i].t);
    k.mode_of[i] = static_cast<std::int16_t>(c.cluster_of[i]);
  }
  climb_features(*k.events, static_cast<int>(c.events.size()), cfg, *k.phi);
  k.modes->count = c.modes;
  for (int m = 0; m < c.modes; ++m) k.modes->x[m] = k.modes->y[m] = k.modes->p[m] = k.modes->t[m] = 0;
  return k;
}

// Golden's clusters of case c's events after its split with parameters p.
std::vector<int> golden_clusters(const Case& c, const golden::FeatureMatrix& f, const Params& p) {
  std::vector<Eigen::Vector4d> modes(static_cast<size_t>(c.modes), Eigen::Vector4d::Zero());
  std::vector<int> cluster_of = c.cluster_of;
  golden::PolaritySplit(p, c.sensor).split(c.events, f, modes, cluster_of);
  return cluster_of;
}

TEST(PolaritySplitFixed, TheSameClustersAndModesAsGoldenOnRandomPackets) {
  gen::Random rng(11);
  auto split = std::make_unique<PolaritySplit<S>>();
  split->reset();
  int trials_split = 0, trials_whole = 0, trials_partial = 0, trials_concentric = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Case c = random_case(rng);
    SCOPED_TRACE("trial " + std::to_string(trial));
    // Golden, from modes at 0.
    const golden::FeatureMatrix f = golden::packet_features(c.events, c.sensor, c.params);
    std::vector<Eigen::Vector4d> want_modes(static_cast<size_t>(c.modes), Eigen::Vector4d::Zero());
    std::vector<int> want = c.cluster_of;
    golden::PolaritySplit(c.params, c.sensor).split(c.events, f, want_modes, want);
    // The core.
    const Config cfg = backend::core_config<S>(c.params, c.sensor);
    Packet k = core_packet(c, cfg);
    const int n = static_cast<int>(c.events.size());
    ASSERT_EQ(split->run(*k.events, *k.phi, n, cfg, k.mode_of.data(), *k.modes), 0);
    ASSERT_EQ(std::vector<int>(k.mode_of.begin(), k.mode_of.begin() + n), want);
    ASSERT_EQ(static_cast<size_t>(k.modes->count), want_modes.size());
    // A split mode is its part's mean: golden's in features (x / W), the core's in bandwidth units
    // with kFeatFrac + kClimbFrac fraction bits, each event's feature rounded.
    const double unit = std::ldexp(1.0, S::kFeatFrac + kClimbFrac) / c.params.bandwidth;
    for (size_t m = 0; m < want_modes.size(); ++m) {
      if (want_modes[m].isZero()) continue;
      EXPECT_NEAR(static_cast<double>(k.modes->x[m]), want_modes[m](0) * unit, 1.0) << "mode " << m;
      EXPECT_NEAR(static_cast<double>(k.modes->y[m]), want_modes[m](1) * unit, 1.0) << "mode " << m;
    }
    (want_modes.size() > static_cast<size_t>(c.modes) ? trials_split : trials_whole)++;
    // A split that only split_partial makes: a large part of one polarity beside balanced ones.
    if (c.params.split_partial) {
      Params whole = c.params;
      whole.split_partial = false;
      trials_partial += golden_clusters(c, f, whole) != want;
    }
    // A split that only split_concentric keeps whole.
    if (c.params.split_concentric) {
      Params apart = c.params;
      apart.split_concentric = false;
      trials_concentric += golden_clusters(c, f, apart) != want;
    }
  }
  // Both outcomes, many times: the cases reach the rule's every branch.
  EXPECT_GT(trials_split, 50);
  EXPECT_GT(trials_whole, 50);
  EXPECT_GT(trials_partial, 10);
  EXPECT_GT(trials_concentric, 10);
}

TEST(PolaritySplitFixed, AClusterWhosePartsFindNoRoomInTheModeTableStaysWhole) {
  Params p;
  p.split_balance = 0.3;
  const SensorSize sensor{240, 180};
  Case c;
  c.sensor = sensor, c.params = p, c.modes = 1;
  for (const int x0 : {20, 120}) {  // two squares of both polarities, 100 px apart
    for (int y = 40; y < 50; ++y) {
      for (int x = x0; x < x0 + 10; ++x) {
        c.events.push_back({0, static_cast<std::uint16_t>(x), static_cast<std::uint16_t>(y), static_cast<std::uint8_t>((x + y) % 2)});
        c.cluster_of.push_back(0);
      }
    }
  }
  const Config cfg = backend::core_config<S>(p, sensor);
  auto split = std::make_unique<PolaritySplit<S>>();
  split->reset();
  const int n = static_cast<int>(c.events.size());
  Packet room = core_packet(c, cfg);
  EXPECT_EQ(split->run(*room.events, *room.phi, n, cfg, room.mode_of.data(), *room.modes), 0);
  EXPECT_EQ(room.modes->count, 2) << "with room, the squares are two clusters";
  Packet full = core_packet(c, cfg);
  full.modes->count = S::kModesMax;
  EXPECT_EQ(split->run(*full.events, *full.phi, n, cfg, full.mode_of.data(), *full.modes), 1);
  EXPECT_EQ(full.modes->count, S::kModesMax);
  EXPECT_EQ(std::vector<std::int16_t>(full.mode_of.begin(), full.mode_of.begin() + n), std::vector<std::int16_t>(static_cast<size_t>(n), 0));
}

TEST(PolaritySplitFixed, ASmallPartMidwayBetweenTwoLargeOnesJoinsTheOneWhoseFirstEventCameFirst) {
  Params p;
  p.split_balance = 0.3;
  Case c;
  c.sensor = {240, 180}, c.params = p, c.modes = 1;
  auto square = [&](int x0, int side) {
    for (int y = 40; y < 40 + side; ++y) {
      for (int x = x0; x < x0 + side; ++x) {
        c.events.push_back({0, static_cast<std::uint16_t>(x), static_cast<std::uint16_t>(y), static_cast<std::uint8_t>((x + y) % 2)});
        c.cluster_of.push_back(0);
      }
    }
  };
  square(60, 10), square(20, 10), square(44, 2);  // centres 64.5, 24.5 and 44.5 px along x, the same along y
  const Config cfg = backend::core_config<S>(p, c.sensor);
  auto split = std::make_unique<PolaritySplit<S>>();
  split->reset();
  const int n = static_cast<int>(c.events.size());
  Packet k = core_packet(c, cfg);
  split->run(*k.events, *k.phi, n, cfg, k.mode_of.data(), *k.modes);
  ASSERT_EQ(k.modes->count, 2);
  for (int i = 200; i < n; ++i) EXPECT_EQ(k.mode_of[static_cast<size_t>(i)], 0) << "the square at 60 came first";
  const golden::FeatureMatrix f = golden::packet_features(c.events, c.sensor, p);
  std::vector<Eigen::Vector4d> modes(1, Eigen::Vector4d::Zero());
  std::vector<int> want = c.cluster_of;
  golden::PolaritySplit(p, c.sensor).split(c.events, f, modes, want);
  EXPECT_EQ(std::vector<int>(k.mode_of.begin(), k.mode_of.begin() + n), want);
}

}  // namespace
}  // namespace evms::hls
