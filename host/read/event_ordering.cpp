#include "host/read/event_ordering.h"

#include <algorithm>

namespace evms::read {

EventOrdering::EventOrdering(std::string path, SensorSize sensor, TimeUs tolerance_us)
    : path_(std::move(path)), sensor_(sensor), tolerance_us_(tolerance_us) {}

void EventOrdering::push(TimeUs t, long x, long y, int p, InputPosition where) {
  if (x < 0 || x >= sensor_.width || y < 0 || y >= sensor_.height) {
    fail(path_, where,
         "event at x=" + std::to_string(x) + " y=" + std::to_string(y) + " is outside the " +
             std::to_string(sensor_.width) + "x" + std::to_string(sensor_.height) +
             " sensor (set --width/--height if the size is wrong)");
  }
  const Event e{t, static_cast<std::uint16_t>(x), static_cast<std::uint16_t>(y),
                static_cast<std::uint8_t>(p != 0)};
  if (newest_ != INT64_MIN && t < newest_ && newest_ - t > tolerance_us_) {
    fail(path_, where,
         "timestamp " + std::to_string(t) + " us goes back " + std::to_string(newest_ - t) +
             " us, more than the reorder tolerance of " + std::to_string(tolerance_us_) +
             " us (--reorder-us)");
  }
  if (held_.empty() || t >= held_.back().t) {
    held_.push_back(e);
  } else {
    auto at = std::upper_bound(held_.begin(), held_.end(), t,
                               [](TimeUs v, const Event& h) { return v < h.t; });
    held_.insert(at, e);
    ++reordered_;
  }
  newest_ = std::max(newest_, t);
}

size_t EventOrdering::pop(std::span<Event> out) {
  size_t n = 0;
  while (n < out.size() && !held_.empty() &&
         (finished_ || newest_ - held_.front().t > tolerance_us_)) {
    out[n++] = held_.front();
    held_.pop_front();
  }
  return n;
}

}  // namespace evms::read
