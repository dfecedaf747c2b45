// Reciprocal and division through a table and one Newton-Raphson step.
//
// For x > 0 with its most significant bit at position m, x = M * 2^(m - MF) where the mantissa
// M = x normalized to [1, 2) has MF fraction bits. A table indexed by the T bits after the
// leading one holds 1 / (1 + (i + 1/2) / 2^T) (the midpoint of the interval), rounded to RF
// fraction bits: good to about T + 1 bits. One Newton-Raphson step,
//   r1 = r0 * (2 - M * r0),
// squares the error: about 2T + 2 bits, limited by RF. So 1/x = r1 * 2^-m, r1 in (1/2, 1].
//
// divide() gives num / x = (num * r1) >> (m + shift) with round-half-up, where the caller
// chooses `shift` to land on the result's fraction bits.
//
// Bound (tests/hls/test_math.cpp, exhaustive over x < 2^20, random above): the relative error
// of r1 * 2^-m against 1/x is below 2^-(RF - 3) = 2^-17 for the default T = 8, RF = 20.
#pragma once

#include <cstdint>

namespace evms::hls {

template <int T, int RF>
struct Reciprocal {
  static constexpr int kTableBits = T;
  static constexpr int kFracBits = RF;
  static constexpr int kMantFrac = RF;  // mantissa fraction bits used by the NR step
  std::uint32_t table[1 << T];

  constexpr Reciprocal() : table() {
    for (int i = 0; i < (1 << T); ++i) {
      const double m = 1.0 + (i + 0.5) / (1 << T);
      table[i] = static_cast<std::uint32_t>((1.0 / m) * (1u << RF) + 0.5);
    }
  }

  struct Result {
    std::uint32_t r;  // 1/x = r * 2^-(RF + m)
    int m;            // position of x's most significant bit
  };

  static constexpr int msb(std::uint64_t x) {
    int m = 0;
    while (x >> (m + 1)) ++m;
    return m;
  }

  constexpr Result reciprocal(std::uint64_t x) const {
    const int m = msb(x);
    // Mantissa with RF fraction bits (truncated).
    const std::uint64_t mant = m >= RF ? (x >> (m - RF)) : (x << (RF - m));
    const std::uint32_t index = static_cast<std::uint32_t>((mant >> (RF - T)) & ((1u << T) - 1));
    const std::uint64_t r0 = table[index];
    const std::uint64_t two = std::uint64_t{2} << RF;
    const std::uint64_t mr0 = (mant * r0) >> RF;           // M * r0, RF fraction bits, near 1
    const std::uint64_t r1 = (r0 * (two - mr0)) >> RF;     // RF fraction bits
    return {static_cast<std::uint32_t>(r1), m};
  }

  // num / x, scaled by 2^extra_frac: returns round(num * 2^extra_frac / x), for num >= 0.
  // Needs num * 2^extra_frac * r to fit 64 bits (the callers' widths see to it).
  template <int ExtraFrac>
  constexpr std::uint64_t divide(std::uint64_t num, std::uint64_t x) const {
    const Result rx = reciprocal(x);
    const int shift = RF + rx.m - ExtraFrac;
    const std::uint64_t p = num * rx.r;
    if (shift <= 0) return p << -shift;
    return (p + (std::uint64_t{1} << (shift - 1))) >> shift;
  }
};

}  // namespace evms::hls
