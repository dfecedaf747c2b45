// The stages of `evms run`: reading, the method (a backend) and writing, in turn on one thread
// or each on a thread of its own joined by bounded queues. The method sees the same batches in
// the same order either way, so the outputs are the same bytes. bench_backends times the same
// stages.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "host/backend/backend.h"
#include "host/eval/latency_histogram.h"
#include "host/read/event_source.h"
#include "host/write/binary_writers.h"
#include "host/write/event_writers.h"
#include "types/output.h"

namespace evms::cli {

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
  OutputBatch take() {
    OutputBatch out = std::move(batch_);
    batch_ = std::move(spare_);
    spare_ = {};
    return out;
  }
  // A batch the writers are done with: its memory holds the batch after next. Reusing it spares
  // the fresh pages that a new batch of this size (hundreds of kB, beyond malloc's reuse) costs
  // a page fault each.
  void recycle(OutputBatch&& spent) {
    spent.events.clear();
    spent.tracks.clear();
    spare_ = std::move(spent);
  }

  std::int64_t events = 0, noise = 0, track_rows = 0, confirmed = 0;
  eval::ArrivalLatency latency;  // live sources: from arrival to label

 private:
  bool keep_;
  OutputBatch batch_, spare_;
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

// What a run of the stages measured.
struct StageReport {
  std::int64_t read_ns = 0, method_ns = 0, write_ns = 0;  // busy time of each stage
  TimeUs t_first = 0, t_last = 0;                          // the first and last event's time
  std::string source_error;  // a source that failed part way: what came before was labelled and written
};

struct StageOptions {
  int threads = 1;                                         // 1: in turn; more: a thread a stage
  // Checked before each read: true ends the input there (Ctrl-C). May be empty.
  std::function<bool()> stop;
  // After each batch the method labelled: the source's progress (or -1) and the events in.
  std::function<void(double, std::int64_t)> progress;
};

// Reads `source` to its end through `backend` into `sink`, and writes what `sink` kept with
// `writers` (closing them). Throws what a writer or the backend throws.
StageReport run_stages(read::EventSource& source, backend::Backend& backend, Collector& sink, Writers& writers, const StageOptions& o);

// Listens to a backend with input of its own (a board whose events enter at its AER pins,
// Backend::listen) until `o.stop` says so or its input has reached `limit` events (0: no
// limit), then flushes it; writes what `sink` kept as it comes. The report's times are those
// of the first and last track update.
StageReport listen_stages(backend::Backend& backend, Collector& sink, Writers& writers, const StageOptions& o, std::int64_t limit);

}  // namespace evms::cli
