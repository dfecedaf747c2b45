// AEDAT 2.0 (jAER): '#' header lines ending in CRLF, then 8-byte big-endian records
// {int32 address, int32 timestamp_us}. The address layout (jaer_address.h) depends on the
// camera, which the header names in its "# AEChip:" line.
#include "host/read/bytes.h"
#include "host/read/event_source.h"
#include "host/read/formats/jaer_address.h"

namespace evms::read {
namespace {

class Aedat2Source final : public FileEventSource {
 public:
  Aedat2Source(ByteReader in, const SourceOptions& o) : FileEventSource(std::move(in), "AEDAT 2.0", o) {
    std::optional<SensorSize> size;
    std::string_view line;
    while (in_.peek(1) == "#") {
      in_.next_line(line);
      if (in_.line() == 1 && line.rfind("#!AER-DAT2.0", 0) != 0) {
        fail(in_.path(), InputPosition::line(1), "bad header: expected '#!AER-DAT2.0'");
      }
      size_t chip = line.find("AEChip:");
      if (chip != std::string_view::npos) {
        std::string name(line.substr(chip + 7));
        davis_ = name.find("DAVIS") != std::string::npos || name.find("Davis") != std::string::npos;
        size = sensor_of_model(name);
        info_.format = "AEDAT 2.0 (" + std::string(davis_ ? "DAVIS" : "DVS128") + " addresses)";
      }
    }
    set_sensor(size, davis_ ? std::nullopt : std::optional<SensorSize>(SensorSize{128, 128}),
               "DVS128 default");
  }

 protected:
  bool decode_more() override {
    unsigned char rec[8];
    for (int n = 0; n < 4096; ++n) {
      const std::uint64_t at = in_.offset();
      const size_t got = in_.read(rec, 8);
      if (got == 0) return false;
      if (got < 8) {
        fail(in_.path(), InputPosition::byte(at),
             "truncated record (" + std::to_string(got) + " of 8 bytes)");
      }
      const JaerAddress a = decode_jaer_address(be32(rec), davis_ ? JaerLayout::kDavis : JaerLayout::kDvs128);
      const TimeUs t = clock_.extend(be32(rec + 4));
      switch (a.kind) {
        case JaerAddress::Kind::kApsOrImu: count_skipped("APS/IMU records"); break;
        case JaerAddress::Kind::kExternal: count_skipped("external events"); break;
        case JaerAddress::Kind::kPolarity: emit(t, a.x, a.y, a.p, InputPosition::byte(at)); break;
      }
    }
    return true;
  }

 private:
  bool davis_ = false;
  JaerClock clock_;
};

// AEDAT 3.1 (libcaer): '#' header lines up to "#!END-HEADER", then little-endian packets,
// each a 28-byte header {int16 type, int16 source, int32 eventSize, int32 tsOffset,
// int32 tsOverflow, int32 capacity, int32 number, int32 valid} and number * eventSize bytes.
// Type 1 (polarity) events are {uint32 data, int32 timestamp}: bit 0 valid, bit 1 polarity,
// y = bits 16..2, x = bits 31..17; the full timestamp is (tsOverflow << 31) | timestamp.
class Aedat3Source final : public FileEventSource {
 public:
  Aedat3Source(ByteReader in, const SourceOptions& o) : FileEventSource(std::move(in), "AEDAT 3.1", o) {
    std::optional<SensorSize> size;
    std::string_view line;
    bool ended = false;
    while (!ended && in_.peek(1) == "#") {
      in_.next_line(line);
      if (in_.line() == 1 && line.rfind("#!AER-DAT3.1", 0) != 0) {
        fail(in_.path(), InputPosition::line(1), "bad header: expected '#!AER-DAT3.1'");
      }
      if (line.rfind("#Source", 0) == 0 && !size) size = sensor_of_model(std::string(line));
      if (line.rfind("#Format:", 0) == 0 && line.find("RAW") == std::string_view::npos) {
        fail(in_.path(), InputPosition::line(in_.line()),
             "bad header: only '#Format: RAW' is supported, got '" + std::string(line) + "'");
      }
      ended = line.rfind("#!END-HEADER", 0) == 0;
    }
    if (!ended) fail(in_.path(), in_.byte_position(), "bad header: no '#!END-HEADER' line");
    set_sensor(size, std::nullopt, "");
  }

 protected:
  bool decode_more() override {
    const std::uint64_t at = in_.offset();
    unsigned char h[28];
    const size_t got = in_.read(h, 28);
    if (got == 0) return false;
    if (got < 28) {
      fail(in_.path(), InputPosition::byte(at),
           "truncated packet header (" + std::to_string(got) + " of 28 bytes)");
    }
    const int type = static_cast<std::int16_t>(le16(h));
    const auto size = static_cast<std::int32_t>(le32(h + 4));
    const auto overflow = static_cast<std::int32_t>(le32(h + 12));
    const auto number = static_cast<std::int32_t>(le32(h + 20));
    if (size <= 0 || number < 0 || size > (1 << 20)) {
      fail(in_.path(), InputPosition::byte(at),
           "bad packet header: event size " + std::to_string(size) + ", number " + std::to_string(number));
    }
    if (type != 1) {
      count_skipped("non-polarity packets");
      const std::uint64_t body = std::uint64_t(size) * std::uint64_t(number);
      if (in_.offset() + body > in_.size()) {
        fail(in_.path(), InputPosition::byte(at), "truncated packet (body runs past the end of the file)");
      }
      in_.skip(body);
      return true;
    }
    if (size != 8) {
      fail(in_.path(), InputPosition::byte(at), "bad packet header: polarity event size " + std::to_string(size) + " (expected 8)");
    }
    for (std::int32_t i = 0; i < number; ++i) {
      const std::uint64_t ev_at = in_.offset();
      unsigned char r[8];
      const size_t n = in_.read(r, 8);
      if (n < 8) {
        fail(in_.path(), InputPosition::byte(ev_at),
             "truncated record (" + std::to_string(n) + " of 8 bytes)");
      }
      const std::uint32_t data = le32(r);
      const std::uint32_t ts = le32(r + 4);
      if (!(data & 1)) {
        count_skipped("invalid (unset valid bit) events");
        continue;
      }
      const TimeUs t = (static_cast<TimeUs>(overflow) << 31) | static_cast<TimeUs>(ts & 0x7FFFFFFF);
      emit(t, data >> 17, (data >> 2) & 0x7FFF, (data >> 1) & 1, InputPosition::byte(ev_at));
    }
    return true;
  }
};

}  // namespace

std::unique_ptr<EventSource> open_aedat2(ByteReader in, const SourceOptions& o) {
  return std::make_unique<Aedat2Source>(std::move(in), o);
}

std::unique_ptr<EventSource> open_aedat3(ByteReader in, const SourceOptions& o) {
  return std::make_unique<Aedat3Source>(std::move(in), o);
}

}  // namespace evms::read
