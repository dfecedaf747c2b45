#include "host/backend/fixed_backend.h"

#include "hls/core/configs.h"

#include "host/backend/registry.h"

namespace evms::backend {

std::unique_ptr<Backend> make_fixed_backend(const BackendOptions& o) {
  check_core_build(o.core);
  if (o.core == "arty") return std::make_unique<FixedBackend<hls::ArtyShape>>(o);
  if (o.core == "ice40") return std::make_unique<FixedBackend<hls::Ice40Shape>>(o);
  return std::make_unique<FixedBackend<hls::HostShape>>(o);
}

}  // namespace evms::backend
