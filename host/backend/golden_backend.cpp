#include "golden/pipeline.h"
#include "host/backend/backend.h"
#include "host/backend/registry.h"

namespace evms::backend {
namespace {

class GoldenBackend final : public Backend {
 public:
  explicit GoldenBackend(const BackendOptions& o) : pipeline_(o.params, o.sensor) {}
  void push(std::span<const Event> events, OutputSink& out) override {
    for (const Event& e : events) pipeline_.push(e, out);
  }
  void finish(OutputSink& out) override { pipeline_.finish(out); }
  BackendStats stats() const override {
    const auto& s = pipeline_.stats();
    return {s.events_in, s.events_kept, s.packets, s.clusters, s.iterations,
            pipeline_.tracker().tracks_started(), pipeline_.tracker().unassigned_clusters(), s.kernel_evaluations};
  }

 private:
  golden::Pipeline pipeline_;
};

}  // namespace

std::unique_ptr<Backend> make_golden_backend(const BackendOptions& o) {
  return std::make_unique<GoldenBackend>(o);
}

}  // namespace evms::backend
