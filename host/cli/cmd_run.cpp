// evms run [SOURCE] : source -> backend -> labelled events and tracks, with a summary.
#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "host/backend/backend.h"
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
};

// Writes the outputs (when asked) and counts what the summary reports.
class RunSink final : public OutputSink {
 public:
  // `out_dir` "-": CSV rows on standard output, and no tracks file.
  RunSink(const std::string& out_dir, const std::string& format, SensorSize sensor) {
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
  // Labelled events are held and written a batch at a time (write_held), so that the summary can
  // time writing apart from the method.
  void on_event(const LabelledEvent& e) override {
    latency.labelled();
    ++events;
    if (e.label == kNoiseLabel) ++noise;
    if (!files.empty() || csv_) held_.push_back(e);
  }
  void write_held() {
    for (const LabelledEvent& e : held_) {
      if (csv_) csv_->write(e);
      if (npy_) npy_->write(e);
      if (evt3_) evt3_->write(e);
      if (aedat4_) aedat4_->write(e);
    }
    held_.clear();
  }
  void on_track(const TrackUpdate& u) override {
    ++track_rows;
    const auto id = static_cast<size_t>(u.id);
    if (u.state == TrackState::kConfirmed) {
      if (id >= seen_.size()) seen_.resize(id + 1, false);
      if (!seen_[id]) seen_[id] = true, ++confirmed;
    }
    if (tracks_) tracks_->write(u);
  }
  void on_packet(const PacketSummary&) override {}
  void close() {
    write_held();
    if (csv_) csv_->close();
    if (npy_) npy_->close();
    if (evt3_) evt3_->close();
    if (aedat4_) aedat4_->close();
    if (tracks_) tracks_->close();
  }

  std::vector<std::string> files;  // written, for the summary
  std::int64_t events = 0, noise = 0, track_rows = 0, confirmed = 0;
  eval::ArrivalLatency latency;  // live sources: from arrival to label

 private:
  std::vector<LabelledEvent> held_;
  std::vector<bool> seen_;  // track IDs with at least one confirmed update
  std::optional<write::LabelledEventsCsv> csv_;
  std::optional<write::LabelledEventsNpy> npy_;
  std::optional<write::Evt3Events> evt3_;
  std::optional<write::Aedat4Events> aedat4_;
  std::optional<write::TracksCsv> tracks_;
};

volatile std::sig_atomic_t g_interrupted = 0;

void run(const RunOptions& o) {
  auto source = read::open_source(o.source, o.source_options);
  const read::SourceInfo& info = source->info();
  const Params params = o.method.resolve(info.sensor);
  auto backend = backend::make_backend(o.backend, {params, info.sensor, o.core, o.device, o.baud});
  RunSink sink(o.out, o.format, info.sensor);
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

  std::vector<Event> batch(4096);
  TimeUs t_first = 0, t_last = 0;
  bool any = false;
  const auto start = std::chrono::steady_clock::now();
  // A source that fails part way (a camera unplugged, a corrupt record) ends the input: what
  // came before it is labelled and written, then the cause is reported.
  std::string source_error;
  // Wall clock by stage: reading, the backend, writing (the backend's own split comes from its stats).
  std::int64_t read_ns = 0, method_ns = 0, write_ns = 0;
  auto mark = std::chrono::steady_clock::now();
  const auto lap = [&mark](std::int64_t& total) {
    const auto now = std::chrono::steady_clock::now();
    total += std::chrono::duration_cast<std::chrono::nanoseconds>(now - mark).count();
    mark = now;
  };
  for (;;) {
    if (g_interrupted && !live) break;
    size_t n = 0;
    try {
      n = source->read(batch);
    } catch (const read::InputError& e) {
      source_error = e.what();
    }
    lap(read_ns);
    if (n == 0) break;
    if (!any) t_first = batch[0].t, any = true;
    t_last = batch[n - 1].t;
    sink.latency.arrived(source->arrivals());
    backend->push(std::span(batch).first(n), sink);
    lap(method_ns);
    sink.write_held();
    lap(write_ns);
    progress.update(source->progress(), backend->stats().events_in);
  }
  backend->finish(sink);
  lap(method_ns);
  sink.close();
  lap(write_ns);
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
    // Where the wall clock went. A live source's read time is mostly waiting for events.
    const auto seconds = [](std::int64_t ns) { return static_cast<double>(ns) * 1e-9; };
    std::fprintf(summary, "time        read %.3f s%s, method %.3f s", seconds(read_ns), live ? " (waiting included)" : "", seconds(method_ns));
    if (s.cluster_ns + s.track_ns > 0) {
      std::fprintf(summary, " (cluster %.3f, track %.3f, filter and the rest %.3f)", seconds(s.cluster_ns), seconds(s.track_ns),
                   seconds(std::max<std::int64_t>(0, method_ns - s.cluster_ns - s.track_ns)));
    }
    std::fprintf(summary, ", write %.3f s\n", seconds(write_ns));
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
  if (!sink.files.empty()) {
    std::string listed;
    for (const std::string& f : sink.files) listed += (listed.empty() ? "" : ", ") + f;
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
  add_source_options(*cmd, o->source_options);
  add_replay_options(*cmd, o->source_options, Pacing::kRealtimeFlag);
  add_method_options(*cmd, o->method);
  cmd->callback([o] { run(*o); });
}

}  // namespace evms::cli
