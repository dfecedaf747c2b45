// Latency from an event's arrival on the host to its label, as a histogram with buckets 1 %
// wide on a log scale from 1 us to 1000 s: constant memory for runs of any length, and
// percentiles within 1 % of the exact order statistic.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <deque>
#include <span>

#include "host/read/live/live_source.h"

namespace evms::eval {

class LatencyHistogram {
 public:
  // `count` events of latency `ns`.
  void add(std::int64_t ns, std::int64_t count = 1) {
    const double us = std::max(static_cast<double>(ns) * 1e-3, 1.0);
    const int b = std::min(static_cast<int>(std::log(us) / kLogStep), kBuckets - 1);
    counts_[static_cast<size_t>(b)] += count;
    total_ += count;
    max_ns_ = std::max(max_ns_, ns);
  }
  std::int64_t count() const { return total_; }
  std::int64_t max_ns() const { return max_ns_; }
  // The q-quantile (0 < q <= 1) in microseconds: the upper edge of its bucket.
  double quantile_us(double q) const {
    if (total_ == 0) return 0;
    const auto rank = static_cast<std::int64_t>(std::ceil(q * static_cast<double>(total_)));
    std::int64_t seen = 0;
    for (int b = 0; b < kBuckets; ++b) {
      seen += counts_[static_cast<size_t>(b)];
      if (seen >= rank) return std::min(std::exp((b + 1) * kLogStep), static_cast<double>(max_ns_) * 1e-3);
    }
    return static_cast<double>(max_ns_) * 1e-3;
  }

 private:
  static constexpr double kLogStep = 0.00995033;  // ln(1.01)
  static constexpr int kBuckets = 2083;           // ln(1e9) / ln(1.01): up to 1000 s
  std::array<std::int64_t, kBuckets> counts_{};
  std::int64_t total_ = 0, max_ns_ = 0;
};

// Pairs each labelled event with the arrival time of the event pushed in the same order (labels
// come out in input order) and records the difference. Sources that are not live have no
// arrival times, and then nothing is recorded.
//
// Events arrive in runs that share one arrival time (a USB transfer, a datagram, a slice of a
// replay), so the waiting events are kept as (arrival, count) runs and each run of labels is one
// histogram entry.
class ArrivalLatency {
 public:
  void arrived(std::span<const std::int64_t> arrival_ns) {
    for (const std::int64_t t : arrival_ns) {
      if (!waiting_.empty() && waiting_.back().arrival_ns == t) ++waiting_.back().count;
      else waiting_.push_back({t, 1});
    }
  }
  // The next `n` events (in input order) have their labels now.
  void labelled(std::int64_t n = 1) {
    if (waiting_.empty() || n <= 0) return;
    const std::int64_t now = read::steady_now_ns();
    while (n > 0 && !waiting_.empty()) {
      Run& run = waiting_.front();
      const std::int64_t take = std::min(n, run.count);
      histogram_.add(now - run.arrival_ns, take);
      n -= take;
      if ((run.count -= take) == 0) waiting_.pop_front();
    }
  }
  // Events pushed to a backend that is then dropped will not be labelled.
  void forget_waiting() { waiting_.clear(); }
  const LatencyHistogram& histogram() const { return histogram_; }

 private:
  struct Run {
    std::int64_t arrival_ns;
    std::int64_t count;
  };
  std::deque<Run> waiting_;
  LatencyHistogram histogram_;
};

}  // namespace evms::eval
