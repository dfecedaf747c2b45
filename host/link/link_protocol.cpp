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

size_t expected_length(std::uint8_t type) {
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

void append_event(std::vector<std::uint8_t>& out, const hls::EventWord& e, Sequence seq) {
  std::vector<std::uint8_t> p;
  put(p, e.t, 4);
  put(p, e.x, 2);
  put(p, e.y, 2);
  put(p, e.p, 1);
  put(p, seq, 2);
  frame(out, kEvent, p);
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
    frames_.push_back({static_cast<FrameType>(type), std::vector<std::uint8_t>(body.begin() + 2, body.end())});
    buf_.erase(buf_.begin(), buf_.begin() + 6 + len);
  }
}

bool FrameDecoder::next(Frame& out) {
  if (frames_.empty()) return false;
  out = std::move(frames_.front());
  frames_.pop_front();
  return true;
}

hls::LabelWord decode_label(const Frame& f) {
  if (f.type == kVerdict) {
    // x and y in a byte each (the boards whose cores stop at the filter are 256x256 at most);
    // flags: bit 0 the polarity, bit 1 passed the filter.
    const std::uint32_t flags = get(f.payload, 6, 1);
    return {get(f.payload, 0, 4), static_cast<std::uint16_t>(get(f.payload, 4, 1)), static_cast<std::uint16_t>(get(f.payload, 5, 1)),
            static_cast<std::uint8_t>(flags & 1), (flags & 2) != 0 ? hls::kLabelPassedFilter : -1};
  }
  if (f.type != kLabel) throw std::logic_error("not a label frame");
  return {get(f.payload, 0, 4), static_cast<std::uint16_t>(get(f.payload, 4, 2)), static_cast<std::uint16_t>(get(f.payload, 6, 2)),
          static_cast<std::uint8_t>(get(f.payload, 8, 1)), static_cast<std::int32_t>(get(f.payload, 9, 4))};
}

Sequence label_sequence(const Frame& f) {
  if (f.type == kVerdict) return static_cast<Sequence>(get(f.payload, 7, 2));
  if (f.type != kLabel) throw std::logic_error("not a label frame");
  return static_cast<Sequence>(get(f.payload, 13, 2));
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

Progress decode_progress(const Frame& f) {
  if (f.type != kProgress) throw std::logic_error("not a progress frame");
  return {get(f.payload, 0, 4), get(f.payload, 4, 4), get(f.payload, 8, 4)};
}

}  // namespace evms::link
