// The integer square root of a 128-bit value, floor(sqrt(v)) for 0 <= v < 2^126: one result bit
// a step, by the digit-by-digit method (no multiplier, no table). tests/hls/test_math.cpp checks
// r^2 <= v < (r + 1)^2 exhaustively below 2^20 and on random values of every width.
#pragma once

namespace evms::hls {

inline __int128 isqrt(__int128 v) {
  __int128 root = 0, bit = __int128{1} << 124;  // the largest power of four below 2^126
top_bit:
  for (int k = 0; k < 63; ++k) {
    if (bit <= v) break;
    bit >>= 2;
  }
digits:
  for (int k = 0; k < 63; ++k) {
    if (bit == 0) break;
    if (v >= root + bit) {
      v -= root + bit;
      root = (root >> 1) + bit;
    } else {
      root >>= 1;
    }
    bit >>= 2;
  }
  return root;
}

}  // namespace evms::hls
