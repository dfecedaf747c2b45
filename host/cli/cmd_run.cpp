// evms run [SOURCE] : source -> backend -> labelled events and tracks, with a summary.
#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <optional>

#include <thread>

#include "host/backend/backend.h"
#include "host/cli/bounded_queue.h"
#include "host/cli/common.h"
#include "host/cli/commands.h"
#include "host/eval/latency_histogram.h"
#include "host/read/live/live_source.h"
#include "host/write/binary_writers.h"
#include "host/write/event_writers.h"

namespace evms::cli {
namespace {

struct RunOptions {
  std::string source = "gen://rotation";
  std::string backend = "golden";
  std::string out;
  std::string format = "csv";
  std::string device;
  std::string core = "host";
  int baud = 3000000;
  read::SourceOptions source_options;
  Method method;
  bool quiet = false;
  int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
};

// Events read at a time: one batch through the three stages.
constexpr size_t kBatchEvents = 16384;

// What the method hands to the writing stage for one batch of input: its labelled events and
// the track updates they produced.
struct OutputBatch {
  std::vector<LabelledEvent> events;
  std::vector<TrackUpdate> tracks;
};

// The method's side of the outputs: collects what the backend labels into the batch for the
// writers, and counts what the summary reports.
class Collector final : public OutputSink {
 public:
  explicit Collector(bool keep) : keep_(keep) {}
  void on_event(const LabelledEvent& e) override { on_events({&e, 1}); }
  void on_events(std::span<const LabelledEvent> labelled) override {
    events += static_cast<std::int64_t>(labelled.size());
    labelled_since_ += static_cast<std::int64_t>(labelled.size());
    for (const LabelledEvent& e : labelled) noise += e.label == kNoiseLabel;
    if (keep_) batch_.events.insert(batch_.events.end(), labelled.begin(), labelled.end());
  }
  void on_track(const TrackUpdate& u) override {
    ++track_rows;
    const auto id = static_cast<size_t>(u.id);
    if (u.state == TrackState::kConfirmed) {
      if (id >= seen_.size()) seen_.resize(id + 1, false);
      if (!seen_[id]) seen_[id] = true, ++confirmed;
    }
    if (keep_) batch_.tracks.push_back(u);
  }
  // The events labelled since the last call: their labels are out now (one clock read for all).
  void stamp_latency() {
    latency.labelled(labelled_since_);
    labelled_since_ = 0;
  }
  OutputBatch take() { return std::exchange(batch_, {}); }

  std::int64_t events = 0, noise = 0, track_rows = 0, confirmed = 0;
  eval::ArrivalLatency latency;  // live sources: from arrival to label

 private:
  bool keep_;
  OutputBatch batch_;
  std::int64_t labelled_since_ = 0;
  std::vector<bool> seen_;  // track IDs with at least one confirmed update
};

// The writing stage: the labelled events in the chosen format and tracks.csv.
class Writers {
 public:
  // `out_dir` "-": CSV rows on standard output, and no tracks file.
  Writers(const std::string& out_dir, const std::string& format, SensorSize sensor) {
    if (out_dir == "-") {
      if (format != "csv") throw std::invalid_argument("--out - writes CSV only (--format " + format + " needs a folder)");
      csv_.emplace("-", sensor);
      return;
    }
    if (out_dir.empty()) return;
    std::filesystem::create_directories(out_dir);
    if (format == "csv") csv_.emplace(out_dir + "/events.csv", sensor), files.push_back(out_dir + "/events.csv");
    if (format == "npy") npy_.emplace(out_dir + "/events.npy"), files.push_back(out_dir + "/events.npy");
    if (format == "evt3") {
      evt3_.emplace(out_dir + "/events.raw", out_dir + "/labels.csv", sensor);
      files.push_back(out_dir + "/events.raw");
      files.push_back(out_dir + "/labels.csv");
    }
    if (format == "aedat4") {
      aedat4_.emplace(out_dir + "/events.aedat4", out_dir + "/labels.csv", sensor);
      files.push_back(out_dir + "/events.aedat4");
      files.push_back(out_dir + "/labels.csv");
    }
    tracks_.emplace(out_dir + "/tracks.csv");
    files.push_back(out_dir + "/tracks.csv");
  }
  bool any() const { return csv_.has_value() || !files.empty(); }
  void write(const OutputBatch& b) {
    for (const LabelledEvent& e : b.events) {
      if (csv_) csv_->write(e);
      if (npy_) npy_->write(e);
      if (evt3_) evt3_->write(e);
      if (aedat4_) aedat4_->write(e);
    }
    if (tracks_) {
      for (const TrackUpdate& u : b.tracks) tracks_->write(u);
    }
  }
  void close() {
    if (csv_) csv_->close();
    if (npy_) npy_->close();
    if (evt3_) evt3_->close();
    if (aedat4_) aedat4_->close();
    if (tracks_) tracks_->close();
  }

  std::vector<std::string> files;  // written, for the summary

 private:
  std::optional<write::LabelledEventsCsv> csv_;
  std::optional<write::LabelledEventsNpy> npy_;
  std::optional<write::Evt3Events> evt3_;
  std::optional<write::Aedat4Events> aedat4_;
  std::optional<write::TracksCsv> tracks_;
};

// One batch of input as the reading stage hands it on.
struct InputBatch {
  std::vector<Event> events;
  std::vector<std::int64_t> arrivals;  // live sources: each event's arrival
  double progress = -1;                // of the source, after this batch
};

volatile std::sig_atomic_t g_interrupted = 0;

void run(const RunOptions& o) {
  auto source = read::open_source(o.source, o.source_options);
  const read::SourceInfo& info = source->info();
  const Params params = o.method.resolve(info.sensor);
  auto backend = backend::make_backend(o.backend, {params, info.sensor, o.core, o.device, o.baud});
  Writers writers(o.out, o.format, info.sensor);
  Progress progress(!o.quiet);

  // Ctrl-C (or a SIGTERM) ends any source as if its input had ended, so that the outputs are
  // complete files: a live source delivers what it has buffered, a recording stops at the next
  // batch. A second Ctrl-C ends evms at once.
  const bool live = dynamic_cast<read::LiveSource*>(source.get()) != nullptr;
  g_interrupted = 0;
  for (const int sig : {SIGINT, SIGTERM}) {
    std::signal(sig, [](int) {
      g_interrupted = 1;
      read::end_live_sources();
      std::signal(SIGINT, SIG_DFL), std::signal(SIGTERM, SIG_DFL);
    });
  }

  Collector sink(writers.any());
  TimeUs t_first = 0, t_last = 0;
  bool any = false;
  const auto start = std::chrono::steady_clock::now();
  // A source that fails part way (a camera unplugged, a corrupt record) ends the input: what
  // came before it is labelled and written, then the cause is reported.
  std::string source_error;
  // Busy time by stage: reading, the backend, writing (the backend's own split comes from its stats).
  std::int64_t read_ns = 0, method_ns = 0, write_ns = 0;
  const auto since = [](std::chrono::steady_clock::time_point& mark) {
    const auto now = std::chrono::steady_clock::now();
    const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(now - mark).count();
    mark = now;
    return ns;
  };
  // Reading: the next batch, or an empty one at the end (or at Ctrl-C, or after a failure).
  const auto read_batch = [&](InputBatch& b) {
    b.events.resize(kBatchEvents);
    size_t n = 0;
    if (!g_interrupted || live) {
      try {
        n = source->read(b.events);
      } catch (const read::InputError& e) {
        source_error = e.what();
      }
    }
    b.events.resize(n);
    const auto arrivals = source->arrivals();
    b.arrivals.assign(arrivals.begin(), arrivals.end());
    b.progress = source->progress();
  };
  // The method: labels a batch into the collector; its outputs go to the writers.
  const auto label_batch = [&](const InputBatch& b) {
    if (!any) t_first = b.events.front().t, any = true;
    t_last = b.events.back().t;
    sink.latency.arrived(b.arrivals);
    backend->push(b.events, sink);
    sink.stamp_latency();
    progress.update(b.progress, backend->stats().events_in);
  };
  const auto finish_method = [&] {
    backend->finish(sink);
    sink.stamp_latency();
  };

  if (o.threads <= 1) {
    InputBatch in;
    auto mark = std::chrono::steady_clock::now();
    for (;;) {
      read_batch(in);
      read_ns += since(mark);
      if (in.events.empty()) break;
      label_batch(in);
      method_ns += since(mark);
      writers.write(sink.take());
      write_ns += since(mark);
    }
    finish_method();
    method_ns += since(mark);
    writers.write(sink.take());
    writers.close();
    write_ns += since(mark);
  } else {
    // Reading, the method and writing, each in a thread of its own, joined by queues: the
    // method sees the same batches in the same order, so the outputs are the same bytes.
    BoundedQueue<InputBatch> inputs(4);
    BoundedQueue<OutputBatch> outputs(4);
    std::exception_ptr reader_failed, writer_failed;
    std::thread reader([&] {
      try {
        auto mark = std::chrono::steady_clock::now();
        for (;;) {
          InputBatch b;
          read_batch(b);
          read_ns += since(mark);
          const bool end = b.events.empty();
          if (!end && !inputs.push(std::move(b))) break;
          if (end) break;
          mark = std::chrono::steady_clock::now();
        }
      } catch (...) {
        reader_failed = std::current_exception();
      }
      inputs.close();
    });
    std::thread writer([&] {
      try {
        OutputBatch b;
        while (outputs.pop(b)) {
          auto mark = std::chrono::steady_clock::now();
          writers.write(b);
          write_ns += since(mark);
        }
        auto mark = std::chrono::steady_clock::now();
        writers.close();
        write_ns += since(mark);
      } catch (...) {
        writer_failed = std::current_exception();
        outputs.close();  // the method stops handing over what could not be written
      }
    });
    try {
      InputBatch b;
      while (inputs.pop(b)) {
        auto mark = std::chrono::steady_clock::now();
        label_batch(b);
        method_ns += since(mark);
        outputs.push(sink.take());
      }
      auto mark = std::chrono::steady_clock::now();
      finish_method();
      method_ns += since(mark);
      outputs.push(sink.take());
    } catch (...) {
      inputs.close();
      outputs.close();
      reader.join();
      writer.join();
      throw;
    }
    outputs.close();
    reader.join();
    writer.join();
    if (reader_failed) std::rethrow_exception(reader_failed);
    if (writer_failed) std::rethrow_exception(writer_failed);
  }
  progress.done();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const backend::BackendStats s = backend->stats();
  if (sink.events != s.events_in) {
    throw std::logic_error("backend '" + o.backend + "' returned " + grouped(sink.events) + " labelled events for " +
                           grouped(s.events_in) + " inputs");
  }
  // With the rows on standard output, the summary goes to standard error.
  std::FILE* summary = o.out == "-" ? stderr : stdout;
  const double span_s = static_cast<double>(t_last - t_first) * 1e-6;
  std::fprintf(summary, "source      %s (%s, %s)\n", info.name.c_str(), info.format.c_str(), sensor_text(info).c_str());
  std::fprintf(summary, "backend     %s\n", o.backend.c_str());
  std::fprintf(summary, "events in   %s over %.3f s of sensor time (%s labelled noise)\n", grouped(s.events_in).c_str(), span_s,
              grouped(sink.noise).c_str());
  std::fprintf(summary, "throughput  %sevents/s (%.2f s wall clock, reading included)\n", si(s.events_in / std::max(wall, 1e-9)).c_str(), wall);
  std::fprintf(summary, "packets     %s, %.1f mean-shift iterations each", grouped(s.packets).c_str(),
              s.packets ? static_cast<double>(s.iterations) / s.packets : 0.0);
  // Counted by the backends that count them (golden).
  if (s.kernel_evaluations > 0) {
    std::fprintf(summary, ", %.1f kernel evaluations per event", static_cast<double>(s.kernel_evaluations) / static_cast<double>(s.events_in));
  }
  std::fprintf(summary, "\n");
  {
    // Where the time went, stage by stage (busy time: with threads the stages overlap). A live
    // source's read time is mostly waiting for events.
    const auto seconds = [](std::int64_t ns) { return static_cast<double>(ns) * 1e-9; };
    std::fprintf(summary, "time        read %.3f s%s, method %.3f s", seconds(read_ns), live ? " (waiting included)" : "", seconds(method_ns));
    if (s.cluster_ns + s.track_ns > 0) {
      std::fprintf(summary, " (cluster %.3f, track %.3f, filter and the rest %.3f)", seconds(s.cluster_ns), seconds(s.track_ns),
                   seconds(std::max<std::int64_t>(0, method_ns - s.cluster_ns - s.track_ns)));
    }
    std::fprintf(summary, ", write %.3f s%s\n", seconds(write_ns), o.threads > 1 ? " (each in its own thread)" : "");
  }
  std::fprintf(summary, "clusters    %.2f per packet on average\n", s.packets ? static_cast<double>(s.clusters) / s.packets : 0.0);
  std::fprintf(summary, "tracks      %s started, %s confirmed, %s track updates\n", grouped(s.tracks_started).c_str(),
              grouped(sink.confirmed).c_str(), grouped(sink.track_rows).c_str());
  if (s.unassigned_clusters) std::fprintf(summary, "            %s clusters found no free track slot (labelled noise)\n", grouped(s.unassigned_clusters).c_str());
  if (o.backend == "board") {
    std::fprintf(summary, "link        %s frames failed their check, %s events sent again, %s labels lost (labelled %d)\n",
                 grouped(s.link_bad_frames).c_str(), grouped(s.link_events_resent).c_str(), grouped(s.link_labels_lost).c_str(),
                 kLabelLostOnLink);
  }
  if (!live && !source->skipped().empty()) {
    const char* separator = "skipped     ";
    for (const auto& [kind, count] : source->skipped()) {
      std::fprintf(summary, "%s%s %s", separator, grouped(count).c_str(), kind.c_str());
      separator = "; ";
    }
    std::fprintf(summary, "\n");
  }
  if (live) {
    std::fprintf(summary, "live        %s events dropped while the backend was behind", grouped(source->dropped()).c_str());
    for (const auto& [kind, count] : source->skipped()) std::fprintf(summary, "; %s %s", grouped(count).c_str(), kind.c_str());
    std::fprintf(summary, "\n");
    const eval::LatencyHistogram& l = sink.latency.histogram();
    std::fprintf(summary, "latency     arrival to label: p50 %.0f us, p99 %.0f us, max %.0f us over %s events\n", l.quantile_us(0.5),
                l.quantile_us(0.99), static_cast<double>(l.max_ns()) * 1e-3, grouped(l.count()).c_str());
  }
  if (!writers.files.empty()) {
    std::string listed;
    for (const std::string& f : writers.files) listed += (listed.empty() ? "" : ", ") + f;
    std::fprintf(summary, "outputs     %s\n", listed.c_str());
  }
  if (!source_error.empty()) {
    std::fflush(summary);
    std::fprintf(stderr, "evms: %s\n", read::printable(source_error).c_str());
    throw ExitStatus{1};
  }
  // A live source has no end but the one the user gives it; a recording cut short says so.
  if (g_interrupted && !live) {
    std::fprintf(summary, "interrupted before the end of the source: the outputs hold the events read until then\n");
    std::fflush(summary);
    throw ExitStatus{130};
  }
}

}  // namespace

void register_run(CLI::App& app) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand("run", "cluster and track a source; write labelled events and tracks");
  cmd->add_option("source", o->source, "event file or URI (default: a generated rotation scene)")->default_val(o->source);
  std::string names;
  for (const auto& b : backend::backends()) names += std::string(names.empty() ? "" : ", ") + b.name;
  cmd->add_option("--backend", o->backend, "implementation to run: " + names)->default_val(o->backend);
  cmd->add_option("--out", o->out, "directory for the labelled events and tracks.csv (not written when absent); - writes the CSV rows to standard output and the summary to standard error");
  cmd->add_option("--format", o->format, "labelled events as csv (events.csv), npy (events.npy, a NumPy structured array), evt3 "
                                         "(events.raw, EVT 3.0) or aedat4 (events.aedat4, AEDAT 4.0); evt3 and aedat4 put the labels in labels.csv, one per event")
      ->default_val(o->format)
      ->check(CLI::IsMember({"csv", "npy", "evt3", "aedat4"}));
  cmd->add_option("--core", o->core, "core build of the fixed and rtl backends: host (1280x720), arty or ice40 (hls/core/shape.h)")
      ->default_val(o->core);
  cmd->add_option("--device", o->device, "serial device of the board backend (or the path evms vboard prints)");
  cmd->add_option("--baud", o->baud, "line rate of the board's serial link")->default_val(o->baud);
  cmd->add_flag("--quiet", o->quiet, "no progress bar");
  cmd->add_option("--threads", o->threads, "1: read, label and write in turn; 2 or more: reading, the method and writing each in a "
                                          "thread of its own (the outputs are the same bytes either way)")
      ->default_str("the cores present")
      ->check(CLI::Range(1, 256));
  add_source_options(*cmd, o->source_options);
  add_replay_options(*cmd, o->source_options, Pacing::kRealtimeFlag);
  add_method_options(*cmd, o->method);
  cmd->callback([o] { run(*o); });
}

}  // namespace evms::cli
