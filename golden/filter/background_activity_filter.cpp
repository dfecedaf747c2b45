#include "golden/filter/background_activity_filter.h"

#include <algorithm>
#include <limits>

namespace evms::golden {

BackgroundActivityFilter::BackgroundActivityFilter(SensorSize sensor, TimeUs window_us, int support, TimeUs warm_up_us,
                                                   std::int64_t noise_count, std::int64_t quiet_count, TimeUs quiet_window_us)
    : sensor_(sensor),
      window_us_(window_us),
      support_(support),
      warm_up_us_(warm_up_us),
      noise_count_(noise_count),
      quiet_count_(quiet_count),
      quiet_window_us_(quiet_window_us),
      stride_(static_cast<size_t>(sensor.width) + 2),
      last_fired_(stride_ * (static_cast<size_t>(sensor.height) + 2), kNever) {}

bool BackgroundActivityFilter::accept(const Event& e) {
  if (window_us_ == 0) return true;
  // The border pixels never fire, so a border event's missing neighbours give no support.
  const TimeUs* above = &last_fired(e.x - 1, e.y - 1);
  const TimeUs* row = above + stride_;
  const TimeUs* below = row + stride_;
  const auto fired_since = [&](TimeUs since) {
    return (above[0] >= since) + (above[1] >= since) + (above[2] >= since) + (row[0] >= since) + (row[2] >= since) +
           (below[0] >= since) + (below[1] >= since) + (below[2] >= since);
  };
  const int supporters = fired_since(e.t - window_us_);
  last_fired(e.x, e.y) = e.t;
  const TimeUs interval = e.t >> kFilterNoiseIntervalLog2;
  if (!started_) {
    started_ = true;
    warm_until_ = e.t + warm_up_us_;
    interval_ = interval;
  }
  if (interval != interval_) {
    noisy_ = noise_count_ > 0 && interval == interval_ + 1 && unsupported_ >= noise_count_;
    quiet_ = quiet_count_ > 0 && unsupported_ < quiet_count_;
    interval_ = interval, unsupported_ = 0;
  }
  unsupported_ += supporters == 0;
  // The own pixel, written above, is not among the neighbours fired_since reads.
  return (quiet_ ? fired_since(e.t - quiet_window_us_) : supporters) >= support_ + (noisy_ ? 1 : 0) || e.t < warm_until_;
}

int BackgroundActivityFilter::neighbours_fired_since(int x, int y, TimeUs since) const {
  return neighbours_fired_after(x, y, since - 1, std::numeric_limits<TimeUs>::max());
}

int BackgroundActivityFilter::neighbours_fired_after(int x, int y, TimeUs after, TimeUs until) const {
  int fired = 0;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const TimeUs t = last_fired(x + dx, y + dy);
      fired += (dx != 0 || dy != 0) && t > after && t <= until;
    }
  }
  return fired;
}

}  // namespace evms::golden
