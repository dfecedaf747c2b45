// Tracking accuracy against the objects' true centres, the way the paper measured it.
//
// Association of tracks to objects: at every update of a track, the object whose true centre
// (interpolated between the millisecond samples) is nearest votes for it, if it is within
// `association_radius_px`. A track belongs to the object with most votes (ties: the lower
// object index); tracks without a vote belong to none and are counted as spurious. An object
// may own several tracks in turn (after it left the view, say).
//
// For each object, every update of its tracks at a time when its true centre is known is one
// estimate, whose error is the distance to that centre. Reported side by side for the
// Kalman-filtered estimate and the raw cluster centroid of the same update. Coverage is the
// share of the object's true-centre samples that have one of its track updates within
// `coverage_window_us` before them.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "types/event.h"
#include "host/gen/scene_generator.h"

namespace evms::eval {

struct ErrorStats {
  std::int64_t samples = 0;
  double mean = 0, std = 0, within = 0;  // px, px, share within tau
};

struct ObjectTracking {
  int object = 0;
  std::vector<std::int32_t> tracks;  // IDs associated with the object
  ErrorStats kalman, raw;
  double velocity_error = 0;         // mean |v_kalman - v_true|, px/s (true: central difference)
  double coverage = 0;
};

struct TrackingReport {
  std::vector<ObjectTracking> objects;
  std::int64_t spurious_updates = 0;   // updates of tracks associated with no object
  ErrorStats all_kalman, all_raw;      // pooled over every object
  double velocity_error = 0;           // pooled, px/s
};

TrackingReport tracking_report(std::span<const TrackUpdate> updates, std::span<const gen::TruthSample> centres,
                               int objects, double tau_px = 2.5, double association_radius_px = 15.0,
                               TimeUs coverage_window_us = 20000);

}  // namespace evms::eval
