// The core's edge join (hls/cluster/edge_join.h) against golden's (golden/cluster/edge_join.h): the
// same events in the same clusters on dense random packets of one-polarity and mixed bars over the
// rule's settings and sensors.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <memory>

#include "golden/cluster/edge_join.h"
#include "hls/cluster/edge_join.h"
#include "hls/core/shape.h"
#include "host/backend/core_config.h"
#include "host/gen/random.h"

namespace evms::hls {
namespace {

using S = HostShape;

TEST(EdgeJoinFixed, TheSameClustersAsGoldenOnRandomPackets) {
  static constexpr SensorSize kSensors[] = {{128, 128}, {240, 180}, {346, 260}, {640, 480}, {1280, 720}};
  gen::Random rng(13);
  auto join = std::make_unique<EdgeJoin<S>>();
  auto events = std::make_unique<PacketEvents<S>>();
  std::vector<std::int16_t> mode_of(S::kPacketMax);
  int trials_joined = 0, trials_apart = 0;
  for (int trial = 0; trial < 400; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    const SensorSize sensor = kSensors[rng.below(5)];
    Params p;
    p.edge_join = std::array{1.0, 3.0, 5.0, 8.0}[rng.below(4)];
    p.edge_balance = std::array{0.1, 0.5, 0.8, 1.0}[rng.below(4)];
    p.edge_min_events = static_cast<int>(std::array{1, 16, 40}[rng.below(3)]);
    p.bandwidth = std::array{0.02, 0.04, 0.08}[rng.below(3)];
    p.min_cluster_size = static_cast<int>(std::array{1, 8}[rng.below(2)]);
    // Bars of random length and direction, each its own cluster, mostly one polarity or mixed,
    // and scattered events of no cluster; clusters numbered in random order.
    const int clusters = 1 + static_cast<int>(rng.below(12));
    std::vector<Event> ev;
    std::vector<int> want;
    for (int c = 0; c < clusters; ++c) {
      const double x0 = rng.uniform(0, sensor.width - 1), y0 = rng.uniform(0, sensor.height - 1), a = rng.uniform(0, 2 * M_PI);
      const double length = rng.uniform(1, 60), on_share = std::array{0.0, 0.1, 0.5, 0.75, 0.9, 1.0}[rng.below(6)];
      const int n = 1 + static_cast<int>(rng.below(200));
      for (int i = 0; i < n && ev.size() < 3000; ++i) {
        const double s = rng.uniform(0, length);
        const auto x = static_cast<std::uint16_t>(std::clamp(std::lround(x0 + s * std::cos(a)), 0L, static_cast<long>(sensor.width - 1)));
        const auto y = static_cast<std::uint16_t>(std::clamp(std::lround(y0 + s * std::sin(a)), 0L, static_cast<long>(sensor.height - 1)));
        ev.push_back({0, x, y, static_cast<std::uint8_t>(rng.uniform() < on_share)});
        want.push_back(c);
      }
    }
    for (int i = 0; i < 30; ++i) {
      ev.push_back({0, static_cast<std::uint16_t>(rng.below(static_cast<std::uint64_t>(sensor.width))),
                    static_cast<std::uint16_t>(rng.below(static_cast<std::uint64_t>(sensor.height))), 0});
      want.push_back(-1);
    }
    const std::vector<int> before = want;
    golden::join_edges(ev, edge_rule(p, sensor), clusters, want);
    const Config cfg = backend::core_config<S>(p, sensor);
    const int n = static_cast<int>(ev.size());
    for (int j = 0; j < n; ++j) {
      events->x[j] = ev[static_cast<size_t>(j)].x, events->y[j] = ev[static_cast<size_t>(j)].y, events->p[j] = ev[static_cast<size_t>(j)].p;
      mode_of[static_cast<size_t>(j)] = static_cast<std::int16_t>(before[static_cast<size_t>(j)]);
    }
    const int pairs = join->run(*events, n, cfg, clusters, mode_of.data());
    ASSERT_EQ(std::vector<int>(mode_of.begin(), mode_of.begin() + n), want);
    (pairs > 0 ? trials_joined : trials_apart)++;
    EXPECT_EQ(pairs > 0, want != before);
  }
  // Both outcomes, many times: the cases reach the rule's every branch.
  EXPECT_GT(trials_joined, 60);
  EXPECT_GT(trials_apart, 60);
}

TEST(EdgeJoinFixed, OffLeavesEveryModeAsItIs) {
  Params p;
  p.edge_join = 0;
  const Config cfg = backend::core_config<S>(p, {240, 180});
  EXPECT_EQ(cfg.edge_radius2, 0u);
  auto events = std::make_unique<PacketEvents<S>>();
  std::vector<std::int16_t> mode_of(S::kPacketMax, -1);
  for (int j = 0; j < 80; ++j) {  // an ON bar at x = 60 and an OFF bar at x = 100
    events->x[j] = static_cast<std::uint16_t>(j < 40 ? 60 : 100), events->y[j] = static_cast<std::uint16_t>(60 + j % 40);
    events->p[j] = j < 40, mode_of[static_cast<size_t>(j)] = static_cast<std::int16_t>(j < 40 ? 0 : 1);
  }
  auto join = std::make_unique<EdgeJoin<S>>();
  EXPECT_EQ(join->run(*events, 80, cfg, 2, mode_of.data()), 0);
  EXPECT_EQ(mode_of[79], 1);
  p.edge_join = 5;
  EXPECT_EQ(join->run(*events, 80, backend::core_config<S>(p, {240, 180}), 2, mode_of.data()), 1) << "on, the two bars join";
  EXPECT_EQ(mode_of[79], 0);
}

}  // namespace
}  // namespace evms::hls
