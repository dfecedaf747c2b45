// Reading serialized ROS messages, in either of the two serializations:
//  - ROS 2's CDR (OMG XCDR1, as rmw_fastrtps writes them): a 4-byte encapsulation header
//    {0x00, 0x00|0x01, options} whose second byte says big (0) or little (1) endian, then the
//    fields in order. A primitive of n bytes starts at a multiple of n counted from the end of
//    the header. A string is a uint32 length that counts its terminating NUL, then the bytes.
//  - ROS 1's: the fields in order, little-endian, with no header and no alignment; a string is
//    a uint32 length (no NUL), then the bytes.
// In both, a sequence is a uint32 element count, then the elements.
#pragma once

#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>

namespace evms::read {

class RosMessageReader {
 public:
  // Errors carry the byte offset into `data` (header included).
  struct Error {
    std::uint64_t offset;
    std::string what;
  };

  enum class Serialization { kCdr, kRos1 };

  RosMessageReader(std::span<const unsigned char> data, Serialization s) : data_(data), cdr_(s == Serialization::kCdr) {
    if (!cdr_) return;
    if (data_.size() < 4) throw Error{0, "shorter than the 4-byte CDR header"};
    if (data_[0] != 0 || data_[1] > 1) throw Error{0, "not plain CDR (encapsulation " + std::to_string(data_[0]) + "," + std::to_string(data_[1]) + ")"};
    little_ = data_[1] == 1;
    pos_ = 4;
  }

  std::uint8_t u8() { return static_cast<std::uint8_t>(unsigned_of(1)); }
  std::uint16_t u16() { return static_cast<std::uint16_t>(unsigned_of(2)); }
  std::uint32_t u32() { return static_cast<std::uint32_t>(unsigned_of(4)); }
  std::int32_t i32() { return static_cast<std::int32_t>(u32()); }
  std::uint64_t u64() { return unsigned_of(8); }
  bool boolean() { return u8() != 0; }
  std::string_view string() {
    const std::uint32_t n = u32();
    if (n == 0) return {};
    const std::span<const unsigned char> b = bytes(n);
    return {reinterpret_cast<const char*>(b.data()), cdr_ ? n - 1 : n};
  }
  // A sequence's element count, checked against the bytes left at `min_element_bytes` each.
  std::uint32_t sequence_length(size_t min_element_bytes) {
    const std::uint64_t at = pos_;
    const std::uint32_t n = u32();
    if (min_element_bytes > 0 && n > (data_.size() - pos_) / min_element_bytes) {
      throw Error{at, "a sequence of " + std::to_string(n) + " elements runs past the end of the message"};
    }
    return n;
  }
  std::span<const unsigned char> bytes(size_t n) {
    if (n > data_.size() - pos_) throw Error{pos_, "field of " + std::to_string(n) + " bytes runs past the end of the message"};
    const auto out = data_.subspan(pos_, n);
    pos_ += n;
    return out;
  }
  std::uint64_t offset() const { return pos_; }
  bool little_endian() const { return little_; }

 private:
  std::uint64_t unsigned_of(size_t n) {
    if (cdr_) pos_ += (n - (pos_ - 4) % n) % n;
    if (pos_ > data_.size() || n > data_.size() - pos_) throw Error{pos_, "message ends inside a field"};
    std::uint64_t v = 0;
    for (size_t i = 0; i < n; ++i) {
      const std::uint64_t b = data_[pos_ + i];
      v |= little_ ? b << (8 * i) : b << (8 * (n - 1 - i));
    }
    pos_ += n;
    return v;
  }

  std::span<const unsigned char> data_;
  bool cdr_;
  size_t pos_ = 0;
  bool little_ = true;
};

}  // namespace evms::read
