// evms run [SOURCE] : source -> backend -> labelled events and tracks, with a summary. With
// --listen the events enter at the board's AER pins instead (docs/link.md, "Listening").
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>

#include <thread>

#include "host/backend/backend.h"
#include "host/backend/core_config.h"
#include "host/cli/common.h"
#include "host/cli/commands.h"
#include "host/cli/run_stages.h"
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
  int baud = 0;
  std::string board_link = "labels";
  read::SourceOptions source_options;
  Method method;
  bool quiet = false;
  bool listen = false;
  bool source_given = false;
  int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
};

void run(const RunOptions& o) {
  const bool keeps_labels = board_keeps_labels(o.board_link, o.backend);
  // Listening, the events enter at the board's AER pins: there is no source on the host, and
  // the sensor is the one the board's registers hold.
  std::unique_ptr<read::EventSource> source = o.listen ? nullptr : read::open_source(o.source, o.source_options);
  const read::SourceInfo info =
      o.listen ? listening_input(o.backend, o.core, keeps_labels, o.source_given, o.source_options) : source->info();
  const Params method_params = o.method.resolve(info.sensor);
  const Params params = backend::fit_core_build(o.backend, o.core, method_params, o.method);
  auto backend = backend::make_backend(o.backend, {params, info.sensor, o.core, o.device, o.baud, keeps_labels});
  Writers writers(o.out, o.format, info.sensor);
  Progress progress(!o.quiet);

  // Ctrl-C (or a SIGTERM) ends any source as if its input had ended, so that the outputs are
  // complete files: a live source delivers what it has buffered, a recording stops at the next
  // batch. A second Ctrl-C ends evms at once.
  const bool live = o.listen || dynamic_cast<read::LiveSource*>(source.get()) != nullptr;
  catch_interrupts();

  Collector sink(writers.any());
  const auto start = std::chrono::steady_clock::now();
  StageOptions stages;
  stages.threads = o.threads;
  // Ctrl-C ends a recording at the next batch; a live source ends on its own (end_live_sources).
  // Listening, Ctrl-C ends the listening.
  stages.stop = [ends_itself = live && !o.listen] { return interrupted() && !ends_itself; };
  stages.progress = [&progress](double fraction, std::int64_t events) { progress.update(fraction, events); };
  const StageReport report = o.listen ? listen_stages(*backend, sink, writers, stages, o.source_options.window.limit)
                                      : run_stages(*source, *backend, sink, writers, stages);
  const std::int64_t read_ns = report.read_ns, method_ns = report.method_ns, write_ns = report.write_ns;
  const TimeUs t_first = report.t_first, t_last = report.t_last;
  const std::string& source_error = report.source_error;
  progress.done();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const backend::BackendStats s = backend->stats();
  if (sink.events + s.labels_kept_on_board != s.events_in) {
    throw std::logic_error("backend '" + o.backend + "' returned " + grouped(sink.events) + " labelled events for " +
                           grouped(s.events_in) + " inputs");
  }
  const auto fail_on_source_error = [&source_error] {
    std::fprintf(stderr, "evms: %s\n", read::printable(source_error).c_str());
    throw ExitStatus{1};
  };
  // A source that failed before its first event has nothing to summarize: the error alone.
  if (!source_error.empty() && s.events_in == 0) fail_on_source_error();
  // With the rows on standard output, the summary goes to standard error.
  std::FILE* summary = o.out == "-" ? stderr : stdout;
  const double span_s = static_cast<double>(t_last - t_first) * 1e-6;
  std::fprintf(summary, "source      %s (%s, %s)\n", info.name.c_str(), info.format.c_str(), sensor_text(info).c_str());
  std::fprintf(summary, "backend     %s\n", o.backend.c_str());
  if (const std::string note = core_build_note(o.backend, o.core, method_params, params); !note.empty()) {
    std::fprintf(summary, "            %s\n", note.c_str());
  }
  std::fprintf(summary, "events in   %s over %.3f s of sensor time (%s labelled noise%s)\n", grouped(s.events_in).c_str(), span_s,
              grouped(sink.noise + s.board_noise).c_str(), s.labels_kept_on_board ? ", on the board" : "");
  std::fprintf(summary, "throughput  %sevents/s (%.2f s wall clock, reading included)\n", si(s.events_in / std::max(wall, 1e-9)).c_str(), wall);
  // Packets count sweeps when every event shifts, and climb steps (summed over climbs) when seeds climb.
  std::fprintf(summary, "packets     %s, %.1f %s each", grouped(s.packets).c_str(), s.packets ? static_cast<double>(s.iterations) / s.packets : 0.0,
               params.seeding == Seeding::kEvery ? "mean-shift iterations" : "climb steps");
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
    // Listening, a lost label's event never reached the host: it has no row to mark.
    const std::string lost_rows = o.listen ? "their events have no rows" : "labelled " + std::to_string(kLabelLostOnLink);
    std::fprintf(summary, "link        %s frames failed their check, %s events sent again, %s labels lost (%s)\n",
                 grouped(s.link_bad_frames).c_str(), grouped(s.link_events_resent).c_str(), grouped(s.link_labels_lost).c_str(),
                 lost_rows.c_str());
    if (s.board_passed + s.board_filtered > 0) {
      std::fprintf(summary, "board       filtered and climbed (its core stops after the climbs): %s events passed, %s noise, %s packets "
                   "climbed; linked, measured and tracked on the host",
                   grouped(s.board_passed).c_str(), grouped(s.board_filtered).c_str(), grouped(s.board_climbed_packets).c_str());
      if (s.host_climbed_packets > 0) {
        std::fprintf(summary, ", %s packets climbed on the host (the line lost words before them)", grouped(s.host_climbed_packets).c_str());
      }
      std::fprintf(summary, "\n");
    }
    if (s.labels_kept_on_board && o.listen) {
      std::fprintf(summary, "board       kept the labels (tracks mode): %s events from its AER pins labelled with a track, %s noise, "
                   "by its last progress frame\n", grouped(s.board_labelled).c_str(), grouped(s.board_noise).c_str());
    } else if (s.labels_kept_on_board) {
      std::fprintf(summary, "board       kept the labels (tracks mode): %s events labelled with a track, %s noise; the tracks and summaries "
                   "of %s packets were not sent (the line was busy)\n",
                   grouped(s.board_labelled).c_str(), grouped(s.board_noise).c_str(), grouped(s.link_packets_skipped).c_str());
    }
  }
  // Events put back into time order change no label's meaning, but the user should know the
  // file was not in order (the tolerance is --reorder-us; docs/formats.md).
  if (source && source->reordered()) std::fprintf(summary, "reordered   %s events moved back into time order\n", grouped(source->reordered()).c_str());
  if (!live && !source->skipped().empty()) {
    const char* separator = "skipped     ";
    for (const auto& [kind, count] : source->skipped()) {
      std::fprintf(summary, "%s%s %s", separator, grouped(count).c_str(), kind.c_str());
      separator = "; ";
    }
    std::fprintf(summary, "\n");
  }
  if (live && source) {
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
    fail_on_source_error();
  }
  // A live source has no end but the one the user gives it; a recording cut short says so.
  if (interrupted() && !live) {
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
  cmd->add_option("--core", o->core, "core build of the fixed and rtl backends: host (1280x720), arty or ice40 (hls/core/configs.h); "
                                     "of the board backend: ice40 (the iCEBreaker, also for host) or arty")
      ->default_val(o->core);
  cmd->add_option("--device", o->device, "serial device of the board backend (or the path evms vboard prints); without it, the one board's UART connected (an FT2232H's channel B)");
  std::string board_rates;  // each board's own line rate, from EVMS_BOARD_BUILDS (hls/core/configs.h)
#define EVMS_BOARD_RATE(name, clock_hz, clocks_per_bit, link_fifo_depth, cut, cut_shape) \
  board_rates += std::string(board_rates.empty() ? "" : ", ") + std::to_string(backend::board_of(#name).baud()) + " on " #name;
  EVMS_BOARD_BUILDS(EVMS_BOARD_RATE)
#undef EVMS_BOARD_RATE
  cmd->add_option("--baud", o->baud, "line rate of the board's serial link; 0: the board's own (" + board_rates + ")")
      ->default_val(o->baud)
      ->check(CLI::Range(0, 12000000));
  add_board_link_option(*cmd, o->board_link, "tracks.csv and the board's counts, no event rows");
  cmd->add_flag("--quiet", o->quiet, "no progress bar");
  cmd->add_option("--threads", o->threads, "1: read, label and write in turn; 2 or more: reading, the method and writing each in a "
                                          "thread of its own (the outputs are the same bytes either way)")
      ->default_str("the cores present")
      ->check(CLI::Range(1, 256));
  add_source_options(*cmd, o->source_options);
  add_replay_options(*cmd, o->source_options, Pacing::kRealtimeFlag);
  add_method_options(*cmd, o->method);
  add_listen_option(*cmd, o->listen);
  cmd->callback([o, cmd] {
    o->source_given = cmd->count("source") > 0;
    run(*o);
  });
}

}  // namespace evms::cli
