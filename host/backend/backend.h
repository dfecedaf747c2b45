// The backend seam: events in, labelled events and track updates out. Every implementation
// of the method (the floating-point golden model, the fixed-point core, the Verilated RTL, a
// board over a serial link) sits behind this one interface, and the CLI only ever names one.
#pragma once

#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "types/event.h"
#include "types/output.h"
#include "types/params.h"

namespace evms::backend {

struct BackendStats {
  std::int64_t events_in = 0;          // pushed; a listening board's: those it took at its AER pins
  std::int64_t events_kept = 0;        // passed the background-activity filter
  std::int64_t packets = 0;
  std::int64_t clusters = 0;           // summed over packets
  std::int64_t iterations = 0;         // mean-shift sweeps, summed over packets
  std::int64_t tracks_started = 0;
  std::int64_t unassigned_clusters = 0;
  std::int64_t kernel_evaluations = 0; // point-to-point distances the mean shift took
  // Wall clock in the method's stages, where the backend measures them (golden); 0 otherwise.
  std::int64_t cluster_ns = 0;         // clustering packets
  std::int64_t track_ns = 0;           // measuring clusters and tracking them
  // The board's serial link (the board backend only).
  std::int64_t link_bad_frames = 0;    // frames that failed their check: the host's and the board's counts
  std::int64_t link_events_resent = 0; // events sent again, when the board asked or fell silent
  std::int64_t link_labels_lost = 0;   // events labelled kLabelLostOnLink
  // Tracks mode (BackendOptions::board_keeps_labels): the events whose labels stayed on the
  // board, and how the board labelled them; packets whose tracks and summary were not sent.
  std::int64_t labels_kept_on_board = 0;
  std::int64_t board_labelled = 0, board_noise = 0;
  std::int64_t link_packets_skipped = 0;
  // A board whose core is cut: the verdicts it returned (passed, noise), which the host
  // completed. Cut after its climbs: the packets whose climbs the board returned, and those the
  // host climbed itself (the line lost a verdict or a climbs word before them).
  std::int64_t board_passed = 0, board_filtered = 0;
  std::int64_t board_climbed_packets = 0, host_climbed_packets = 0;
};

struct BackendOptions {
  Params params;
  SensorSize sensor;
  std::string core = "host";           // core build of the fixed and rtl backends: host, arty or ice40
  std::string device;                  // serial device, for the board backend
  int baud = 0;                        // its line rate; 0: the board's own (BoardOfBuild::baud)
  bool board_keeps_labels = false;     // the board backend's tracks mode (docs/link.md)
};

// Options for a backend that needs only the method's parameters and the sensor.
inline BackendOptions options_for(const Params& params, SensorSize sensor) {
  BackendOptions o;
  o.params = params;
  o.sensor = sensor;
  return o;
}

// The core builds (hls/core/configs.h, EVMS_CORE_BUILDS) a backend can run: "host", "arty" or
// "ice40". Throws std::invalid_argument naming them for anything else.
void check_core_build(const std::string& core);
// The build a board backend talks to: --core arty or ice40; the iCEBreaker's (ice40) unless
// --core names the Arty's.
inline constexpr const char* kBoardCoreBuild = "ice40";
inline std::string board_build(const std::string& core) { return core == "host" ? kBoardCoreBuild : core; }
// The sensor a core build is sized for (EVMS_CORE_BUILDS): the size a board's registers hold.
SensorSize core_build_sensor(const std::string& build);

// `p` (resolved from `method`) within the packet size, cluster and track counts of the build
// `core` of `backend` (fixed: the build's C++ Shape; rtl and board: its RTL Shape; golden: no
// limits): each of the three that the method's preset makes larger than the build holds is cut
// to the build's, unless the command line set it (then the backend refuses it with a one-line
// error). So `--core ice40` alone runs the iCE40 build's sizes. The board builds (arty, ice40),
// in every backend, also run without the polarity split (--split-balance 0), the edge join
// (--edge-join 0), the measurement noise from the spread (--meas-noise-from-spread false), the
// gate's boxes (--gate-boxes false) and the least density on the linked sets
// (--density-after-links false), and measure by the centroid (--measure centroid), as they hold
// none of them (Shape::kHasPolaritySplit, kHasEdgeJoin, kHasSpreadNoise, kHasGateBoxes,
// kHasDensityAfterLinks, kHasPolarityMidpoint), unless the command line set them.
Params fit_core_build(const std::string& backend, const std::string& core, Params p, const Method& method);
// The parameters (types/params.h's table, in its order) whose values differ between a and b.
std::vector<const ParamInfo*> differing_params(const Params& a, const Params& b);
// What fit_core_build changed, for the user: "--packet-size 256 (the method's 2048), ...", or
// empty when the build runs the method as it is.
std::string fitted_settings(const Params& method, const Params& fitted);

class Backend {
 public:
  virtual ~Backend() = default;
  // Events must be in time order. Outputs may lag the inputs by up to one packet.
  virtual void push(std::span<const Event> events, OutputSink& out) = 0;
  // Flushes everything still held.
  virtual void finish(OutputSink& out) = 0;
  virtual BackendStats stats() const = 0;
  // Takes, for up to `wait_ms`, what the backend produced from input of its own, without any
  // pushed: a board in tracks mode whose events enter at its AER pins (listening, docs/link.md).
  // With `limit` (0: none) it takes at most that many events in all, where the events come
  // back one by one (a board whose core is cut), and returns once it has them; a board
  // that keeps its labels counts them, and it returns once the count reached `limit`. Backends
  // that have no input of their own refuse.
  virtual void listen(OutputSink& /*out*/, int /*wait_ms*/, std::int64_t /*limit*/ = 0) {
    throw std::invalid_argument("only the board backend listens to input of its own (--backend board --core arty)");
  }
};

struct BackendInfo {
  const char* name;
  const char* description;
  std::unique_ptr<Backend> (*make)(const BackendOptions&);
};

// Every backend this build has.
std::span<const BackendInfo> backends();
// Throws std::invalid_argument naming the known backends when `name` is not one.
std::unique_ptr<Backend> make_backend(const std::string& name, const BackendOptions& options);

}  // namespace evms::backend
