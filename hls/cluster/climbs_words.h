// The words a core cut after its climbs sends each packet's climbs frame (ClimbsFrame,
// hls/cluster/seeded_climbs.h) in: rtl/core/evms_climbs_core.sv's clm_kind and clm_data, which
// a board carries in the link's frames 0x88-0x8A (docs/link.md: a frame for the head and for each
// mode, and the events' words up to 32 a frame). A head, then a word a mode, then a word an
// event of the packet, in packet order. Fields from the word's top bit (80 bits:
// `top` holds bits 79-64, `low` bits 63-0):
//   head   n (16), modes (16), steps (16), climbs (16), modes lost (16)
//   mode   x (32), y (32), support (16)
//   event  the event's mode (16, -1: none)
#pragma once

#include <cstdint>

#include "hls/cluster/seeded_climbs.h"

namespace evms::hls {

enum class ClimbsWordKind : std::uint8_t { kHead = 0, kMode = 1, kEvent = 2 };

struct ClimbsWord {
  ClimbsWordKind kind = ClimbsWordKind::kHead;
  std::uint16_t top = 0;  // bits 79-64
  std::uint64_t low = 0;  // bits 63-0
};

// A word's fields, from its top bit: {n, modes, steps, climbs, modes lost} of a head, {x, y,
// support} of a mode, {mode} of an event; the rest 0.
inline void climbs_word_fields(const ClimbsWord& w, std::int64_t fields[5]) {
  for (int k = 0; k < 5; ++k) fields[k] = 0;
  switch (w.kind) {
    case ClimbsWordKind::kHead:
      fields[0] = w.top;
      for (int k = 1; k < 5; ++k) fields[k] = static_cast<std::int64_t>((w.low >> (64 - 16 * k)) & 0xFFFF);
      break;
    case ClimbsWordKind::kMode:
      fields[0] = (static_cast<std::int64_t>(w.top) << 16) | static_cast<std::int64_t>(w.low >> 48);
      fields[1] = static_cast<std::int64_t>((w.low >> 16) & 0xFFFFFFFF);
      fields[2] = static_cast<std::int64_t>(w.low & 0xFFFF);
      break;
    default: fields[0] = static_cast<std::int16_t>(w.top); break;
  }
}

// Builds climbs frames from their words. A word out of place (a mode or an event with no frame
// open, a head before the frame it ends is whole, more modes or events than its head gave, a
// head beyond the shape's packet or mode table, an event's mode beyond the frame's modes) breaks
// the frame: it is dropped, and the words up to the next head with it, and it counts once. A
// host that lost words on the line sees it here.
template <class S>
class ClimbsFrameAssembler {
 public:
  // Takes the next word; true when it makes the frame whole (frame() holds it until the next head).
  bool take(const ClimbsWord& w) {
    std::int64_t f[5];
    climbs_word_fields(w, f);
    if (w.kind == ClimbsWordKind::kHead) {
      if (open_) ++broken_;
      skipping_ = false;
      open_ = f[0] >= 1 && f[0] <= S::kPacketMax && f[1] <= S::kModesMax;
      if (!open_) return breaks();
      frame_.n = static_cast<int>(f[0]), frame_.mode_count = static_cast<int>(f[1]);
      frame_.trace.steps = static_cast<int>(f[2]), frame_.trace.climbs = static_cast<int>(f[3]), frame_.trace.modes_lost = static_cast<int>(f[4]);
      modes_ = events_ = 0;
    } else if (!open_) {
      return breaks();
    } else if (w.kind == ClimbsWordKind::kMode && modes_ < frame_.mode_count && events_ == 0) {
      frame_.x[modes_] = static_cast<std::uint32_t>(f[0]), frame_.y[modes_] = static_cast<std::uint32_t>(f[1]);
      frame_.support[modes_++] = static_cast<std::uint16_t>(f[2]);
    } else if (w.kind == ClimbsWordKind::kEvent && modes_ == frame_.mode_count && f[0] >= -1 && f[0] < frame_.mode_count) {
      frame_.first_mode[events_++] = static_cast<std::int16_t>(f[0]);
    } else {
      return breaks();
    }
    if (modes_ < frame_.mode_count || events_ < frame_.n) return false;
    open_ = false;
    return true;
  }
  const ClimbsFrame<S>& frame() const { return frame_; }
  // Frames broken so far; and whether a frame is open (part of it taken).
  long broken() const { return broken_; }
  bool open() const { return open_; }

 private:
  // A word out of place: the open frame, if any, is dropped; counted once until the next head.
  bool breaks() {
    if (!skipping_) ++broken_;
    open_ = false, skipping_ = true;
    return false;
  }

  ClimbsFrame<S> frame_;
  int modes_ = 0, events_ = 0;
  bool open_ = false, skipping_ = false;
  long broken_ = 0;
};

}  // namespace evms::hls
