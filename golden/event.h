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

// One output row per input event, in input order. label is the persistent track ID of the
// event's cluster, or kNoiseLabel.
struct LabelledEvent {
  Event event;
  std::int32_t label = kNoiseLabel;

  friend bool operator==(const LabelledEvent&, const LabelledEvent&) = default;
};

// The filtered Kalman estimate of one track after a measurement update.
struct TrackUpdate {
  TimeUs t = 0;            // time of the measurement (mean timestamp of the cluster's events)
  std::int32_t id = 0;     // persistent track ID, never reused
  double x = 0, y = 0;     // px
  double vx = 0, vy = 0;   // px/s
  double zx = 0, zy = 0;   // the raw measurement (cluster centre of mass) of this update, px
};

struct SensorSize {
  int width = 0;
  int height = 0;

  bool contains(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height; }
  friend bool operator==(const SensorSize&, const SensorSize&) = default;
};

}  // namespace evms
