#include "host/backend/registry.h"

#include <algorithm>
#include <array>
#include <stdexcept>

#include "hls/core/configs.h"
#include "host/backend/core_config.h"

namespace evms::backend {

namespace {
const std::array kBackends = {
    BackendInfo{"golden", "floating-point reference model (Eigen, double)", &make_golden_backend},
    BackendInfo{"fixed", "bit-accurate fixed-point core (hls/), in C++", &make_fixed_backend},
    BackendInfo{"rtl", "the SystemVerilog core (rtl/), simulated by Verilator", &make_rtl_backend},
    BackendInfo{"board", "an FPGA board (or evms vboard) running the board top, over its serial link (docs/link.md)", &make_board_backend},
};
}  // namespace

void check_core_build(const std::string& core) {
  std::string known;
  for (const char* name : hls::kCoreBuildNames) {
    if (core == name) return;
    known += (known.empty() ? "" : ", ") + std::string(name);
  }
  throw std::invalid_argument("unknown core build '" + core + "' (known: " + known + ")");
}

namespace {

// The method within build S (within_build, host/backend/core_config.h), keeping what the
// command line set.
template <class S>
Params fit_sizes(Params p, const Method& method) {
  return within_build<S>(p, [&](const char* name) { return method.sets(name); });
}

}  // namespace

Params fit_core_build(const std::string& backend, const std::string& core, Params p, const Method& method) {
  check_core_build(core);
  if (backend == "golden") return p;
  const bool fixed = backend == "fixed";
  const std::string build = backend == "board" ? board_build(core) : core;
#define EVMS_FIT_BUILD(name, fixed_shape, rtl_shape, width, height, description) \
  if (build == #name) return fixed ? fit_sizes<hls::fixed_shape>(p, method) : fit_sizes<hls::rtl_shape>(p, method);
  EVMS_CORE_BUILDS(EVMS_FIT_BUILD)
#undef EVMS_FIT_BUILD
  return p;
}

SensorSize core_build_sensor(const std::string& build) {
  check_core_build(build);
#define EVMS_SENSOR_OF_BUILD(name, fixed_shape, rtl_shape, width, height, description) \
  if (build == #name) return SensorSize{width, height};
  EVMS_CORE_BUILDS(EVMS_SENSOR_OF_BUILD)
#undef EVMS_SENSOR_OF_BUILD
  return {};
}

std::span<const BackendInfo> backends() { return kBackends; }

std::unique_ptr<Backend> make_backend(const std::string& name, const BackendOptions& options) {
  std::string known;
  for (const BackendInfo& b : kBackends) {
    if (name == b.name) return b.make(options);
    known += (known.empty() ? "" : ", ") + std::string(b.name);
  }
  throw std::invalid_argument("unknown backend '" + name + "' (this build has: " + known + ")");
}

}  // namespace evms::backend
