// The registers of a Config (hls/core/registers.h) on the cfg_* ports of a Verilated core: every
// register the model has a port for, so that the whole core (sim/rtl_core.h) and a core cut
// before its end (tests/sim/test_climbs_core.cpp) are configured from the one list.
#pragma once

#include <cstdint>

#include "hls/core/config.h"

namespace evms::sim {

template <class Model>
void set_cfg_ports(Model& model, const hls::Config& c) {
#define EVMS_SET_CFG_PORT(name, type, bits, reset, description) \
  if constexpr (requires { model.cfg_##name; }) model.cfg_##name = static_cast<std::uint64_t>(c.name);
  EVMS_CORE_RTL_REGISTERS(EVMS_SET_CFG_PORT)
#undef EVMS_SET_CFG_PORT
}

}  // namespace evms::sim
