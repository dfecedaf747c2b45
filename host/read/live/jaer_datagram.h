// One datagram of a jAER AEUnicast stream (udp_source.cpp): a big-endian int32 sequence number,
// then 8-byte {int32 address, int32 timestamp_us} records in jAER's address layout for the
// camera. Kept apart from the socket so that tests and the fuzz target feed it bytes directly.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "types/event.h"
#include "host/read/bytes.h"
#include "host/read/formats/jaer_address.h"

namespace evms::read {

class JaerDatagramDecoder {
 public:
  JaerDatagramDecoder(JaerLayout layout, SensorSize sensor) : layout_(layout), sensor_(sensor) {}

  // Appends the datagram's polarity events to `out`; `skip(kind)` counts what is not one.
  // A gap in the sequence numbers adds the datagrams missing to lost().
  template <class Skip>
  void decode(std::span<const std::uint8_t> datagram, std::vector<Event>& out, Skip&& skip) {
    if (datagram.size() < 4 || (datagram.size() - 4) % 8 != 0) {
      skip("malformed datagrams (length not 4 + 8k bytes)");
      return;
    }
    const std::uint32_t seq = be32(datagram.data());
    if (have_seq_ && seq != next_seq_) {
      if (seq > next_seq_) {
        lost_ += seq - next_seq_;
      } else {
        skip("datagrams out of sequence");
      }
    }
    have_seq_ = true;
    next_seq_ = seq + 1;
    for (size_t at = 4; at < datagram.size(); at += 8) {
      const JaerAddress a = decode_jaer_address(be32(datagram.data() + at), layout_);
      const TimeUs t = clock_.extend(be32(datagram.data() + at + 4));
      if (a.kind == JaerAddress::Kind::kApsOrImu) {
        skip("APS/IMU records");
      } else if (a.kind == JaerAddress::Kind::kExternal) {
        skip("external events");
      } else if (a.x >= static_cast<unsigned>(sensor_.width) || a.y >= static_cast<unsigned>(sensor_.height)) {
        skip("addresses outside the sensor");
      } else if (t < last_t_) {
        skip("events older than their predecessor");
      } else {
        last_t_ = t;
        out.push_back(Event{t, static_cast<std::uint16_t>(a.x), static_cast<std::uint16_t>(a.y), static_cast<std::uint8_t>(a.p)});
      }
    }
  }
  std::int64_t lost() const { return lost_; }

 private:
  JaerLayout layout_;
  SensorSize sensor_;
  JaerClock clock_;
  TimeUs last_t_ = 0;
  bool have_seq_ = false;
  std::uint32_t next_seq_ = 0;
  std::int64_t lost_ = 0;
};

}  // namespace evms::read
