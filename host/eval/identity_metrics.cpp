#include "host/eval/identity_metrics.h"

#include <algorithm>
#include <limits>
#include <map>
#include <vector>

namespace evms::eval {
namespace {

// The assignment of rows to distinct columns (rows <= columns) that maximizes the total weight:
// Hungarian method with potentials on the cost -weight. Returns the column of each row.
std::vector<int> max_weight_assignment(const std::vector<std::vector<double>>& weight) {
  const int n = static_cast<int>(weight.size());
  const int m = n ? static_cast<int>(weight[0].size()) : 0;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::vector<double> u(static_cast<size_t>(n + 1)), v(static_cast<size_t>(m + 1));
  std::vector<int> p(static_cast<size_t>(m + 1), 0), way(static_cast<size_t>(m + 1), 0);
  auto cost = [&](int i, int j) { return -weight[static_cast<size_t>(i - 1)][static_cast<size_t>(j - 1)]; };
  for (int i = 1; i <= n; ++i) {
    p[0] = i;
    int j0 = 0;
    std::vector<double> minv(static_cast<size_t>(m + 1), kInf);
    std::vector<bool> used(static_cast<size_t>(m + 1), false);
    do {
      used[static_cast<size_t>(j0)] = true;
      const int i0 = p[static_cast<size_t>(j0)];
      double delta = kInf;
      int j1 = 0;
      for (int j = 1; j <= m; ++j) {
        if (used[static_cast<size_t>(j)]) continue;
        const double cur = cost(i0, j) - u[static_cast<size_t>(i0)] - v[static_cast<size_t>(j)];
        if (cur < minv[static_cast<size_t>(j)]) minv[static_cast<size_t>(j)] = cur, way[static_cast<size_t>(j)] = j0;
        if (minv[static_cast<size_t>(j)] < delta) delta = minv[static_cast<size_t>(j)], j1 = j;
      }
      for (int j = 0; j <= m; ++j) {
        if (used[static_cast<size_t>(j)]) {
          u[static_cast<size_t>(p[static_cast<size_t>(j)])] += delta;
          v[static_cast<size_t>(j)] -= delta;
        } else {
          minv[static_cast<size_t>(j)] -= delta;
        }
      }
      j0 = j1;
    } while (p[static_cast<size_t>(j0)] != 0);
    do {
      const int j1 = way[static_cast<size_t>(j0)];
      p[static_cast<size_t>(j0)] = p[static_cast<size_t>(j1)];
      j0 = j1;
    } while (j0);
  }
  std::vector<int> column(static_cast<size_t>(n), -1);
  for (int j = 1; j <= m; ++j) {
    if (p[static_cast<size_t>(j)] > 0) column[static_cast<size_t>(p[static_cast<size_t>(j)] - 1)] = j - 1;
  }
  return column;
}

}  // namespace

IdentityScores identity_scores(std::span<const Event> events, std::span<const std::int32_t> truth, std::span<const std::int32_t> predicted,
                               TimeUs frame_us) {
  IdentityScores s;
  // Contingency of true objects and predicted IDs, over events that have both.
  std::map<std::int32_t, int> object_row, id_column;
  for (size_t i = 0; i < events.size(); ++i) {
    if (truth[i] >= 0) object_row.try_emplace(truth[i], static_cast<int>(object_row.size()));
    if (predicted[i] >= 0) id_column.try_emplace(predicted[i], static_cast<int>(id_column.size()));
  }
  s.objects = static_cast<std::int64_t>(object_row.size());
  // Relabel densely in order of first appearance.
  int r = 0, c = 0;
  for (auto& [key, row] : object_row) row = r++;
  for (auto& [key, col] : id_column) col = c++;
  const int columns = std::max(c, r);  // padded so that every object can be matched
  std::vector<std::vector<double>> common(static_cast<size_t>(r), std::vector<double>(static_cast<size_t>(columns), 0.0));
  double truth_events = 0, predicted_events = 0;
  for (size_t i = 0; i < events.size(); ++i) {
    truth_events += truth[i] >= 0;
    predicted_events += predicted[i] >= 0;
    if (truth[i] >= 0 && predicted[i] >= 0) {
      common[static_cast<size_t>(object_row[truth[i]])][static_cast<size_t>(id_column[predicted[i]])] += 1;
    }
  }
  double idtp = 0;
  const std::vector<int> match = max_weight_assignment(common);
  for (int row = 0; row < r; ++row) {
    if (match[static_cast<size_t>(row)] >= 0) idtp += common[static_cast<size_t>(row)][static_cast<size_t>(match[static_cast<size_t>(row)])];
  }
  const double idfp = predicted_events - idtp, idfn = truth_events - idtp;
  s.idf1 = idtp > 0 ? 2 * idtp / (2 * idtp + idfp + idfn) : 0.0;
  s.id_precision = predicted_events > 0 ? idtp / predicted_events : 0.0;
  s.id_recall = truth_events > 0 ? idtp / truth_events : 0.0;

  // Per object and frame, the ID most of its events carry (-1: mostly noise).
  struct Track {
    std::int32_t last_id = -1;
    bool gap = false;
  };
  std::vector<Track> tracks(static_cast<size_t>(r));
  size_t begin = 0;
  while (begin < events.size()) {
    const TimeUs frame = events[begin].t / frame_us;
    size_t end = begin;
    std::map<std::pair<int, std::int32_t>, int> votes;  // (object row, predicted ID) -> events
    for (; end < events.size() && events[end].t / frame_us == frame; ++end) {
      if (truth[end] >= 0) ++votes[{object_row[truth[end]], predicted[end]}];
    }
    std::vector<std::pair<int, std::int32_t>> frame_id(static_cast<size_t>(r), {0, -2});  // (votes, id); -2: absent
    for (const auto& [key, n] : votes) {
      auto& best = frame_id[static_cast<size_t>(key.first)];
      if (n > best.first || (n == best.first && key.second < best.second)) best = {n, key.second};
    }
    for (int row = 0; row < r; ++row) {
      const std::int32_t id = frame_id[static_cast<size_t>(row)].second;
      if (id == -2) continue;  // the object has no events in this frame
      Track& t = tracks[static_cast<size_t>(row)];
      if (id < 0) {
        t.gap = t.last_id >= 0;
        continue;
      }
      if (t.last_id >= 0 && id != t.last_id) ++s.id_switches;
      else if (t.last_id >= 0 && t.gap) ++s.fragmentations;
      t.last_id = id;
      t.gap = false;
    }
    begin = end;
  }
  return s;
}

}  // namespace evms::eval
