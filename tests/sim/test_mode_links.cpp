// Block-level cosimulation of rtl/cluster/evms_mode_links.sv against ModeLinks in
// hls/cluster/link.h: one instance of each takes a run of packets (the map must be clear again
// after each), and every event's mode after linking, and whether it is the first with a mode on
// its pixel, must be equal. The seed is printed
// (EVMS_SEED=N repeats a run); a mismatch repeats the run with an FST trace
// (sim/verilated_block.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "Vmode_links.h"
#include "hls/cluster/link.h"
#include "hls/core/shape.h"
#include "sim/verilated_block.h"

namespace evms {
namespace {

using S = hls::DefaultShape;
static_assert(EVMS_LINKS_MaxWidth == S::kMaxWidth && EVMS_LINKS_MaxHeight == S::kMaxHeight && EVMS_LINKS_PacketMax == S::kPacketMax &&
                  EVMS_LINKS_ModesMax == S::kModesMax && EVMS_LINKS_LinkMax == S::kLinkMax,
              "sim/CMakeLists.txt builds the block at DefaultShape's sizes");

struct Packet {
  hls::PacketEvents<S> events{};
  std::vector<std::int16_t> first_mode;   // the climbs' modes, -1 for none
  int modes = 0;
  hls::Config cfg{};
};

// Blobs of events (1 to 12 blobs, 1 to 15 px across, some sharing a pixel, some touching, some on
// the sensor's edges), each
// event with one of its blob's modes or none, on a sensor up to the Shape's, under link
// distances from off to beyond LinkMax.
Packet draw_packet(std::mt19937_64& rng) {
  Packet p;
  sim::Draws draw{rng};
  p.cfg.sensor_width = static_cast<std::uint16_t>(draw.below(4) == 0 ? 1 + draw.below(S::kMaxWidth) : S::kMaxWidth);
  p.cfg.sensor_height = static_cast<std::uint16_t>(draw.below(4) == 0 ? 1 + draw.below(S::kMaxHeight) : S::kMaxHeight);
  p.cfg.link2 = draw.one_of<std::uint32_t>({0, 1, 2, 4, 5, 9, 16, 18, 25, 32, 100});
  p.modes = 1 + draw.below(S::kModesMax);
  const int n = 1 + draw.below(S::kPacketMax), blobs = 1 + draw.below(12);
  std::vector<double> bx(static_cast<size_t>(blobs)), by(bx), br(bx);
  std::vector<int> mode_base(static_cast<size_t>(blobs));
  for (size_t b = 0; b < bx.size(); ++b) {
    bx[b] = draw.uniform(0, p.cfg.sensor_width - 1);
    by[b] = draw.uniform(0, p.cfg.sensor_height - 1);
    if (draw.below(3) == 0) bx[b] = draw.below(2) == 0 ? 0 : p.cfg.sensor_width - 1;   // on an edge, where the window leaves the sensor
    if (draw.below(3) == 0) by[b] = draw.below(2) == 0 ? 0 : p.cfg.sensor_height - 1;
    br[b] = draw.uniform(0.3, 7.0);
    mode_base[b] = draw.below(p.modes);
  }
  for (int j = 0; j < n; ++j) {
    const size_t b = static_cast<size_t>(draw.below(blobs));
    const long x = std::lround(std::normal_distribution<double>(bx[b], br[b])(rng));
    const long y = std::lround(std::normal_distribution<double>(by[b], br[b])(rng));
    p.events.x[j] = static_cast<std::uint16_t>(std::clamp(x, 0L, long{p.cfg.sensor_width - 1}));
    p.events.y[j] = static_cast<std::uint16_t>(std::clamp(y, 0L, long{p.cfg.sensor_height - 1}));
    const int mode = draw.below(8) == 0 ? -1 : std::min(p.modes - 1, mode_base[b] + draw.below(3));
    p.first_mode.push_back(static_cast<std::int16_t>(mode));
  }
  return p;
}

// Per packet, per event: its linked mode m (-1: none) and whether it is the first event with a
// mode on its pixel, as 2 m + first.
using Modes = std::vector<std::vector<std::int16_t>>;
std::int16_t mode_and_first(int mode, bool first) { return static_cast<std::int16_t>(2 * mode + (first ? 1 : 0)); }

Modes run_model(const std::vector<Packet>& run) {
  auto links = std::make_unique<hls::ModeLinks<S>>();
  links->reset();
  Modes out;
  for (const Packet& p : run) {
    std::int16_t mode[S::kPacketMax];
    bool first[S::kPacketMax];
    std::copy(p.first_mode.begin(), p.first_mode.end(), mode);
    const int n = static_cast<int>(p.first_mode.size());
    links->run(p.events, n, p.modes, p.cfg, mode, first);
    std::vector<std::int16_t> modes;
    for (int j = 0; j < n; ++j) modes.push_back(mode_and_first(mode[j], first[j]));
    out.push_back(modes);
  }
  return out;
}

using RtlRun = sim::BlockRun<std::vector<std::int16_t>>;  // its results: Modes

RtlRun run_rtl(const std::vector<Packet>& run, const std::string& trace_path) {
  sim::VerilatedBlock<Vmode_links> rtl(trace_path);
  RtlRun r;
  rtl.tick_until_ready();
  for (const Packet& p : run) {
    const int n = static_cast<int>(p.first_mode.size());
    rtl->n = static_cast<std::uint16_t>(n);
    rtl->cfg_link2 = p.cfg.link2;
    rtl->cfg_sensor_width = p.cfg.sensor_width;
    rtl->cfg_sensor_height = p.cfg.sensor_height;
    // The packet's memories answer ev_j the clock after, as a block RAM's registered read does;
    // the first bits are written where the block says.
    std::vector<bool> first_bits(static_cast<size_t>(n), false);
    auto tick_with_memories = [&] {
      rtl->eval();
      if (rtl->first_we && rtl->first_j < n) first_bits[rtl->first_j] = rtl->first_on_pixel;
      const int j = rtl->ev_j;
      rtl.tick();
      const bool in = j < n;
      rtl->ev_x = in ? p.events.x[j] : 0, rtl->ev_y = in ? p.events.y[j] : 0;
      rtl->ev_mode = static_cast<std::uint16_t>(in ? p.first_mode[static_cast<size_t>(j)] : 0);
    };
    const std::uint64_t cycles = rtl.run_until_done(tick_with_memories, 10'000'000);
    r.cycles += cycles, r.events += static_cast<std::uint64_t>(n);
    // With the links off the block passes the packet by, as the model's write pass does not run.
    const auto first_of = [&](int j) { return p.cfg.link2 == 0 ? p.first_mode[static_cast<size_t>(j)] >= 0 : bool{first_bits[static_cast<size_t>(j)]}; };
    std::vector<std::int16_t> modes;
    for (int j = 0; j < n; ++j) {
      const int first = p.first_mode[static_cast<size_t>(j)];
      if (first < 0) {
        modes.push_back(mode_and_first(-1, first_of(j)));
        continue;
      }
      rtl->rd_c = static_cast<std::uint8_t>(first);
      rtl->eval();
      modes.push_back(mode_and_first(rtl->rd_root, first_of(j)));
    }
    r.results.push_back(modes);
    rtl.tick();
  }
  return r;
}

// What differs between two results of one packet: its events' modes.
std::string describe(const std::vector<std::int16_t>& want, const std::vector<std::int16_t>& got) {
  for (size_t j = 0; j < want.size(); ++j) {
    if (j >= got.size()) return "event " + std::to_string(j) + ": no mode";
    if (want[j] != got[j]) {
      const auto text = [](int v) { return "mode " + std::to_string(v >> 1) + (v & 1 ? " (first on its pixel)" : ""); };
      return "event " + std::to_string(j) + ": " + text(got[j]) + ", want " + text(want[j]);
    }
  }
  return std::to_string(got.size()) + " modes, want " + std::to_string(want.size());
}

TEST(ModeLinksRtl, EveryEventsLinkedModeEqualsTheCppModelOverRunsOfPackets) {
  const std::uint64_t seed = sim::cosim_seed();
  std::mt19937_64 rng(seed);
  std::uint64_t joined = 0;
  const auto draw_run = [&](int) {
    std::vector<Packet> run;
    for (int k = 0; k < 20; ++k) run.push_back(draw_packet(rng));
    return run;
  };
  const auto tally = [&](const std::vector<Packet>& run, const Modes& want) {
    for (size_t k = 0; k < run.size(); ++k) {
      for (size_t j = 0; j < want[k].size(); ++j) joined += (want[k][j] >> 1) != run[k].first_mode[j];
    }
  };
  const sim::RunsCompared compared = sim::compare_runs("mode_links", seed, 12, draw_run, run_model, run_rtl, describe, tally);
  ASSERT_TRUE(compared.verdict.empty()) << compared.verdict;
  const std::uint64_t events = compared.events;
  std::printf("%llu events, %llu took an older mode, %.1f cycles an event\n", static_cast<unsigned long long>(events),
              static_cast<unsigned long long>(joined), static_cast<double>(compared.cycles) / static_cast<double>(events));
  EXPECT_GT(joined, events / 10) << "too few packets joined modes to test the links";
}

}  // namespace
}  // namespace evms
