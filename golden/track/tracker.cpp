#include "golden/track/tracker.h"

#include <algorithm>
#include <tuple>

namespace evms::golden {

MultiTargetTracker::MultiTargetTracker(const Params& params)
    : params_(params), slots_(static_cast<size_t>(params.max_tracks)) {}

int MultiTargetTracker::live_tracks() const {
  return static_cast<int>(std::count_if(slots_.begin(), slots_.end(),
                                        [](const auto& s) { return s.has_value(); }));
}

std::vector<std::int32_t> MultiTargetTracker::step(TimeUs packet_time,
                                                   std::span<const Measurement> measurements,
                                                   std::vector<TrackUpdate>& updates) {
  for (auto& slot : slots_) {
    if (slot && packet_time - slot->filter.time() > params_.coast_us) slot.reset();
  }

  struct Candidate {
    double distance;
    size_t slot;
    size_t measurement;
  };
  std::vector<Candidate> candidates;
  for (size_t s = 0; s < slots_.size(); ++s) {
    if (!slots_[s]) continue;
    for (size_t m = 0; m < measurements.size(); ++m) {
      const Measurement& z = measurements[m];
      const double d = (slots_[s]->filter.predicted_position(z.t) - Eigen::Vector2d(z.x, z.y)).norm();
      if (d <= params_.gate_px) candidates.push_back({d, s, m});
    }
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return std::tie(a.distance, a.slot, a.measurement) <
           std::tie(b.distance, b.slot, b.measurement);
  });

  std::vector<std::int32_t> ids(measurements.size(), kNoiseLabel);
  std::vector<bool> slot_matched(slots_.size(), false);
  std::vector<bool> measurement_matched(measurements.size(), false);
  for (const Candidate& c : candidates) {
    if (slot_matched[c.slot] || measurement_matched[c.measurement]) continue;
    slot_matched[c.slot] = measurement_matched[c.measurement] = true;
    Track& track = *slots_[c.slot];
    const Measurement& z = measurements[c.measurement];
    track.filter.predict(z.t);
    track.filter.update(z.x, z.y);
    track.confirmed = track.confirmed || ++track.hits >= params_.confirm_hits;
    ids[c.measurement] = track.id;
    if (track.confirmed) {
      const auto& s = track.filter.state();
      updates.push_back({z.t, track.id, s(0), s(1), s(2), s(3), z.x, z.y});
    }
  }

  for (size_t s = 0; s < slots_.size(); ++s) {
    if (slots_[s] && !slot_matched[s] && !slots_[s]->confirmed) slots_[s].reset();
  }

  for (size_t m = 0; m < measurements.size(); ++m) {
    if (measurement_matched[m]) continue;
    auto free = std::find_if(slots_.begin(), slots_.end(), [](const auto& s) { return !s; });
    if (free == slots_.end()) {
      ++unassigned_clusters_;
      continue;
    }
    const Measurement& z = measurements[m];
    free->emplace(Track{next_id_++, KalmanFilter(z.x, z.y, z.t, params_), 1, false});
    Track& track = **free;
    track.confirmed = params_.confirm_hits <= 1;
    ids[m] = track.id;
    if (track.confirmed) updates.push_back({z.t, track.id, z.x, z.y, 0.0, 0.0, z.x, z.y});
  }
  return ids;
}

}  // namespace evms::golden
