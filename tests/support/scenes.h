// Small synthetic inputs with known answers for the method's tests.
#pragma once

#include <vector>

#include "types/event.h"
#include "types/output.h"
#include "host/gen/random.h"

namespace evms::test {

// The DAVIS240C's sensor, which most of the method's tests use.
inline constexpr SensorSize kSensor{240, 180};

// The events of `a`, then those of `b`.
inline std::vector<Event> concat(std::vector<Event> a, const std::vector<Event>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// A Gaussian blob of events around a centre moving at constant velocity.
struct Blob {
  double x0, y0;          // px at t = 0
  double vx = 0, vy = 0;  // px/s
  double sigma = 3.0;     // px
};

// `rate` events per second spread over the blobs in turn, from t0 for `duration` us.
std::vector<Event> blob_events(const std::vector<Blob>& blobs, double rate, TimeUs t0, TimeUs duration,
                               SensorSize sensor, std::uint64_t seed, std::vector<int>* which = nullptr);

// Collects every output.
struct CollectingSink final : OutputSink {
  std::vector<LabelledEvent> events;
  std::vector<TrackUpdate> tracks;
  std::vector<PacketSummary> packets;
  void on_event(const LabelledEvent& e) override { events.push_back(e); }
  void on_track(const TrackUpdate& u) override { tracks.push_back(u); }
  void on_packet(const PacketSummary& p) override { packets.push_back(p); }
};

}  // namespace evms::test
