#include "host/eval/chunks.h"

namespace evms::eval {

std::vector<std::pair<size_t, size_t>> chunk_ranges(std::span<const Event> events, Chunking c) {
  std::vector<std::pair<size_t, size_t>> out;
  if (events.empty()) return out;
  if (c.kind == Chunking::Kind::kEvents) {
    const auto n = static_cast<size_t>(c.size);
    for (size_t i = 0; i < events.size(); i += n) out.emplace_back(i, std::min(events.size(), i + n));
    return out;
  }
  size_t begin = 0;
  TimeUs window_end = events.front().t + c.size;
  for (size_t i = 0; i < events.size(); ++i) {
    while (events[i].t >= window_end) {
      if (i > begin) out.emplace_back(begin, i);
      begin = i;
      window_end += c.size;
    }
  }
  out.emplace_back(begin, events.size());
  return out;
}

}  // namespace evms::eval
