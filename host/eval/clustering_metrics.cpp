#include "host/eval/clustering_metrics.h"

#include <cmath>
#include <unordered_map>
#include <vector>

namespace evms::eval {
namespace {

double pairs(double n) { return n * (n - 1) / 2; }

// Relabels so that every -1 becomes a fresh singleton label, and labels are 0..k-1.
std::vector<std::int64_t> canonical(std::span<const std::int32_t> labels) {
  std::unordered_map<std::int32_t, std::int64_t> ids;
  std::vector<std::int64_t> out(labels.size());
  std::int64_t next = 0;
  for (size_t i = 0; i < labels.size(); ++i) {
    if (labels[i] < 0) {
      out[i] = next++;
    } else {
      auto [it, fresh] = ids.try_emplace(labels[i], next);
      if (fresh) ++next;
      out[i] = it->second;
    }
  }
  return out;
}

}  // namespace

ClusteringScores score(std::span<const std::int32_t> truth, std::span<const std::int32_t> pred, PairCounts* counts) {
  const auto t = canonical(truth), p = canonical(pred);
  const double n = static_cast<double>(t.size());
  std::unordered_map<std::int64_t, double> a, b;   // true and predicted cluster sizes
  std::unordered_map<std::uint64_t, double> nij;  // contingency table
  for (size_t i = 0; i < t.size(); ++i) {
    a[t[i]] += 1;
    b[p[i]] += 1;
    nij[(static_cast<std::uint64_t>(t[i]) << 32) | static_cast<std::uint64_t>(p[i])] += 1;
  }
  double same_both = 0, same_true = 0, same_pred = 0;
  for (const auto& [k, v] : nij) same_both += pairs(v);
  for (const auto& [k, v] : a) same_true += pairs(v);
  for (const auto& [k, v] : b) same_pred += pairs(v);

  PairCounts c;
  c.tp = same_both;
  c.fp = same_pred - same_both;
  c.fn = same_true - same_both;
  c.tn = pairs(n) - c.tp - c.fp - c.fn;
  if (counts) *counts = c;

  ClusteringScores s;
  s.precision = c.tp + c.fp > 0 ? c.tp / (c.tp + c.fp) : 1.0;
  s.recall = c.tp + c.fn > 0 ? c.tp / (c.tp + c.fn) : 1.0;
  s.f = s.precision + s.recall > 0 ? 2 * s.precision * s.recall / (s.precision + s.recall) : 0.0;
  if (c.fp == 0 && c.fn == 0) {
    s.ari = 1.0;
  } else {
    const double den = (c.tp + c.fn) * (c.fn + c.tn) + (c.tp + c.fp) * (c.fp + c.tn);
    s.ari = den > 0 ? 2 * (c.tp * c.tn - c.fn * c.fp) / den : 0.0;
  }

  double h_true = 0, h_pred = 0, mi = 0;
  for (const auto& [k, v] : a) h_true -= v / n * std::log(v / n);
  for (const auto& [k, v] : b) h_pred -= v / n * std::log(v / n);
  for (const auto& [k, v] : nij) {
    const double ai = a[static_cast<std::int64_t>(k >> 32)], bj = b[static_cast<std::int64_t>(k & 0xFFFFFFFFu)];
    mi += v / n * std::log(n * v / (ai * bj));
  }
  if (h_true == 0 && h_pred == 0) {
    s.nmi = 1.0;
  } else {
    const double mean = (h_true + h_pred) / 2;
    s.nmi = mean > 0 ? std::max(0.0, mi) / mean : 0.0;
  }
  return s;
}

void ScoreAverage::add(const ClusteringScores& s) {
  sum_.ari += s.ari;
  sum_.nmi += s.nmi;
  sum_.precision += s.precision;
  sum_.recall += s.recall;
  sum_.f += s.f;
  ++n_;
}

ClusteringScores ScoreAverage::mean() const {
  if (n_ == 0) return {};
  const double k = static_cast<double>(n_);
  return {sum_.ari / k, sum_.nmi / k, sum_.precision / k, sum_.recall / k, sum_.f / k};
}

}  // namespace evms::eval
