#include "host/link/link_protocol.h"

#include <stdexcept>

namespace evms::link {
namespace {

void put(std::vector<std::uint8_t>& out, std::uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}

std::uint32_t get(const std::vector<std::uint8_t>& p, size_t at, int bytes) {
  std::uint32_t v = 0;
  for (int i = 0; i < bytes; ++i) v |= std::uint32_t{p.at(at + static_cast<size_t>(i))} << (8 * i);
  return v;
}

void frame(std::vector<std::uint8_t>& out, FrameType type, const std::vector<std::uint8_t>& payload) {
  std::vector<std::uint8_t> body = {type, static_cast<std::uint8_t>(payload.size())};
  body.insert(body.end(), payload.begin(), payload.end());
  const std::uint16_t c = crc16(body);
  out.push_back(0xA5);
  out.push_back(0x5A);
  out.insert(out.end(), body.begin(), body.end());
  put(out, c, 2);
}

constexpr size_t expected_length(std::uint8_t type) {
  switch (type) {
#define EVMS_LINK_FRAME_LENGTH(name, type, length, what) \
  case k##name:                                          \
    return length;
    EVMS_LINK_FRAMES(EVMS_LINK_FRAME_LENGTH)
#undef EVMS_LINK_FRAME_LENGTH
    default: return 256;  // unknown
  }
}

}  // namespace

std::uint16_t crc16(std::span<const std::uint8_t> bytes) {
  std::uint16_t c = 0xFFFF;
  for (std::uint8_t b : bytes) {
    c ^= static_cast<std::uint16_t>(b << 8);
    for (int k = 0; k < 8; ++k) c = (c & 0x8000) ? static_cast<std::uint16_t>((c << 1) ^ 0x1021) : static_cast<std::uint16_t>(c << 1);
  }
  return c;
}

std::uint32_t pack_entry(const BatchEntry& e) {
  return std::uint32_t{e.x} | std::uint32_t{e.y} << 8 | std::uint32_t{e.p & 1u} << 16 | std::uint32_t{e.passed} << 17 |
         std::uint32_t{e.present} << 18 | e.gap << (32 - kBatchGapBits);
}

BatchEntry unpack_entry(std::uint32_t word) {
  return {static_cast<std::uint8_t>(word & 0xFF), static_cast<std::uint8_t>((word >> 8) & 0xFF), static_cast<std::uint8_t>((word >> 16) & 1),
          ((word >> 17) & 1) != 0, ((word >> 18) & 1) != 0, word >> (32 - kBatchGapBits)};
}

void append_events(std::vector<std::uint8_t>& out, std::span<const hls::EventWord> events, Sequence first) {
  for (size_t i = 0; i < events.size();) {
    std::vector<std::uint8_t> p;
    put(p, events[i].t, 4);
    put(p, static_cast<Sequence>(first + i), 2);
    std::uint32_t previous = events[i].t;
    for (int k = 0; k < kBatchEntries && i < events.size(); ++k, ++i) {
      const hls::EventWord& e = events[i];
      const std::uint32_t gap = e.t - previous;
      if (k > 0 && gap > kBatchGapMax) break;  // the next frame starts at this event's time
      if (e.x > 0xFF || e.y > 0xFF) throw std::invalid_argument("an events frame carries x and y in a byte each (boards of 256x256 at most)");
      put(p, pack_entry({static_cast<std::uint8_t>(e.x), static_cast<std::uint8_t>(e.y), e.p, false, true, gap}), kBatchEntryBytes);
      previous = e.t;
    }
    frame(out, kEvents, p);
  }
}

void append_flush(std::vector<std::uint8_t>& out, Sequence next_event) {
  std::vector<std::uint8_t> p;
  put(p, next_event, 2);
  frame(out, kFlush, p);
}
void append_reset(std::vector<std::uint8_t>& out, LinkMode mode) { frame(out, kReset, {static_cast<std::uint8_t>(mode)}); }

void FrameDecoder::push(std::span<const std::uint8_t> bytes) {
  buf_.insert(buf_.end(), bytes.begin(), bytes.end());
  for (;;) {
    // Hunt for the sync pair.
    while (buf_.size() >= 2 && !(buf_[0] == 0xA5 && buf_[1] == 0x5A)) buf_.pop_front();
    if (buf_.size() < 4) return;
    const std::uint8_t type = buf_[2], len = buf_[3];
    if (expected_length(type) != len) {
      ++bad_;
      buf_.pop_front();
      continue;
    }
    if (buf_.size() < 6u + len) return;
    std::vector<std::uint8_t> body(buf_.begin() + 2, buf_.begin() + 4 + len);
    const std::uint16_t got = static_cast<std::uint16_t>(buf_[4 + len] | (buf_[5 + len] << 8));
    if (crc16(body) != got) {
      ++bad_;
      buf_.pop_front();
      continue;
    }
    frames_.push_back({static_cast<FrameType>(type), std::vector<std::uint8_t>(body.begin() + 2, body.end()), bad_});
    buf_.erase(buf_.begin(), buf_.begin() + 6 + len);
  }
}

bool FrameDecoder::next(Frame& out) {
  if (frames_.empty()) return false;
  out = std::move(frames_.front());
  frames_.pop_front();
  return true;
}

std::vector<NumberedLabel> decode_labels(const Frame& f) {
  if (f.type == kLabel) {
    return {{static_cast<Sequence>(get(f.payload, 13, 2)),
             {get(f.payload, 0, 4), static_cast<std::uint16_t>(get(f.payload, 4, 2)), static_cast<std::uint16_t>(get(f.payload, 6, 2)),
              static_cast<std::uint8_t>(get(f.payload, 8, 1)), static_cast<std::int32_t>(get(f.payload, 9, 4))}}};
  }
  if (f.type != kVerdict) throw std::logic_error("not a label or verdict frame");
  static_assert(expected_length(kVerdict) == kBatchHeaderBytes + kBatchEntries * kBatchEntryBytes &&
                    expected_length(kEvents) == expected_length(kVerdict),
                "host/link/link_frames.h: a batch of kBatchEntries fills the longest events frame and every verdict frame");
  std::vector<NumberedLabel> out;
  std::uint32_t t = get(f.payload, 0, 4);
  const auto first = static_cast<Sequence>(get(f.payload, 4, 2));
  for (int k = 0; k < kBatchEntries; ++k) {
    const std::uint32_t word = get(f.payload, static_cast<size_t>(kBatchHeaderBytes + k * kBatchEntryBytes), kBatchEntryBytes);
    const BatchEntry e = unpack_entry(word);
    if (!e.present) {
      if (word != 0) return {};  // an absent entry is all zeros
      continue;
    }
    // The present entries come first, and the first is at the frame's own time.
    if (static_cast<int>(out.size()) != k || (k == 0 && e.gap != 0)) return {};
    t += e.gap;
    out.push_back({static_cast<Sequence>(first + k), {t, e.x, e.y, e.p, e.passed ? hls::kLabelPassedFilter : -1}});
  }
  return out;
}

Sequence decode_resend(const Frame& f) {
  if (f.type != kResend) throw std::logic_error("not a resend frame");
  return static_cast<Sequence>(get(f.payload, 0, 2));
}

hls::TrackWord decode_track(const Frame& f) {
  if (f.type != kTrack) throw std::logic_error("not a track frame");
  auto s = [&](size_t i) { return static_cast<std::int32_t>(get(f.payload, 4 * i, 4)); };
  hls::TrackWord w{get(f.payload, 0, 4), s(1), s(2), s(3), s(4), s(5), s(6), s(7)};
  w.confirmed = (get(f.payload, 32, 1) & 1) != 0;
  return w;
}

hls::PacketWord decode_packet(const Frame& f) {
  if (f.type != kPacket) throw std::logic_error("not a packet frame");
  return {get(f.payload, 0, 4), get(f.payload, 4, 4), static_cast<std::uint16_t>(get(f.payload, 8, 2)),
          static_cast<std::uint8_t>(get(f.payload, 10, 1)), static_cast<std::uint8_t>(get(f.payload, 11, 1))};
}

Status decode_status(const Frame& f) {
  if (f.type != kStatus) throw std::logic_error("not a status frame");
  auto u = [&](size_t i) { return get(f.payload, 4 * i, 4); };
  return {u(0), u(1), u(2), u(3), u(4), u(5), u(6), u(7), u(8), u(9), u(10)};
}

std::vector<hls::ClimbsWord> decode_climbs(const Frame& f) {
  if (f.type != kClimbsHead && f.type != kClimbsMode && f.type != kClimbsEvents) throw std::logic_error("not a climbs frame");
  if (f.type == kClimbsEvents) {
    static_assert(expected_length(kClimbsEvents) == kBatchEntries, "host/link/link_frames.h: a climbs events frame holds a batch");
    std::vector<hls::ClimbsWord> out;
    for (int k = 0; k < kBatchEntries; ++k) {
      const auto entry = static_cast<std::uint8_t>(get(f.payload, static_cast<size_t>(k), 1));
      if ((entry & kClimbsEntryPresent) == 0) {
        if (entry != 0) return {};  // an absent entry is all zeros
        continue;
      }
      if (static_cast<int>(out.size()) != k) return {};  // the present entries come first
      // Bits 6-0 in two's complement: the mode, -64 to 63, in the word's 16 bits.
      const auto mode = static_cast<std::int16_t>(static_cast<std::int8_t>(static_cast<std::uint8_t>(entry << 1)) >> 1);
      out.push_back({hls::ClimbsWordKind::kEvent, static_cast<std::uint16_t>(mode), 0});
    }
    return out;
  }
  const hls::ClimbsWordKind kind = f.type == kClimbsHead ? hls::ClimbsWordKind::kHead : hls::ClimbsWordKind::kMode;
  const std::uint64_t low = std::uint64_t{get(f.payload, 2, 4)} | std::uint64_t{get(f.payload, 6, 4)} << 32;
  return {{kind, static_cast<std::uint16_t>(get(f.payload, 0, 2)), low}};
}

Progress decode_progress(const Frame& f) {
  if (f.type != kProgress) throw std::logic_error("not a progress frame");
  return {get(f.payload, 0, 4), get(f.payload, 4, 4), get(f.payload, 8, 4)};
}

}  // namespace evms::link
