// The core's runtime settings, as registers (the list: hls/core/registers.h). The host computes
// them from the method's parameters (host/backend/core_config.h); a board has them as reset
// values (rtl/generated/evms_cfg_<build>.svh).
#pragma once

#include <cstdint>

#include "hls/core/registers.h"

namespace evms::hls {

struct Config {
#define EVMS_CONFIG_MEMBER(name, type, bits, reset, description) type name = reset;
  EVMS_CORE_RTL_REGISTERS(EVMS_CONFIG_MEMBER)
  EVMS_CORE_HLS_REGISTERS(EVMS_CONFIG_MEMBER)
#undef EVMS_CONFIG_MEMBER
};

#define EVMS_COUNT_REGISTER(name, type, bits, reset, description) +1
constexpr int kRtlRegisterCount = 0 EVMS_CORE_RTL_REGISTERS(EVMS_COUNT_REGISTER);
#undef EVMS_COUNT_REGISTER

// A Config whose RTL registers hold `values` (the bits of each, in list order, as
// rtl/generated/evms_cfg_registers.h gives a build's reset values) and the rest their resets.
inline Config config_of_rtl_registers(const std::uint64_t (&values)[kRtlRegisterCount]) {
  Config c;
  int i = 0;
#define EVMS_SET_REGISTER(name, type, bits, reset, description) c.name = static_cast<type>(values[i++]);
  EVMS_CORE_RTL_REGISTERS(EVMS_SET_REGISTER)
#undef EVMS_SET_REGISTER
  return c;
}

}  // namespace evms::hls
