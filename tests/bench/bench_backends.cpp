// Backend throughput, default parameters:
//  - run/BACKEND_INPUT: one core, events held in memory so that only the method is timed, with
//    the time per event of its clustering and tracking and the kernel evaluations per event;
//  - stages/INPUT/threads:N: evms run's stages on golden as a whole, from the recording to
//    events.csv and tracks.csv, with the busy time of each stage per event (read; the method as
//    filter and packets, cluster and track; write) on N threads.
// Reading and writing alone have their own benchmarks (bench_io.cpp). Real recordings are used
// when ../shared/data/real is present.
//   build/bin/bench_backends --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include "host/backend/backend.h"
#include "host/cli/run_stages.h"
#include "tests/support/encoders.h"
#include "tests/support/read_all.h"

namespace evms {
namespace {

struct NullSink final : OutputSink {
  std::int64_t labelled = 0;
  void on_event(const LabelledEvent& e) override { labelled += e.label >= 0; }
  void on_track(const TrackUpdate&) override {}
};

void run(benchmark::State& state, const std::string& backend, const std::string& source) {
  std::string path = source;
  if (source.find("://") == std::string::npos) {
    const std::string dir = test::shared_data_dir();
    if (dir.empty()) {
      state.SkipWithError("../shared/data/real is absent");
      return;
    }
    path = dir + "/" + source;
  }
  const auto events = test::read_all(path);
  const SensorSize sensor = read::open_source(path, {})->info().sensor;
  backend::BackendStats stats;
  std::int64_t cluster_ns = 0, track_ns = 0;
  for (auto _ : state) {
    auto b = backend::make_backend(backend, backend::options_for(Params{}, sensor));
    NullSink sink;
    b->push(events, sink);
    b->finish(sink);
    benchmark::DoNotOptimize(sink.labelled);
    stats = b->stats();
    cluster_ns += stats.cluster_ns, track_ns += stats.track_ns;
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(events.size()));
  state.counters["events"] = static_cast<double>(events.size());
  state.counters["kept"] = static_cast<double>(stats.events_kept) / static_cast<double>(events.size());
  state.counters["iters/packet"] = stats.packets ? static_cast<double>(stats.iterations) / stats.packets : 0;
  state.counters["kernel/event"] = static_cast<double>(stats.kernel_evaluations) / static_cast<double>(events.size());
  // The stages' time per event (the backends that time them: golden); filter and the rest is the
  // time per event less these.
  const double per_event = 1.0 / (static_cast<double>(state.iterations()) * static_cast<double>(events.size()));
  state.counters["cluster_ns/ev"] = static_cast<double>(cluster_ns) * per_event;
  state.counters["track_ns/ev"] = static_cast<double>(track_ns) * per_event;
  state.counters["us/packet"] = benchmark::Counter(static_cast<double>(stats.packets) * state.iterations(),
                                                   benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

std::string recording(const std::string& source) {
  if (source.find("://") != std::string::npos) return source;
  const std::string dir = test::shared_data_dir();
  return dir.empty() ? "" : dir + "/" + source;
}

void stages(benchmark::State& state, const std::string& source) {
  const std::string path = recording(source);
  if (path.empty()) {
    state.SkipWithError("../shared/data/real is absent");
    return;
  }
  const int threads = static_cast<int>(state.range(0));
  test::TempDir dir;
  cli::StageReport report;
  backend::BackendStats stats;
  std::int64_t events = 0, read_ns = 0, method_ns = 0, write_ns = 0, cluster_ns = 0, track_ns = 0;
  for (auto _ : state) {
    auto in = read::open_source(path, {});
    auto b = backend::make_backend("golden", backend::options_for(Params{}, in->info().sensor));
    cli::Writers writers(dir.path("out"), "csv", in->info().sensor);
    cli::Collector sink(true);
    cli::StageOptions o;
    o.threads = threads;
    report = cli::run_stages(*in, *b, sink, writers, o);
    stats = b->stats();
    events += stats.events_in;
    read_ns += report.read_ns, method_ns += report.method_ns, write_ns += report.write_ns;
    cluster_ns += stats.cluster_ns, track_ns += stats.track_ns;
  }
  state.SetItemsProcessed(events);
  state.counters["events"] = static_cast<double>(stats.events_in);
  state.counters["threads"] = threads;
  const double per_event = 1.0 / static_cast<double>(events);
  state.counters["read_ns/ev"] = static_cast<double>(read_ns) * per_event;
  state.counters["filter_ns/ev"] = static_cast<double>(method_ns - cluster_ns - track_ns) * per_event;
  state.counters["cluster_ns/ev"] = static_cast<double>(cluster_ns) * per_event;
  state.counters["track_ns/ev"] = static_cast<double>(track_ns) * per_event;
  state.counters["write_ns/ev"] = static_cast<double>(write_ns) * per_event;
  state.counters["kernel/event"] = static_cast<double>(stats.kernel_evaluations) / static_cast<double>(stats.events_in);
}
#define EVMS_STAGES(name, source) \
  BENCHMARK_CAPTURE(stages, name, source)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->MinTime(2)->UseRealTime()
EVMS_STAGES(dvxplorer_indoor, "dvxplorer_indoor.aedat4");
EVMS_STAGES(gen3_moving_blob, "gen3_moving_blob.evt2.raw");
EVMS_STAGES(gen41_dense_scene, "gen41_dense_scene.evt3.raw");

#define EVMS_BENCH(backend)                                                                                                  \
  BENCHMARK_CAPTURE(run, backend##_dvxplorer_indoor, #backend, "dvxplorer_indoor.aedat4")->Unit(benchmark::kMillisecond)->MinTime(2); \
  BENCHMARK_CAPTURE(run, backend##_gen3_moving_blob, #backend, "gen3_moving_blob.evt2.raw")->Unit(benchmark::kMillisecond)->MinTime(2); \
  BENCHMARK_CAPTURE(run, backend##_gen41_dense_scene, #backend, "gen41_dense_scene.evt3.raw")->Unit(benchmark::kMillisecond)->MinTime(2); \
  BENCHMARK_CAPTURE(run, backend##_rotation_2s, #backend, "gen://rotation?duration-s=2")->Unit(benchmark::kMillisecond)->MinTime(2)
EVMS_BENCH(golden);
EVMS_BENCH(fixed);

}  // namespace
}  // namespace evms

BENCHMARK_MAIN();
