#include "host/read/event_ordering.h"

#include <algorithm>

namespace evms::read {

EventOrdering::EventOrdering(std::string path, SensorSize sensor, TimeUs tolerance_us)
    : path_(std::move(path)), sensor_(sensor), tolerance_us_(tolerance_us) {}

void EventOrdering::push_checked(TimeUs t, long x, long y, int p, InputPosition where) {
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
  if (t < newest_ && newest_ - t > tolerance_us_) {
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
  if (t < newest_) {
    ++reordered_;
    held_.push({e, arrivals_++});
    return;
  }
  if (tail_ - head_ == in_order_.size()) {
    // Full: double the ring, its events moved to the front in order.
    std::vector<Held> bigger(2 * in_order_.size());
    for (size_t i = head_; i < tail_; ++i) bigger[i - head_] = ring(i);
    in_order_.swap(bigger);
    tail_ -= head_;
    head_ = 0;
  }
  ring(tail_++) = {e, arrivals_++};
  newest_ = t;
}

size_t EventOrdering::pop(std::span<Event> out) {
  size_t n = 0;
  const auto final = [this](const Held& h) { return finished_ || newest_ - h.event.t > tolerance_us_; };
  while (n < out.size()) {
    if (held_.empty()) {
      // Only the ring: its final events leave in one run.
      while (n < out.size() && head_ < tail_ && final(ring(head_))) out[n++] = ring(head_++).event;
      break;
    }
    // The earlier of the two fronts, (t, arrival) order: equal times leave in file order.
    if (head_ < tail_ && held_.top() > ring(head_)) {
      if (!final(ring(head_))) break;
      out[n++] = ring(head_++).event;
    } else {
      if (!final(held_.top())) break;
      out[n++] = held_.top().event;
      held_.pop();
    }
  }
  return n;
}

}  // namespace evms::read
