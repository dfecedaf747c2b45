#pragma once

#include <string>
#include <vector>

#include "host/read/event_source.h"

namespace evms::test {

// Options with a sensor size and an out-of-order tolerance, the rest at their defaults.
inline read::SourceOptions sized(int width, int height, TimeUs reorder_us) {
  read::SourceOptions o;
  o.width = width, o.height = height, o.reorder_us = reorder_us;
  return o;
}

// Appends the events `source` gives to `all`; what came before an error it throws stays there.
// `batch_size` events at a time.
inline void read_into(read::EventSource& source, std::vector<Event>& all, size_t batch_size = 1000) {
  std::vector<Event> batch(batch_size);
  while (size_t n = source.read(batch)) all.insert(all.end(), batch.begin(), batch.begin() + static_cast<long>(n));
}

inline std::vector<Event> read_all(const std::string& path, const read::SourceOptions& o = {}) {
  auto source = read::open_source(path, o);
  std::vector<Event> all;
  read_into(*source, all);
  return all;
}

// The message of the InputError that reading `path` throws, or "" when it reads cleanly.
inline std::string read_error(const std::string& path, const read::SourceOptions& o = {}) {
  try {
    read_all(path, o);
  } catch (const read::InputError& e) {
    return e.what();
  }
  return "";
}

// The folder of real recordings next to the repository, or "" when it is absent.
std::string shared_data_dir();

}  // namespace evms::test
