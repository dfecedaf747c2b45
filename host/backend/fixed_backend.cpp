#include "host/backend/fixed_backend.h"

#include "hls/core/configs.h"

#include "host/backend/registry.h"

namespace evms::backend {

std::unique_ptr<Backend> make_fixed_backend(const BackendOptions& o) {
  check_core_build(o.core);
#define EVMS_FIXED_OF_BUILD(name, fixed, rtl, width, height, description) \
  if (o.core == #name) return std::make_unique<FixedBackend<hls::fixed>>(o);
  EVMS_CORE_BUILDS(EVMS_FIXED_OF_BUILD)
#undef EVMS_FIXED_OF_BUILD
  return nullptr;  // check_core_build refused any other name
}

}  // namespace evms::backend
