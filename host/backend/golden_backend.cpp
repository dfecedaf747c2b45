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
    BackendStats b;
    b.events_in = s.events_in, b.events_kept = s.events_kept, b.packets = s.packets, b.clusters = s.clusters;
    b.iterations = s.iterations, b.kernel_evaluations = s.kernel_evaluations;
    b.tracks_started = pipeline_.tracker().tracks_started(), b.unassigned_clusters = pipeline_.tracker().unassigned_clusters();
    b.cluster_ns = s.cluster_ns, b.track_ns = s.track_ns;
    return b;
  }

 private:
  golden::Pipeline pipeline_;
};

}  // namespace

std::unique_ptr<Backend> make_golden_backend(const BackendOptions& o) {
  return std::make_unique<GoldenBackend>(o);
}

}  // namespace evms::backend
