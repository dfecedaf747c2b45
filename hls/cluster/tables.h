// The ROM tables of a Shape, generated at compile time (host/tools/rtl_gen writes the same
// tables into rtl/generated/ for the RTL).
#pragma once

#include "hls/math/exp_table.h"
#include "hls/math/reciprocal.h"

namespace evms::hls {

template <class S>
struct Tables {
  using Exp = ExpTable<S::kExpTableLog2, S::kWeightFrac, S::kExpInterpBits>;
  using Recip = Reciprocal<S::kRecipTableLog2, S::kRecipFrac>;
  static constexpr Exp exp{};
  static constexpr Recip recip{};
};

}  // namespace evms::hls
