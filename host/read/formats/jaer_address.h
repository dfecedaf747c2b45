// jAER's 32-bit addresses and timestamps, as AEDAT 2.0 files and AEUnicast UDP streams carry
// them (big-endian {int32 address, int32 timestamp_us} records):
//   DVS128: bit 15 external, y = bits 14..8, x = bits 7..1, polarity = bit 0 (1 = ON)
//   DAVIS:  bit 31 type (0 = DVS), y = bits 30..22, x = bits 21..12, bits 11..10 subtype
//           (00 OFF, 10 ON, x1 external), bits 9..0 APS ADC
// Coordinates stay as jAER stores them: the origin is the sensor's lower left.
#pragma once

#include <cstdint>

#include "types/event.h"

namespace evms::read {

enum class JaerLayout { kDvs128, kDavis };

struct JaerAddress {
  enum class Kind { kPolarity, kExternal, kApsOrImu };
  Kind kind = Kind::kPolarity;
  std::uint32_t x = 0, y = 0;
  int p = 0;
};

inline JaerAddress decode_jaer_address(std::uint32_t addr, JaerLayout layout) {
  JaerAddress a;
  if (layout == JaerLayout::kDavis) {
    if (addr >> 31) {
      a.kind = JaerAddress::Kind::kApsOrImu;
    } else if (addr & (1u << 10)) {
      a.kind = JaerAddress::Kind::kExternal;
    } else {
      a.x = (addr >> 12) & 0x3FF, a.y = (addr >> 22) & 0x1FF, a.p = static_cast<int>((addr >> 11) & 1);
    }
  } else if (addr & (1u << 15)) {
    a.kind = JaerAddress::Kind::kExternal;
  } else {
    a.x = (addr >> 1) & 0x7F, a.y = (addr >> 8) & 0x7F, a.p = static_cast<int>(addr & 1);
  }
  return a;
}

// jAER's timestamps are 32-bit microseconds that wrap; each wrap (a step back of more than
// half the range) adds 2^32 us. Smaller steps back are left to the ordering stage.
class JaerClock {
 public:
  TimeUs extend(std::uint32_t ts) {
    if (have_last_ && ts < last_ && last_ - ts > (1u << 31)) wraps_ += std::int64_t{1} << 32;
    have_last_ = true;
    last_ = ts;
    return wraps_ + ts;
  }

 private:
  bool have_last_ = false;
  std::uint32_t last_ = 0;
  TimeUs wraps_ = 0;
};

}  // namespace evms::read
