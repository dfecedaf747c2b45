// EVT 3.0 word decoding, shared by RAW files (prophesee.cpp) and ROS 2 event packets with the
// encoding "evt3" (ros2_bag.cpp). 16-bit little-endian words, type in bits 15..12, decoded with
// state that carries across buffers:
//   0x0 ADDR_Y (y in 10..0)   0x2 ADDR_X (x in 10..0, polarity bit 11: one event)
//   0x3 VECT_BASE_X (x, polarity)   0x4 VECT_12 / 0x5 VECT_8: one event per set bit at base
//   x + i, then base x += 12 / 8   0x6 TIME_LOW / 0x8 TIME_HIGH: 12 bits each of a 24-bit time
//   that wraps at 2^24 us (a wrap is TIME_HIGH going down by more than half its range; a lone
//   TIME_LOW going down is not a wrap)   0xA trigger, 0xE others, 0x7 / 0xF continued: counted
// CD events before the first TIME_HIGH have no time base and are counted too. Any other word
// type is reserved.
#pragma once

#include <bit>
#include <cstdint>

#include "types/event.h"

namespace evms::read {

class Evt3Decoder {
 public:
  // `time_base_us`: added to every time (a multiple of 2^24 us that the words cannot hold).
  explicit Evt3Decoder(TimeUs time_base_us = 0) : epoch_(time_base_us) {}

  // Decodes one word. `sink` takes event(t_us, x, y, p) and skipped(const char* kind). Returns
  // false for a reserved word type, which the caller reports with its position.
  template <class Sink>
  bool word(std::uint16_t w, Sink& sink) {
    const unsigned payload = w & 0x0FFF;
    switch (w >> 12) {
      case 0x0: y_ = payload & 0x7FF; return true;
      case 0x2: event(payload & 0x7FF, payload >> 11, sink); return true;
      case 0x3: base_x_ = payload & 0x7FF, base_p_ = payload >> 11; return true;
      case 0x4: vector(payload, 12, sink); return true;
      case 0x5: vector(payload, 8, sink); return true;
      case 0x6: time_low_ = payload; return true;
      case 0x8:
        if (have_time_ && payload < time_high_ && time_high_ - payload > 0x800) epoch_ += TimeUs{1} << 24;
        time_high_ = payload;
        have_time_ = true;
        return true;
      case 0xA: sink.skipped("external triggers"); return true;
      case 0xE: sink.skipped("OTHERS words"); return true;
      case 0x7:
      case 0xF: sink.skipped("CONTINUED words"); return true;
      default: return false;
    }
  }

 private:
  template <class Sink>
  void vector(unsigned bits, int width, Sink& sink) {
    bits &= (1u << width) - 1;
    for (; bits != 0; bits &= bits - 1) event(base_x_ + static_cast<unsigned>(std::countr_zero(bits)), base_p_, sink);
    base_x_ += static_cast<unsigned>(width);
  }
  template <class Sink>
  void event(unsigned x, unsigned p, Sink& sink) {
    if (!have_time_) {
      sink.skipped("CD events before the first TIME_HIGH");
      return;
    }
    sink.event(epoch_ + (TimeUs{time_high_} << 12) + time_low_, x, y_, static_cast<int>(p));
  }

  bool have_time_ = false;
  unsigned time_high_ = 0, time_low_ = 0, y_ = 0, base_x_ = 0, base_p_ = 0;
  TimeUs epoch_ = 0;
};

}  // namespace evms::read
