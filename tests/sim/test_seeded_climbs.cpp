// Block-level cosimulation of rtl/cluster/evms_seeded_climbs.sv against SeededClimbs in
// hls/cluster/seeded_climbs.h: the same packet, warm seeds and registers; every event's mode,
// every mode, and the climb, step and lost-mode counts must be equal. The seed is drawn anew
// each run and printed (EVMS_SEED=N repeats one); a mismatch repeats the packet with an FST
// trace in the temporary directory (sim/verilated_block.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>
#include <sstream>
#include <string>

#include "Vseeded_climbs.h"
#include "hls/cluster/seeded_climbs.h"
#include "hls/core/shape.h"
#include "sim/verilated_block.h"
#include "tests/sim/climbs_readout.h"

namespace evms {
namespace {

using S = hls::DefaultShape;
static_assert(EVMS_CLIMBS_PacketMax == S::kPacketMax && EVMS_CLIMBS_ModesMax == S::kModesMax && EVMS_CLIMBS_GridSide == S::kGridSide &&
                  EVMS_CLIMBS_ReachMax == S::kReachMax && EVMS_CLIMBS_IterationsMax == S::kIterationsMax &&
                  EVMS_CLIMBS_UnitShift == S::kFeatFrac + hls::kClimbFrac,
              "sim/CMakeLists.txt builds the engine at DefaultShape's sizes");

constexpr int kWidth = 240, kHeight = 180;

struct Case {
  hls::PacketEvents<S> events{};
  hls::Features<S> phi{};         // the events' climb features, which both sides take
  int n = 0;
  hls::Config cfg{};
  hls::Modes<S> warm{};
};

// A packet of blobs (1 to 6, 2 to 25 px across) and uniform noise, under registers drawn from
// the ranges the method uses: bandwidth 0.03-0.15, tolerance, merge radius, iteration cap
// 0-8, warm seeds with balls of 1-8 bandwidths (some on no event, some beyond the sensor), the
// least density off or 0.5-20 times a uniform spread's, tested by the climbs or left to the core.
Case draw_case(std::mt19937_64& rng) {
  Case c;
  sim::Draws draw{rng};
  const double h = draw.one_of<double>({0.03, 0.05, 0.08, 0.15});
  constexpr double kClimbUnit = 1 << (S::kFeatFrac + hls::kClimbFrac);
  c.cfg.climb_scale_x = static_cast<std::uint64_t>(std::llround(std::ldexp(1.0 / (kWidth * h), hls::kClimbScaleFrac)));
  c.cfg.climb_scale_y = static_cast<std::uint64_t>(std::llround(std::ldexp(1.0 / (kHeight * h), hls::kClimbScaleFrac)));
  c.cfg.max_iterations = static_cast<std::uint8_t>(draw.below(9));
  c.cfg.tolerance = static_cast<std::uint32_t>(draw.one_of<double>({0, 0.001, 0.01, 0.05}) * kClimbUnit);
  const double merge = draw.one_of<double>({0.1, 0.5, 1.0}) * kClimbUnit;
  c.cfg.merge_radius2 = static_cast<std::uint64_t>(merge * merge);
  c.cfg.warm_start = draw.below(4) != 0;
  // The least density (0: off, as half the cases): md times n pi h^2 events on (x/W, y/H).
  const double min_density = draw.one_of<double>({0, 0, 0.5, 2, 6, 20});
  c.cfg.min_density = static_cast<std::uint32_t>(std::llround(std::ldexp(min_density * M_PI * h * h, hls::kDensityFrac)));
  // Half the time the events keep their modes and the modes' tests are read out
  // (hls/cluster/sparse_sets.h makes them on the linked sets).
  c.cfg.density_after_links = draw.below(2) == 0;

  c.n = 1 + draw.below(S::kPacketMax);
  const int blobs = 1 + draw.below(6);
  double bx[6], by[6], br[6];
  for (int b = 0; b < blobs; ++b) bx[b] = draw.uniform(0, kWidth - 1), by[b] = draw.uniform(0, kHeight - 1), br[b] = draw.uniform(1, 12);
  for (int i = 0; i < c.n; ++i) {
    double x, y;
    if (draw.below(10) == 0) {
      x = draw.uniform(0, kWidth - 1), y = draw.uniform(0, kHeight - 1);
    } else {
      const int b = draw.below(blobs);
      x = std::normal_distribution<double>(bx[b], br[b])(rng), y = std::normal_distribution<double>(by[b], br[b])(rng);
    }
    c.events.x[i] = static_cast<std::uint16_t>(std::clamp(std::lround(x), 0L, long{kWidth - 1}));
    c.events.y[i] = static_cast<std::uint16_t>(std::clamp(std::lround(y), 0L, long{kHeight - 1}));
  }
  constexpr std::uint64_t kOne = hls::SeededClimbs<S>::kOne;
  c.warm.count = draw.below(12);
  for (int k = 0; k < c.warm.count; ++k) {
    const bool far = draw.below(8) == 0;
    c.warm.x[k] = static_cast<std::int64_t>((far ? draw.uniform(0, 40) : draw.uniform(0, 1.0 / h)) * kClimbUnit);
    c.warm.y[k] = static_cast<std::int64_t>((far ? draw.uniform(0, 40) : draw.uniform(0, 1.0 / h)) * kClimbUnit);
    const double r = draw.uniform(1, S::kReachMax);
    c.warm.ball2[k] = draw.below(3) == 0 ? kOne : static_cast<std::uint64_t>(r * r * static_cast<double>(kOne));
  }
  hls::climb_features(c.events, c.n, c.cfg, c.phi);
  return c;
}

struct Result : sim::ClimbsReadout {
  std::vector<bool> sparse;   // each mode below the least density
  std::uint64_t least = 0;    // the packet's least density, which the core tests the linked sets on
};

Result run_model(const Case& c) {
  auto climbs = std::make_unique<hls::SeededClimbs<S>>();
  std::int16_t first_mode[S::kPacketMax];
  hls::Modes<S> modes;
  hls::ClimbTrace trace;
  climbs->run(c.phi, c.n, c.cfg, c.warm, first_mode, modes, trace);
  Result r;
  static_cast<sim::ClimbsReadout&>(r) = sim::model_readout(first_mode, c.n, modes, trace);
  for (int k = 0; k < modes.count; ++k) r.sparse.push_back(c.cfg.min_density != 0 && climbs->sparse(k, c.n, c.cfg));
  r.least = hls::SeededClimbs<S>::least(c.n, c.cfg);
  return r;
}

Result run_rtl(const Case& c, const std::string& trace_path) {
  sim::VerilatedBlock<Vseeded_climbs> rtl(trace_path);
  sim::load_packet(rtl, c.phi, c.n, c.cfg);
  for (int k = 0; k < c.warm.count; ++k) {
    rtl->warm_we = 1, rtl->warm_k = static_cast<std::uint8_t>(k);
    rtl->warm_x = static_cast<std::uint32_t>(c.warm.x[k]), rtl->warm_y = static_cast<std::uint32_t>(c.warm.y[k]);
    rtl->warm_ball2 = c.warm.ball2[k];
    rtl.tick();
  }
  rtl->warm_we = 0;
  rtl->warm_count = static_cast<std::uint8_t>(c.warm.count);
  rtl->cfg_warm_start = c.cfg.warm_start;
  rtl->cfg_min_density = c.cfg.min_density;
  rtl->cfg_density_after_links = c.cfg.density_after_links;
  std::vector<bool> sparse;
  Result r;
  static_cast<sim::ClimbsReadout&>(r) = sim::rtl_readout(rtl, c.n, 50'000'000, [&](int) { sparse.push_back(rtl->rd_c_sparse != 0); });
  r.sparse = sparse;
  r.least = rtl->least;
  return r;
}

std::string difference(const Result& want, const Result& got) {
  const std::string readout = sim::readout_difference(want, got);
  if (!readout.empty()) return readout;
  std::ostringstream o;
  for (size_t k = 0; k < want.sparse.size(); ++k) {
    if (want.sparse[k] != got.sparse[k]) {
      o << "mode " << k << (got.sparse[k] ? " sparse" : " dense") << ", want " << (want.sparse[k] ? "sparse" : "dense");
      return o.str();
    }
  }
  if (want.least != got.least) o << "least density " << got.least << ", want " << want.least;
  return o.str();
}

TEST(SeededClimbsRtl, EveryModeAndLabelEqualTheCppModelOnRandomPackets) {
  const std::uint64_t seed = sim::cosim_seed();
  std::mt19937_64 rng(seed);
  std::uint64_t cycles = 0, events = 0, climbs = 0;
  int sparse_packets = 0;  // packets in which the least density made some event noise
  int sparse_modes_read = 0;  // packets whose events kept their modes while some mode was sparse
  for (int packet = 0; packet < 200; ++packet) {
    const Case c = draw_case(rng);
    const Result want = run_model(c);
    if (c.cfg.min_density != 0 && !c.cfg.density_after_links) {
      Case any = c;
      any.cfg.min_density = 0;
      const Result without = run_model(any);
      sparse_packets += std::count(want.first_mode.begin(), want.first_mode.end(), -1) >
                        std::count(without.first_mode.begin(), without.first_mode.end(), -1);
    }
    sparse_modes_read += c.cfg.density_after_links && std::count(want.sparse.begin(), want.sparse.end(), true) > 0;
    const Result got = run_rtl(c, "");
    const std::string verdict = sim::mismatch_traced("seeded_climbs", seed,
                                                     "packet " + std::to_string(packet) + " (n " + std::to_string(c.n) + ", warm " +
                                                         std::to_string(c.warm.count) + ", iterations " + std::to_string(int{c.cfg.max_iterations}) + ")",
                                                     difference(want, got), [&](const std::string& trace) { run_rtl(c, trace); });
    ASSERT_TRUE(verdict.empty()) << verdict;
    cycles += got.cycles, events += static_cast<std::uint64_t>(c.n), climbs += static_cast<std::uint64_t>(got.climbs);
  }
  std::printf("%llu events, %llu climbs, %.1f cycles an event\n", static_cast<unsigned long long>(events),
              static_cast<unsigned long long>(climbs), static_cast<double>(cycles) / static_cast<double>(events));
  EXPECT_GT(climbs, 200u);
  EXPECT_GT(sparse_packets, 5) << "packets with a sparse mode";
  EXPECT_GT(sparse_modes_read, 5) << "packets whose sparse modes the core tests after the links";
}

}  // namespace
}  // namespace evms
