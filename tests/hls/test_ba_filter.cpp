// The fixed-point background-activity filter (hls/filter/ba_filter.h) against golden's
// (golden/filter/background_activity_filter.h): with 32-bit stamps in microseconds (HostShape)
// it keeps exactly the events golden keeps, warm-up, noise check and quiet window included; and its warm-up
// counts microseconds on every Shape, from the stream's first event, across the 32-bit time's
// wrap, and never again after it ended.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include "golden/filter/background_activity_filter.h"
#include "hls/core/configs.h"
#include "hls/filter/ba_filter.h"

namespace evms {
namespace {

// Blobs that wander over the sensor, and background activity: events in time order from t0.
std::vector<Event> random_stream(std::uint32_t seed, TimeUs t0, SensorSize sensor, int events) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0, 1);
  struct Blob {
    double x, y, vx, vy;
  };
  std::vector<Blob> blobs(3);
  for (Blob& b : blobs) b = {unit(rng) * sensor.width, unit(rng) * sensor.height, (unit(rng) - 0.5) * 2e-3, (unit(rng) - 0.5) * 2e-3};
  std::vector<Event> out;
  TimeUs t = t0;
  for (int i = 0; i < events; ++i) {
    t += static_cast<TimeUs>(unit(rng) * 120);  // about 17 k events a second: sparse enough to need the window
    double x, y;
    if (unit(rng) < 0.3) {
      x = unit(rng) * sensor.width, y = unit(rng) * sensor.height;
    } else {
      Blob& b = blobs[static_cast<size_t>(rng() % blobs.size())];
      const double dt = static_cast<double>(t - t0);
      x = b.x + b.vx * dt + (unit(rng) - 0.5) * 12, y = b.y + b.vy * dt + (unit(rng) - 0.5) * 12;
    }
    const auto clamp = [](double v, int n) { return static_cast<std::uint16_t>(std::min(std::max(v, 0.0), n - 1.0)); };
    out.push_back({t, clamp(x, sensor.width), clamp(y, sensor.height), static_cast<std::uint8_t>(rng() & 1)});
  }
  return out;
}

TEST(BaFilterAgreesWithGolden, EveryDecisionOnRandomStreams) {
  constexpr SensorSize kSensor{240, 180};
  auto fixed = std::make_unique<hls::BackgroundActivityFilter<hls::HostShape>>();
  constexpr TimeUs kQuietWindowUs = 40000;
  int compared = 0, kept_by_warm_up_only = 0, kept_by_quiet_window_only = 0;
  std::uint32_t seed = 1;
  for (const TimeUs warm_up : {0, 1000, 10000, 60000}) {
    for (const std::int64_t noise_count : {0, 3, 40}) {
      for (const std::int64_t quiet_count : {0, 60, 1000}) {  // 1000: every interval of the stream is quiet
        for (const TimeUs t0 : {TimeUs{1000}, TimeUs{5000000}, TimeUs{123456789}}) {
          SCOPED_TRACE(testing::Message() << "seed " << seed << ", warm-up " << warm_up << " us, noise count " << noise_count
                                          << ", quiet count " << quiet_count << ", start " << t0 << " us");
          golden::BackgroundActivityFilter reference(kSensor, 10000, 1, warm_up, noise_count, quiet_count, kQuietWindowUs);
          golden::BackgroundActivityFilter no_warm_up(kSensor, 10000, 1, 0, noise_count, quiet_count, kQuietWindowUs);
          golden::BackgroundActivityFilter never_quiet(kSensor, 10000, 1, warm_up, noise_count);
          hls::Config cfg;
          cfg.sensor_width = kSensor.width, cfg.sensor_height = kSensor.height;
          cfg.filter_enabled = true, cfg.filter_window = 10000, cfg.filter_support = 1;
          cfg.filter_noise_count = static_cast<std::uint32_t>(noise_count), cfg.filter_warm_up = static_cast<std::uint32_t>(warm_up);
          cfg.filter_quiet_count = static_cast<std::uint32_t>(quiet_count), cfg.filter_quiet_window = kQuietWindowUs;
          fixed->reset();
          for (const Event& e : random_stream(seed, t0, kSensor, 4000)) {
            const bool expected = reference.accept(e);
            kept_by_warm_up_only += expected && !no_warm_up.accept(e);
            kept_by_quiet_window_only += expected && !never_quiet.accept(e);
            ASSERT_EQ(fixed->accept({static_cast<std::uint32_t>(e.t), e.x, e.y, e.p, false}, cfg), expected) << "event at " << e.t << " us";
            ++compared;
          }
          ++seed;
        }
      }
    }
  }
  EXPECT_EQ(compared, 4 * 3 * 3 * 3 * 4000);
  EXPECT_GT(kept_by_warm_up_only, 100) << "the warm-up kept nothing the window would not have";
  EXPECT_GT(kept_by_quiet_window_only, 1000) << "the quiet window kept nothing the window would not have";
}

// Shape S's whole sensor, a window of 2 stored time units (at most 256 us) and the warm-up.
template <class S>
hls::Config warm_up_config(std::uint32_t warm_up) {
  hls::Config cfg;
  cfg.sensor_width = S::kMaxWidth, cfg.sensor_height = S::kMaxHeight;
  cfg.filter_enabled = true, cfg.filter_window = 2, cfg.filter_support = 1, cfg.filter_warm_up = warm_up;
  return cfg;
}

// Isolated events, 700 us apart, that no neighbour ever supports: the warm-up alone keeps them.
template <class S>
std::vector<bool> kept_alone(std::uint32_t t0, std::uint32_t warm_up, int events) {
  auto filter = std::make_unique<hls::BackgroundActivityFilter<S>>();
  filter->reset();
  const hls::Config cfg = warm_up_config<S>(warm_up);
  std::vector<bool> kept;
  for (int k = 0; k < events; ++k) {
    const auto x = static_cast<std::uint16_t>((7 * k) % (S::kMaxWidth / 3) * 3), y = static_cast<std::uint16_t>((7 * k) / (S::kMaxWidth / 3) * 3);
    kept.push_back(filter->accept({t0 + static_cast<std::uint32_t>(700 * k), x, y, 1, false}, cfg));
  }
  return kept;
}

template <class S>
void expect_warm_up_in_microseconds() {
  // 10 ms from the first event: events 0..14 (0 to 9,800 us) are kept, 15 on (10,500 us) are not.
  for (const std::uint32_t t0 : {1000u, 4294967295u - 5000u}) {  // the second start wraps the 32-bit time at its 8th event
    const std::vector<bool> kept = kept_alone<S>(t0, 10000, 40);
    for (int k = 0; k < 40; ++k) EXPECT_EQ(kept[static_cast<size_t>(k)], k < 15) << "event " << k << ", start " << t0;
  }
  EXPECT_EQ(kept_alone<S>(1000, 0, 5), std::vector<bool>(5, false)) << "warm-up 0 is off";
  EXPECT_EQ(kept_alone<S>(1000, 1, 2), (std::vector<bool>{true, false})) << "1 us keeps the first event only";
  EXPECT_EQ(kept_alone<S>(1000, 2100, 5), (std::vector<bool>{true, true, true, false, false})) << "an event 2,100 us on is past 2,100 us";
}

TEST(BaFilterWarmUp, CountsMicrosecondsFromTheFirstEventOnEveryShape) {
  expect_warm_up_in_microseconds<hls::HostShape>();
  expect_warm_up_in_microseconds<hls::ArtyShape>();
  expect_warm_up_in_microseconds<hls::Ice40Shape>();
}

// Once ended, the warm-up stays ended: an event whose 32-bit time wraps back to within it is
// judged by the window.
TEST(BaFilterWarmUp, EndsForGoodAcrossTheTimesWrap) {
  auto filter = std::make_unique<hls::BackgroundActivityFilter<hls::Ice40Shape>>();
  filter->reset();
  const hls::Config cfg = warm_up_config<hls::Ice40Shape>(10000);
  EXPECT_TRUE(filter->accept({1000, 10, 10, 1, false}, cfg));
  EXPECT_FALSE(filter->accept({20000, 40, 40, 1, false}, cfg));
  // Nearly 2^32 us (71.6 minutes) on, in steps that the stamps' scrubbing follows.
  std::uint32_t t = 20000;
  for (int k = 0; k < (1 << 13) - 1; ++k) {
    t += 1u << 19;
    filter->accept({t, static_cast<std::uint16_t>(k % 128), 100, 1, false}, cfg);
  }
  // 2^32 + 6,000 us after the start: its 32-bit time is 5,000 us after the first event's.
  EXPECT_FALSE(filter->accept({1000u + 5000u, 70, 10, 1, false}, cfg)) << "the warm-up came back after the wrap";
}

// A quiet sensor on the board builds' 16-bit stamps (128 us units, an 8.4 s wrap): noise at 300
// events a second, too few for two scrubs an event to sweep the memory within half the wrap,
// with silences of 3 s and 9 s (longer than the wrap). Every time is a whole number of stored
// units, so the stored ages are exact and the filter must keep exactly the events golden keeps,
// the quiet window's 100 ms included: a pixel's time never ages into the window a wrap later.
template <class S>
void expect_golden_decisions_on_a_quiet_sensor() {
  const SensorSize sensor{S::kMaxWidth, S::kMaxHeight};
  constexpr TimeUs kUnit = TimeUs{1} << S::kTimestampShift;
  constexpr double kRate = 300;
  ASSERT_LT(2 * kRate * static_cast<double>(TimeUs{1} << (S::kTimestampBits - 1 + S::kTimestampShift)) * 1e-6, sensor.width * sensor.height)
      << "the events alone sweep the memory: the test would not need the time scrubber";
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0, 1);
  golden::BackgroundActivityFilter reference(sensor, 30000, 1, 0, 0, 1000, 100000);
  auto fixed = std::make_unique<hls::BackgroundActivityFilter<S>>();
  fixed->reset();
  hls::Config cfg;
  cfg.sensor_width = static_cast<std::uint16_t>(sensor.width), cfg.sensor_height = static_cast<std::uint16_t>(sensor.height);
  cfg.filter_enabled = true, cfg.filter_window = 30000 / kUnit, cfg.filter_support = 1;
  cfg.filter_quiet_count = 1000, cfg.filter_quiet_window = 100000 / kUnit;
  TimeUs t = 5 * kUnit;
  int events = 0, kept = 0;
  for (int k = 0; t < 60'000'000; ++k) {
    t += static_cast<TimeUs>(-std::log(1 - unit(rng)) / kRate * 1e6) / kUnit * kUnit + kUnit;
    if (k == 3000) t += 3'000'000 / kUnit * kUnit;
    if (k == 9000) t += 9'000'000 / kUnit * kUnit;
    const Event e{t, static_cast<std::uint16_t>(rng() % static_cast<std::uint32_t>(sensor.width)),
                  static_cast<std::uint16_t>(rng() % static_cast<std::uint32_t>(sensor.height)), 1};
    const bool expected = reference.accept(e);
    ASSERT_EQ(fixed->accept({static_cast<std::uint32_t>(e.t), e.x, e.y, e.p, false}, cfg), expected) << "event " << events << " at " << e.t << " us";
    ++events, kept += expected;
  }
  EXPECT_GT(events, 12000);
  EXPECT_GT(kept, 10) << "too few events kept to compare the windows";
}

TEST(BaFilterAgreesWithGolden, AQuietSensorsStaleTimesNeverSupportOnTheBoardBuilds) {
  expect_golden_decisions_on_a_quiet_sensor<hls::Ice40Shape>();
  expect_golden_decisions_on_a_quiet_sensor<hls::ArtyShape>();
}

}  // namespace
}  // namespace evms
