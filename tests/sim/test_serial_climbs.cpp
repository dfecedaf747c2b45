// Block-level cosimulation of rtl/cluster/evms_serial_climbs.sv against SeededClimbs in
// hls/cluster/seeded_climbs.h, without warm seeds: the same packet and registers; every event's
// mode, every mode's position and support, and the climb, step and lost-mode counts must be
// equal. The seed is drawn anew each run and printed (EVMS_SEED=N repeats one); a mismatch
// repeats the packet with an FST trace in the temporary directory (sim/verilated_block.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "Vserial_climbs.h"
#include "hls/cluster/seeded_climbs.h"
#include "hls/core/shape.h"
#include "hls/filter/ba_filter.h"
#include "host/backend/core_config.h"
#include "host/eval/scene_run.h"
#include "host/gen/family.h"
#include "sim/verilated_block.h"
#include "tests/sim/climbs_readout.h"

namespace evms {
namespace {

// A DVS128's packets of up to 1,024 events with 6 feature fraction bits (climb features of
// 14 fraction bits: the squares fit 16x16 multipliers), the sizes sim/CMakeLists.txt builds
// the engine at. The formats after the seeded path's sizes play no part in the climbs.
using S = hls::Shape<128, 128, 1024, 1, 8, 8, 8, 16, 7, 2 * 1024, 6, 15, 8, 12, 4, 64, 4, 32, 8, 0, 1>;
static_assert(EVMS_SERIAL_PacketMax == S::kPacketMax && EVMS_SERIAL_ModesMax == S::kModesMax &&
                  EVMS_SERIAL_IterationsMax == S::kIterationsMax && EVMS_SERIAL_UnitShift == S::kFeatFrac + hls::kClimbFrac &&
                  EVMS_SERIAL_Bands == S::kGridSide,
              "sim/CMakeLists.txt builds the engine at this test's sizes");

constexpr int kWidth = 128, kHeight = 128;

struct Case {
  hls::PacketEvents<S> events{};
  hls::Features<S> phi{};
  int n = 0;
  hls::Config cfg{};
};

// A packet of blobs (1 to 8, 2 to 25 px across) and uniform noise (a tenth of the events, or
// all of them in one packet in eight, which opens more modes than the table holds at small
// bandwidths), under registers drawn from the ranges the method uses: bandwidth 0.035-0.15 (the features below 32 bandwidths: CoordBits 19),
// tolerance, merge radius up to one bandwidth, iteration cap 0-8. At a bandwidth of 1/16 (8 px)
// the features are exact, so that events lie on the ball's boundary, which is outside it.
Case draw_case(std::mt19937_64& rng) {
  Case c;
  sim::Draws draw{rng};
  const double h = draw.one_of<double>({0.035, 0.04, 0.0625, 0.08, 0.15});
  constexpr double kClimbUnit = 1 << (S::kFeatFrac + hls::kClimbFrac);
  c.cfg.climb_scale_x = static_cast<std::uint64_t>(std::llround(std::ldexp(1.0 / (kWidth * h), hls::kClimbScaleFrac)));
  c.cfg.climb_scale_y = static_cast<std::uint64_t>(std::llround(std::ldexp(1.0 / (kHeight * h), hls::kClimbScaleFrac)));
  c.cfg.max_iterations = static_cast<std::uint8_t>(draw.below(9));
  c.cfg.tolerance = static_cast<std::uint32_t>(draw.one_of<double>({0, 0.001, 0.01, 0.05}) * kClimbUnit);
  const double merge = draw.one_of<double>({0.1, 0.5, 1.0}) * kClimbUnit;
  c.cfg.merge_radius2 = static_cast<std::uint64_t>(merge * merge);
  c.cfg.warm_start = false;

  c.n = 1 + draw.below(S::kPacketMax);
  const bool all_noise = draw.below(8) == 0;
  const int blobs = 1 + draw.below(8);
  double bx[8], by[8], br[8];
  for (int b = 0; b < blobs; ++b) bx[b] = draw.uniform(0, kWidth - 1), by[b] = draw.uniform(0, kHeight - 1), br[b] = draw.uniform(1, 12);
  for (int i = 0; i < c.n; ++i) {
    double x, y;
    if (all_noise || draw.below(10) == 0) {
      x = draw.uniform(0, kWidth - 1), y = draw.uniform(0, kHeight - 1);
    } else {
      const int b = draw.below(blobs);
      x = std::normal_distribution<double>(bx[b], br[b])(rng), y = std::normal_distribution<double>(by[b], br[b])(rng);
    }
    c.events.x[i] = static_cast<std::uint16_t>(std::clamp(std::lround(x), 0L, long{kWidth - 1}));
    c.events.y[i] = static_cast<std::uint16_t>(std::clamp(std::lround(y), 0L, long{kHeight - 1}));
  }
  hls::climb_features(c.events, c.n, c.cfg, c.phi);
  return c;
}

struct Result : sim::ClimbsReadout {
  std::vector<int> supports;
};

Result run_model(const Case& c) {
  auto climbs = std::make_unique<hls::SeededClimbs<S>>();
  std::int16_t first_mode[S::kPacketMax];
  hls::Modes<S> modes, no_warm_seeds;
  hls::ClimbTrace trace;
  climbs->run(c.phi, c.n, c.cfg, no_warm_seeds, first_mode, modes, trace);
  Result r;
  static_cast<sim::ClimbsReadout&>(r) = sim::model_readout(first_mode, c.n, modes, trace);
  for (int k = 0; k < modes.count; ++k) r.supports.push_back(climbs->support(k));
  return r;
}

Result run_rtl(const Case& c, const std::string& trace_path) {
  sim::VerilatedBlock<Vserial_climbs> rtl(trace_path);
  sim::load_packet(rtl, c.phi, c.n, c.cfg);
  std::vector<int> supports;
  Result r;
  static_cast<sim::ClimbsReadout&>(r) = sim::rtl_readout(rtl, c.n, 200'000'000, [&](int) { supports.push_back(rtl->rd_support); });
  r.supports = supports;
  return r;
}

std::string difference(const Result& want, const Result& got) {
  const std::string readout = sim::readout_difference(want, got);
  if (!readout.empty()) return readout;
  std::ostringstream o;
  for (size_t k = 0; k < want.supports.size(); ++k) {
    if (want.supports[k] != got.supports[k]) {
      o << "mode " << k << " holding " << got.supports[k] << ", want " << want.supports[k];
      return o.str();
    }
  }
  return o.str();
}

TEST(SerialClimbsRtl, EveryModeSupportAndLabelEqualTheCppModelOnRandomPackets) {
  const std::uint64_t seed = sim::cosim_seed();
  std::mt19937_64 rng(seed);
  std::uint64_t cycles = 0, events = 0, climbs = 0, steps = 0;
  int packets_with_lost_modes = 0, joins = 0;
  for (int packet = 0; packet < 120; ++packet) {
    const Case c = draw_case(rng);
    const Result want = run_model(c);
    const Result got = run_rtl(c, "");
    const std::string verdict = sim::mismatch_traced(
        "serial_climbs", seed,
        "packet " + std::to_string(packet) + " (n " + std::to_string(c.n) + ", iterations " + std::to_string(int{c.cfg.max_iterations}) + ")",
        difference(want, got), [&](const std::string& trace) { run_rtl(c, trace); });
    ASSERT_TRUE(verdict.empty()) << verdict;
    cycles += got.cycles, events += static_cast<std::uint64_t>(c.n), climbs += static_cast<std::uint64_t>(got.climbs);
    steps += static_cast<std::uint64_t>(got.steps);
    packets_with_lost_modes += want.modes_lost > 0;
    joins += want.climbs - static_cast<int>(want.modes.size()) - want.modes_lost;
  }
  std::printf("%llu events, %llu climbs, %llu steps, %.1f cycles an event\n", static_cast<unsigned long long>(events),
              static_cast<unsigned long long>(climbs), static_cast<unsigned long long>(steps),
              static_cast<double>(cycles) / static_cast<double>(events));
  EXPECT_GT(climbs, 500u);
  EXPECT_GT(joins, 50) << "climbs that joined an earlier mode";
  EXPECT_GT(packets_with_lost_modes, 2) << "packets whose modes overflowed the table";
}

// The packets the core would give the climbs on the family's scenes at 128x128: each type's first
// validation member (its first 0.25 s) through the core's filter, in packets of 1,024 kept
// events (the last closed by the stream's end), the default method's registers without warm seeds. The clocks an event are printed for
// docs/rtl.md; the climbs must agree on every packet.
TEST(SerialClimbsRtl, EveryModeSupportAndLabelEqualTheCppModelOnTheFamilysPackets) {
  Params p = backend::build_default_params<S>();
  p.packet_size = S::kPacketMax, p.warm_start = false, p.density_after_links = true;
  p.max_clusters = S::kClustersMax, p.max_tracks = S::kTracksMax;
  const hls::Config cfg = backend::core_config<S>(p, {kWidth, kHeight});
  gen::FamilyPins pins;
  pins.width = kWidth, pins.height = kHeight;
  std::uint64_t cycles = 0, events = 0;
  int packets = 0;
  for (const char* type : gen::family_types()) {
    gen::SceneConfig config = gen::family_scene(type, gen::split_seed(gen::Split::kValidation, 0), pins);
    config.duration_s = std::min(config.duration_s, 0.25);
    const eval::Scene scene = eval::generate_scene(config);
    auto filter = std::make_unique<hls::BackgroundActivityFilter<S>>();
    filter->reset();
    Case c;
    c.cfg = cfg;
    std::uint64_t type_cycles = 0, type_events = 0;
    auto close_packet = [&] {
      hls::climb_features(c.events, c.n, c.cfg, c.phi);
      const Result want = run_model(c);
      const Result got = run_rtl(c, "");
      const std::string verdict = sim::mismatch_traced("serial_climbs", 0, std::string(type) + " packet " + std::to_string(packets),
                                                       difference(want, got), [&](const std::string& trace) { run_rtl(c, trace); });
      ASSERT_TRUE(verdict.empty()) << verdict;
      type_cycles += got.cycles, type_events += static_cast<std::uint64_t>(c.n);
      ++packets;
      c.n = 0;
    };
    for (const Event& e : scene.events) {
      const hls::EventWord word{static_cast<std::uint32_t>(e.t + 1), e.x, e.y, e.p, false};
      if (!filter->accept(word, cfg)) continue;
      c.events.x[c.n] = e.x, c.events.y[c.n] = e.y, ++c.n;
      if (c.n == S::kPacketMax) close_packet();
      if (HasFatalFailure()) return;
    }
    if (c.n > 0) close_packet();   // the stream's last packet, closed by its end
    if (HasFatalFailure()) return;
    std::printf("%s: %llu events in packets, %.1f clocks an event\n", type, static_cast<unsigned long long>(type_events),
                static_cast<double>(type_cycles) / static_cast<double>(type_events));
    cycles += type_cycles, events += type_events;
  }
  std::printf("%d packets, %.1f clocks an event\n", packets, static_cast<double>(cycles) / static_cast<double>(events));
  EXPECT_GT(packets, 20);
}

}  // namespace
}  // namespace evms
