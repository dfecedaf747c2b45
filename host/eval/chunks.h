// Chunks of an event sequence on which clustering is scored: N consecutive events (by
// default the packet size, so a chunk is about one packet), or fixed time windows.
#pragma once

#include <span>
#include <utility>
#include <vector>

#include "types/event.h"

namespace evms::eval {

struct Chunking {
  enum class Kind { kEvents, kTime } kind = Kind::kEvents;
  std::int64_t size = 256;  // events, or us
};

// Half-open index ranges [first, second) covering the events in order.
std::vector<std::pair<size_t, size_t>> chunk_ranges(std::span<const Event> events, Chunking c);

}  // namespace evms::eval
