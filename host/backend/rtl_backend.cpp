// The rtl backend: the Verilated RTL of a core build (sim/, Vcore_<build>) behind the backend
// seam. Its output must equal the fixed backend's of the same build, file for file.
#include "Vcore_arty.h"
#include "Vcore_arty___024root.h"
#include "Vcore_host.h"
#include "Vcore_host___024root.h"
#include "Vcore_ice40.h"
#include "Vcore_ice40___024root.h"
#include "hls/core/configs.h"
#include "host/backend/core_backend.h"
#include "host/backend/registry.h"
#include "sim/rtl_core.h"

namespace evms::backend {
namespace {

template <class V, class S>
class RtlBackend final : public Backend {
 public:
  explicit RtlBackend(const BackendOptions& o) : core_(core_config<S>(o.params, o.sensor)) {}
  void push(std::span<const Event> events, OutputSink& out) override {
    for (const Event& e : events) {
      ++stats_.s.events_in;
      core_.push(mapper_.to_word(e));
      drain(out);
    }
  }
  void finish(OutputSink& out) override {
    hls::EventWord flush;
    flush.flush = true;
    core_.push(flush);
    core_.settle();
    drain(out);
  }
  BackendStats stats() const override {
    BackendStats s = stats_.s;
    s.tracks_started = core_.tracks_started();
    s.unassigned_clusters = core_.unassigned();
    return s;
  }

 private:
  void drain(OutputSink& out) {
    for (; !core_.labels.empty(); core_.labels.pop_front()) out.on_event(mapper_.label(core_.labels.front()));
    for (; !core_.tracks.empty(); core_.tracks.pop_front()) out.on_track(mapper_.track(core_.tracks.front()));
    for (; !core_.packets.empty(); core_.packets.pop_front()) {
      stats_.on_packet(core_.packets.front());
      out.on_packet(mapper_.packet(core_.packets.front()));
    }
  }

  sim::RtlCore<V> core_;
  CoreWordMapper<S> mapper_;
  CoreStats stats_;
};

}  // namespace

std::unique_ptr<Backend> make_rtl_backend(const BackendOptions& o) {
  check_core_build(o.core);
  if (std::string unsupported = rtl_unsupported(o.params, o.core); !unsupported.empty()) throw std::invalid_argument(unsupported);
#define EVMS_RTL_OF_BUILD(name, fixed, rtl, width, height, description) \
  if (o.core == #name) return std::make_unique<RtlBackend<Vcore_##name, hls::rtl>>(o);
  EVMS_CORE_BUILDS(EVMS_RTL_OF_BUILD)
#undef EVMS_RTL_OF_BUILD
  return nullptr;  // check_core_build refused any other name
}

}  // namespace evms::backend
