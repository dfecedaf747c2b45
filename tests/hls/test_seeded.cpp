// The core's seeded climbs against golden's, packet by packet: the same clusters on dense random
// packets, and the pixel-map link against the all-pairs rule it implements.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <memory>
#include <set>

#include "golden/cluster/clustering.h"
#include "hls/cluster/link.h"
#include "hls/cluster/seeded_climbs.h"
#include "hls/cluster/sparse_sets.h"
#include "hls/core/shape.h"
#include "host/backend/core_config.h"
#include "host/gen/random.h"

namespace evms::hls {
namespace {

using S = HostShape;

// Blobs of events with some scattered ones, in a 240x180 sensor.
std::vector<Event> random_packet(std::uint64_t seed, int n) {
  gen::Random rng(seed);
  std::vector<Event> e;
  std::vector<std::pair<double, double>> centres;
  for (int k = 0; k < 6; ++k) centres.emplace_back(rng.uniform(10, 230), rng.uniform(10, 170));
  for (int i = 0; i < n; ++i) {
    if (rng.uniform() < 0.1) {
      e.push_back({i, static_cast<std::uint16_t>(rng.below(240)), static_cast<std::uint16_t>(rng.below(180)), 1});
      continue;
    }
    const auto& c = centres[rng.below(centres.size())];
    const double r = rng.uniform(0, 18), a = rng.uniform(0, 2 * M_PI);
    e.push_back({i, static_cast<std::uint16_t>(std::clamp(c.first + r * std::cos(a), 0.0, 239.0)),
                 static_cast<std::uint16_t>(std::clamp(c.second + r * std::sin(a), 0.0, 179.0)), 1});
  }
  return e;
}

// A partition as a set of sets of event indices, so that two labellings compare regardless of
// their cluster numbers.
template <class Label>
std::set<std::set<int>> partition(const std::vector<Label>& labels) {
  std::map<int, std::set<int>> groups;
  for (size_t i = 0; i < labels.size(); ++i) {
    if (labels[i] >= 0) groups[static_cast<int>(labels[i])].insert(static_cast<int>(i));
  }
  std::set<std::set<int>> out;
  for (auto& [c, g] : groups) out.insert(g);
  return out;
}

// The climbs and links of `events` as the core finds them, with golden's least cluster size.
std::vector<int> core_clusters(const std::vector<Event>& events, const Params& p, const Config& cfg) {
  auto climbs = std::make_unique<SeededClimbs<S>>();
  auto links = std::make_unique<ModeLinks<S>>();
  links->reset();
  auto ev = std::make_unique<PacketEvents<S>>();
  for (size_t i = 0; i < events.size(); ++i) ev->x[i] = events[i].x, ev->y[i] = events[i].y, ev->p[i] = 1, ev->t[i] = static_cast<std::uint32_t>(i);
  const int n = static_cast<int>(events.size());
  auto phi = std::make_unique<Features<S>>();
  climb_features(*ev, n, cfg, *phi);
  auto modes = std::make_unique<Modes<S>>(), warm = std::make_unique<Modes<S>>();
  warm->count = 0;
  std::vector<std::int16_t> mode_of(S::kPacketMax);
  ClimbTrace trace;
  climbs->run(*phi, n, cfg, *warm, mode_of.data(), *modes, trace);
  bool first_on_pixel[S::kPacketMax];
  links->run(*ev, n, modes->count, cfg, mode_of.data(), first_on_pixel);
  if (cfg.min_density != 0 && cfg.density_after_links) drop_sparse_sets(*climbs, *links, n, modes->count, cfg, mode_of.data());
  mode_of.resize(events.size());
  std::map<int, int> size;
  for (auto m : mode_of) size[m]++;
  std::vector<int> kept(events.size());
  for (size_t i = 0; i < events.size(); ++i) kept[i] = mode_of[i] >= 0 && size[mode_of[i]] >= p.min_cluster_size ? mode_of[i] : -1;
  return kept;
}

// With and without the least density (--min-density), tested on each mode before the links and
// on each linked set after them (--density-after-links): the core agrees with golden at each,
// and the density and where it is tested make a difference on these packets.
TEST(SeededClimbsFixed, TheSameClustersAsGoldenOnRandomPackets) {
  const SensorSize sensor{240, 180};
  std::map<double, int> noise_at;
  int noise_after_links = 0;
  for (const double min_density : {0.0, 6.0, -6.0}) {
    Params p;  // the defaults: seeded climbs, first-reach labels, links
    p.warm_start = false;
    p.min_density = min_density < 0 ? -min_density : min_density;
    p.density_after_links = min_density < 0;
    const Config cfg = backend::core_config<S>(p, sensor);
    int identical = 0, noise = 0;
    for (std::uint64_t seed = 1; seed <= 40; ++seed) {
      const std::vector<Event> events = random_packet(seed, 1500);
      const golden::FeatureMatrix f = golden::packet_features(events, sensor, p);
      const golden::PacketClusters want = golden::cluster_packet(events, f, p, {}, {}, sensor);
      const std::vector<int> got = core_clusters(events, p, cfg);
      identical += partition(got) == partition(want.cluster_of);
      noise += static_cast<int>(std::count(got.begin(), got.end(), -1));
    }
    EXPECT_EQ(identical, 40) << "packets whose clusters differ from golden's at --min-density " << p.min_density
                             << (p.density_after_links ? " after the links" : "");
    (p.density_after_links ? noise_after_links : noise_at[min_density]) = noise;
  }
  // These packets' modes all link to a dense one: tested after the links, the density labels
  // no more events noise than without it (SeededClimbs.ASparseArcTouchingADenseModeStaysWithIt...
  // in tests/golden/test_clustering.cpp has a set of sparse modes alone).
  EXPECT_LT(noise_after_links, noise_at[6.0]) << "sparse modes linked to dense ones stay";
  // At six times a uniform spread's density the sparser modes are noise: 4,478 events are noise
  // at 0 and 5,748 at 6 in the optimized build. The packets' pixels come from sines and cosines,
  // which the sanitizer build rounds otherwise (4,442 and 5,430), so the bound is a share.
  EXPECT_GT(noise_at[6.0], noise_at[0.0] * 11 / 10) << noise_at[0.0] << " noise events at --min-density 0";
}

TEST(ModeLinks, ThePixelMapJoinsExactlyTheModesTheAllPairsRuleJoins) {
  gen::Random rng(7);
  auto links = std::make_unique<ModeLinks<S>>();
  links->reset();
  Config cfg;
  cfg.sensor_width = 240, cfg.sensor_height = 180;
  for (int trial = 0; trial < 30; ++trial) {
    const int n = 400, modes = 60;
    cfg.link2 = static_cast<std::uint32_t>(1 + rng.below(40));
    auto ev = std::make_unique<PacketEvents<S>>();
    std::vector<std::int16_t> mode_of(S::kPacketMax);
    for (int i = 0; i < n; ++i) {
      ev->x[i] = static_cast<std::uint16_t>(rng.below(60)), ev->y[i] = static_cast<std::uint16_t>(rng.below(40));
      mode_of[i] = static_cast<std::int16_t>(rng.uniform() < 0.1 ? -1 : static_cast<int>(rng.below(modes)));
    }
    // The rule: union-find over every pair within reach, the smaller index the root.
    std::vector<int> root(modes);
    for (int c = 0; c < modes; ++c) root[c] = c;
    auto find = [&](int c) {
      while (root[c] != c) c = root[c];
      return c;
    };
    for (int a = 0; a < n; ++a) {
      for (int b = a + 1; b < n; ++b) {
        if (mode_of[a] < 0 || mode_of[b] < 0) continue;
        const int dx = ev->x[a] - ev->x[b], dy = ev->y[a] - ev->y[b];
        if (static_cast<std::uint32_t>(dx * dx + dy * dy) > cfg.link2) continue;
        const int ra = find(mode_of[a]), rb = find(mode_of[b]);
        root[std::max(ra, rb)] = std::min(ra, rb);
      }
    }
    std::vector<std::int16_t> want(mode_of.begin(), mode_of.begin() + n);
    for (auto& m : want) m = static_cast<std::int16_t>(m < 0 ? -1 : find(m));
    bool first_on_pixel[S::kPacketMax];
    links->run(*ev, n, modes, cfg, mode_of.data(), first_on_pixel);
    ASSERT_EQ(std::vector<std::int16_t>(mode_of.begin(), mode_of.begin() + n), want) << "trial " << trial << ", link2 " << cfg.link2;
  }
}

}  // namespace
}  // namespace evms::hls
