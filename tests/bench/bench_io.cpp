// Reading and writing throughput on one core: each reader decoding a recording from the page
// cache to events in time order, and each writer of evms run writing labelled events to a file.
// Real recordings are used when ../shared/data/real is present.
//   build/bin/bench_io --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>

#include "host/write/binary_writers.h"
#include "host/write/event_writers.h"
#include "tests/support/encoders.h"
#include "tests/support/read_all.h"

namespace evms {
namespace {

// Reads `path` to its end in every iteration, opening it anew, and counts the events.
void read_through(benchmark::State& state, const std::string& path, const read::SourceOptions& options) {
  std::int64_t events = 0;
  std::vector<Event> batch(1 << 14);
  for (auto _ : state) {
    auto source = read::open_source(path, options);
    events = 0;
    while (const size_t n = source->read(batch)) events += static_cast<std::int64_t>(n);
    benchmark::DoNotOptimize(batch.data());
  }
  state.SetItemsProcessed(state.iterations() * events);
  state.counters["events"] = static_cast<double>(events);
}

void read_file(benchmark::State& state, const std::string& name) {
  const std::string dir = test::shared_data_dir();
  if (dir.empty()) {
    state.SkipWithError("../shared/data/real is absent");
    return;
  }
  read_through(state, dir + "/" + name, {});
}
BENCHMARK_CAPTURE(read_file, evt2_gen3_moving_blob, "gen3_moving_blob.evt2.raw")->Unit(benchmark::kMillisecond)->MinTime(1);
BENCHMARK_CAPTURE(read_file, evt3_gen41_dense_scene, "gen41_dense_scene.evt3.raw")->Unit(benchmark::kMillisecond)->MinTime(1);
BENCHMARK_CAPTURE(read_file, aedat4_dvxplorer_indoor, "dvxplorer_indoor.aedat4")->Unit(benchmark::kMillisecond)->MinTime(1);
BENCHMARK_CAPTURE(read_file, ros2_libcaer_rollover, "ros2/libcaer_rollover")->Unit(benchmark::kMillisecond)->MinTime(1);

// The same 1 M events (640x480) in a file of each format that needs no recording: evms's own
// events.csv and events.npy, a CSV in Metavision's column order, EVT 2.1 RAW (a word an event:
// random events share none), a ROS 1 bag in lz4 or bz2 chunks, a ROS 2 MCAP file in zstd chunks.
void read_written(benchmark::State& state, const std::string& format) {
  const std::vector<Event> events = test::sample_events(1 << 20, {640, 480});
  static const test::TempDir dir;
  const std::string path = dir.path("events." + format);
  if (format == "csv") {
    write::LabelledEventsCsv w(path, {640, 480});
    for (const Event& e : events) w.write(LabelledEvent{e, -1});
    w.close();
  } else if (format == "npy") {
    write::LabelledEventsNpy w(path);
    for (const Event& e : events) w.write(LabelledEvent{e, -1});
    w.close();
  } else if (format == "xypt.csv") {
    std::string text = "x,y,p,t\n";
    for (const Event& e : events) text += std::to_string(e.x) + "," + std::to_string(e.y) + "," + std::to_string(e.p) + "," + std::to_string(e.t) + "\n";
    dir.write("events." + format, text);
  } else if (format == "evt21.raw") {
    dir.write("events." + format, test::evt21(events, {640, 480}, true));
  } else {
    const bool mcap = format == "mcap";
    std::vector<test::Bytes> messages;
    for (size_t at = 0; at < events.size(); at += 4096) {
      messages.push_back(test::dvs_event_array_cdr({events.begin() + static_cast<long>(at), events.begin() + static_cast<long>(std::min(events.size(), at + 4096))},
                                                   {640, 480}, !mcap));
    }
    if (mcap) {
      dir.write("events." + format, test::mcap_file({{"/dvs/events", "dvs_msgs/msg/EventArray", messages}}, "zstd", 16));
    } else {
      dir.write("events." + format, test::ros1_bag({{"/dvs/events", "dvs_msgs/EventArray", messages}}, format == "bz2.bag" ? "bz2" : "lz4", 16));
    }
  }
  read::SourceOptions options;
  options.width = 640, options.height = 480;
  read_through(state, path, options);
  if (state.counters["events"] != static_cast<double>(events.size())) state.SkipWithError("read back a different number of events");
}
BENCHMARK_CAPTURE(read_written, csv, "csv")->Unit(benchmark::kMillisecond)->MinTime(1);
BENCHMARK_CAPTURE(read_written, csv_metavision_order, "xypt.csv")->Unit(benchmark::kMillisecond)->MinTime(1);
BENCHMARK_CAPTURE(read_written, npy, "npy")->Unit(benchmark::kMillisecond)->MinTime(1);
BENCHMARK_CAPTURE(read_written, evt21, "evt21.raw")->Unit(benchmark::kMillisecond)->MinTime(1);
BENCHMARK_CAPTURE(read_written, ros1_bag_lz4, "bag")->Unit(benchmark::kMillisecond)->MinTime(1);
BENCHMARK_CAPTURE(read_written, ros1_bag_bz2, "bz2.bag")->Unit(benchmark::kMillisecond)->MinTime(1);
BENCHMARK_CAPTURE(read_written, ros2_mcap_zstd, "mcap")->Unit(benchmark::kMillisecond)->MinTime(1);

template <class Writer>
Writer make(const std::string& base);
template <>
write::LabelledEventsCsv make(const std::string& base) { return write::LabelledEventsCsv(base + ".csv", {640, 480}); }
template <>
write::LabelledEventsNpy make(const std::string& base) { return write::LabelledEventsNpy(base + ".npy"); }
template <>
write::Evt3Events make(const std::string& base) { return write::Evt3Events(base + ".raw", base + ".labels", {640, 480}); }
template <>
write::Aedat4Events make(const std::string& base) { return write::Aedat4Events(base + ".aedat4", base + ".labels", {640, 480}); }

template <class Writer>
void write_events(benchmark::State& state) {
  const std::vector<Event> events = test::sample_events(1 << 20, {640, 480});
  char dir[] = "/tmp/evms-bench-XXXXXX";
  if (!mkdtemp(dir)) {
    state.SkipWithError("mkdtemp failed");
    return;
  }
  const std::string base = std::string(dir) + "/events";
  for (auto _ : state) {
    Writer w = make<Writer>(base);
    std::int32_t label = 0;
    for (const Event& e : events) w.write(LabelledEvent{e, (label = (label + 1) & 15) - 1});
    w.close();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(events.size()));
  std::remove((base + ".csv").c_str()), std::remove((base + ".npy").c_str());
  std::remove((base + ".raw").c_str()), std::remove((base + ".aedat4").c_str()), std::remove((base + ".labels").c_str()), rmdir(dir);
}
BENCHMARK_TEMPLATE(write_events, write::LabelledEventsCsv)->Name("write/csv")->Unit(benchmark::kMillisecond)->MinTime(1);
BENCHMARK_TEMPLATE(write_events, write::LabelledEventsNpy)->Name("write/npy")->Unit(benchmark::kMillisecond)->MinTime(1);
BENCHMARK_TEMPLATE(write_events, write::Evt3Events)->Name("write/evt3")->Unit(benchmark::kMillisecond)->MinTime(1);
BENCHMARK_TEMPLATE(write_events, write::Aedat4Events)->Name("write/aedat4")->Unit(benchmark::kMillisecond)->MinTime(1);

}  // namespace
}  // namespace evms

BENCHMARK_MAIN();
