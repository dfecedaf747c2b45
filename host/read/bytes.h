// Fixed-endian integer loads from byte buffers, independent of the host's byte order.
#pragma once

#include <cstdint>

namespace evms::read {

inline std::uint16_t le16(const unsigned char* b) {
  return static_cast<std::uint16_t>(b[0] | (b[1] << 8));
}
inline std::uint32_t le32(const unsigned char* b) {
  return std::uint32_t{b[0]} | (std::uint32_t{b[1]} << 8) | (std::uint32_t{b[2]} << 16) |
         (std::uint32_t{b[3]} << 24);
}
inline std::uint64_t le64(const unsigned char* b) {
  return std::uint64_t{le32(b)} | (std::uint64_t{le32(b + 4)} << 32);
}
inline std::uint32_t be32(const unsigned char* b) {
  return (std::uint32_t{b[0]} << 24) | (std::uint32_t{b[1]} << 16) | (std::uint32_t{b[2]} << 8) |
         std::uint32_t{b[3]};
}

}  // namespace evms::read
