// Prophesee recordings. Both kinds start with ASCII header lines "% key value".
//  - RAW (.raw): "% evt 2.0" / "% evt 2.1" / "% evt 3.0" or "% format EVT2|EVT21|EVT3;width=..;height=..",
//    optionally "% geometry WxH", optionally closed by "% end"; then little-endian words.
//  - DAT (.dat): "% Version 2" and friends, then two bytes {event type, event size} and
//    8-byte records {uint32 t_us, uint32 x:14 | y:14 << 14 | p:1 << 28}.
//
// EVT 2.0: 32-bit words, type in bits 31..28.
//   0x0 CD_OFF / 0x1 CD_ON: ts[5:0] in 27..22, x in 21..11, y in 10..0
//   0x8 EVT_TIME_HIGH: ts[33:6] in 27..0 (wraps at 2^34 us)
//   0xA external trigger, 0xE others, 0xF continued: not polarity events (counted)
// EVT 2.1: 64-bit words, each an EVT 2.0 word (its x the base of a vector) and a 32-bit mask:
//   bit i of a CD word's mask is an event at (x + i, y), in ascending i. The two 32-bit halves
//   are stored as little-endian words in one of two orders, which the header names:
//   "endianness=legacy" (the IMX636's: the EVT 2.0 half first, then the mask) or "little" (the
//   whole 64-bit word little-endian: the mask first; Metavision's default for EVT21). A
//   "% evt 2.1" header without a format line is the IMX636's, legacy. A stream starts with a
//   TIME_HIGH word, whose other half is 0: when the first word reads as a zero half beside a
//   TIME_HIGH, the words are in the other order, and are read so.
// EVT 3.0: 16-bit words, decoded with state (evt3_decoder.h).
// In EVT 2.0, CD events before the first TIME_HIGH have no time base and are counted as skipped.
// Any other word type is reserved and means the file is not what its header says: an error.
#include <bit>
#include <charconv>
#include <cstdio>
#include <cstring>

#include "host/read/bytes.h"
#include "host/read/event_source.h"
#include "host/read/formats/evt3_decoder.h"

namespace evms::read {
namespace {

// Words are decoded a block at a time from the reader's buffer.
constexpr size_t kBlockBytes = 1 << 14;

struct PropheseeHeader {
  enum class Kind { kEvt2, kEvt21, kEvt3, kDat, kUnknown } kind = Kind::kUnknown;
  bool mask_first = false;  // EVT 2.1 halves in "little" order
  std::optional<SensorSize> size;
  std::string plugin;
  bool dat_markers = false;
  TimeUs time_base_us = 0;  // "% evms_time_base_us N", which evms's EVT 3.0 writer adds
};

std::optional<int> key_int(std::string_view text, std::string_view key) {
  size_t at = text.find(key);
  if (at == std::string_view::npos) return std::nullopt;
  text = text.substr(at + key.size());
  int v = 0;
  auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc()) return std::nullopt;
  return v;
}

PropheseeHeader read_header(ByteReader& in) {
  PropheseeHeader h;
  std::optional<int> width, height;
  std::string_view line;
  while (in.peek(1) == "%") {
    in.next_line(line);
    std::string_view body = line.substr(1);
    while (!body.empty() && body.front() == ' ') body.remove_prefix(1);
    if (body == "end") break;
    const bool evt21 = body.rfind("evt 2.1", 0) == 0;
    if ((body.rfind("evt 2", 0) == 0 && !evt21) || body.find("format EVT2;") != std::string_view::npos || body == "format EVT2") {
      h.kind = PropheseeHeader::Kind::kEvt2;
    }
    if (evt21) h.kind = PropheseeHeader::Kind::kEvt21;
    if (body.find("format EVT21") != std::string_view::npos) h.kind = PropheseeHeader::Kind::kEvt21, h.mask_first = true;
    if (body.find("endianness=legacy") != std::string_view::npos || body == "endianness legacy") h.mask_first = false;
    if (body.find("endianness=little") != std::string_view::npos || body == "endianness little") h.mask_first = true;
    if (body.rfind("evt 3", 0) == 0 || body.find("format EVT3") != std::string_view::npos) h.kind = PropheseeHeader::Kind::kEvt3;
    if (body.rfind("evt ", 0) == 0 && h.kind == PropheseeHeader::Kind::kUnknown) {
      fail(in.path(), InputPosition::line(in.line()), "bad header: unsupported encoding '" + std::string(body) + "' (EVT 2.0, 2.1 and 3.0 are supported)");
    }
    if (body.rfind("Version", 0) == 0 || body.rfind("Data file", 0) == 0) h.dat_markers = true;
    if (auto w = key_int(body, "width=")) width = w;
    if (auto v = key_int(body, "height=")) height = v;
    if (body.rfind("geometry ", 0) == 0) {
      int gw = 0, gh = 0;
      if (std::sscanf(std::string(body).c_str(), "geometry %dx%d", &gw, &gh) == 2) width = gw, height = gh;
    }
    if (body.rfind("Width ", 0) == 0) width = key_int(body, "Width ");
    if (body.rfind("Height ", 0) == 0) height = key_int(body, "Height ");
    if (body.rfind("plugin_name ", 0) == 0) h.plugin = std::string(body.substr(12));
    if (body.rfind("evms_time_base_us ", 0) == 0) {
      const std::string_view v = body.substr(18);
      const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), h.time_base_us);
      if (ec != std::errc() || end != v.data() + v.size() || h.time_base_us < 0 || h.time_base_us % (TimeUs{1} << 24) != 0) {
        fail(in.path(), InputPosition::line(in.line()), "bad header: evms_time_base_us must be a multiple of 2^24 us");
      }
    }
  }
  if (width && height && *width > 0 && *height > 0) h.size = SensorSize{*width, *height};
  if (h.kind == PropheseeHeader::Kind::kUnknown && h.dat_markers) h.kind = PropheseeHeader::Kind::kDat;
  return h;
}

// Cameras whose RAW headers carry no geometry: the plugin names the sensor generation.
std::optional<SensorSize> size_of_plugin(const std::string& plugin) {
  if (plugin.find("gen41") != std::string::npos || plugin.find("imx636") != std::string::npos) return SensorSize{1280, 720};
  if (plugin.find("gen3") != std::string::npos) return SensorSize{640, 480};
  if (plugin.find("genx320") != std::string::npos) return SensorSize{320, 320};
  return std::nullopt;
}

// A RAW recording: its sensor from the header's geometry or its plugin's name, and its words
// a block at a time, straight from the reader's buffer.
class RawSource : public FileEventSource {
 public:
  RawSource(ByteReader in, std::string format, const SourceOptions& o, const PropheseeHeader& h)
      : FileEventSource(std::move(in), std::move(format), o) {
    const std::optional<SensorSize> from_plugin = size_of_plugin(h.plugin);
    set_sensor(h.size ? h.size : from_plugin, std::nullopt, "");
    if (!h.size && from_plugin && options_.width == 0) info_.sensor_origin = "plugin name in header";
  }

 protected:
  // The next block of whole words (empty at the end); a piece of a word at the end is an error.
  std::string_view next_words(size_t word_bytes) {
    const std::string_view block = in_.peek(kBlockBytes);
    if (!block.empty() && block.size() < word_bytes) {
      fail(in_.path(), InputPosition::byte(in_.offset()),
           "truncated word (" + std::to_string(block.size()) + " of " + std::to_string(word_bytes) + " bytes)");
    }
    return block.substr(0, block.size() - block.size() % word_bytes);
  }
  static std::string hex(unsigned v) {
    char b[8];
    std::snprintf(b, sizeof b, "%X", v);
    return b;
  }
};

// EVT 2.0 and EVT 2.1: a 2.1 word is a 2.0 word and a mask of the events at x, x + 1, ...
class Evt2Source final : public RawSource {
 public:
  Evt2Source(ByteReader in, const SourceOptions& o, const PropheseeHeader& h)
      : RawSource(std::move(in), h.kind == PropheseeHeader::Kind::kEvt21 ? "EVT 2.1 RAW" : "EVT 2.0 RAW", o, h),
        vectors_(h.kind == PropheseeHeader::Kind::kEvt21),
        first_word_at_(in_.offset()),
        word_bytes_(vectors_ ? 8 : 4),
        head_at_(h.mask_first ? 4 : 0) {}

 protected:
  bool decode_more() override {
    const std::uint64_t base = in_.offset();
    const std::string_view block = next_words(word_bytes_);
    if (block.empty()) return false;
    const size_t words = block.size() / word_bytes_;
    const auto* bytes = reinterpret_cast<const unsigned char*>(block.data());
    if (vectors_ && base == first_word_at_ && le32(bytes + head_at_) == 0 && (le32(bytes + (4 - head_at_)) >> 28) == 0x8) head_at_ = 4 - head_at_;
    for (size_t i = 0; i < words; ++i) {
      const std::uint64_t at = base + word_bytes_ * i;
      const unsigned char* w = bytes + word_bytes_ * i;
      const std::uint32_t word = le32(w + head_at_);
      switch (word >> 28) {
        case 0x0:
        case 0x1:
          if (!have_time_) {
            count_skipped("CD events before the first TIME_HIGH");
          } else {
            const TimeUs t = time_high_ | ((word >> 22) & 0x3F);
            const int x = static_cast<int>((word >> 11) & 0x7FF), y = static_cast<int>(word & 0x7FF);
            if (!vectors_) {
              emit(t, x, y, word >> 28, InputPosition::byte(at));
            } else {
              for (std::uint32_t mask = le32(w + (4 - head_at_)); mask != 0; mask &= mask - 1) {
                emit(t, x + std::countr_zero(mask), y, word >> 28, InputPosition::byte(at));
              }
            }
          }
          break;
        case 0x8: {
          const TimeUs high = static_cast<TimeUs>(word & 0x0FFFFFFF) << 6;
          // A wrap drops from the top of the 34-bit range to its bottom; a small step back is
          // a real step back in time, for the ordering stage to judge.
          if (have_time_ && (time_high_ & kMask) - high > (kMask >> 1)) epoch_ += kMask + 1;
          time_high_ = epoch_ + high;
          have_time_ = true;
          break;
        }
        case 0xA: count_skipped("external triggers"); break;
        case 0xE: count_skipped("OTHERS words"); break;
        case 0xF: count_skipped("CONTINUED words"); break;
        default:
          fail(in_.path(), InputPosition::byte(at), std::string("reserved ") + (vectors_ ? "EVT 2.1" : "EVT 2.0") + " word type 0x" + hex(word >> 28) +
                                                        (vectors_ ? std::string(" (is the header's endianness, ") + (head_at_ ? "little" : "legacy") + ", the file's?)" : ""));
      }
    }
    in_.skip(words * word_bytes_);
    return true;
  }

 private:
  static constexpr TimeUs kMask = (TimeUs{1} << 34) - 1;
  const bool vectors_;
  const std::uint64_t first_word_at_;
  const size_t word_bytes_;
  size_t head_at_;  // the byte of the EVT 2.0 half in a word
  bool have_time_ = false;
  TimeUs time_high_ = 0;
  TimeUs epoch_ = 0;
};

class Evt3Source final : public RawSource {
 public:
  Evt3Source(ByteReader in, const SourceOptions& o, const PropheseeHeader& h)
      : RawSource(std::move(in), "EVT 3.0 RAW", o, h), decoder_(h.time_base_us) {}

 protected:
  bool decode_more() override {
    const std::uint64_t base = in_.offset();
    const std::string_view block = next_words(2);
    if (block.empty()) return false;
    const size_t words = block.size() / 2;
    const auto* bytes = reinterpret_cast<const unsigned char*>(block.data());
    for (size_t i = 0; i < words; ++i) {
      sink_.at = base + 2 * i;
      if (!decoder_.word(le16(bytes + 2 * i), sink_)) {
        fail(in_.path(), InputPosition::byte(sink_.at), "reserved EVT 3.0 word type 0x" + hex(le16(bytes + 2 * i) >> 12u));
      }
    }
    in_.skip(words * 2);
    return true;
  }

 private:
  struct Sink {
    Evt3Source& source;
    std::uint64_t at = 0;  // the word being decoded
    void event(TimeUs t, unsigned x, unsigned y, int p) { source.emit(t, x, y, p, InputPosition::byte(at)); }
    void skipped(const char* kind) { source.count_skipped(kind); }
  };
  Evt3Decoder decoder_;
  Sink sink_{*this};
};

class DatSource final : public FileEventSource {
 public:
  DatSource(ByteReader in, const SourceOptions& o, const PropheseeHeader& h) : FileEventSource(std::move(in), "Prophesee DAT", o) {
    const std::uint64_t at = in_.offset();
    unsigned char ts[2];
    if (in_.read(ts, 2) < 2) fail(in_.path(), InputPosition::byte(at), "bad header: missing event type and size bytes");
    if ((ts[0] != 0 && ts[0] != 0x0C) || ts[1] != 8) {
      fail(in_.path(), InputPosition::byte(at), "bad header: event type " + std::to_string(ts[0]) + " of size " + std::to_string(ts[1]) +
                                                    " (only 8-byte 2D events, type 0 or 12, are supported)");
    }
    set_sensor(h.size, SensorSize{304, 240}, "ATIS default for DAT files");
  }

 protected:
  bool decode_more() override {
    unsigned char r[8];
    for (int n = 0; n < 8192; ++n) {
      const std::uint64_t at = in_.offset();
      const size_t got = in_.read(r, 8);
      if (got == 0) return false;
      if (got < 8) fail(in_.path(), InputPosition::byte(at), "truncated record (" + std::to_string(got) + " of 8 bytes)");
      const std::uint32_t t = le32(r), data = le32(r + 4);
      if (have_last_ && t < last_t_ && last_t_ - t > (1u << 31)) epoch_ += TimeUs{1} << 32;
      have_last_ = true;
      last_t_ = t;
      emit(epoch_ + t, data & 0x3FFF, (data >> 14) & 0x3FFF, (data >> 28) & 1, InputPosition::byte(at));
    }
    return true;
  }

 private:
  bool have_last_ = false;
  std::uint32_t last_t_ = 0;
  TimeUs epoch_ = 0;
};

}  // namespace

std::unique_ptr<EventSource> open_prophesee(ByteReader in, const SourceOptions& o) {
  const PropheseeHeader h = read_header(in);
  switch (h.kind) {
    case PropheseeHeader::Kind::kEvt2:
    case PropheseeHeader::Kind::kEvt21: return std::make_unique<Evt2Source>(std::move(in), o, h);
    case PropheseeHeader::Kind::kEvt3: return std::make_unique<Evt3Source>(std::move(in), o, h);
    case PropheseeHeader::Kind::kDat: return std::make_unique<DatSource>(std::move(in), o, h);
    case PropheseeHeader::Kind::kUnknown: break;
  }
  fail(in.path(), InputPosition::line(in.line()),
       "bad header: a '%' header without '% evt 2.0', '% evt 2.1', '% evt 3.0' or a DAT '% Version' line");
}

}  // namespace evms::read
