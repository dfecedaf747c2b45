// The ROS event messages, as ROS 1 and ROS 2 bags hold them (the layouts are the .msg
// definitions; the type names are given without ROS 2's "/msg/"):
//   event_camera_msgs/EventPacket
//       std_msgs/Header header, uint32 height, uint32 width, uint64 seq, uint64 time_base,
//       string encoding, bool is_bigendian, uint8[] events
//     encodings: "evt3"    Prophesee EVT 3.0 words (evt3_decoder.h), state kept across
//                          packets; sensor time, time_base unused
//                "libcaer" 8 bytes an event: uint32 address (bit 1 polarity, y in 2..16, x in
//                          17..31) and int32 t_us; t = time_base (ns) + t_us * 1000, and t_us
//                          going down inside a packet is a roll-over of 2^31 us
//                "mono"    uint64: dt in 0..31 (ns), x in 32..47, y in 48..62, polarity in 63;
//                          t = time_base + dt
//                "trigger" uint64 trigger records: counted and skipped
//   dvs_msgs/EventArray, prophesee_event_msgs/EventArray
//       std_msgs/Header header, uint32 height, uint32 width, Event[] events with
//       Event = {uint16 x, uint16 y, time ts, bool polarity}
// std_msgs/Header is {uint32 seq, time stamp, string frame_id} in ROS 1 and {time stamp, string
// frame_id} in ROS 2; a time is {int32 or uint32 sec, uint32 nanosec}. Times become
// microseconds (floor).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "types/event.h"
#include "host/read/formats/evt3_decoder.h"
#include "host/read/formats/ros_message_reader.h"

namespace evms::read {

// What a bag reader does with what a message holds; offsets are bytes into the message.
class EventMessageSink {
 public:
  virtual void event(TimeUs t, std::uint64_t x, std::uint64_t y, int p, std::uint64_t at) = 0;
  virtual void skipped_records(const char* kind, std::int64_t n) = 0;
  [[noreturn]] virtual void refuse(std::uint64_t at, const std::string& what) = 0;

 protected:
  ~EventMessageSink() = default;
};

class EventMessages {
 public:
  using Serialization = RosMessageReader::Serialization;

  // `type` as the bag names it ("dvs_msgs/EventArray" or "dvs_msgs/msg/EventArray").
  EventMessages(std::string_view type, Serialization serialization);
  // One of the types above, by either spelling.
  static bool is_event_type(std::string_view type);
  // The event types, for messages.
  static const char* types_known();

  // The sensor size a message's header says, or nothing when its height and width are 0.
  std::optional<SensorSize> sensor(std::span<const unsigned char> message, EventMessageSink& sink) const;
  void decode(std::span<const unsigned char> message, EventMessageSink& sink);
  // The type as the bag names it, and a packet's encoding once one was read:
  // "event_camera_msgs/msg/EventPacket (evt3)".
  const std::string& format() const { return format_; }

 private:
  void skip_header(RosMessageReader& r) const;
  void decode_packet(RosMessageReader& r, EventMessageSink& sink);
  void decode_array(RosMessageReader& r, EventMessageSink& sink);

  std::string type_;  // without "/msg/"
  Serialization serialization_;
  std::string format_;
  bool described_ = false;  // format_ names the encoding
  Evt3Decoder evt3_;
};

}  // namespace evms::read
