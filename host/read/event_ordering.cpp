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
  // Timestamps are microseconds from the recording's (or the epoch's) start: negative ones and
  // ones beyond 2^62 us (146,000 years) are corrupt, and bounding them keeps every difference
  // of two timestamps from overflowing.
  if (t < 0 || t > kMaxTimestampUs) {
    fail(path_, where, "timestamp " + std::to_string(t) + " us is " + (t < 0 ? "negative" : "beyond 2^62 us"));
  }
  const Event e{t, static_cast<std::uint16_t>(x), static_cast<std::uint16_t>(y),
                static_cast<std::uint8_t>(p != 0)};
  if (newest_ != INT64_MIN && t < newest_ && newest_ - t > tolerance_us_) {
    fail(path_, where,
         "timestamp " + std::to_string(t) + " us goes back " + std::to_string(newest_ - t) +
             " us, more than the reorder tolerance of " + std::to_string(tolerance_us_) +
             " us (--reorder-us)");
  }
  if (held() >= kMaxHeldEvents) {
    fail(path_, where,
         "more than " + std::to_string(kMaxHeldEvents) + " events within the reorder tolerance of " + std::to_string(tolerance_us_) +
             " us (--reorder-us)");
  }
  if (newest_ != INT64_MIN && t < newest_) {
    ++reordered_;
    held_.push({t, arrivals_++, e});
    return;
  }
  in_order_.push_back({t, arrivals_++, e});
  newest_ = t;
}

size_t EventOrdering::pop(std::span<Event> out) {
  size_t n = 0;
  const auto final = [this](const Held& h) { return finished_ || newest_ - h.t > tolerance_us_; };
  while (n < out.size()) {
    const bool fifo = in_order_head_ < in_order_.size();
    // The earlier of the two fronts, (t, arrival) order: equal times leave in file order.
    if (fifo && (held_.empty() || held_.top() > in_order_[in_order_head_])) {
      if (!final(in_order_[in_order_head_])) break;
      out[n++] = in_order_[in_order_head_++].event;
    } else if (!held_.empty()) {
      if (!final(held_.top())) break;
      out[n++] = held_.top().event;
      held_.pop();
    } else {
      break;
    }
  }
  // Drop what left the FIFO once it is most of the buffer, so that memory follows what is held.
  if (in_order_head_ > 4096 && in_order_head_ * 2 > in_order_.size()) {
    in_order_.erase(in_order_.begin(), in_order_.begin() + static_cast<long>(in_order_head_));
    in_order_head_ = 0;
  }
  return n;
}

}  // namespace evms::read
