// Byte-level encoders of every input format, written from the format specifications (not
// from the readers), so that tests can build files with known contents and then corrupt
// them on purpose.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "golden/event.h"

namespace evms::test {

using Bytes = std::vector<std::uint8_t>;

std::string rpg_text(const std::vector<Event>& events);
std::string csv(const std::vector<Event>& events);
Bytes aedat2_dvs128(const std::vector<Event>& events);
Bytes aedat2_davis240(const std::vector<Event>& events);
Bytes aedat3_davis240(const std::vector<Event>& events);
enum class Aedat4Compression { kNone = 0, kLz4 = 1, kZstd = 3 };
Bytes aedat4(const std::vector<Event>& events, SensorSize sensor, Aedat4Compression c, size_t events_per_packet = 100);
Bytes evt2(const std::vector<Event>& events, SensorSize sensor);
Bytes evt3(const std::vector<Event>& events, SensorSize sensor);
Bytes dat(const std::vector<Event>& events);

// A temporary directory removed at the end of the test.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  std::string path(const std::string& name) const { return dir_ + "/" + name; }
  std::string write(const std::string& name, const std::string& text) const;
  std::string write(const std::string& name, const Bytes& bytes) const;

 private:
  std::string dir_;
};

// Events of a few moving dots, deterministic, in time order.
std::vector<Event> sample_events(size_t n, SensorSize sensor, std::uint64_t seed = 1);

}  // namespace evms::test
