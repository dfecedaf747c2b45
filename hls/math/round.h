// Integer helpers with the core's one rounding rule for right shifts: round half up
// (toward plus infinity), i.e. add half an LSB and shift arithmetically. Saturation clamps.
#pragma once

#include <cstdint>

namespace evms::hls {

constexpr std::int64_t shr_rnd(std::int64_t v, int s) {
  return s <= 0 ? v * (std::int64_t{1} << -s) : (v + (std::int64_t{1} << (s - 1))) >> s;
}

constexpr std::int64_t clamp_sym(std::int64_t v, std::int64_t bound) {
  return v > bound ? bound : (v < -bound ? -bound : v);
}

constexpr std::int64_t clamp(std::int64_t v, std::int64_t lo, std::int64_t hi) {
  return v > hi ? hi : (v < lo ? lo : v);
}

}  // namespace evms::hls
