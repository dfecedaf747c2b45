// Block-level cosimulation of rtl/cluster/evms_edge_join.sv against EdgeJoin in
// hls/cluster/edge_join.h: one instance of each takes a run of packets, and every event's mode
// after the join and the count of pairs joined must be equal. The seed is printed (EVMS_SEED=N
// repeats a run); a mismatch repeats the run with an FST trace (sim/verilated_block.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <memory>
#include <numeric>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "Vedge_join.h"
#include "hls/cluster/edge_join.h"
#include "hls/core/shape.h"
#include "sim/verilated_block.h"

namespace evms {
namespace {

using S = hls::RtlHostShape;
static_assert(EVMS_EDGE_PacketMax == S::kPacketMax && EVMS_EDGE_ModesMax == S::kModesMax && EVMS_EDGE_EdgeSizeRatio == S::kEdgeSizeRatio,
              "sim/CMakeLists.txt builds the block at RtlHostShape's sizes");

struct Packet {
  std::unique_ptr<hls::PacketEvents<S>> events = std::make_unique<hls::PacketEvents<S>>();
  std::vector<std::int16_t> mode;  // after the split, -1 for none
  int modes = 0;
  hls::Config cfg{};
};

// Objects on sensors up to the Shape's: a mixed bar (one mode), or an outline's two edges, a
// mostly-ON and a mostly-OFF bar a few pixels to tens of pixels apart (two modes), of sizes
// that differ up to eightfold; scattered events of no mode; modes numbered in random order, some
// holding no event. The rule's settings span reaches of 6 to 400 px, balances from 1/256 to
// whole, and minimum sizes from none to 40.
Packet draw_packet(std::mt19937_64& rng) {
  Packet p;
  sim::Draws draw{rng};
  const auto [width, height] = draw.sensor();
  const int reach_px = draw.one_of<int>({6, 24, 48, 96, 400});
  p.cfg.edge_radius2 = static_cast<std::uint64_t>(16 * reach_px) * static_cast<std::uint64_t>(16 * reach_px);
  p.cfg.edge_balance = draw.one_of<std::uint16_t>({1, 26, 128, 205, 256});
  p.cfg.edge_min_events = draw.one_of<std::uint16_t>({0, 1, 8, 16, 40});
  p.modes = draw.below(4) == 0 ? S::kModesMax - draw.below(4) : 2 + draw.below(20);
  std::vector<int> numbering(static_cast<size_t>(p.modes));
  std::iota(numbering.begin(), numbering.end(), 0);
  std::shuffle(numbering.begin(), numbering.end(), rng);
  const int n = 16 + draw.below(S::kPacketMax - 15);
  struct Bar {
    double x, y, dx, dy, length, on_share;
    int mode;
    double weight;
  };
  std::vector<Bar> bars;
  size_t next_mode = 0;
  const int objects = 1 + draw.below(6);
  for (int o = 0; o < objects && next_mode < numbering.size(); ++o) {
    const double x = draw.uniform(0, width - 1), y = draw.uniform(0, height - 1), a = draw.uniform(0, 2 * M_PI), length = draw.uniform(2, 60);
    const double dx = std::cos(a), dy = std::sin(a);
    if (draw.below(3) == 0 || next_mode + 1 >= numbering.size()) {
      bars.push_back({x, y, dx, dy, length, draw.uniform(0.3, 0.7), numbering[next_mode++], draw.uniform(0.5, 2)});
    } else {
      // The two edges, apart across the bar's direction; each mostly one polarity (sometimes not).
      const double gap = draw.one_of<double>({3, 10, 30, 60});
      const double lean = draw.one_of<double>({1.0, 0.95, 0.8, 0.7});
      const double w = draw.uniform(0.5, 2), ratio = draw.one_of<double>({1, 2, 4, 8});
      bars.push_back({x, y, dx, dy, length, lean, numbering[next_mode++], w});
      bars.push_back({x - gap * dy, y + gap * dx, dx, dy, length, 1 - lean, numbering[next_mode++], w / ratio});
    }
  }
  double total = 0;
  for (const Bar& b : bars) total += b.weight;
  for (int j = 0; j < n; ++j) {
    int x = draw.below(width), y = draw.below(height), mode = -1, on = draw.below(2);
    if (draw.below(12) != 0) {
      double pick = draw.uniform(0, total);
      size_t k = 0;
      while (k + 1 < bars.size() && pick > bars[k].weight) pick -= bars[k++].weight;
      const Bar& b = bars[k];
      const double s = draw.uniform(0, b.length);
      x = static_cast<int>(std::clamp(std::lround(b.x + s * b.dx), 0L, static_cast<long>(width - 1)));
      y = static_cast<int>(std::clamp(std::lround(b.y + s * b.dy), 0L, static_cast<long>(height - 1)));
      mode = b.mode;
      on = draw.uniform(0, 1) < b.on_share;
    }
    p.events->x[j] = static_cast<std::uint16_t>(x), p.events->y[j] = static_cast<std::uint16_t>(y), p.events->p[j] = static_cast<std::uint8_t>(on);
    p.mode.push_back(static_cast<std::int16_t>(mode));
  }
  return p;
}

// Packets on the rule's edges, where random centres seldom fall: clusters of one pixel each, so
// that the centres are exact.
//   reach: an ON and an OFF cluster exactly the reach apart join; another pair 1 px farther does not;
//   ties: an OFF cluster between two ON clusters at equal distances takes the lower.
std::vector<Packet> edge_packets() {
  struct Cluster {
    int x, y, on;
  };
  auto packet = [](const std::vector<Cluster>& clusters) {
    Packet p;
    p.cfg.edge_radius2 = (16 * 48) * (16 * 48);
    p.cfg.edge_balance = 128;
    p.cfg.edge_min_events = 16;
    p.modes = static_cast<int>(clusters.size());
    int j = 0;
    for (int m = 0; m < p.modes; ++m) {
      for (int k = 0; k < 20; ++k, ++j) {
        const Cluster& c = clusters[static_cast<size_t>(m)];
        p.events->x[j] = static_cast<std::uint16_t>(c.x), p.events->y[j] = static_cast<std::uint16_t>(c.y);
        p.events->p[j] = static_cast<std::uint8_t>(c.on);
        p.mode.push_back(static_cast<std::int16_t>(m));
      }
    }
    return p;
  };
  std::vector<Packet> packets;
  packets.push_back(packet({{100, 100, 1}, {148, 100, 0}, {300, 100, 1}, {349, 100, 0}}));
  packets.push_back(packet({{200, 50, 0}, {180, 50, 1}, {220, 50, 1}}));
  return packets;
}

struct Result {
  std::vector<std::int16_t> mode;
  int joined = 0;
  bool operator==(const Result&) const = default;
};

std::vector<Result> run_model(const std::vector<Packet>& run) {
  auto join = std::make_unique<hls::EdgeJoin<S>>();
  std::vector<Result> out;
  for (const Packet& p : run) {
    std::int16_t mode[S::kPacketMax];
    std::copy(p.mode.begin(), p.mode.end(), mode);
    const int n = static_cast<int>(p.mode.size());
    const int joined = join->run(*p.events, n, p.cfg, p.modes, mode);
    out.push_back({{mode, mode + n}, joined});
  }
  return out;
}

using RtlRun = sim::BlockRun<Result>;

RtlRun run_rtl(const std::vector<Packet>& run, const std::string& trace_path) {
  sim::VerilatedBlock<Vedge_join> rtl(trace_path);
  RtlRun r;
  for (const Packet& p : run) {
    const int n = static_cast<int>(p.mode.size());
    rtl->n = static_cast<std::uint16_t>(n);
    rtl->mode_count = static_cast<std::uint16_t>(p.modes);
    rtl->cfg_edge_radius2 = p.cfg.edge_radius2;
    rtl->cfg_edge_balance = p.cfg.edge_balance;
    rtl->cfg_edge_min_events = p.cfg.edge_min_events;
    // The packet's memories answer ev_j the clock after, as a block RAM's registered read does.
    auto tick_with_memories = [&] {
      const int j = rtl->ev_j;
      rtl.tick();
      const bool in = j < n;
      rtl->ev_x = in ? p.events->x[j] : 0, rtl->ev_y = in ? p.events->y[j] : 0, rtl->ev_p = in ? p.events->p[j] : 0;
      rtl->ev_mode = static_cast<std::uint16_t>(in ? p.mode[static_cast<size_t>(j)] : 0);
    };
    const std::uint64_t cycles = rtl.run_until_done(tick_with_memories, 1'000'000);
    rtl.tick();
    r.cycles += cycles, r.events += static_cast<std::uint64_t>(n);
    Result got;
    got.joined = rtl->joined;
    for (int j = 0; j < n; ++j) {
      const int before = p.mode[static_cast<size_t>(j)];
      rtl->rd_c = static_cast<std::uint8_t>(std::max(before, 0));
      rtl->eval();
      got.mode.push_back(static_cast<std::int16_t>(before < 0 ? -1 : rtl->rd_into));
    }
    r.results.push_back(got);
  }
  return r;
}

// What differs between two results of one packet.
std::string describe(const Result& want, const Result& got) {
  std::ostringstream o;
  if (want.joined != got.joined) o << got.joined << " pairs joined, want " << want.joined << "; ";
  for (size_t j = 0; j < want.mode.size(); ++j) {
    if (want.mode[j] != got.mode[j]) {
      o << "event " << j << ": mode " << got.mode[j] << ", want " << want.mode[j];
      break;
    }
  }
  return o.str();
}

TEST(EdgeJoinRtl, EveryEventsModeAndThePairsJoinedEqualTheCppModelOverRunsOfPackets) {
  const std::uint64_t seed = sim::cosim_seed();
  std::mt19937_64 rng(seed);
  int packets = 0, joined_packets = 0, pairs = 0;
  const auto draw_run = [&](int r) {
    std::vector<Packet> run = r == 0 ? edge_packets() : std::vector<Packet>{};
    for (int k = 0; k < 25; ++k) run.push_back(draw_packet(rng));
    return run;
  };
  const auto tally = [&](const std::vector<Packet>&, const std::vector<Result>& want) {
    for (const Result& w : want) {
      ++packets;
      joined_packets += w.joined > 0;
      pairs += w.joined;
    }
  };
  const sim::RunsCompared compared = sim::compare_runs("edge_join", seed, 8, draw_run, run_model, run_rtl, describe, tally);
  ASSERT_TRUE(compared.verdict.empty()) << compared.verdict;
  // The edge packets' outcomes, as worked by hand: the pair at the reach joins, the one beyond
  // it does not, and of equal distances the lower cluster is taken.
  const std::vector<Result> edges = run_model(edge_packets());
  auto modes_of = [](std::initializer_list<int> per_cluster) {
    std::vector<std::int16_t> modes;
    for (int m : per_cluster) modes.insert(modes.end(), 20, static_cast<std::int16_t>(m));
    return modes;
  };
  EXPECT_EQ(edges[0].mode, modes_of({0, 0, 2, 3}));
  EXPECT_EQ(edges[1].mode, modes_of({0, 0, 2}));
  std::printf("%d packets, %d with a join, %d pairs joined, %.1f cycles an event\n", packets, joined_packets, pairs,
              static_cast<double>(compared.cycles) / static_cast<double>(compared.events));
  // Both outcomes, many times: the packets reach the rule's every branch.
  EXPECT_GE(joined_packets, 10) << "too few packets joined a pair to test the join";
  EXPECT_GE(packets - joined_packets, 10) << "too few packets joined nothing to test the rule";
}

}  // namespace
}  // namespace evms
