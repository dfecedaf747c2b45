// Integer helpers with the core's one rounding rule for right shifts: round half up
// (toward plus infinity), i.e. add half an LSB and shift arithmetically. Saturation clamps.
#pragma once

#include <cstdint>

namespace evms::hls {

constexpr std::int64_t shr_rnd(std::int64_t v, int s) {
  return s <= 0 ? v * (std::int64_t{1} << -s) : (v + (std::int64_t{1} << (s - 1))) >> s;
}

// A mean of `count` pixel coordinates from their sum, in 1/16 px, rounded half up (count > 0).
constexpr std::int64_t mean_sixteenths(std::int64_t sum, int count) { return (32 * sum + count) / (2 * std::int64_t{count}); }

// $clog2 of SystemVerilog, at compile time: the bits that index n entries (n > 0).
constexpr int ceil_log2(int n) {
  int bits = 0;
  while ((1 << bits) < n) ++bits;
  return bits;
}

constexpr std::int64_t clamp_sym(std::int64_t v, std::int64_t bound) {
  return v > bound ? bound : (v < -bound ? -bound : v);
}

constexpr std::int64_t clamp(std::int64_t v, std::int64_t lo, std::int64_t hi) {
  return v > hi ? hi : (v < lo ? lo : v);
}

}  // namespace evms::hls
