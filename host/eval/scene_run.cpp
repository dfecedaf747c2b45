#include "host/eval/scene_run.h"

#include <chrono>
#include <stdexcept>

namespace evms::eval {

Scene generate_scene(const gen::SceneConfig& config) {
  gen::SceneGenerator g(config);
  Scene s;
  s.config = config;
  s.sensor = g.sensor();
  for (int i = 0; i < g.object_count(); ++i) s.object_names.push_back(g.object_name(i));
  std::vector<LabelledEvent> batch;
  while (g.next(batch, s.centres)) {
    for (const LabelledEvent& e : batch) {
      s.events.push_back(e.event);
      s.truth.push_back(e.label);
    }
    batch.clear();
  }
  return s;
}

namespace {
struct Collector final : OutputSink {
  RunResult* r;
  explicit Collector(RunResult* result) : r(result) {}
  void on_event(const LabelledEvent& e) override { r->labels.push_back(e.label); }
  void on_track(const TrackUpdate& u) override { r->tracks.push_back(u); }
  void on_packet(const PacketSummary& p) override { r->packets.push_back(p); }
};
}  // namespace

RunResult run_backend(const std::string& backend, const Params& params, SensorSize sensor, std::span<const Event> events) {
  auto b = backend::make_backend(backend, backend::options_for(params, sensor));
  return run_backend(*b, events);
}

RunResult run_backend(backend::Backend& backend, std::span<const Event> events) {
  RunResult r;
  r.labels.reserve(events.size());
  backend::Backend* b = &backend;
  Collector sink(&r);
  const auto start = std::chrono::steady_clock::now();
  constexpr size_t kBatch = 4096;
  for (size_t i = 0; i < events.size(); i += kBatch) b->push(events.subspan(i, std::min(kBatch, events.size() - i)), sink);
  b->finish(sink);
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.stats = b->stats();
  if (r.labels.size() != events.size()) throw std::logic_error("a backend lost events");
  return r;
}

}  // namespace evms::eval
