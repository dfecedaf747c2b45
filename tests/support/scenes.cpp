#include "tests/support/scenes.h"

#include <algorithm>
#include <cmath>

namespace evms::test {

std::vector<Event> blob_events(const std::vector<Blob>& blobs, double rate, TimeUs t0, TimeUs duration,
                               SensorSize sensor, std::uint64_t seed, std::vector<int>* which) {
  gen::Random rng(seed);
  std::vector<Event> out;
  const auto n = static_cast<size_t>(rate * static_cast<double>(duration) * 1e-6);
  for (size_t i = 0; i < n; ++i) {
    const TimeUs t = t0 + static_cast<TimeUs>(static_cast<double>(i) * 1e6 / rate);
    const size_t b = i % blobs.size();
    const Blob& blob = blobs[b];
    const double s = static_cast<double>(t) * 1e-6;
    const double x = blob.x0 + blob.vx * s + blob.sigma * rng.normal();
    const double y = blob.y0 + blob.vy * s + blob.sigma * rng.normal();
    const long xi = std::lround(x), yi = std::lround(y);
    if (xi < 0 || yi < 0 || xi >= sensor.width || yi >= sensor.height) continue;
    out.push_back({t, static_cast<std::uint16_t>(xi), static_cast<std::uint16_t>(yi), static_cast<std::uint8_t>(rng.below(2))});
    if (which) which->push_back(static_cast<int>(b));
  }
  return out;
}

}  // namespace evms::test
