// Where every decoder hands over its events: it checks them and restores time order.
//
// Policy (docs/formats.md):
//  - A coordinate outside the sensor is an error.
//  - Events may arrive out of time order by up to `tolerance_us` (sensor readout and USB
//    transfers interleave rows); they are re-sorted, stably, so equal timestamps keep their
//    file order. An event older than the newest seen so far by more than the tolerance is an
//    error: it means a timestamp reset, a corrupt record or a concatenated file.
//  - Memory is bounded by the events that arrive within one tolerance window.
#pragma once

#include <deque>
#include <span>
#include <string>

#include "golden/event.h"
#include "host/read/input_error.h"

namespace evms::read {

class EventOrdering {
 public:
  EventOrdering(std::string path, SensorSize sensor, TimeUs tolerance_us);

  void push(TimeUs t, long x, long y, int p, InputPosition where);
  // Moves out events that no later input can precede.
  size_t pop(std::span<Event> out);
  // End of input: everything held becomes final.
  void finish() { finished_ = true; }

  std::int64_t reordered() const { return reordered_; }

 private:
  std::string path_;
  SensorSize sensor_;
  TimeUs tolerance_us_;
  std::deque<Event> held_;   // sorted by time
  TimeUs newest_ = INT64_MIN;
  bool finished_ = false;
  std::int64_t reordered_ = 0;
};

}  // namespace evms::read
