// Small synthetic inputs with known answers for the method's tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdlib>
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

// An edge swept over the pixels [x0, x1) x [y0, y1) at (vx, vy) px/s, one of vx and vy zero: each
// pixel fires once, when the edge reaches it.
inline std::vector<Event> swept_edge(int x0, int x1, int y0, int y1, double vx, double vy) {
  std::vector<Event> e;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      const double s = vx != 0 ? (vx > 0 ? x - x0 : x1 - 1 - x) / std::abs(vx) : (vy > 0 ? y - y0 : y1 - 1 - y) / std::abs(vy);
      e.push_back({static_cast<TimeUs>(std::lround(s * 1e6)), static_cast<std::uint16_t>(x), static_cast<std::uint16_t>(y), 1});
    }
  }
  return e;
}

struct SweptPacket {
  std::vector<Event> events;
  std::vector<int> object;  // per event: which edge fired it
};

// The events of `edges`, in time order.
inline SweptPacket swept_packet(const std::vector<std::vector<Event>>& edges) {
  SweptPacket p;
  for (size_t k = 0; k < edges.size(); ++k) {
    for (const Event& e : edges[k]) p.events.push_back(e), p.object.push_back(static_cast<int>(k));
  }
  std::vector<size_t> order(p.events.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return p.events[a].t < p.events[b].t; });
  SweptPacket sorted;
  for (size_t i : order) sorted.events.push_back(p.events[i]), sorted.object.push_back(p.object[i]);
  return sorted;
}

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
