#include "host/read/formats/event_messages.h"

#include "host/read/bytes.h"
#include "host/read/event_ordering.h"
#include "host/read/event_source.h"
#include "host/read/input_error.h"

namespace evms::read {
namespace {

constexpr std::string_view kEventPacket = "event_camera_msgs/EventPacket";
constexpr std::string_view kDvsArray = "dvs_msgs/EventArray";
constexpr std::string_view kPropheseeArray = "prophesee_event_msgs/EventArray";

// ROS 2 names a type "pkg/msg/Type", ROS 1 "pkg/Type".
std::string without_msg(std::string_view type) {
  std::string s(type);
  const size_t at = s.find("/msg/");
  if (at != std::string::npos) s.erase(at, 4);
  return s;
}

}  // namespace

EventMessages::EventMessages(std::string_view type, Serialization serialization)
    : type_(without_msg(type)), serialization_(serialization), format_(type) {}

bool EventMessages::is_event_type(std::string_view type) {
  const std::string t = without_msg(type);
  return t == kEventPacket || t == kDvsArray || t == kPropheseeArray;
}

const char* EventMessages::types_known() {
  return "event_camera_msgs/EventPacket, dvs_msgs/EventArray, prophesee_event_msgs/EventArray";
}

void EventMessages::skip_header(RosMessageReader& r) const {
  if (serialization_ == Serialization::kRos1) r.u32();  // seq
  r.u32();     // stamp.sec
  r.u32();     // stamp.nanosec
  r.string();  // frame_id
}

std::optional<SensorSize> EventMessages::sensor(std::span<const unsigned char> message, EventMessageSink& sink) const {
  std::uint32_t height = 0, width = 0;
  std::uint64_t at = 0;
  try {
    RosMessageReader r(message, serialization_);
    skip_header(r);
    height = r.u32(), width = r.u32();
    at = r.offset();
  } catch (const RosMessageReader::Error& e) {
    sink.refuse(e.offset, e.what);
  }
  if (width == 0 || height == 0) return std::nullopt;
  if (width > static_cast<std::uint32_t>(kMaxSensorSide) || height > static_cast<std::uint32_t>(kMaxSensorSide)) {
    sink.refuse(at, "a sensor of " + std::to_string(width) + "x" + std::to_string(height) + " is larger than " +
                        std::to_string(kMaxSensorSide) + "x" + std::to_string(kMaxSensorSide));
  }
  return SensorSize{static_cast<int>(width), static_cast<int>(height)};
}

void EventMessages::decode(std::span<const unsigned char> message, EventMessageSink& sink) {
  try {
    RosMessageReader r(message, serialization_);
    skip_header(r);
    r.u32();  // height
    r.u32();  // width
    if (type_ == kEventPacket) {
      decode_packet(r, sink);
    } else {
      decode_array(r, sink);
    }
  } catch (const RosMessageReader::Error& e) {
    sink.refuse(e.offset, e.what);
  }
}

void EventMessages::decode_packet(RosMessageReader& r, EventMessageSink& sink) {
  // Times in ns become us; a time that does not fit is corrupt input.
  const auto us_of_ns = [&](unsigned __int128 ns, std::uint64_t at) {
    const unsigned __int128 us = ns / 1000;
    if (us > static_cast<unsigned __int128>(kMaxTimestampUs)) sink.refuse(at, "a timestamp beyond 2^62 us");
    return static_cast<TimeUs>(us);
  };
  r.u64();  // seq
  const std::uint64_t time_base = r.u64();
  const std::uint64_t encoding_at = r.offset();
  const std::string encoding(r.string());
  r.boolean();  // is_bigendian: every encoding fixes its own byte order
  const std::uint32_t n = r.sequence_length(1);
  const std::uint64_t start = r.offset();
  const std::span<const unsigned char> events = r.bytes(n);
  if (!described_) format_ += " (" + printable(encoding) + ")", described_ = true;
  if (encoding == "evt3") {
    if (n % 2) sink.refuse(start, "an evt3 packet of " + std::to_string(n) + " bytes (not whole 16-bit words)");
    struct Evt3Sink {
      EventMessageSink& sink;
      std::uint64_t at;
      void event(TimeUs t, unsigned x, unsigned y, int p) { sink.event(t, x, y, p, at); }
      void skipped(const char* kind) { sink.skipped_records(kind, 1); }
    } words{sink, start};
    for (size_t i = 0; i < n; i += 2, words.at += 2) {
      if (!evt3_.word(le16(&events[i]), words)) sink.refuse(words.at, "reserved EVT 3.0 word type " + std::to_string(le16(&events[i]) >> 12));
    }
  } else if (encoding == "libcaer" || encoding == "mono" || encoding == "trigger") {
    if (n % 8) sink.refuse(start, "a " + encoding + " packet of " + std::to_string(n) + " bytes (not whole 8-byte events)");
    if (encoding == "trigger") {
      sink.skipped_records("trigger events", n / 8);
      return;
    }
    const bool libcaer = encoding == "libcaer";
    std::uint64_t high = time_base;  // libcaer: ns, raised by 2^31 us at each roll-over
    std::uint32_t last_low = 0;
    for (size_t i = 0; i < n; i += 8) {
      const std::uint64_t at = start + i;
      if (libcaer) {
        const std::uint32_t address = le32(&events[i]);
        const std::int32_t low = static_cast<std::int32_t>(le32(&events[i + 4]));
        if (low < 0) sink.refuse(at + 4, "a negative libcaer timestamp (" + std::to_string(low) + ")");
        if (static_cast<std::uint32_t>(low) < last_low) high += (std::uint64_t{1} << 31) * 1000;
        last_low = static_cast<std::uint32_t>(low);
        sink.event(us_of_ns(static_cast<unsigned __int128>(high) + static_cast<unsigned __int128>(low) * 1000, at), (address >> 17) & 0x7FFF,
                   (address >> 2) & 0x7FFF, static_cast<int>((address >> 1) & 1), at);
      } else {
        const std::uint64_t word = std::uint64_t{le32(&events[i])} | (std::uint64_t{le32(&events[i + 4])} << 32);
        sink.event(us_of_ns(static_cast<unsigned __int128>(time_base) + (word & 0xFFFFFFFFu), at), (word >> 32) & 0xFFFF,
                   (word >> 48) & 0x7FFF, static_cast<int>(word >> 63), at);
      }
    }
  } else {
    sink.refuse(encoding_at, "encoding '" + printable(encoding) + "' is not supported (evt3, libcaer, mono, trigger)");
  }
}

void EventMessages::decode_array(RosMessageReader& r, EventMessageSink& sink) {
  const std::uint32_t n = r.sequence_length(13);
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint64_t at = r.offset();
    const std::uint16_t x = r.u16(), y = r.u16();
    const std::int32_t sec = r.i32();
    const std::uint32_t nanosec = r.u32();
    const bool polarity = r.boolean();
    if (sec < 0 || nanosec >= 1000000000u) sink.refuse(at, "a bad event time (" + std::to_string(sec) + " s, " + std::to_string(nanosec) + " ns)");
    sink.event(static_cast<TimeUs>(sec) * 1000000 + nanosec / 1000, x, y, polarity ? 1 : 0, at);
  }
}

}  // namespace evms::read
