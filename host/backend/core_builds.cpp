// The core builds a backend can run (hls/core/configs.h, EVMS_CORE_BUILDS): their names, the
// method within their sizes, and the sensor each is sized for (backend.h). Apart from the
// registry, so that what runs the C++ core alone (the Python module) needs no RTL model.
#include <stdexcept>
#include <string>
#include <vector>

#include "hls/core/configs.h"
#include "host/backend/backend.h"
#include "host/backend/core_config.h"

namespace evms::backend {

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
  const std::string build = backend == "board" ? board_build(core) : core;
  // A board whose core is cut runs the rest on the host, in the build's fixed core.
  const bool fixed = backend == "fixed" || (backend == "board" && board_of(build).cut());
#define EVMS_FIT_BUILD(name, fixed_shape, rtl_shape, width, height, description) \
  if (build == #name) return fixed ? fit_sizes<hls::fixed_shape>(p, method) : fit_sizes<hls::rtl_shape>(p, method);
  EVMS_CORE_BUILDS(EVMS_FIT_BUILD)
#undef EVMS_FIT_BUILD
  return p;
}

std::vector<const ParamInfo*> differing_params(const Params& a, const Params& b) {
  std::vector<const ParamInfo*> differ;
  for (const ParamInfo& info : param_table()) {
    if (param_value(a, info) != param_value(b, info)) differ.push_back(&info);
  }
  return differ;
}

std::string fitted_settings(const Params& method, const Params& fitted) {
  std::string changes;
  for (const ParamInfo* info : differing_params(method, fitted)) {
    changes += (changes.empty() ? "--" : ", --") + std::string(info->name) + " " + param_text(fitted, *info) + " (the method's " +
               param_text(method, *info) + ")";
  }
  return changes;
}

SensorSize core_build_sensor(const std::string& build) {
  check_core_build(build);
#define EVMS_SENSOR_OF_BUILD(name, fixed_shape, rtl_shape, width, height, description) \
  if (build == #name) return SensorSize{width, height};
  EVMS_CORE_BUILDS(EVMS_SENSOR_OF_BUILD)
#undef EVMS_SENSOR_OF_BUILD
  return {};
}

}  // namespace evms::backend
