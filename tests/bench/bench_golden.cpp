// Golden-model throughput on one core, default parameters, events held in memory so that
// only the method is timed. Real recordings are used when ../shared/data/real is present.
//   build/bin/bench_golden --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include "golden/pipeline.h"
#include "tests/support/read_all.h"

namespace evms {
namespace {

struct NullSink final : OutputSink {
  std::int64_t labelled = 0;
  void on_event(const LabelledEvent& e) override { labelled += e.label >= 0; }
  void on_track(const TrackUpdate&) override {}
};

void run_golden(benchmark::State& state, const std::string& source) {
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
  golden::PipelineStats stats;
  for (auto _ : state) {
    golden::Pipeline pipeline(Params{}, sensor);
    NullSink sink;
    for (const Event& e : events) pipeline.push(e, sink);
    pipeline.finish(sink);
    benchmark::DoNotOptimize(sink.labelled);
    stats = pipeline.stats();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(events.size()));
  state.counters["events"] = static_cast<double>(events.size());
  state.counters["kept"] = static_cast<double>(stats.events_kept) / static_cast<double>(events.size());
  state.counters["iters/packet"] = stats.packets ? static_cast<double>(stats.iterations) / stats.packets : 0;
  state.counters["us/packet"] = benchmark::Counter(static_cast<double>(stats.packets) * state.iterations(),
                                                   benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

BENCHMARK_CAPTURE(run_golden, dvxplorer_indoor, std::string("dvxplorer_indoor.aedat4"))->Unit(benchmark::kMillisecond)->MinTime(2);
BENCHMARK_CAPTURE(run_golden, gen3_moving_blob, std::string("gen3_moving_blob.evt2.raw"))->Unit(benchmark::kMillisecond)->MinTime(2);
BENCHMARK_CAPTURE(run_golden, rotation_2s, std::string("gen://rotation?duration-s=2"))->Unit(benchmark::kMillisecond)->MinTime(2);

}  // namespace
}  // namespace evms

BENCHMARK_MAIN();
