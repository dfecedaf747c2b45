// The core builds evms knows by name: the host/simulation core and the two boards. The RTL
// generator (host/tools/rtl_gen) writes each one's parameters and tables for rtl/; the
// cosimulation checks each RTL build against the C++ core of the same Shape.
#pragma once

#include "hls/core/shape.h"

namespace evms::hls {

// iCEBreaker (iCE40 UP5K) beside a DVS128: 128x128, packets of 64, one kernel lane, 16-bit
// timestamps (one SPRAM), 10-bit feature fractions and 1.15 weights so that every kernel
// multiplier fits a 16x16 SB_MAC16, and a digit-serial shared multiplier (4 bits a clock).
using Ice40Shape = Shape<128, 128, 64, 1, 8, 8, 8, 16, 7, 4 * 64, 10, 15, 8, 12, 4>;
// Arty A7-35T beside a DAVIS240: the default board core, eight kernel lanes (what fits its DSPs).
using ArtyShape = DefaultShape;

}  // namespace evms::hls
