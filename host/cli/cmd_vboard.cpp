// evms vboard : the virtual board. The Verilated board top of a core build (sim/), its UART
// bridged to a pseudo-terminal, so that the board backend runs end to end without hardware:
//
//   evms vboard &                      # prints the terminal's path, e.g. /dev/pts/3
//   evms run SCENE --backend board --device /dev/pts/3
//   evms vboard --build arty &         # the Arty's board: evms run ... --core arty
//
// The iCEBreaker's board (ice40) is its bitstream's design: its core stops after the climbs and
// the host completes its verdicts and climbs frames. The Arty's holds the whole core, and tracks
// mode.
//
// Bytes written to the terminal go into the board's receive line at the board's clocks a bit
// (3 on the iCEBreaker's 18 MHz, 50 on the Arty's 100 MHz); bytes the board transmits come out
// of it. It runs until it is interrupted.
//
// --aer SOURCE plays a recording into the board's AER pins as a DVS128 would, from the moment
// the host first writes to the terminal (its reset frame): each event in the board's
// microsecond its own time falls in, after the first. With `evms run --listen --backend board
// --core arty --board-link tracks` (or `--core ice40`, whose board sends each event's verdict
// and each packet's climbs),
// that is the live demo without a sensor. --aer-stamped FILE then writes the events as the board
// stamped them (events.txt format, at the board's sensor size), for `evms run --backend fixed
// --core arty` (or ice40) to compare with.
//
// --error-rate R makes the line unreliable, as a UART beside a sensor can be: each byte, in
// either direction, is hit with probability R by one fault, equally often a flipped bit, the
// byte dropped, or the byte repeated (--seed chooses the faults).
#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>
#include <random>
#include <stdexcept>
#include <vector>

#include <CLI/CLI.hpp>

#include "Vboard_arty.h"
#include "Vboard_ice40.h"
#include "host/backend/backend.h"
#include "host/backend/core_config.h"
#include "host/cli/commands.h"
#include "host/cli/common.h"
#include "host/read/event_source.h"
#include "host/write/event_writers.h"
#include "sim/virtual_board.h"

namespace evms::cli {
namespace {

// Keep clocking this long after the last byte (the core may still be clustering a packet):
// 33 ms of the board's time.
constexpr double kBusySeconds = 0.033;

struct VboardOptions {
  std::string build = "ice40";
  std::string path_file;
  std::string aer, aer_stamped;
  double error_rate = 0;
  std::uint64_t seed = 1;
};

// The faults of an unreliable line, applied to the bytes crossing it in one direction.
class LineFaults {
 public:
  LineFaults(double rate, std::uint64_t seed) : rate_(rate), rng_(seed) {}
  std::vector<std::uint8_t> pass(std::span<const std::uint8_t> bytes) {
    std::vector<std::uint8_t> out;
    out.reserve(bytes.size() + 8);
    for (std::uint8_t b : bytes) {
      if (rate_ == 0 || uniform_(rng_) >= rate_) {
        out.push_back(b);
        continue;
      }
      switch (rng_() % 3) {
        case 0: out.push_back(static_cast<std::uint8_t>(b ^ (1u << (rng_() % 8)))); break;  // a flipped bit
        case 1: break;                                                                       // dropped
        default: out.push_back(b), out.push_back(b); break;                                  // repeated
      }
    }
    return out;
  }

 private:
  double rate_;
  std::mt19937_64 rng_;
  std::uniform_real_distribution<double> uniform_{0.0, 1.0};
};

// The events a DVS128 would put on the board's AER pins: a recording of at most 128x128.
std::vector<Event> aer_events(const std::string& source_name) {
  auto source = read::open_source(source_name, {});
  const SensorSize sensor = source->info().sensor;
  if (sensor.width > 128 || sensor.height > 128) {
    throw std::invalid_argument(source_name + ": a " + std::to_string(sensor.width) + "x" + std::to_string(sensor.height) +
                                " sensor; the board's AER pins take a DVS128's 7-bit addresses (128x128 at most)");
  }
  std::vector<Event> events, batch(16384);
  while (const size_t n = source->read(batch)) events.insert(events.end(), batch.begin(), batch.begin() + static_cast<std::ptrdiff_t>(n));
  if (events.empty()) throw std::invalid_argument(source_name + ": no events to play into the AER pins");
  return events;
}

// The recording on the AER pins, its first event in the board's microsecond `start_us`.
sim::AerSender aer_sender(const std::vector<Event>& events, std::uint64_t start_us, int ticks_per_us) {
  std::vector<sim::AerSender::Event> due;
  due.reserve(events.size());
  for (const Event& e : events) {
    due.push_back({static_cast<std::uint32_t>(start_us + static_cast<std::uint64_t>(e.t - events.front().t)), e.x, e.y, e.p});
  }
  return sim::AerSender(std::move(due), ticks_per_us);
}

// The recording as the board stamped it, in the events.txt format `evms gen` writes. It appears
// under its name whole (written beside it, then renamed), so a reader waiting for it never
// reads part of it.
void write_stamped(const std::string& path, const std::vector<Event>& events, const sim::AerSender& sender, SensorSize sensor) {
  const std::string part = path + ".part";
  write::RpgEventsTxt out(part, sensor);
  for (size_t i = 0; i < events.size(); ++i) out.write({sender.stamp(i), events[i].x, events[i].y, events[i].p});
  out.close();
  std::filesystem::rename(part, path);
}

// The board's clock and UART: its build's board (EVMS_BOARD_BUILDS, from which the virtual
// board's Verilated parameters are generated too).
template <class V>
void serve(const VboardOptions& o, const backend::BoardOfBuild& of_build) {
  const auto clocks_per_bit = static_cast<int>(of_build.clocks_per_bit);
  const auto clock_hz = static_cast<double>(of_build.clock_hz);
  const auto busy_cycles = static_cast<std::uint64_t>(kBusySeconds * clock_hz);
  const std::string& path_file = o.path_file;
  const std::vector<Event> recording = o.aer.empty() ? std::vector<Event>{} : aer_events(o.aer);
  const int master = posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (master < 0 || grantpt(master) != 0 || unlockpt(master) != 0) {
    throw std::runtime_error(std::string("cannot create a pseudo-terminal: ") + std::strerror(errno));
  }
  const std::string path = ptsname(master);
  // Holding the terminal open keeps it usable between clients, and makes it raw before any
  // client has set it: the line discipline must not echo or translate the link's bytes.
  const int slave = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_CLOEXEC);
  termios t{};
  tcgetattr(slave, &t);
  cfmakeraw(&t);
  tcsetattr(slave, TCSANOW, &t);
  std::printf("%s\n", path.c_str());
  std::fflush(stdout);
  if (!path_file.empty()) {
    if (std::FILE* f = std::fopen(path_file.c_str(), "w")) std::fprintf(f, "%s\n", path.c_str()), std::fclose(f);
  }

  if (o.error_rate > 0) std::fprintf(stderr, "evms vboard: %g of the bytes each way hit by a fault (seed %llu)\n", o.error_rate,
                                     static_cast<unsigned long long>(o.seed));
  LineFaults to_board(o.error_rate, o.seed), to_host(o.error_rate, o.seed ^ 0x9E3779B97F4A7C15ull);
  sim::VirtualBoard<V> board(clocks_per_bit);
  const int ticks_per_us = static_cast<int>(of_build.clock_hz / 1000000);
  std::optional<sim::AerSender> aer;  // from the host's first bytes
  bool aer_reported = false;
  std::vector<std::uint8_t> in(4096), out;
  std::uint64_t last_activity = 0;
  for (;;) {
    const bool playing = aer && !aer->done();
    const bool busy = board.sending() || board.cycles() - last_activity < busy_cycles || playing;
    pollfd p{master, POLLIN, 0};
    if (::poll(&p, 1, busy ? 0 : 20) > 0 && (p.revents & POLLIN)) {
      const ssize_t n = ::read(master, in.data(), in.size());
      if (n > 0) {
        board.send(to_board.pass(std::span(in.data(), static_cast<size_t>(n))));
        last_activity = board.cycles();
        if (!recording.empty() && !aer) {
          // Once the host's reset frame has restarted the core and the board has said so (a label
          // sent before the reset's status frame is not the run's): the filter forgets its pixels'
          // times a pixel a clock (rtl/filter/evms_ba_filter.sv), 1.4 ms on the iCEBreaker, and a
          // millisecond more covers the reset frame and the status.
          const SensorSize sensor = backend::core_build_sensor(o.build);
          const std::uint64_t clear_us = static_cast<std::uint64_t>(sensor.width) * sensor.height / static_cast<std::uint64_t>(ticks_per_us);
          const std::uint64_t start_us =
              (board.cycles() - sim::VirtualBoard<V>::kResetCycles) / static_cast<std::uint64_t>(ticks_per_us) + clear_us + 1000;
          aer.emplace(aer_sender(recording, start_us, ticks_per_us));
          std::fprintf(stderr, "evms vboard: %zu events into the AER pins from the board's microsecond %llu\n", recording.size(),
                       static_cast<unsigned long long>(start_us));
        }
      }
    }
    if (aer && aer->done() && !aer_reported) {
      aer_reported = true;
      std::fprintf(stderr, "evms vboard: the AER pins took all %zu events; the longest a sensor waited was %llu us\n", recording.size(),
                   static_cast<unsigned long long>(aer->max_lag_us()));
      if (!o.aer_stamped.empty()) write_stamped(o.aer_stamped, recording, *aer, backend::core_build_sensor(o.build));
    }
    if (!busy && !board.sending()) continue;
    if (playing) {
      for (int i = 0; i < 4096; ++i) {
        aer->drive(board.pins(), board.cycles());
        board.tick();
      }
    } else {
      board.run(4096);
    }
    if (!board.received.empty()) {
      out = to_host.pass(std::vector<std::uint8_t>(board.received.begin(), board.received.end()));
      board.received.clear();
      for (size_t done = 0; done < out.size();) {
        const ssize_t n = ::write(master, out.data() + done, out.size() - done);
        if (n < 0 && errno != EINTR && errno != EAGAIN) throw std::runtime_error(path + ": write failed: " + std::strerror(errno));
        if (n > 0) done += static_cast<size_t>(n);
      }
      last_activity = board.cycles();
    }
  }
}

}  // namespace

void register_vboard(CLI::App& app) {
  auto o = std::make_shared<VboardOptions>();
  CLI::App* cmd = app.add_subcommand("vboard", "the virtual board: the simulated board top behind a pseudo-terminal, for --backend board");
  cmd->add_option("--build", o->build, "the board's core build: ice40 (the iCEBreaker, 18 MHz; its core stops after the climbs, "
                                       "the host completes the clusters and tracks) or arty (the Arty, 100 MHz, the whole core); evms run --core names the same")
      ->default_val(o->build)
      ->check(CLI::IsMember({"ice40", "arty"}));
  cmd->add_option("--path-file", o->path_file, "also write the terminal's path to this file");
  cmd->add_option("--error-rate", o->error_rate, "the chance that a byte crossing the line, either way, is hit by a fault: a flipped bit, "
                                                 "dropped or repeated")
      ->default_val(o->error_rate)
      ->check(finite_in(0.0, 0.1));
  cmd->add_option("--seed", o->seed, "seed of the line's faults")->default_val(o->seed);
  cmd->add_option("--aer", o->aer, "play this recording (128x128 at most) into the board's AER pins as a DVS128 would, from the host's "
                                   "first bytes on (with evms run --listen, the live demo without a sensor)");
  cmd->add_option("--aer-stamped", o->aer_stamped, "once --aer's events are all in, write them as the board stamped them (the events.txt "
                                                   "format of evms gen, at the board's sensor size), to compare with --backend fixed");
  cmd->callback([o] {
    if (!o->aer_stamped.empty() && o->aer.empty()) throw std::invalid_argument("--aer-stamped needs --aer");
    if (o->build == "arty") serve<Vboard_arty>(*o, backend::board_of("arty"));
    else serve<Vboard_ice40>(*o, backend::board_of("ice40"));
  });
}

}  // namespace evms::cli
