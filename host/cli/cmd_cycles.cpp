// evms cycles SOURCE [--build host|arty|ice40] [--rtl] [--table] : clocks per event of a core
// build, stage by stage, from the cycle model (hls/core/schedule.h) fed by the C++ core, and,
// with --rtl, measured on the Verilated RTL beside it. The model counts the Gaussian path (the
// host build's --preset gaussian); the seeded path (the default method, every build's reset
// method) is measured on the RTL whether or not --rtl is given. For a build whose board runs its
// core cut after the climbs (the iCEBreaker), the board's core is measured too, on the RTL.
#include <cstdio>

#include "Vclimbs_core.h"
#include "Vcore_arty.h"
#include "Vcore_arty___024root.h"
#include "Vcore_host.h"
#include "Vcore_host___024root.h"
#include "Vcore_ice40.h"
#include "Vcore_ice40___024root.h"
#include "hls/core/configs.h"
#include "hls/core/schedule.h"
#include "host/backend/core_backend.h"
#include "host/cli/commands.h"
#include "host/cli/common.h"
#include "sim/climbs_core_run.h"
#include "sim/schedule_runs.h"

namespace evms::cli {
namespace {

struct CyclesOptions {
  std::string source;
  std::string build = "host";
  bool rtl = false;
  bool table = false;
  std::vector<int> lanes = {1, 2, 4, 8, 16, 32, 64};
  read::SourceOptions source_options;
  Method method;  // the defaults unless told another, in the build's sizes
};

template <class V>
hls::StageCycles rtl_run(const std::vector<hls::EventWord>& words, const hls::Config& cfg) {
  Progress progress(true);
  const hls::StageCycles cycles = sim::measured_schedule<V>(words, cfg, [&](size_t i) {
    if (i % 4096 == 0) progress.update(static_cast<double>(i) / words.size(), static_cast<std::int64_t>(i));
  });
  progress.done();
  return cycles;
}

// The clocks an event of the core cut after its climbs (rtl/core/evms_climbs_core.sv, Verilated
// at the iCEBreaker's cut shape, hls::Ice40ClimbsShape) with its board's registers, each output
// always ready, and what that sustains at the board's clock.
void board_climbs_cycles(const std::vector<Event>& events, SensorSize sensor, const std::string& build, const backend::BoardOfBuild& board) {
  using Cut = hls::Ice40ClimbsShape;
  std::vector<hls::EventWord> words = backend::core_words_of<Cut>(events);
  hls::EventWord flush;
  flush.flush = true;
  words.push_back(flush);
  const hls::Config cfg = backend::core_config<Cut>(backend::build_default_params<Cut>(), sensor);
  const sim::ClimbsCoreOutputs run = sim::run_climbs_core<Vclimbs_core>(words, cfg, 1, 1.0, "");
  if (!run.finished) throw std::runtime_error("the board's climbs core did not finish the events");
  const double per_event = static_cast<double>(run.clocks) / static_cast<double>(events.size());
  const double rate = static_cast<double>(board.clock_hz) / per_event;
  std::printf("\nthe %s board's core, cut after its climbs (rtl/core/evms_climbs_core.sv, its registers: packets of %d, no warm seeds), "
              "on the same events:\n", build.c_str(), cfg.packet_size);
  std::printf("board core       %.2f clocks/event (the RTL's), %.0f k events/s at the build's %.0f MHz clock\n", per_event, rate / 1e3,
              static_cast<double>(board.clock_hz) / 1e6);
  std::printf("the host runs the rest of the core on its verdicts and climbs frames: docs/rtl.md, \"Builds\"\n");
}

template <class V, class S>
void cycles(const CyclesOptions& o) {
  SensorSize sensor;
  const std::vector<Event> events = read_all_events(o.source, o.source_options, sensor);
  // The cycle model is the RTL's: it counts the method the RTL implements.
  const Method& method = o.method;
  const Params params = backend::fit_core_build("rtl", o.build, method.resolve(sensor), method);
  if (std::string unsupported = backend::rtl_unsupported(params, o.build); !unsupported.empty()) {
    throw std::invalid_argument(unsupported + "; the cycle model counts the RTL's method");
  }
  if (events.empty()) throw std::runtime_error(o.source + ": no events");
  const bool seeded = params.seeding != Seeding::kEvery;
  if (seeded && o.table) {
    throw std::invalid_argument("--table sweeps the cycle model, which counts the Gaussian path only (--preset gaussian on the host build); without --table the seeded path is measured on the RTL");
  }
  const bool measure_rtl = o.rtl || seeded;
  const auto words = backend::core_words_of<S>(events);
  if (o.table) {
    // Cycles per event against packet size, iteration cap and lane count.
    std::printf("| packet size | iterations cap | mean sweeps |");
    for (int p : o.lanes) std::printf(" P = %d |", p);
    std::printf("\n|---|---|---|");
    for (size_t i = 0; i < o.lanes.size(); ++i) std::printf("---|");
    std::printf("\n");
    for (int n : {64, 128, 256}) {
      if (n > S::kPacketMax) continue;
      for (int it : {2, 4, 8}) {
        if (it > S::kIterationsMax) continue;
        Params p = params;
        p.packet_size = n;
        p.max_iterations = it;
        const auto model = sim::modelled_schedule<S>(words, backend::core_config<S>(p, sensor));
        std::printf("| %d | %d | %.2f |", n, it, model.mean_sweeps());
        for (int lanes : o.lanes) std::printf(" %.0f |", model.cycles(lanes).total() / model.events());
        std::printf("\n");
      }
    }
    return;
  }
  const hls::Config cfg = backend::core_config<S>(params, sensor);
  const auto model = sim::modelled_schedule<S>(words, cfg);
  const double n_events = static_cast<double>(model.events());
  std::printf("build %s (P = %d, multiplier latency %d), %s, packets of %d, %d clusters, %d tracks\n", o.build.c_str(), S::kLanes,
              hls::multiplier_latency(S::kMulDigitBits), method.describe().c_str(), params.packet_size, params.max_clusters, params.max_tracks);
  std::printf("%s events, %s kept, %s packets, %.2f %s a packet\n", grouped(model.events()).c_str(), grouped(model.kept()).c_str(),
              grouped(model.packets()).c_str(), model.mean_sweeps(), seeded ? "climb steps" : "sweeps");
  const hls::StageCycles predicted = model.cycles();
  hls::StageCycles measured;
  if (measure_rtl) measured = rtl_run<V>(words, cfg);
  const bool modelled = !seeded;
  const hls::StageCycles& shares = modelled ? predicted : measured;
  std::printf("%-16s", "stage");
  if (modelled) std::printf(" %14s", "model cyc/ev");
  std::printf(" %8s", "share");
  if (measure_rtl) std::printf(" %14s", "rtl cyc/ev");
  std::printf("\n");
  for (int s = 0; s < hls::kStageCount; ++s) {
    std::printf("%-16s", hls::kStageNames[s]);
    if (modelled) std::printf(" %14.2f", predicted[s] / n_events);
    std::printf(" %7.1f%%", 100.0 * shares[s] / shares.total());
    if (measure_rtl) std::printf(" %14.2f", measured[s] / n_events);
    std::printf("\n");
  }
  std::printf("%-16s", "total");
  if (modelled) std::printf(" %14.2f", predicted.total() / n_events);
  std::printf(" %8s", "");
  if (measure_rtl) std::printf(" %14.2f", measured.total() / n_events);
  std::printf("\n");
  // What the build sustains at its board's clock (the RTL's cycles where they were measured):
  // the figure a sensor's peak rate is held against.
  const backend::BoardOfBuild board = backend::board_of(o.build);
  if (board.clock_hz > 0) {
    const double per_event = (measure_rtl ? measured.total() : predicted.total()) / n_events;
    const double rate = static_cast<double>(board.clock_hz) / per_event;
    std::printf("rate             %.*f %s events/s at the build's %.0f MHz clock (%s cycles)\n", rate >= 1e6 ? 2 : 0,
                rate >= 1e6 ? rate / 1e6 : rate / 1e3, rate >= 1e6 ? "M" : "k", static_cast<double>(board.clock_hz) / 1e6,
                measure_rtl ? "the RTL's" : "the model's");
  }
  if (board.cut()) {
    std::printf("\nthese are the whole %s core's cycles; its board runs it cut after the climbs (the whole core does not fit the "
                "device)\n",
                o.build.c_str());
    board_climbs_cycles(events, sensor, o.build, board);
  }
  if (!modelled) {
    std::printf("\nthe seeded path, measured on the RTL (the cycle model counts the Gaussian path): climbs count in \"mean shift\", links, the least density on the linked sets, the polarity split, the edge join and warm seeds in \"merge\"\n");
    return;
  }
  std::printf("\nmodel, other lane counts:");
  for (int lanes : o.lanes) std::printf("  P=%d: %.1f", lanes, model.cycles(lanes).total() / n_events);
  std::printf(" cycles/event\n");
}

}  // namespace

void register_cycles(CLI::App& app) {
  auto o = std::make_shared<CyclesOptions>();
  auto* cmd = app.add_subcommand("cycles", "Clocks per event of a core build, stage by stage: the cycle model, and the RTL with --rtl (always for the seeded path)");
  cmd->add_option("source", o->source, "Event file or gen:// scene")->required();
  add_core_build_option(*cmd, "--build", o->build, "Core build: host, arty or ice40 (hls/core/configs.h); its packet, cluster and track sizes apply");
  cmd->add_flag("--rtl", o->rtl, "Also simulate the Verilated RTL and print its measured cycles (done without it when the method is seeded, which the model does not count)");
  cmd->add_flag("--table", o->table, "Print cycles per event against packet size, iteration cap and lanes (markdown)");
  cmd->add_option("--lanes", o->lanes, "Lane counts for the model's comparison (1, 2, 4 .. 64)")
      ->delimiter(',')
      ->check(CLI::IsMember(std::vector<int>(std::begin(hls::kModelLaneCounts), std::end(hls::kModelLaneCounts))));
  o->source_options.window.limit = 1000000;  // the cycle model holds every event it measures
  add_source_options(*cmd, o->source_options);
  add_method_options(*cmd, o->method);
  cmd->callback([o] {
#define EVMS_CYCLES_OF_BUILD(name, fixed, rtl, width, height, description) \
  if (o->build == #name) return cycles<Vcore_##name, hls::rtl>(*o);
    EVMS_CORE_BUILDS(EVMS_CYCLES_OF_BUILD)
#undef EVMS_CYCLES_OF_BUILD
  });
}

}  // namespace evms::cli
