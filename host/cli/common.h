// Pieces every subcommand shares: source and parameter options, the progress bar, and
// number formatting.
#pragma once

#include <CLI/CLI.hpp>
#include <chrono>
#include <string>

#include "types/params.h"
#include "host/read/event_source.h"

namespace evms::cli {

// --width, --height, --reorder-us and the window (--start-us, --duration-us, --limit, --roi,
// --hot-pixels), under the heading "Input".
void add_source_options(CLI::App& cmd, read::SourceOptions& options);
// How a subcommand paces a recording: run takes --realtime; view chooses its own default and
// takes --realtime or --no-realtime; live always replays at the recording's pace.
enum class Pacing { kRealtimeFlag, kChosenByCommand, kAlwaysRealtime };
// --speed, --live-buffer and, with Pacing::kRealtimeFlag, --realtime: for the subcommands that
// feed a backend as events come, under the heading "Replay".
void add_replay_options(CLI::App& cmd, read::SourceOptions& options, Pacing pacing);
// --preset and one option per row of the parameter table (types/params.cpp). Values are
// checked as they are parsed; Method::resolve applies them over the preset.
void add_method_options(CLI::App& cmd, Method& method);

// The check of a floating-point option: a finite number in [lo, hi], in the words the method's
// options use ("'nan' is not a number", "2000 is outside [0, 1000]"). CLI::Range and
// CLI::PositiveNumber let NaN through, as every comparison with it is false.
CLI::Validator finite_in(double lo, double hi);

// --board-link labels|tracks: what the board backend's board sends back (docs/link.md).
// `in_tracks_mode` says what the subcommand shows when the labels stay on the board.
void add_board_link_option(CLI::App& cmd, std::string& board_link, const std::string& in_tracks_mode);
// Whether --board-link keeps the labels on the board; refuses it with any backend but the board.
bool board_keeps_labels(const std::string& board_link, const std::string& backend);

// Every event of SOURCE (read with `options`), and its sensor size: for the subcommands that
// hold a whole run (evms cycles, evms vectors).
std::vector<Event> read_all_events(const std::string& source, const read::SourceOptions& options, SensorSize& sensor);

// How the backend's core build runs the method (backend::fit_core_build): "the host build runs
// --packet-size 256 (the method's 2048)", or empty when it runs the method as it is (golden
// always does).
std::string core_build_note(const std::string& backend, const std::string& core, const Params& method, const Params& fitted);

// An option naming one of the core builds of hls/core/configs.h (host, arty, ice40), whose
// default is `build` as it stands.
void add_core_build_option(CLI::App& cmd, const std::string& name, std::string& build, const std::string& description);

// --listen: the events enter at the board's AER pins (a sensor wired to the board), and the
// host sends none.
void add_listen_option(CLI::App& cmd, bool& listen);
// What a listening run reports as its source: the board's AER pins, at the sensor size the board's
// build (`core`) holds. Refuses --listen with a backend other than the board in tracks mode,
// with a SOURCE, or with an input option other than --limit, each in one line.
read::SourceInfo listening_input(const std::string& backend, const std::string& core, bool board_keeps_labels, bool source_given,
                                 const read::SourceOptions& input);

// From now on, Ctrl-C (or a SIGTERM) sets interrupted() and ends every live source as if its
// input had ended (read::end_live_sources), so that a subcommand can stop where its outputs
// are whole; a second one ends evms at once.
void catch_interrupts();
bool interrupted();

// "240x180", or "240x180 assumed: ..." when the source does not say its sensor size.
std::string sensor_text(const read::SourceInfo& info);

// The command line evms was started with, for reports.
const std::string& invocation();
void set_invocation(int argc, char** argv);

// "1,234,567"
std::string grouped(std::int64_t v);
// "1.23 M", "456 k"
std::string si(double v);

// A one-line progress bar on stderr, drawn only when stderr is a terminal.
class Progress {
 public:
  explicit Progress(bool enabled);
  ~Progress();
  void update(double fraction, std::int64_t events);
  void done();

 private:
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace evms::cli
