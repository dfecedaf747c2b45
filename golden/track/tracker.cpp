#include "golden/track/tracker.h"

#include <algorithm>
#include <limits>
#include <memory>
#include <tuple>

namespace evms::golden {

std::unique_ptr<Tracker> make_tracker(const Params& params, SensorSize sensor) {
  if (params.association == Association::kNearestCentre) return std::make_unique<NearestCentreIds>(params);
  Params on_sensor = params;  // the filters take the process noise of this sensor
  on_sensor.accel_psd = accel_psd_at(params, sensor);
  on_sensor.accel_psd_width = 0;
  return std::make_unique<MultiTargetTracker>(on_sensor);
}

MultiTargetTracker::MultiTargetTracker(const Params& params)
    : params_(params), slots_(static_cast<size_t>(params.max_tracks)) {}

int MultiTargetTracker::live_tracks() const {
  return static_cast<int>(std::count_if(slots_.begin(), slots_.end(),
                                        [](const auto& s) { return s.has_value(); }));
}

std::vector<TrackPrediction> MultiTargetTracker::confirmed_predictions(TimeUs t) const {
  std::vector<TrackPrediction> at;
  for (const auto& s : slots_) {
    if (s && s->confirmed) at.push_back({s->filter.predicted_position(t), s->filter.state().tail<2>(), s->missed == 0, s->id});
  }
  return at;
}

double MultiTargetTracker::gate(const Measurement& z) const {
  return std::max(params_.gate_px, params_.gate_spread * z.spread);
}

double MultiTargetTracker::measurement_variance(const Measurement& z) const {
  const double sigma2 = params_.meas_sigma_px * params_.meas_sigma_px;
  if (!params_.meas_noise_from_spread || z.events <= 0) return sigma2;
  // The spread is the events' RMS distance from their centre over both axes, from whole pixels;
  // a pixel's own width adds 1/12 px^2 an axis, which also keeps R above 0 for a cluster of
  // events on one pixel.
  return sigma2 * (z.spread * z.spread + 1.0 / 6.0) / z.events;
}

bool MultiTargetTracker::sizes_match(int track_events, int measurement_events) const {
  if (params_.size_ratio <= 0) return true;
  const double ratio = std::max(params_.size_ratio, 1.0);
  return std::max(track_events, measurement_events) <= ratio * std::min(track_events, measurement_events);
}

void MultiTargetTracker::report(const Track& track, const Measurement& z, std::vector<TrackUpdate>& updates) const {
  if (!track.confirmed && !params_.report_tentative) return;
  const auto& s = track.filter.state();
  const auto& p = track.filter.covariance();
  updates.push_back({z.t, track.id, s(0), s(1), s(2), s(3), z.x, z.y,
                     track.confirmed ? TrackState::kConfirmed : TrackState::kTentative, z.events, z.x_min, z.y_min, z.x_max,
                     z.y_max, p(0, 0), p(0, 1), p(1, 1)});
}

bool MultiTargetTracker::boxes_cover(const Track& track, const Measurement& z) const {
  return params_.gate_boxes && (z.box().holds(track.last_z.x(), track.last_z.y()) || track.last_box.holds(z.x, z.y));
}

std::optional<size_t> MultiTargetTracker::slot_for_new_track(const std::vector<bool>& matched) const {
  auto free = std::find_if(slots_.begin(), slots_.end(), [](const auto& s) { return !s; });
  if (free != slots_.end()) return static_cast<size_t>(free - slots_.begin());
  if (!params_.evict_stale) return std::nullopt;
  std::optional<size_t> stalest;
  for (size_t s = 0; s < slots_.size(); ++s) {
    if (matched[s]) continue;
    if (!stalest || slots_[s]->filter.time() < slots_[*stalest]->filter.time()) stalest = s;
  }
  return stalest;
}

std::vector<std::int32_t> MultiTargetTracker::step(TimeUs packet_time,
                                                   std::span<const Measurement> measurements,
                                                   std::vector<TrackUpdate>& updates) {
  for (auto& slot : slots_) {
    if (!slot) continue;
    const bool too_old = packet_time - slot->filter.time() > params_.coast_us;
    const bool too_many_missed = params_.coast_packets > 0 && slot->missed >= params_.coast_packets;
    if (too_old || too_many_missed) slot.reset();
  }

  struct Candidate {
    bool beyond_gate;   // a gate_boxes pair: taken only after every pair within the gate
    bool sizes_differ;  // taken only after every pair whose sizes match
    double distance;
    size_t slot;
    size_t measurement;
  };
  std::vector<Candidate> candidates;
  for (size_t s = 0; s < slots_.size(); ++s) {
    if (!slots_[s]) continue;
    for (size_t m = 0; m < measurements.size(); ++m) {
      const Measurement& z = measurements[m];
      const Eigen::Vector2d from = params_.association == Association::kLastMeasurement ? slots_[s]->last_z
                                                                                         : slots_[s]->filter.predicted_position(z.t);
      const double d = (from - Eigen::Vector2d(z.x, z.y)).norm();
      const bool within = d <= gate(z);
      if (within || boxes_cover(*slots_[s], z)) {
        candidates.push_back({!within, !sizes_match(slots_[s]->last_events, z.events), d, s, m});
      }
    }
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return std::tie(a.beyond_gate, a.sizes_differ, a.distance, a.slot, a.measurement) <
           std::tie(b.beyond_gate, b.sizes_differ, b.distance, b.slot, b.measurement);
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
    track.filter.update(z.x, z.y, measurement_variance(z));
    track.confirmed = track.confirmed || ++track.hits >= params_.confirm_hits;
    track.missed = 0;
    track.last_z = {z.x, z.y};
    track.last_events = z.events;
    track.last_box = z.box();
    ids[c.measurement] = track.id;
    report(track, z, updates);
  }

  for (size_t s = 0; s < slots_.size(); ++s) {
    if (!slots_[s] || slot_matched[s]) continue;
    if (slots_[s]->confirmed) ++slots_[s]->missed;
    else slots_[s].reset();
  }

  for (size_t m = 0; m < measurements.size(); ++m) {
    if (measurement_matched[m]) continue;
    const std::optional<size_t> slot = slot_for_new_track(slot_matched);
    if (!slot) {
      ++unassigned_clusters_;
      continue;
    }
    const Measurement& z = measurements[m];
    slots_[*slot].emplace(Track{next_id_++, KalmanFilter(z.x, z.y, z.t, params_), 1, params_.confirm_hits <= 1, 0, {z.x, z.y}, z.events, z.box()});
    slot_matched[*slot] = true;
    ids[m] = slots_[*slot]->id;
    report(*slots_[*slot], z, updates);
  }
  return ids;
}

std::vector<std::int32_t> NearestCentreIds::step(TimeUs, std::span<const Measurement> measurements,
                                                 std::vector<TrackUpdate>& updates) {
  std::vector<std::int32_t> ids(measurements.size(), kNoiseLabel);
  for (size_t m = 0; m < measurements.size(); ++m) {
    const Measurement& z = measurements[m];
    double best = params_.gate_px * params_.gate_px;
    for (size_t k = 0; k < previous_.size(); ++k) {
      const double d2 = (z.x - previous_[k].x) * (z.x - previous_[k].x) + (z.y - previous_[k].y) * (z.y - previous_[k].y);
      if (d2 < best) best = d2, ids[m] = previous_ids_[k];
    }
    if (ids[m] == kNoiseLabel) ids[m] = next_id_++;
    updates.push_back({z.t, ids[m], z.x, z.y, 0, 0, z.x, z.y, TrackState::kConfirmed, z.events, z.x_min, z.y_min, z.x_max, z.y_max,
                       0, 0, 0});
  }
  previous_.assign(measurements.begin(), measurements.end());
  previous_ids_ = ids;
  return ids;
}

}  // namespace evms::golden
