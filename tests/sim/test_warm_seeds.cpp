// Block-level cosimulation of rtl/cluster/evms_warm_seeds.sv against keep_clusters and
// warm_balls in hls/cluster/warm_seeds.h: the same modes, events and registers; the cluster
// count, every event's cluster and every warm seed (position and ball) must be equal. The seed
// is printed (EVMS_SEED=N repeats a run); a mismatch repeats the packet with an FST trace
// (sim/verilated_block.h).
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "Vwarm_seeds.h"
#include "hls/cluster/warm_seeds.h"
#include "hls/core/shape.h"
#include "sim/verilated_block.h"

namespace evms {
namespace {

using S = hls::DefaultShape;
static_assert(EVMS_WARM_PacketMax == S::kPacketMax && EVMS_WARM_ModesMax == S::kModesMax && EVMS_WARM_ClustersMax == S::kClustersMax &&
                  EVMS_WARM_UnitShift == S::kFeatFrac + hls::kClimbFrac,
              "sim/CMakeLists.txt builds the block at DefaultShape's sizes");

constexpr std::uint64_t kOne = hls::SeededClimbs<S>::kOne;

struct Case {
  hls::Features<S> phi{};
  std::int16_t mode_of[S::kPacketMax] = {};
  int n = 0;
  hls::Modes<S> modes{};
  hls::Config cfg{};
};

// Modes at random climb positions, events spread about their mode by up to 3 bandwidths (some
// far, some without a mode), minimum sizes that keep most, some or none of the modes, cluster
// caps below and above ClustersMax, and ball scales and caps that clamp at both ends.
Case draw_case(std::mt19937_64& rng) {
  Case c;
  auto below = [&](std::uint64_t k) { return static_cast<int>(rng() % k); };
  constexpr double kUnit = 1 << (S::kFeatFrac + hls::kClimbFrac);
  c.modes.count = 1 + below(S::kModesMax);
  for (int k = 0; k < c.modes.count; ++k) {
    c.modes.x[k] = static_cast<std::int64_t>(std::uniform_real_distribution<double>(0, 34)(rng) * kUnit);
    c.modes.y[k] = static_cast<std::int64_t>(std::uniform_real_distribution<double>(0, 34)(rng) * kUnit);
    c.modes.p[k] = c.modes.t[k] = 0;
  }
  c.n = 1 + below(S::kPacketMax);
  const double spread = std::vector<double>{0.01, 0.5, 1.0, 3.0}[static_cast<size_t>(below(4))];
  for (int j = 0; j < c.n; ++j) {
    const int mode = below(10) == 0 ? -1 : below(static_cast<std::uint64_t>(c.modes.count));
    c.mode_of[j] = static_cast<std::int16_t>(mode);
    const int at = mode < 0 ? 0 : mode;
    auto near = [&](std::int64_t m) {
      const double v = static_cast<double>(m) + std::normal_distribution<double>(0, spread * kUnit)(rng);
      return static_cast<std::uint32_t>(std::clamp(v, 0.0, 40 * kUnit));
    };
    c.phi.x[j] = near(c.modes.x[at]), c.phi.y[j] = near(c.modes.y[at]);
  }
  c.cfg.min_cluster_size = static_cast<std::uint16_t>(std::vector<int>{1, 2, 5, 20, 300}[static_cast<size_t>(below(5))]);
  c.cfg.max_clusters = static_cast<std::uint8_t>(1 + below(24));
  c.cfg.warm_scale2 = static_cast<std::uint32_t>(below(2000));
  c.cfg.warm_ball2_max = std::vector<std::uint64_t>{0, 4 * kOne, 16 * kOne, 64 * kOne}[static_cast<size_t>(below(4))];
  return c;
}

struct Result {
  int clusters = 0;
  std::vector<int> cluster_of;
  std::vector<std::uint64_t> seeds;   // x, y, ball2 of each
  std::uint64_t cycles = 0;
};

Result run_model(const Case& c) {
  std::int8_t cluster_of[S::kPacketMax];
  hls::Modes<S> warm;
  Result r;
  r.clusters = hls::keep_clusters<S>(c.mode_of, c.n, c.modes, c.cfg, cluster_of, warm);
  hls::warm_balls<S>(c.phi, c.n, cluster_of, c.cfg, warm);
  r.cluster_of.assign(cluster_of, cluster_of + c.n);
  for (int k = 0; k < warm.count; ++k) {
    r.seeds.insert(r.seeds.end(), {static_cast<std::uint64_t>(warm.x[k]), static_cast<std::uint64_t>(warm.y[k]), warm.ball2[k]});
  }
  return r;
}

Result run_rtl(const Case& c, const std::string& trace_path) {
  sim::VerilatedBlock<Vwarm_seeds> rtl(trace_path);
  rtl->n = static_cast<std::uint16_t>(c.n);
  rtl->mode_count = static_cast<std::uint16_t>(c.modes.count);
  rtl->cfg_min_cluster_size = c.cfg.min_cluster_size;
  rtl->cfg_max_clusters = c.cfg.max_clusters;
  rtl->cfg_warm_scale2 = c.cfg.warm_scale2;
  rtl->cfg_warm_ball2_max = c.cfg.warm_ball2_max;
  Result r;
  r.cluster_of.assign(static_cast<size_t>(c.n), 99);
  std::vector<std::uint64_t> seeds(3 * S::kClustersMax, 0);
  // The outputs are taken at the clock edge that writes them; the event and mode memories
  // answer the address of the clock before, as block RAMs do.
  auto tick = [&] {
    if (rtl->co_we && rtl->co_j < c.n) r.cluster_of[rtl->co_j] = static_cast<std::int8_t>(rtl->co_value);
    if (rtl->warm_we && rtl->warm_k < S::kClustersMax) {
      seeds[3 * rtl->warm_k] = rtl->warm_x, seeds[3 * rtl->warm_k + 1] = rtl->warm_y, seeds[3 * rtl->warm_k + 2] = rtl->warm_ball2;
    }
    const int j = rtl->ev_j, k = rtl->md_c;
    rtl.tick();
    const bool in = j < c.n;
    rtl->ev_mode = static_cast<std::uint16_t>(in ? c.mode_of[j] : 0);
    rtl->ev_x = in ? c.phi.x[j] : 0, rtl->ev_y = in ? c.phi.y[j] : 0;
    rtl->md_x = k < c.modes.count ? static_cast<std::uint32_t>(c.modes.x[k]) : 0;
    rtl->md_y = k < c.modes.count ? static_cast<std::uint32_t>(c.modes.y[k]) : 0;
    rtl->eval();   // the write ports depend on the data read
  };
  r.cycles = rtl.run_until_done(tick, 10'000'000);
  r.clusters = rtl->clusters;
  seeds.resize(3 * static_cast<size_t>(std::min<int>(r.clusters, S::kClustersMax)));
  r.seeds = seeds;
  return r;
}

std::string difference(const Result& want, const Result& got) {
  std::ostringstream o;
  if (want.clusters != got.clusters) {
    o << got.clusters << " clusters, want " << want.clusters;
    return o.str();
  }
  for (size_t j = 0; j < want.cluster_of.size(); ++j) {
    if (want.cluster_of[j] != got.cluster_of[j]) {
      o << "event " << j << ": cluster " << got.cluster_of[j] << ", want " << want.cluster_of[j];
      return o.str();
    }
  }
  static constexpr const char* kField[] = {"x", "y", "ball2"};
  for (size_t i = 0; i < want.seeds.size(); ++i) {
    if (want.seeds[i] != got.seeds[i]) {
      o << "seed " << i / 3 << " " << kField[i % 3] << ": " << got.seeds[i] << ", want " << want.seeds[i];
      return o.str();
    }
  }
  return "";
}

TEST(WarmSeedsRtl, ClustersLabelsAndWarmBallsEqualTheCppModelOnRandomPackets) {
  const std::uint64_t seed = sim::cosim_seed();
  std::mt19937_64 rng(seed);
  std::uint64_t cycles = 0, events = 0, clamped = 0, balls = 0;
  for (int packet = 0; packet < 200; ++packet) {
    const Case c = draw_case(rng);
    const Result want = run_model(c);
    const Result got = run_rtl(c, "");
    const std::string verdict = sim::mismatch_traced("warm_seeds", seed,
                                                     "packet " + std::to_string(packet) + " (n " + std::to_string(c.n) + ", modes " +
                                                         std::to_string(c.modes.count) + ")",
                                                     difference(want, got), [&](const std::string& trace) { run_rtl(c, trace); });
    ASSERT_TRUE(verdict.empty()) << verdict;
    cycles += got.cycles, events += static_cast<std::uint64_t>(c.n);
    for (size_t i = 2; i < want.seeds.size(); i += 3) {
      ++balls;
      clamped += want.seeds[i] == kOne || want.seeds[i] == std::max(c.cfg.warm_ball2_max, kOne);
    }
  }
  std::printf("%llu events, %llu warm balls (%llu at a bound), %.1f cycles an event\n", static_cast<unsigned long long>(events),
              static_cast<unsigned long long>(balls), static_cast<unsigned long long>(clamped),
              static_cast<double>(cycles) / static_cast<double>(events));
  EXPECT_GT(balls - clamped, balls / 10) << "too few balls between their bounds to test the variance";
  EXPECT_GT(clamped, 0u) << "no ball at a bound";
}

}  // namespace
}  // namespace evms
