// The rules on the time surface's slopes in fixed point against golden's: the motion measure
// (hls/cluster/time_surface_slopes.h, hls/track/motion_measure.h; golden/cluster/time_surface_slopes.h,
// golden/track/motion_measure.h), its slope verdict dense over edges, directions, speeds and
// jittered times, and the fast tracks the tracker gives it; and the split by motion's slope and
// velocity words (hls/cluster/motion_split.h) against golden's doubles.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "golden/cluster/time_surface_slopes.h"
#include "hls/cluster/motion_split.h"
#include "hls/cluster/time_surface_slopes.h"
#include "hls/core/configs.h"
#include "host/backend/core_config.h"

namespace evms {
namespace {

using hls::HostShape;
constexpr SensorSize kSlopeSensor{64, 48};

// px/s of a tracker velocity word (kPosFrac fraction bits, px per tick).
double speed_of_word(std::int32_t word) {
  return word / (std::ldexp(1.0, HostShape::kPosFrac) * std::ldexp(1.0, HostShape::kTickLog2) * 1e-6);
}

// A packet of an edge swept over a 12x12 patch at (vx, vy) px/s, each pixel firing one to three
// times with jitter, among scattered events of either polarity.
std::vector<Event> jittered_edge(std::mt19937& rng, double vx, double vy) {
  std::uniform_int_distribution<int> fires(1, 3), jitter(-400, 400), coordinate(0, 47), polarity(0, 1);
  std::vector<Event> events;
  const double speed2 = vx * vx + vy * vy;
  for (int y = 18; y < 30; ++y) {
    for (int x = 24; x < 36; ++x) {
      const double s = ((x - 24) * vx + (y - 18) * vy) / speed2;
      for (int k = fires(rng); k > 0; --k) {
        events.push_back({100000 + std::lround(s * 1e6) + jitter(rng), static_cast<std::uint16_t>(x), static_cast<std::uint16_t>(y), 1});
      }
    }
  }
  for (int k = 0; k < 60; ++k) {
    events.push_back({100000 + jitter(rng) * 20, static_cast<std::uint16_t>(coordinate(rng)), static_cast<std::uint16_t>(coordinate(rng)),
                      static_cast<std::uint8_t>(polarity(rng))});
  }
  std::sort(events.begin(), events.end(), [](const Event& a, const Event& b) { return a.t < b.t; });
  // A packet starts at its first event: the times after it are what the sums hold.
  return events;
}

// The events as the core holds a packet of them.
std::unique_ptr<hls::PacketEvents<HostShape>> packet_of(const std::vector<Event>& events) {
  auto ev = std::make_unique<hls::PacketEvents<HostShape>>();
  for (size_t i = 0; i < events.size(); ++i) {
    ev->x[i] = events[i].x, ev->y[i] = events[i].y, ev->p[i] = events[i].p, ev->t[i] = static_cast<std::uint32_t>(events[i].t);
  }
  return ev;
}

// The fixed-point slopes table and golden's, both on kSlopeSensor.
struct SlopesOnSmallSensor {
  std::unique_ptr<hls::TimeSurfaceSlopes<HostShape>> fixed = std::make_unique<hls::TimeSurfaceSlopes<HostShape>>();
  hls::Config cfg;
  golden::TimeSurfaceSlopes reference{kSlopeSensor};
  SlopesOnSmallSensor() {
    fixed->reset();
    cfg.sensor_width = kSlopeSensor.width, cfg.sensor_height = kSlopeSensor.height;
  }
};

// A jittered edge packet in a random direction at 100-6,000 px/s.
struct RandomEdge {
  double speed = 0, angle = 0;
  std::vector<Event> events;
};
RandomEdge random_edge(std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0, 1);
  RandomEdge edge;
  edge.angle = 2 * M_PI * unit(rng), edge.speed = 100 * std::pow(60.0, unit(rng));
  edge.events = jittered_edge(rng, edge.speed * std::cos(edge.angle), edge.speed * std::sin(edge.angle));
  return edge;
}

// The verdicts of `slopes` and `reference`, both given the packet `events` and cleared after, at
// every event for velocities about (speed, angle) and about where their misfit crosses 1/2.
// Bound: they are equal wherever golden has a slope whose misfit is more than 1e-9 from 1/2, and
// wherever golden has none (the fixed verdict is then false).
struct VerdictCounts {
  int explained = 0, unexplained = 0, compared = 0;
};
void expect_golden_verdicts(hls::TimeSurfaceSlopes<HostShape>& slopes, golden::TimeSurfaceSlopes& reference,
                            const std::vector<Event>& events, double speed, double angle, const hls::Config& cfg,
                            VerdictCounts& counts) {
  const auto ev = packet_of(events);
  const int n = static_cast<int>(events.size());
  slopes.add(*ev, n);
  reference.add(events);
  for (const Event& e : events) {
    const std::optional<Eigen::Vector2d> g = reference.at(e);
    for (double factor : {0.5, 0.66, 0.67, 0.9, 1.0, 1.1, 1.49, 1.5, 1.51, 2.0}) {
      for (double turn : {0.0, 0.3, -0.6}) {
        const double vx = factor * speed * std::cos(angle + turn), vy = factor * speed * std::sin(angle + turn);
        const std::int32_t wx = static_cast<std::int32_t>(std::lround(vx / speed_of_word(1)));
        const std::int32_t wy = static_cast<std::int32_t>(std::lround(vy / speed_of_word(1)));
        const bool fixed = slopes.explains(e.p, e.x, e.y, wx, wy, cfg);
        if (!g) {
          EXPECT_FALSE(fixed) << "no slope under (" << e.x << ", " << e.y << ")";
          continue;
        }
        const double misfit = golden::misfit(*g, Eigen::Vector2d(speed_of_word(wx), speed_of_word(wy)));
        if (std::abs(misfit - 0.5) <= 1e-9) continue;
        ++counts.compared;
        EXPECT_EQ(fixed, misfit <= 0.5) << "misfit " << misfit << " at (" << e.x << ", " << e.y << ")";
        (fixed ? counts.explained : counts.unexplained) += 1;
      }
    }
  }
  slopes.clear(n);
  reference.clear();
}

TEST(TimeSurfaceSlopesInFixedPoint, TheVerdictIsGoldensWhereverGoldensMisfitIsNotWithinRoundingOfTheBound) {
  std::mt19937 rng(20261206);
  SlopesOnSmallSensor tables;
  VerdictCounts counts;
  for (int packet = 0; packet < 60; ++packet) {
    const RandomEdge edge = random_edge(rng);
    expect_golden_verdicts(*tables.fixed, tables.reference, edge.events, edge.speed, edge.angle, tables.cfg, counts);
  }
  // Both verdicts, many times: the test sees the bound from both sides.
  EXPECT_GE(counts.explained, 20000);
  EXPECT_GE(counts.unexplained, 20000);
  EXPECT_GE(counts.compared, 100000);
}

// A full packet of distinct pixels and polarities (a 64x32 block of both, an edge crossing it with
// jittered times) fills half the table of the packet's pixels, where its probes collide most; then
// a second packet over the same block after clear(): every verdict is still golden's.
TEST(TimeSurfaceSlopesInFixedPoint, AFullPacketOfDistinctPixelsKeepsGoldensVerdicts) {
  static_assert(HostShape::kPacketMax == 2 * 64 * 32, "the block's pixels, twice, are a full packet");
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> jitter(-300, 300);
  auto slopes = std::make_unique<hls::TimeSurfaceSlopes<HostShape>>();
  slopes->reset();
  const SensorSize sensor{1280, 720};
  hls::Config cfg;
  cfg.sensor_width = sensor.width, cfg.sensor_height = sensor.height;
  golden::TimeSurfaceSlopes reference(sensor);
  VerdictCounts counts;
  for (const double angle : {0.4, 2.2}) {
    const double speed = 900, vx = speed * std::cos(angle), vy = speed * std::sin(angle);
    std::vector<Event> events;
    for (int y = 600; y < 632; ++y) {
      for (int x = 1200; x < 1264; ++x) {
        for (std::uint8_t p : {0, 1}) {
          const double s = ((x - 1200) * vx + (y - 600) * vy) / (speed * speed);
          events.push_back({200000 + std::lround(s * 1e6) + jitter(rng), static_cast<std::uint16_t>(x), static_cast<std::uint16_t>(y), p});
        }
      }
    }
    std::sort(events.begin(), events.end(), [](const Event& a, const Event& b) { return a.t < b.t; });
    ASSERT_EQ(static_cast<int>(events.size()), HostShape::kPacketMax);
    expect_golden_verdicts(*slopes, reference, events, speed, angle, cfg, counts);
  }
  EXPECT_GE(counts.explained, 10000);
  EXPECT_GE(counts.unexplained, 10000);
}

TEST(TimeSurfaceSlopesInFixedPoint, ClearLeavesEveryPixelAsResetDid) {
  std::mt19937 rng(7);
  auto slopes = std::make_unique<hls::TimeSurfaceSlopes<HostShape>>();
  slopes->reset();
  hls::Config cfg;
  cfg.sensor_width = kSlopeSensor.width, cfg.sensor_height = kSlopeSensor.height;
  const std::vector<Event> events = jittered_edge(rng, 800, 300);
  const auto ev = packet_of(events);
  const std::int32_t wx = static_cast<std::int32_t>(std::lround(800 / speed_of_word(1)));
  const std::int32_t wy = static_cast<std::int32_t>(std::lround(300 / speed_of_word(1)));
  slopes->add(*ev, static_cast<int>(events.size()));
  EXPECT_TRUE(slopes->explains(1, 30, 24, wx, wy, cfg)) << "the edge's own velocity explains its slope";
  slopes->clear(static_cast<int>(events.size()));
  for (int y = 0; y < kSlopeSensor.height; ++y) {
    for (int x = 0; x < kSlopeSensor.width; ++x) {
      ASSERT_FALSE(slopes->explains(1, x, y, wx, wy, cfg) || slopes->explains(0, x, y, wx, wy, cfg)) << x << ", " << y;
    }
  }
}

TEST(MotionMeasureInFixedPoint, TheSpeedRegisterIsTheTrackersVelocityWord) {
  // --motion-measure V px/s is the tracker's velocity word of V, rounded, and at least 1 when on.
  Params p;
  p.motion_measure = 1000;
  const hls::Config c = backend::core_config<HostShape>(p, {640, 480});
  EXPECT_NEAR(speed_of_word(static_cast<std::int32_t>(c.motion_speed)), 1000.0, speed_of_word(1));
  p.motion_measure = 1e-3;
  EXPECT_EQ(backend::core_config<HostShape>(p, {640, 480}).motion_speed, 1u);
  p.motion_measure = 0;
  EXPECT_EQ(backend::core_config<HostShape>(p, {640, 480}).motion_speed, 0u);
}

using Split = hls::MotionSplit<HostShape>;

// The split's slope words (kSlopeFrac bits of us/px) against golden's slopes, dense over jittered
// edges at 100-6,000 px/s. Bound: within half a unit and a relative 1e-9 of golden's slope (one
// rounding of the exact quotient of the sums golden divides in doubles), wherever golden has a
// slope, the words are within kSlopeMax and golden's |g| is not within 1e-6 us/px of the least,
// 0.1 us/px; and no slope where golden has none.
TEST(MotionSplitInFixedPoint, TheSlopeWordsAreGoldensSlopesRounded) {
  std::mt19937 rng(20261207);
  SlopesOnSmallSensor tables;
  auto& slopes = tables.fixed;
  auto& reference = tables.reference;
  const hls::Config& cfg = tables.cfg;
  const double unit_us = std::ldexp(1.0, -Split::kSlopeFrac);
  int compared = 0;
  for (int packet = 0; packet < 60; ++packet) {
    const std::vector<Event> events = random_edge(rng).events;
    const auto ev = packet_of(events);
    const int n = static_cast<int>(events.size());
    slopes->add(*ev, n);
    reference.add(events);
    for (const Event& e : events) {
      const std::optional<Eigen::Vector2d> g = reference.at(e);
      Split::Wide nx = 0, ny = 0, d = 0;
      std::int64_t gx = 0, gy = 0;
      const bool has = slopes->gradient(e.p, e.x, e.y, cfg, nx, ny, d) && Split::slope_words(nx, ny, d, gx, gy);
      if (!g) {
        EXPECT_FALSE(has) << "no slope under (" << e.x << ", " << e.y << ")";
        continue;
      }
      const Eigen::Vector2d g_us = *g * 1e6;
      if (std::abs(g_us.norm() - 0.1) < 1e-6 || std::max(std::abs(g_us.x()), std::abs(g_us.y())) / unit_us >= Split::kSlopeMax) continue;
      ASSERT_TRUE(has) << "golden's slope " << g_us.transpose() << " us/px at (" << e.x << ", " << e.y << ")";
      EXPECT_LE(std::abs(gx * unit_us - g_us.x()), unit_us / 2 + 1e-9 * std::abs(g_us.x()));
      EXPECT_LE(std::abs(gy * unit_us - g_us.y()), unit_us / 2 + 1e-9 * std::abs(g_us.y()));
      ++compared;
    }
    slopes->clear(n);
    reference.clear();
  }
  EXPECT_GE(compared, 5000);
}

// The least-squares velocity of slope words against the exact solution (long double) of the same
// normal equations, dense over slope sets of 3 to a packet's events from velocities of 10 to
// 100,000 px/s with noise, and sets whose slopes all lie along one line. Bound: within half a
// unit (2^-kVelocityFrac px/us) and a relative 1e-12 (the long double's own rounding).
TEST(MotionSplitInFixedPoint, TheVelocityIsTheLeastSquaresSolutionRounded) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0, 1);
  std::normal_distribution<double> noise(0, 1);
  const long double scale = std::ldexp(1.0L, Split::kSlopeFrac + Split::kVelocityFrac);
  int rank_one = 0;
  for (int set = 0; set < 3000; ++set) {
    const double angle = 2 * M_PI * unit(rng), speed = 10 * std::pow(1e4, unit(rng));  // px/s
    const double vx = speed * std::cos(angle) * 1e-6, vy = speed * std::sin(angle) * 1e-6;  // px/us
    const int n = 3 + static_cast<int>(unit(rng) * (HostShape::kPacketMax - 3));
    const bool along_one_line = set % 10 == 0;
    // Sets along one line: multiples of one small integer direction, so that A is singular exactly.
    const std::int64_t ux = std::llround(8 * std::cos(angle)), uy = std::llround(8 * std::sin(angle));
    Split::SlopeSums sums;
    for (int k = 0; k < n; ++k) {
      // An edge's normal near the motion, and its slope's length 1 / (normal speed) with noise.
      const double normal = along_one_line ? angle : angle + 0.8 * noise(rng);
      const double normal_speed = std::max(1e-7, std::abs(vx * std::cos(normal) + vy * std::sin(normal)));
      const double length = std::ldexp(1.0, Split::kSlopeFrac) / normal_speed * (1 + 0.2 * noise(rng));
      std::int64_t gx = std::llround(length * std::cos(normal)), gy = std::llround(length * std::sin(normal));
      if (along_one_line) {
        const std::int64_t times = std::llround(length / std::hypot(static_cast<double>(ux), static_cast<double>(uy)));
        gx = times * ux, gy = times * uy;
      }
      sums.add(std::clamp(gx, -Split::kSlopeMax, Split::kSlopeMax), std::clamp(gy, -Split::kSlopeMax, Split::kSlopeMax));
    }
    std::int64_t got_x = 0, got_y = 0;
    Split::velocity(sums, got_x, got_y);
    // The exact numerators and denominators in 128 bits, divided in long double.
    auto ld = [](Split::Wide v) { return static_cast<long double>(v); };
    const Split::Wide det = sums.a11 * sums.a22 - sums.a12 * sums.a12;
    long double want_x = 0, want_y = 0;
    if (det != 0) {
      want_x = ld(sums.a22 * sums.b1 - sums.a12 * sums.b2) * scale / ld(det);
      want_y = ld(sums.a11 * sums.b2 - sums.a12 * sums.b1) * scale / ld(det);
    } else {
      ++rank_one;
      const long double trace2 = ld(sums.a11 + sums.a22) * ld(sums.a11 + sums.a22);
      want_x = ld(sums.a11 * sums.b1 + sums.a12 * sums.b2) * scale / trace2;
      want_y = ld(sums.a12 * sums.b1 + sums.a22 * sums.b2) * scale / trace2;
    }
    if (std::max(std::abs(want_x), std::abs(want_y)) >= static_cast<long double>(Split::kVelocityMax)) continue;
    EXPECT_LE(std::abs(got_x - want_x), 0.5L + 1e-12L * std::abs(want_x)) << "set " << set;
    EXPECT_LE(std::abs(got_y - want_y), 0.5L + 1e-12L * std::abs(want_y)) << "set " << set;
  }
  EXPECT_GE(rank_one, 100) << "the sets along one line must reach the pseudo-inverse";
}

}  // namespace
}  // namespace evms
