#include "golden/filter/background_activity_filter.h"

#include <algorithm>

namespace evms::golden {

BackgroundActivityFilter::BackgroundActivityFilter(SensorSize sensor, TimeUs window_us, int support)
    : sensor_(sensor),
      window_us_(window_us),
      support_(support),
      last_fired_(static_cast<size_t>(sensor.width) * sensor.height, kNever) {}

bool BackgroundActivityFilter::accept(const Event& e) {
  if (window_us_ == 0) return true;
  const int x0 = std::max(0, e.x - 1), x1 = std::min(sensor_.width - 1, e.x + 1);
  const int y0 = std::max(0, e.y - 1), y1 = std::min(sensor_.height - 1, e.y + 1);
  int supporters = 0;
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      if (x == e.x && y == e.y) continue;
      TimeUs t = last_fired_[static_cast<size_t>(y) * sensor_.width + x];
      if (t != kNever && e.t - t <= window_us_) ++supporters;
    }
  }
  last_fired_[static_cast<size_t>(e.y) * sensor_.width + e.x] = e.t;
  return supporters >= support_;
}

int BackgroundActivityFilter::neighbours_fired_since(int x, int y, TimeUs since) const {
  int fired = 0;
  for (int ny = std::max(0, y - 1); ny <= std::min(sensor_.height - 1, y + 1); ++ny) {
    for (int nx = std::max(0, x - 1); nx <= std::min(sensor_.width - 1, x + 1); ++nx) {
      if ((nx != x || ny != y) && last_fired_[static_cast<size_t>(ny) * sensor_.width + nx] >= since) ++fired;
    }
  }
  return fired;
}

}  // namespace evms::golden
