#include "host/backend/fixed_backend.h"

#include "host/backend/registry.h"

namespace evms::backend {

std::unique_ptr<Backend> make_fixed_backend(const BackendOptions& o) {
  return std::make_unique<FixedBackend<hls::HostShape>>(o);
}

}  // namespace evms::backend
