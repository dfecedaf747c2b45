#include <gtest/gtest.h>

#include <cmath>

#include "golden/cluster/features.h"
#include "golden/cluster/mean_shift.h"

namespace evms::golden {
namespace {

TEST(Features, NormalizedScaledAndDecayedFromTheNewestEvent) {
  Params p = preset("gaussian");
  p.scale_xy = 2.0, p.scale_p = 0.5, p.scale_t = 3.0, p.tau_us = 1000;
  const std::vector<Event> events = {{0, 24, 18, 1}, {1000, 120, 90, 0}};
  const FeatureMatrix f = packet_features(events, {240, 180}, p);
  EXPECT_DOUBLE_EQ(f(0, 0), 2.0 * 24 / 240);
  EXPECT_DOUBLE_EQ(f(1, 0), 2.0 * 18 / 180);
  EXPECT_DOUBLE_EQ(f(2, 0), 0.5);
  EXPECT_DOUBLE_EQ(f(3, 0), 3.0 * std::exp(-1.0));
  EXPECT_DOUBLE_EQ(f(2, 1), 0.0);
  EXPECT_DOUBLE_EQ(f(3, 1), 3.0);
}

// One sweep on two points, computed by hand: positions move against the original positions,
// appearance against the previous iteration's appearance.
TEST(HybridMeanShift, OneSweepMatchesTheDefinition) {
  Params p = preset("gaussian");
  p.bandwidth = 0.1;
  p.max_iterations = 1;
  FeatureMatrix f(4, 2);
  f.col(0) << 0.10, 0.20, 0.0, 0.9;
  f.col(1) << 0.15, 0.20, 0.0, 0.7;
  const MeanShiftResult r = hybrid_mean_shift(f, p);
  const double d2 = 0.05 * 0.05 + 0.2 * 0.2;
  const double w = std::exp(-d2 / (2 * 0.01));
  EXPECT_NEAR(r.modes(0, 0), (0.10 + w * 0.15) / (1 + w), 1e-15);
  EXPECT_NEAR(r.modes(3, 0), (0.9 + w * 0.7) / (1 + w), 1e-15);
  EXPECT_NEAR(r.modes(0, 1), (w * 0.10 + 0.15) / (1 + w), 1e-15);
  EXPECT_EQ(r.iterations, 1);
}

TEST(HybridMeanShift, SecondSweepComparesPositionsWithTheOriginalPoints) {
  Params p = preset("gaussian");
  p.bandwidth = 0.1;
  p.max_iterations = 2;
  p.tolerance = 0;
  FeatureMatrix f(4, 2);
  f.col(0) << 0.10, 0.20, 0.0, 0.9;
  f.col(1) << 0.15, 0.20, 0.0, 0.7;
  Params one = p;
  one.max_iterations = 1;
  const FeatureMatrix y1 = hybrid_mean_shift(f, one).modes;
  // Sweep 2 by hand from y1: distance of point 0's moved position to the ORIGINAL position of
  // each point, plus the distance of appearances both taken from sweep 1.
  auto weight = [&](int i, int j) {
    const double dx = y1(0, i) - f(0, j), dy = y1(1, i) - f(1, j);
    const double dp = y1(2, i) - y1(2, j), dt = y1(3, i) - y1(3, j);
    return std::exp(-(dx * dx + dy * dy + dp * dp + dt * dt) / (2 * 0.01));
  };
  const double w00 = weight(0, 0), w01 = weight(0, 1);
  const MeanShiftResult r = hybrid_mean_shift(f, p);
  EXPECT_NEAR(r.modes(0, 0), (w00 * f(0, 0) + w01 * f(0, 1)) / (w00 + w01), 1e-15);
  EXPECT_NEAR(r.modes(3, 0), (w00 * y1(3, 0) + w01 * y1(3, 1)) / (w00 + w01), 1e-15);
}

TEST(HybridMeanShift, StopsAtTheToleranceOrTheCap) {
  Params p = preset("gaussian");
  FeatureMatrix f(4, 3);
  f.col(0) << 0.5, 0.5, 0, 1;
  f.col(1) << 0.5, 0.5, 0, 1;
  f.col(2) << 0.5, 0.5, 0, 1;
  EXPECT_EQ(hybrid_mean_shift(f, p).iterations, 1);  // nothing moves
  f.col(2) << 0.56, 0.5, 0, 1;
  p.tolerance = 0;
  p.max_iterations = 7;
  EXPECT_EQ(hybrid_mean_shift(f, p).iterations, 7);
}

TEST(MergeModes, NearModesJoinSmallClustersBecomeNoise) {
  Params p = preset("gaussian");
  p.merge_radius = 0.05;
  p.min_cluster_size = 2;
  FeatureMatrix m(4, 5);
  m.col(0) << 0.10, 0.10, 0, 1;
  m.col(1) << 0.12, 0.10, 0, 1;   // within 0.05 of point 0
  m.col(2) << 0.50, 0.50, 0, 1;
  m.col(3) << 0.51, 0.50, 0, 1;
  m.col(4) << 0.90, 0.90, 0, 1;   // alone: too small
  const ModeClusters c = merge_modes(m, p);
  EXPECT_EQ(c.count, 2);
  EXPECT_EQ(c.cluster_of, (std::vector<int>{0, 0, 1, 1, -1}));
}

TEST(MergeModes, ModesBeyondMaxClustersAreNoise) {
  Params p = preset("gaussian");
  p.min_cluster_size = 1;
  p.max_clusters = 2;
  FeatureMatrix m(4, 3);
  m.col(0) << 0.1, 0.1, 0, 1;
  m.col(1) << 0.5, 0.5, 0, 1;
  m.col(2) << 0.9, 0.9, 0, 1;
  EXPECT_EQ(merge_modes(m, p).cluster_of, (std::vector<int>{0, 1, -1}));
}

TEST(MergeModes, AModeJoinsTheNearestSeed) {
  Params p = preset("gaussian");
  p.min_cluster_size = 1;
  p.merge_radius = 0.05;
  FeatureMatrix m(4, 3);
  m.col(0) << 0.10, 0.1, 0, 1;
  m.col(1) << 0.18, 0.1, 0, 1;   // 0.08 from seed 0: a second cluster
  m.col(2) << 0.15, 0.1, 0, 1;   // 0.05 from seed 0, 0.03 from seed 1
  EXPECT_EQ(merge_modes(m, p).cluster_of, (std::vector<int>{0, 1, 1}));
}

}  // namespace
}  // namespace evms::golden
