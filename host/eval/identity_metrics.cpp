#include "host/eval/identity_metrics.h"

#include <algorithm>
#include <map>
#include <vector>

#include "host/eval/assignment.h"

namespace evms::eval {

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
  std::vector<std::vector<double>> common(static_cast<size_t>(r), std::vector<double>(static_cast<size_t>(c), 0.0));
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
