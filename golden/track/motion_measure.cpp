#include "golden/track/motion_measure.h"

#include <algorithm>
#include <cmath>

namespace evms::golden {
namespace {

constexpr int kTrackInBoxMarginPx = 2;
constexpr double kMostMisfitKept = 0.5;
constexpr double kLeastSharePixelsKept = 0.5;  // of the cluster's pixels

}  // namespace

MotionMeasure::MotionMeasure(const Params& params, SensorSize sensor)
    : least_speed_(params.motion_measure), width_(sensor.width), slopes_(sensor),
      pixel_taken_(static_cast<size_t>(sensor.width) * sensor.height, 0) {}

void MotionMeasure::measure(std::span<const Event> events, std::span<const int> cluster_of, std::span<const TrackPrediction> tracks,
                            std::vector<Measurement>& measurements) {
  // Each cluster's fast track, if any, when another track lies in its box too.
  std::vector<const TrackPrediction*> track_of(measurements.size(), nullptr);
  bool any = false;
  for (size_t c = 0; c < measurements.size(); ++c) {
    const Measurement& m = measurements[c];
    const auto in_box = [&](const TrackPrediction& track) {
      const Eigen::Vector2d& p = track.position;
      return p.x() >= m.x_min - kTrackInBoxMarginPx && p.x() <= m.x_max + kTrackInBoxMarginPx && p.y() >= m.y_min - kTrackInBoxMarginPx &&
             p.y() <= m.y_max + kTrackInBoxMarginPx;
    };
    double nearest = INFINITY;
    const TrackPrediction* fast = nullptr;
    for (const TrackPrediction& track : tracks) {
      if (!track.matched || track.velocity.norm() < least_speed_ || !in_box(track)) continue;
      const double d = std::hypot(track.position.x() - m.x, track.position.y() - m.y);
      if (d < nearest) nearest = d, fast = &track;
    }
    if (fast && std::any_of(tracks.begin(), tracks.end(), [&](const TrackPrediction& t) { return &t != fast && in_box(t); })) {
      track_of[c] = fast, any = true;
    }
  }
  if (!any) return;
  slopes_.add(events);
  // Per cluster: its pixels (each counted for the first event on it, as the pixel centre does) and
  // those of its events the track's velocity explains (each counted once).
  std::vector<int> pixels(measurements.size(), 0), kept(measurements.size(), 0);
  std::vector<double> kept_x(measurements.size(), 0.0), kept_y(measurements.size(), 0.0);
  const auto pixel_of = [&](const Event& e) { return static_cast<size_t>(e.y) * static_cast<size_t>(width_) + e.x; };
  for (size_t i = 0; i < events.size(); ++i) {
    const int c = cluster_of[i];
    if (c < 0 || !track_of[static_cast<size_t>(c)]) continue;
    char& taken = pixel_taken_[pixel_of(events[i])];
    if (!(taken & 1)) taken |= 1, ++pixels[static_cast<size_t>(c)];
    if (taken & 2) continue;
    const std::optional<Eigen::Vector2d> slope = slopes_.at(events[i]);
    if (!slope || misfit(*slope, track_of[static_cast<size_t>(c)]->velocity) > kMostMisfitKept) continue;
    taken |= 2;
    kept_x[static_cast<size_t>(c)] += events[i].x, kept_y[static_cast<size_t>(c)] += events[i].y, ++kept[static_cast<size_t>(c)];
  }
  for (size_t i = 0; i < events.size(); ++i) pixel_taken_[pixel_of(events[i])] = 0;
  slopes_.clear();
  for (size_t c = 0; c < measurements.size(); ++c) {
    if (kept[c] > 0 && kept[c] >= kLeastSharePixelsKept * pixels[c]) measurements[c].x = kept_x[c] / kept[c], measurements[c].y = kept_y[c] / kept[c];
  }
}

}  // namespace evms::golden
