// Where every decoder hands over its events: it checks them and restores time order.
//
// Policy (docs/formats.md):
//  - A coordinate outside the sensor is an error.
//  - Events may arrive out of time order by up to `tolerance_us` (sensor readout and USB
//    transfers interleave rows); they are re-sorted, stably, so equal timestamps keep their
//    file order. An event older than the newest seen so far by more than the tolerance is an
//    error: it means a timestamp reset, a corrupt record or a concatenated file.
//  - Timestamps lie in [0, 2^62] us; anything else is an error.
//  - Memory is bounded by the events that arrive within one tolerance window, and at most
//    kMaxHeldEvents of them (more is an error).
//  - Events that arrive in time order (almost all) wait in a FIFO, at O(1) each; only late ones
//    go to a heap, and the two are merged on the way out.
#pragma once

#include <cstdint>
#include <functional>
#include <queue>
#include <vector>
#include <span>
#include <string>

#include "types/event.h"
#include "host/read/input_error.h"

namespace evms::read {

// Events held at once for re-sorting: 16 M (384 MiB), far beyond the densest sensor's events in
// a tolerance window (25 M events/s x 1 ms = 25 k).
inline constexpr size_t kMaxHeldEvents = size_t{1} << 24;

// The largest timestamp a reader accepts, in microseconds.
inline constexpr TimeUs kMaxTimestampUs = TimeUs{1} << 62;

class EventOrdering {
 public:
  EventOrdering(std::string path, SensorSize sensor, TimeUs tolerance_us);

  void push(TimeUs t, long x, long y, int p, InputPosition where) {
    // The common case inline: a valid event no older than the newest goes to the ring.
    const bool valid = static_cast<unsigned long>(x) < static_cast<unsigned long>(sensor_.width) &&
                       static_cast<unsigned long>(y) < static_cast<unsigned long>(sensor_.height) && t >= newest_ && t <= kMaxTimestampUs &&
                       tail_ - head_ < in_order_.size();
    if (!valid) return push_checked(t, x, y, p, where);
    ring(tail_++) = {{t, static_cast<std::uint16_t>(x), static_cast<std::uint16_t>(y), static_cast<std::uint8_t>(p != 0)}, arrivals_++};
    newest_ = t;
  }
  // Moves out events that no later input can precede.
  size_t pop(std::span<Event> out);
  // End of input: everything held becomes final.
  void finish() { finished_ = true; }

  std::int64_t reordered() const { return reordered_; }

 private:
  std::string path_;
  SensorSize sensor_;
  TimeUs tolerance_us_;
  // Events not yet final, earliest first; the arrival number keeps equal timestamps in file
  // order. A heap, so that an event arriving late costs log(held) and not a shift of the rest.
  struct Held {
    Event event;
    std::uint64_t arrival;
    bool operator>(const Held& o) const { return event.t != o.event.t ? event.t > o.event.t : arrival > o.arrival; }
  };
  std::priority_queue<Held, std::vector<Held>, std::greater<>> held_;  // late events
  // Events in time order: a ring of a power-of-two size, from head_ to tail_ (free-running
  // counters), so that memory follows what is held and nothing is moved.
  std::vector<Held> in_order_ = std::vector<Held>(1024);
  size_t head_ = 0, tail_ = 0;
  Held& ring(size_t i) { return in_order_[i & (in_order_.size() - 1)]; }
  size_t held() const { return held_.size() + (tail_ - head_); }
  void push_checked(TimeUs t, long x, long y, int p, InputPosition where);
  std::uint64_t arrivals_ = 0;
  TimeUs newest_ = 0;  // no event is older than this without being late (timestamps are >= 0)
  bool finished_ = false;
  std::int64_t reordered_ = 0;
};

}  // namespace evms::read
