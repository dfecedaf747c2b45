#include "host/backend/registry.h"

#include <array>
#include <stdexcept>

namespace evms::backend {

namespace {
const std::array kBackends = {
    BackendInfo{"golden", "floating-point reference model (Eigen, double)", &make_golden_backend},
    BackendInfo{"fixed", "bit-accurate fixed-point core (hls/), in C++", &make_fixed_backend},
    BackendInfo{"rtl", "the SystemVerilog core (rtl/), simulated by Verilator", &make_rtl_backend},
    BackendInfo{"board", "an FPGA board (or evms vboard) running the board top, over its serial link (docs/link.md)", &make_board_backend},
};
}  // namespace

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
