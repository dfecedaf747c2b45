// The clustering metrics against hand-computed cases and published values.
#include <gtest/gtest.h>

#include <cmath>

#include "host/eval/clustering_metrics.h"
#include "host/eval/identity_metrics.h"

namespace evms::eval {
namespace {

using Labels = std::vector<std::int32_t>;

TEST(ClusteringMetrics, HandComputedSplit) {
  // Pairs of 4 events: {0,1} same in both (TP); {2,3} same truth, split (FN); 4 TN.
  PairCounts c;
  const auto s = score(Labels{0, 0, 1, 1}, Labels{0, 0, 1, 2}, &c);
  EXPECT_EQ(c.tp, 1);
  EXPECT_EQ(c.fp, 0);
  EXPECT_EQ(c.fn, 1);
  EXPECT_EQ(c.tn, 4);
  EXPECT_DOUBLE_EQ(s.precision, 1.0);
  EXPECT_DOUBLE_EQ(s.recall, 0.5);
  EXPECT_DOUBLE_EQ(s.f, 2.0 / 3.0);
  // scikit-learn's documented adjusted_rand_score([0, 0, 1, 1], [0, 0, 1, 2]) = 0.57...
  EXPECT_NEAR(s.ari, 8.0 / 14.0, 1e-15);
  // NMI by hand: H(truth) = ln 2, H(pred) = 1.5 ln 2, I = ln 2.
  EXPECT_NEAR(s.nmi, std::log(2.0) / (1.25 * std::log(2.0)), 1e-15);
}

// Manning, Raghavan & Schuetze, Introduction to Information Retrieval, section 16.3: 17 points
// in three clusters {5x, 1o}, {1x, 4o, 1d}, {2x, 3d}. Published: TP 20, FP 20, FN 24, TN 72,
// P 0.5, R 0.455, F1 0.48, NMI 0.36.
TEST(ClusteringMetrics, ManningRaghavanSchuetzeExample) {
  const Labels truth = {0, 0, 0, 0, 0, 1, /**/ 0, 1, 1, 1, 1, 2, /**/ 0, 0, 2, 2, 2};
  const Labels pred = {0, 0, 0, 0, 0, 0, /**/ 1, 1, 1, 1, 1, 1, /**/ 2, 2, 2, 2, 2};
  PairCounts c;
  const auto s = score(truth, pred, &c);
  EXPECT_EQ(c.tp, 20);
  EXPECT_EQ(c.fp, 20);
  EXPECT_EQ(c.fn, 24);
  EXPECT_EQ(c.tn, 72);
  EXPECT_DOUBLE_EQ(s.precision, 0.5);
  EXPECT_NEAR(s.recall, 0.455, 0.0005);
  EXPECT_NEAR(s.f, 0.48, 0.005);
  EXPECT_NEAR(s.nmi, 0.36, 0.005);
  // ARI from the same pair counts: 2(20*72 - 24*20) / (44*96 + 40*92).
  EXPECT_NEAR(s.ari, 1920.0 / 7904.0, 1e-15);
}

TEST(ClusteringMetrics, PermutingLabelsChangesNothing) {
  const Labels truth = {3, 3, 1, 1, 1, 7, 7, -1};
  const auto a = score(truth, Labels{0, 0, 1, 1, 2, 2, 2, -1});
  const auto b = score(truth, Labels{9, 9, 4, 4, 5, 5, 5, -1});
  EXPECT_DOUBLE_EQ(a.f, b.f);
  EXPECT_DOUBLE_EQ(a.ari, b.ari);
  EXPECT_DOUBLE_EQ(a.nmi, b.nmi);
}

TEST(ClusteringMetrics, NoiseIsASingletonOnBothSides) {
  // Noise called noise is never a pair: a perfect score.
  const auto perfect = score(Labels{0, 0, -1, -1, 1}, Labels{5, 5, -1, -1, 6});
  EXPECT_DOUBLE_EQ(perfect.f, 1.0);
  EXPECT_DOUBLE_EQ(perfect.ari, 1.0);
  EXPECT_DOUBLE_EQ(perfect.nmi, 1.0);
  // A true noise event put in a cluster makes two false-positive pairs.
  PairCounts c;
  score(Labels{0, 0, -1}, Labels{0, 0, 0}, &c);
  EXPECT_EQ(c.tp, 1);
  EXPECT_EQ(c.fp, 2);
  // A true object event called noise makes false-negative pairs with its object.
  score(Labels{0, 0, 0}, Labels{0, 0, -1}, &c);
  EXPECT_EQ(c.tp, 1);
  EXPECT_EQ(c.fn, 2);
}

TEST(ClusteringMetrics, DegenerateLabellings) {
  const auto all_one = score(Labels{4, 4, 4}, Labels{1, 1, 1});
  EXPECT_DOUBLE_EQ(all_one.ari, 1.0);
  EXPECT_DOUBLE_EQ(all_one.nmi, 1.0);
  // scikit-learn's documented adjusted_rand_score([0, 0, 0, 0], [0, 1, 2, 3]) = 0.0.
  const auto opposite = score(Labels{0, 0, 0, 0}, Labels{0, 1, 2, 3});
  EXPECT_DOUBLE_EQ(opposite.ari, 0.0);
  EXPECT_DOUBLE_EQ(opposite.nmi, 0.0);
  EXPECT_DOUBLE_EQ(opposite.precision, 1.0);  // no predicted pair
  EXPECT_DOUBLE_EQ(opposite.recall, 0.0);
}

TEST(ClusteringMetrics, AveragesChunksEqually) {
  ScoreAverage avg;
  avg.add({1, 1, 1, 1, 1});
  avg.add({0, 0.5, 0.5, 0, 0.2});
  const auto m = avg.mean();
  EXPECT_DOUBLE_EQ(m.ari, 0.5);
  EXPECT_DOUBLE_EQ(m.f, 0.6);
  EXPECT_EQ(avg.chunks(), 2);
}

}  // namespace
}  // namespace evms::eval

namespace evms::eval {
namespace {

std::vector<Event> events_at(std::initializer_list<TimeUs> times) {
  std::vector<Event> e;
  for (TimeUs t : times) e.push_back({t, 0, 0, 1});
  return e;
}

TEST(IdentityScores, OneIdPerObjectIsPerfect) {
  const auto events = events_at({0, 1000, 20000, 21000, 40000});
  const std::vector<std::int32_t> truth = {0, 1, 0, 1, 0}, pred = {7, 9, 7, 9, 7};
  const IdentityScores s = identity_scores(events, truth, pred);
  EXPECT_DOUBLE_EQ(s.idf1, 1.0);
  EXPECT_EQ(s.id_switches, 0);
  EXPECT_EQ(s.fragmentations, 0);
  EXPECT_EQ(s.objects, 2);
}

TEST(IdentityScores, ASwitchHalvesTheMatchedEvents) {
  // Object 0 carries ID 5 for two frames, then ID 6 for two: IDTP 2 of 4.
  const auto events = events_at({0, 10000, 20000, 30000});
  const std::vector<std::int32_t> truth = {0, 0, 0, 0}, pred = {5, 5, 6, 6};
  const IdentityScores s = identity_scores(events, truth, pred);
  EXPECT_DOUBLE_EQ(s.idf1, 0.5);
  EXPECT_EQ(s.id_switches, 1);
  EXPECT_EQ(s.fragmentations, 0);
}

TEST(IdentityScores, NoiseBetweenTheSameIdIsAFragmentation) {
  const auto events = events_at({0, 10000, 20000, 30000});
  const std::vector<std::int32_t> truth = {0, 0, 0, 0}, pred = {5, -1, 5, 5};
  const IdentityScores s = identity_scores(events, truth, pred);
  EXPECT_EQ(s.id_switches, 0);
  EXPECT_EQ(s.fragmentations, 1);
  EXPECT_DOUBLE_EQ(s.id_recall, 0.75);
  EXPECT_DOUBLE_EQ(s.id_precision, 1.0);
}

TEST(IdentityScores, OneIdOnTwoObjectsMatchesOnlyOne) {
  const auto events = events_at({0, 1000, 2000, 3000, 4000});
  const std::vector<std::int32_t> truth = {0, 0, 0, 1, 1}, pred = {3, 3, 3, 3, 3};
  const IdentityScores s = identity_scores(events, truth, pred);
  // ID 3 matches object 0 (3 events); object 1's 2 events and ID 3's 2 others are misses.
  EXPECT_DOUBLE_EQ(s.idf1, 2.0 * 3 / (2 * 3 + 2 + 2));
}

}  // namespace
}  // namespace evms::eval
