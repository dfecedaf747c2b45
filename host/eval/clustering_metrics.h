// External clustering metrics between a true and a predicted labelling of the same events.
//
// Pair counting, as the paper defines it, over every pair of events in a chunk:
//   TP  same predicted cluster,       same true label
//   FP  same predicted cluster,       different true labels
//   FN  different predicted clusters, same true label
//   TN  different predicted clusters, different true labels
// P = TP / (TP + FP), R = TP / (TP + FN), F = 2PR / (P + R). With no predicted pair P = 1,
// with no true pair R = 1.
//
// ARI is Hubert and Arabie's adjusted Rand index, from the same pair counts:
//   ARI = 2 (TP TN - FN FP) / ((TP + FN)(FN + TN) + (TP + FP)(FP + TN)),  1 when FP = FN = 0.
// NMI is the mutual information normalized by the arithmetic mean of the two entropies
// (natural logarithms; 1 when both labellings have a single cluster).
//
// Noise: the label -1 is not a cluster. Each event labelled -1, in the truth or in the
// prediction, counts as a cluster of its own. So a true object event the method calls noise
// costs recall (its pairs with its object become FN), and a true noise event the method puts
// in a cluster costs precision (its pairs with that cluster become FP), while noise called
// noise is never a pair of anything.
#pragma once

#include <cstdint>
#include <span>

namespace evms::eval {

struct PairCounts {
  double tp = 0, fp = 0, fn = 0, tn = 0;
};

struct ClusteringScores {
  double ari = 0, nmi = 0, precision = 0, recall = 0, f = 0;
};

// `truth` and `pred` label the same events, index by index.
ClusteringScores score(std::span<const std::int32_t> truth, std::span<const std::int32_t> pred,
                       PairCounts* counts = nullptr);

// Averages scores over chunks (each chunk weighs the same).
class ScoreAverage {
 public:
  void add(const ClusteringScores& s);
  ClusteringScores mean() const;
  std::int64_t chunks() const { return n_; }

 private:
  ClusteringScores sum_;
  std::int64_t n_ = 0;
};

}  // namespace evms::eval
