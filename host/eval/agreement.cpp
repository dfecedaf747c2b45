#include "host/eval/agreement.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace evms::eval {

Agreement agreement(std::span<const Event> events, const RunResult& reference, const RunResult& other, Chunking chunking) {
  Agreement a;
  ScoreAverage average;
  const std::span<const std::int32_t> ref(reference.labels), oth(other.labels);
  for (const auto& [begin, end] : chunk_ranges(events, chunking)) {
    if (end - begin >= 2) average.add(score(ref.subspan(begin, end - begin), oth.subspan(begin, end - begin)));
  }
  a.labels = average.mean();

  std::multimap<TimeUs, const TrackUpdate*> by_time;
  for (const TrackUpdate& u : reference.tracks) by_time.emplace(u.t, &u);
  std::vector<double> d;
  for (const TrackUpdate& u : other.tracks) {
    double best = 1e300;
    for (auto it = by_time.lower_bound(u.t - 2); it != by_time.end() && it->first <= u.t + 2; ++it) {
      best = std::min(best, std::hypot(u.x - it->second->x, u.y - it->second->y));
    }
    if (best <= 5.0) {
      d.push_back(best);
    } else {
      ++a.track_unmatched;
    }
  }
  a.track_matched = static_cast<std::int64_t>(d.size());
  if (!d.empty()) {
    double sum = 0;
    for (double v : d) sum += v;
    a.track_mean_px = sum / static_cast<double>(d.size());
    std::sort(d.begin(), d.end());
    a.track_median_px = d[d.size() / 2];
    a.track_p90_px = d[std::min(d.size() - 1, d.size() * 90 / 100)];
    a.track_p99_px = d[std::min(d.size() - 1, d.size() * 99 / 100)];
    a.track_max_px = d.back();
  }
  return a;
}

}  // namespace evms::eval
