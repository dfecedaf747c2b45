#include "host/cli/common.h"

#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <sstream>

#include "hls/core/configs.h"
#include "host/backend/backend.h"
#include "host/backend/core_config.h"
#include "host/cli/config_file.h"
#include "host/read/live/live_source.h"
#include "host/read/source_window.h"

namespace evms::cli {

void add_board_link_option(CLI::App& cmd, std::string& board_link, const std::string& in_tracks_mode) {
  cmd.add_option("--board-link", board_link, "what the board sends back: labels (a label for every event, and every track update; the "
                                              "line's pace holds the core back) or tracks (the labels stay on the board, which runs at the "
                                              "sensor's rate, and whole packets' track updates come when the line is free; " + in_tracks_mode + ")")
      ->default_val(board_link)
      ->check(CLI::IsMember({"labels", "tracks"}));
}

void add_core_build_option(CLI::App& cmd, const std::string& name, std::string& build, const std::string& description) {
  cmd.add_option(name, build, description)
      ->default_val(build)
      ->check(CLI::IsMember(std::vector<std::string>(std::begin(hls::kCoreBuildNames), std::end(hls::kCoreBuildNames))));
}

bool board_keeps_labels(const std::string& board_link, const std::string& backend) {
  if (board_link != "labels" && backend != "board") {
    throw std::invalid_argument("--board-link " + board_link + " is the board backend's; --backend is " + backend);
  }
  return board_link == "tracks";
}

std::vector<Event> read_all_events(const std::string& source, const read::SourceOptions& options, SensorSize& sensor) {
  auto opened = read::open_source(source, options);
  sensor = opened->info().sensor;
  std::vector<Event> events, batch(8192);
  while (const size_t n = opened->read(batch)) events.insert(events.end(), batch.begin(), batch.begin() + static_cast<long>(n));
  return events;
}

std::string core_build_note(const std::string& backend, const std::string& core, const Params& method, const Params& fitted) {
  const std::string changes = backend::fitted_settings(method, fitted);
  if (changes.empty()) return "";
  return "the " + (backend == "board" ? backend::board_build(core) : core) + " build runs " + changes;
}

namespace {
volatile std::sig_atomic_t g_interrupted = 0;
}  // namespace

void catch_interrupts() {
  g_interrupted = 0;
  for (const int sig : {SIGINT, SIGTERM}) {
    std::signal(sig, [](int) {
      g_interrupted = 1;
      read::end_live_sources();
      std::signal(SIGINT, SIG_DFL), std::signal(SIGTERM, SIG_DFL);
    });
  }
}

bool interrupted() { return g_interrupted != 0; }

void add_listen_option(CLI::App& cmd, bool& listen) {
  cmd.add_flag("--listen", listen, "no SOURCE: the events enter at the board's AER pins (a DVS128 wired to the board) and the host sends "
                                   "none; it takes the board's tracks until Ctrl-C, or until the board has labelled --limit events "
                                   "(--backend board: --board-link tracks with --core arty; with --core ice40 the board's verdicts and "
                                   "climbs come, and the host completes the clusters and tracks them)");
}

read::SourceInfo listening_input(const std::string& backend, const std::string& core, bool keeps_labels, bool source_given,
                                 const read::SourceOptions& input) {
  const bool cut_on_board = backend == "board" && backend::board_of(backend::board_build(core)).cut();
  if (backend != "board" || (!keeps_labels && !cut_on_board)) {
    throw std::invalid_argument("--listen takes the board's own input: add --backend board, and --board-link tracks for a board with the whole "
                                "core (--core arty), whose labels stay on it");
  }
  if (source_given) throw std::invalid_argument("--listen takes the events at the board's AER pins: name no SOURCE");
  const read::SourceWindow& w = input.window;
  if (w.start_us > 0 || w.duration_us > 0 || w.roi || !w.hot_pixels.empty()) {
    throw std::invalid_argument("--listen takes --limit, not --start-us, --duration-us, --roi or --hot-pixels: the host never sees the events");
  }
  read::SourceInfo info;
  info.name = "the board's AER pins";
  info.format = "DVS128 AER, listening";
  info.sensor = backend::core_build_sensor(backend::board_build(core));
  info.sensor_origin = "the board's build";
  return info;
}

void add_source_options(CLI::App& cmd, read::SourceOptions& o) {
  const char* group = "Input";
  cmd.add_option("--width", o.width, "sensor width in px, for files whose header has no size")
      ->check(CLI::Range(1, read::kMaxSensorSide))
      ->group(group);
  cmd.add_option("--height", o.height, "sensor height in px, for files whose header has no size")
      ->check(CLI::Range(1, read::kMaxSensorSide))
      ->group(group);
  cmd.add_option("--reorder-us", o.reorder_us,
                 "events out of time order by up to this much are re-sorted; more is an error")
      ->default_val(o.reorder_us)
      ->check(CLI::Range(0, 1000000000))
      ->group(group);
  read::SourceWindow& w = o.window;
  cmd.add_option("--start-us", w.start_us, "take events from the first event's time plus this on")
      ->check(CLI::Range(TimeUs{0}, read::kMaxTimestampUs))
      ->group(group);
  cmd.add_option("--duration-us", w.duration_us, "take this much time from the start (0: to the end)")
      ->check(CLI::Range(TimeUs{0}, read::kMaxTimestampUs))
      ->group(group);
  cmd.add_option("--limit", w.limit, "take at most this many events (0: all)")
      ->check(CLI::Range(std::int64_t{0}, std::int64_t{1} << 62))
      ->group(group);
  cmd.add_option_function<std::string>("--roi", [&w](const std::string& text) { w.roi = read::parse_roi(text); },
                                       "X,Y,W,H: only events inside this rectangle, moved to its corner (the sensor becomes WxH)")
      ->group(group);
  cmd.add_option("--hot-pixels", w.hot_pixels, "mask the pixels listed in FILE (x,y a line), or 'auto': those firing more than "
                                                "--hot-factor times the median active pixel and their neighbours' mean (a first pass over the recording)")
      ->group(group);
  cmd.add_option("--hot-factor", w.hot_factor, "with --hot-pixels auto: the multiple of the median pixel's event count that is hot")
      ->default_val(w.hot_factor)
      ->check(finite_in(1.0, 1e9))
      ->group(group);
}

void add_replay_options(CLI::App& cmd, read::SourceOptions& o, Pacing pacing) {
  const char* group = "Replay";
  if (pacing == Pacing::kRealtimeFlag) {
    cmd.add_flag("--realtime", o.realtime,
                 "replay a recorded source at the pace of its timestamps; events the backend has no room for are dropped and counted")
        ->group(group);
  }
  cmd.add_option("--speed", o.speed,
                 pacing == Pacing::kAlwaysRealtime ? "replay a recording at this many times real time (the paper's speed factor)"
                                                   : "when paced: this many times real time (the paper's speed factor)")
      ->default_val(o.speed)
      ->check(finite_in(0.001, 1e6))
      ->group(group);
  cmd.add_option("--live-buffer", o.live_buffer_events, "events a live or paced source holds for a backend that falls behind")
      ->default_val(o.live_buffer_events)
      ->check(CLI::Range(1, 1 << 28))
      ->group(group);
}

void add_method_options(CLI::App& cmd, Method& method) {
  std::string presets;
  for (const char* name : preset_names()) presets += std::string(presets.empty() ? "" : ", ") + name;
  cmd.add_option("--preset", method.preset,
                 "named settings the parameters below start from: evms (the defaults), paper (the authors' published "
                 "code), gaussian (the paper's text; the host RTL build holds it beside the default method)")
      ->default_val(method.preset)
      ->check(CLI::IsMember(std::vector<std::string>(preset_names().begin(), preset_names().end())))
      ->group("Method parameters");
  const Params defaults;
  for (const ParamInfo& info : param_table()) {
    std::string help = std::string(info.help);
    if (!info.choices.names.empty()) {
      std::string names;
      for (const char* n : info.choices.names) names += std::string(names.empty() ? "" : "|") + n;
      help += " [" + names + "]";
    } else if (*info.unit) {
      help += " [" + std::string(info.unit) + "]";
    }
    cmd.add_option_function<std::string>(
           std::string("--") + info.name,
           [&method, &info](const std::string& text) {
             Params scratch;
             if (std::string error = set_param(scratch, info, text); !error.empty()) throw CLI::ValidationError(error);
             method.settings.emplace_back(info.name, text);
           },
           help)
        ->default_str(param_text(defaults, info))
        ->group("Method parameters");
  }
  // After --preset, so that a --preset on the command line is known by the time the file is read.
  cmd.add_option_function<std::string>(
         "--config",
         [&method, &cmd](const std::string& path) {
           const bool preset_given = cmd.get_option("--preset")->count() > 0;
           const Method from_file = method_from_config(path);
           if (!preset_given) method.preset = from_file.preset;
           // The command line wins: its settings come after the file's.
           method.settings.insert(method.settings.begin(), from_file.settings.begin(), from_file.settings.end());
         },
         "a YAML file of parameters (name: value, and preset:); the command line wins over it. "
         "evms params --config prints one with every default")
      ->group("Method parameters");
}

std::string sensor_text(const read::SourceInfo& info) {
  std::string s = std::to_string(info.sensor.width) + "x" + std::to_string(info.sensor.height);
  if (info.sensor_assumed()) s += " " + info.sensor_origin;
  return s;
}

namespace {
std::string g_invocation = "evms";
}

const std::string& invocation() { return g_invocation; }

void set_invocation(int argc, char** argv) {
  g_invocation = "evms";
  for (int i = 1; i < argc; ++i) g_invocation += std::string(" ") + argv[i];
}

CLI::Validator finite_in(double lo, double hi) {
  std::ostringstream bounds;
  bounds << "[" << lo << ", " << hi << "]";
  return CLI::Validator(
      [lo, hi, range = bounds.str()](std::string& text) -> std::string {
        double value = 0;
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) return "'" + text + "' is not a number";
        if (value < lo || value > hi) return text + " is outside " + range;
        return {};
      },
      "FLOAT in " + bounds.str());
}

std::string grouped(std::int64_t v) {
  std::string digits = std::to_string(v < 0 ? -v : v);
  std::string out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return v < 0 ? "-" + out : out;
}

std::string si(double v) {
  char b[32];
  if (v >= 1e9) std::snprintf(b, sizeof b, "%.2f G", v / 1e9);
  else if (v >= 1e6) std::snprintf(b, sizeof b, "%.2f M", v / 1e6);
  else if (v >= 1e3) std::snprintf(b, sizeof b, "%.1f k", v / 1e3);
  else std::snprintf(b, sizeof b, "%.0f ", v);
  return b;
}

Progress::Progress(bool enabled)
    : enabled_(enabled && isatty(STDERR_FILENO)), start_(std::chrono::steady_clock::now()), last_(start_) {}

Progress::~Progress() { done(); }

void Progress::update(double fraction, std::int64_t events) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_ < std::chrono::milliseconds(200)) return;
  last_ = now;
  const double secs = std::chrono::duration<double>(now - start_).count();
  const int width = 30;
  const int filled = fraction >= 0 ? static_cast<int>(std::lround(std::min(1.0, fraction) * width)) : 0;
  std::string bar(static_cast<size_t>(filled), '#');
  bar.resize(width, '.');
  std::fprintf(stderr, "\r[%s] %3.0f%%  %sevents  %sevents/s ", bar.c_str(),
               fraction >= 0 ? 100 * fraction : 0.0, si(static_cast<double>(events)).c_str(),
               si(static_cast<double>(events) / std::max(secs, 1e-9)).c_str());
  std::fflush(stderr);
  drawn_ = true;
}

void Progress::done() {
  if (drawn_) std::fprintf(stderr, "\r%80s\r", "");
  drawn_ = false;
}

}  // namespace evms::cli
