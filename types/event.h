// The records that flow through every stage of evms: events in, labelled events and
// track updates out. Times are integer microseconds everywhere inside evms.
#pragma once

#include <cstdint>

namespace evms {

using TimeUs = std::int64_t;

// One address-event. Coordinates are pixel indices as the sensor stores them (no flips);
// p is 1 for ON (brightness up) and 0 for OFF.
struct Event {
  TimeUs t = 0;
  std::uint16_t x = 0;
  std::uint16_t y = 0;
  std::uint8_t p = 0;

  friend bool operator==(const Event&, const Event&) = default;
};

// The label a filtered event, a too-small cluster or an unassigned cluster carries.
inline constexpr std::int32_t kNoiseLabel = -1;

// The label of an event whose label the board's serial link destroyed (the board backend
// only, docs/link.md): the board labelled it, but the host never learnt how.
inline constexpr std::int32_t kLabelLostOnLink = -2;

// One output row per input event, in input order. label is the persistent track ID of the
// event's cluster, or kNoiseLabel (or kLabelLostOnLink).
struct LabelledEvent {
  Event event;
  std::int32_t label = kNoiseLabel;

  friend bool operator==(const LabelledEvent&, const LabelledEvent&) = default;
};

// A track is tentative until it has been measured confirm-hits times, then confirmed.
enum class TrackState : std::uint8_t { kTentative, kConfirmed };

// The filtered Kalman estimate of one track after a measurement update, and the cluster that
// measured it.
struct TrackUpdate {
  TimeUs t = 0;            // time of the measurement (mean timestamp of the events it was measured from)
  std::int32_t id = 0;     // persistent track ID, never reused
  double x = 0, y = 0;     // px
  double vx = 0, vy = 0;   // px/s
  double zx = 0, zy = 0;   // the raw measurement (--measure: centre of mass or polarity midpoint) of this update, px
  TrackState state = TrackState::kConfirmed;
  std::int32_t events = 0;                   // events of the cluster (labelled with this ID)
  std::int32_t x_min = 0, y_min = 0;         // the cluster's bounding box, px (inclusive)
  std::int32_t x_max = 0, y_max = 0;
  double var_x = 0, cov_xy = 0, var_y = 0;   // the estimate's position covariance, px^2
};

struct SensorSize {
  int width = 0;
  int height = 0;

  bool contains(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height; }
  friend bool operator==(const SensorSize&, const SensorSize&) = default;
};

}  // namespace evms
