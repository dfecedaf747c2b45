// Factories of the backends this build has; registry.cpp lists them.
#pragma once

#include "host/backend/backend.h"

namespace evms::backend {
std::unique_ptr<Backend> make_golden_backend(const BackendOptions& o);
std::unique_ptr<Backend> make_fixed_backend(const BackendOptions& o);
std::unique_ptr<Backend> make_rtl_backend(const BackendOptions& o);
std::unique_ptr<Backend> make_board_backend(const BackendOptions& o);
}  // namespace evms::backend
