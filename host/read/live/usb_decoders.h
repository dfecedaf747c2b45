// The byte streams iniVation cameras send on their bulk IN endpoint, decoded as libcaer
// decodes them (facts in ../shared/notes/facts.md, from libcaer's dvs128.c and davis_common.h).
// A decoder is fed transfers of any length: a word split across two transfers is completed
// by the next one. Coordinates come out as libcaer delivers them (origin at the top left), so a
// live camera looks the same as its AEDAT 3.1 / 4.0 recordings.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "types/event.h"

namespace evms::read {

// What a decoder hands its consumer. `skip` counts records that are not polarity events.
struct DecodedSink {
  virtual ~DecodedSink() = default;
  virtual void event(TimeUs t, std::uint16_t x, std::uint16_t y, std::uint8_t p) = 0;
  virtual void skip(const char* kind) = 0;
};

// Gathers the bytes of fixed-size words across transfer boundaries.
template <size_t kWordBytes>
class WordAssembler {
 public:
  template <class OnWord>
  void feed(std::span<const std::uint8_t> bytes, OnWord&& on_word) {
    size_t i = 0;
    if (held_ > 0) {
      while (held_ < kWordBytes && i < bytes.size()) partial_[held_++] = bytes[i++];
      if (held_ < kWordBytes) return;
      on_word(partial_);
      held_ = 0;
    }
    for (; i + kWordBytes <= bytes.size(); i += kWordBytes) on_word(bytes.data() + i);
    while (i < bytes.size()) partial_[held_++] = bytes[i++];
  }
  size_t held() const { return held_; }

 private:
  std::uint8_t partial_[kWordBytes] = {};
  size_t held_ = 0;
};

// DVS128 (PID 0x8400): 4-byte events, a 16-bit LE address then a 16-bit LE timestamp.
//   byte 3 bit 7: timestamp wrap, add 0x4000 us;   byte 3 bit 6: timestamp reset to 0;
//   address bit 15: a synchronisation (external) event;
//   otherwise x = 127 - address[7:1], y = 127 - address[14:8], ON when address bit 0 is 0.
class Dvs128Decoder {
 public:
  explicit Dvs128Decoder(DecodedSink& sink) : sink_(sink) {}

  void feed(std::span<const std::uint8_t> bytes) {
    words_.feed(bytes, [this](const std::uint8_t* b) { word(b); });
  }
  TimeUs resets() const { return resets_; }

 private:
  void word(const std::uint8_t* b) {
    if (b[3] & 0x80) {
      wrap_ += 0x4000;
      return;
    }
    if (b[3] & 0x40) {
      wrap_ = 0;
      epoch_ = last_;  // time keeps increasing across the reset (see DavisDecoder)
      ++resets_;
      return;
    }
    const unsigned addr = b[0] | (b[1] << 8);
    const TimeUs t = epoch_ + wrap_ + (b[2] | (b[3] << 8));
    last_ = t;
    if (addr & 0x8000) {
      sink_.skip("synchronisation events");
      return;
    }
    sink_.event(t, static_cast<std::uint16_t>(127 - ((addr >> 1) & 0x7F)), static_cast<std::uint16_t>(127 - ((addr >> 8) & 0x7F)),
                static_cast<std::uint8_t>(!(addr & 1)));
  }

  DecodedSink& sink_;
  WordAssembler<4> words_;
  TimeUs wrap_ = 0, epoch_ = 0, last_ = 0, resets_ = 0;
};

// DAVIS (FX2 PID 0x841B, FX3 PID 0x841A): 16-bit LE words.
//   bit 15 set: timestamp, t = wrap base + word[14:0];
//   else code = word[14:12], data = word[11:0]:
//     0 special (data 1 = timestamp reset), 1 row (Y) address, 2/3 column (X) address with
//     OFF/ON, which emits an event at the last row, 4 APS sample, 5/6 IMU and other
//     miscellaneous data, 7 timestamp wrap: the base advances by 0x8000 * data.
// A timestamp reset restarts the camera's clock at 0; evms keeps its own time increasing
// across it, so that the ordering stage downstream sees no step back.
class DavisDecoder {
 public:
  explicit DavisDecoder(DecodedSink& sink) : sink_(sink) {}

  void feed(std::span<const std::uint8_t> bytes) {
    words_.feed(bytes, [this](const std::uint8_t* b) { word(static_cast<std::uint16_t>(b[0] | (b[1] << 8))); });
  }
  TimeUs resets() const { return resets_; }

 private:
  void word(std::uint16_t w) {
    if (w & 0x8000) {
      now_ = epoch_ + wrap_ + (w & 0x7FFF);
      return;
    }
    const unsigned code = (w >> 12) & 7, data = w & 0xFFF;
    switch (code) {
      case 0:
        if (data == 1) {
          epoch_ = now_, wrap_ = 0, ++resets_;
        } else {
          sink_.skip("special events");
        }
        break;
      case 1: row_ = data, have_row_ = true; break;
      case 2:
      case 3:
        if (!have_row_) {
          sink_.skip("column addresses before any row");
        } else {
          sink_.event(now_, static_cast<std::uint16_t>(data), static_cast<std::uint16_t>(row_), static_cast<std::uint8_t>(code == 3));
        }
        break;
      case 4: sink_.skip("APS samples"); break;
      case 5:
      case 6: sink_.skip("IMU and miscellaneous words"); break;
      case 7: wrap_ += TimeUs{0x8000} * data; break;
    }
  }

  DecodedSink& sink_;
  WordAssembler<2> words_;
  TimeUs wrap_ = 0, epoch_ = 0, now_ = 0, resets_ = 0;
  unsigned row_ = 0;
  bool have_row_ = false;
};

}  // namespace evms::read
