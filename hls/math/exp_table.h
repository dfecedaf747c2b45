// exp(-u) for u >= 0, from a table with linear interpolation: the kernel of the mean shift
// (w = exp(-|dphi|^2)) and the time decay of the features (exp(-dt / tau)) both use it.
//
//   u       unsigned, UF fraction bits; u >= 2^kRangeLog2 (= 16) gives 0 (e^-16 < 2^-23)
//   table   2^L + 1 samples of exp(-u) on [0, 16], rounded to WF fraction bits (1.0 included)
//   result  v[i] - ((v[i] - v[i+1]) * f) >> IB, f the IB bits of u below the index, rounded
//           down; WF fraction bits
//
// Error bound (exhaustive test in tests/hls/test_math.cpp): |result - exp(-u)| <=
//   h^2/8 (interpolation, h = 16 / 2^L)  +  2^-WF (table rounding and the final truncation)
//   + h * 2^-IB (truncated interpolation fraction).
// For the default L = 9, WF = 16, IB = 8: 1.2e-4 + 1.5e-5 + 1.2e-4 -> 2.6e-4.
#pragma once

#include <cstdint>

#include "hls/math/cexp.h"

namespace evms::hls {

template <int L, int WF, int IB>
struct ExpTable {
  static constexpr int kRangeLog2 = 4;
  static constexpr int kEntries = 1 << L;
  static constexpr int kFracBits = WF;
  static constexpr int kInterpBits = IB;
  std::uint32_t v[kEntries + 1];

  constexpr ExpTable() : v() {
    for (int i = 0; i <= kEntries; ++i) {
      const double x = static_cast<double>(i) * (1 << kRangeLog2) / kEntries;
      v[i] = static_cast<std::uint32_t>(cexp_neg(x) * (1u << WF) + 0.5);
    }
  }

  // exp(-u) for u with UF fraction bits.
  template <int UF>
  constexpr std::uint32_t lookup(std::uint64_t u) const {
    static_assert(UF + kRangeLog2 - L >= IB, "ExpTable: the input has fewer bits below the index than the interpolation uses");
    constexpr int kBelowIndex = UF + kRangeLog2 - L;
    if ((u >> (UF + kRangeLog2)) != 0) return 0;
    const auto i = static_cast<std::uint32_t>(u >> kBelowIndex);
    const auto f = static_cast<std::uint32_t>((u >> (kBelowIndex - IB)) & ((1u << IB) - 1));
    return v[i] - static_cast<std::uint32_t>((static_cast<std::uint64_t>(v[i] - v[i + 1]) * f) >> IB);
  }
};

}  // namespace evms::hls
