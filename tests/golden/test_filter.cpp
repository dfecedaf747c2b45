#include <gtest/gtest.h>

#include "golden/filter/background_activity_filter.h"
#include "types/params.h"
#include "tests/support/scenes.h"

namespace evms::golden {
namespace {

using test::kSensor;

TEST(BackgroundActivityFilter, FirstEventOfASceneIsNoise) {
  BackgroundActivityFilter f(kSensor, 10000);
  EXPECT_FALSE(f.accept({100, 50, 50, 1}));
}

TEST(BackgroundActivityFilter, ANeighbourWithinTheWindowSupports) {
  BackgroundActivityFilter f(kSensor, 10000);
  f.accept({0, 50, 50, 1});
  EXPECT_TRUE(f.accept({10000, 51, 51, 0}));   // diagonal neighbour, exactly at the window
  EXPECT_FALSE(f.accept({30001, 53, 50, 1}));  // two pixels away: not a neighbour
}

TEST(BackgroundActivityFilter, SupportExpiresAfterTheWindow) {
  BackgroundActivityFilter f(kSensor, 10000);
  f.accept({0, 50, 50, 1});
  EXPECT_FALSE(f.accept({10001, 50, 51, 1}));
}

TEST(BackgroundActivityFilter, APixelDoesNotSupportItself) {
  BackgroundActivityFilter f(kSensor, 10000);
  f.accept({0, 50, 50, 1});
  EXPECT_FALSE(f.accept({5, 50, 50, 1}));
  EXPECT_FALSE(f.accept({10, 50, 50, 0}));
}

TEST(BackgroundActivityFilter, RejectedEventsStillSupportLaterNeighbours) {
  BackgroundActivityFilter f(kSensor, 10000);
  EXPECT_FALSE(f.accept({0, 10, 10, 1}));
  EXPECT_TRUE(f.accept({100, 11, 10, 1}));
}

TEST(BackgroundActivityFilter, CornersAndBordersOfA240x180Sensor) {
  // The authors' code swapped the clamping of x and y and read past the map at 240x180.
  BackgroundActivityFilter f(kSensor, 10000);
  f.accept({0, 239, 179, 1});
  EXPECT_TRUE(f.accept({1, 238, 178, 1}));
  EXPECT_TRUE(f.accept({2, 239, 178, 0}));
  f.accept({3, 0, 179, 1});
  EXPECT_TRUE(f.accept({4, 1, 179, 0}));
  f.accept({5, 239, 0, 1});
  EXPECT_TRUE(f.accept({6, 238, 1, 1}));
  EXPECT_FALSE(f.accept({7, 0, 0, 1}));  // nothing near the top-left corner fired
}

TEST(BackgroundActivityFilter, WarmUpKeepsTheFirstWindowFromTheStreamsFirstEvent) {
  BackgroundActivityFilter f(kSensor, 10000, 1, /*warm_up_us=*/10000);
  EXPECT_TRUE(f.accept({500000, 100, 50, 1}));   // the stream starts at 0.5 s, not at 0
  EXPECT_TRUE(f.accept({509999, 10, 10, 1}));    // alone, but within the first window
  EXPECT_FALSE(f.accept({510000, 200, 100, 1}));  // alone, and the window has passed
  EXPECT_TRUE(f.accept({510001, 201, 100, 0}));   // supported, as without the warm-up
}

// With a noise count of 3: an interval of 2^15 us that held 3 events no neighbour supported
// makes the next interval ask two neighbours; an interval after a quiet one, or after an empty
// one, asks one again.
TEST(BackgroundActivityFilter, ANoisyIntervalMakesTheNextAskOneMoreNeighbour) {
  constexpr TimeUs kInterval = TimeUs{1} << kFilterNoiseIntervalLog2;
  BackgroundActivityFilter f(kSensor, 1000000, 1, 0, /*noise_count=*/3);
  for (int k = 0; k < 3; ++k) EXPECT_FALSE(f.accept({100 + k, static_cast<std::uint16_t>(20 + 40 * k), 20, 1}));  // unsupported
  f.accept({kInterval + 0, 100, 100, 1});                    // unsupported, the next interval's first
  EXPECT_FALSE(f.accept({kInterval + 1, 101, 100, 1}));     // one neighbour is not enough now
  EXPECT_TRUE(f.accept({kInterval + 2, 100, 101, 1}));      // two are: (100, 100) and (101, 100)
  // The noisy interval itself held only one unsupported event: the next one asks one neighbour.
  EXPECT_TRUE(f.accept({2 * kInterval, 102, 100, 1}));
  // Without the count, one neighbour is enough in the second interval too.
  BackgroundActivityFilter plain(kSensor, 1000000);
  for (int k = 0; k < 3; ++k) plain.accept({100 + k, static_cast<std::uint16_t>(20 + 40 * k), 20, 1});
  plain.accept({kInterval + 0, 100, 100, 1});
  EXPECT_TRUE(plain.accept({kInterval + 1, 101, 100, 1}));
}

// The noise check's rate holds up to filter_noise_pixels and falls with the square root of a
// larger sensor's pixels; a smaller sensor keeps it.
TEST(BackgroundActivityFilter, TheNoiseChecksRateFallsWithTheSquareRootOfALargerSensorsPixels) {
  const Params p;
  ASSERT_EQ(p.filter_noise_pixels, 240 * 180);
  const auto per_interval = [](double hz, double pixels) {
    return static_cast<std::int64_t>(hz * pixels * static_cast<double>(TimeUs{1} << kFilterNoiseIntervalLog2) * 1e-6);
  };
  EXPECT_EQ(filter_noise_count(p, {240, 180}), per_interval(p.filter_noise_hz, 240 * 180));
  EXPECT_EQ(filter_noise_count(p, {128, 128}), per_interval(p.filter_noise_hz, 128 * 128));
  EXPECT_EQ(filter_noise_count(p, {480, 360}), per_interval(p.filter_noise_hz / 2, 480 * 360));
  EXPECT_EQ(filter_noise_count(p, {960, 720}), per_interval(p.filter_noise_hz / 4, 960 * 720));
  Params unscaled = p;
  unscaled.filter_noise_pixels = 0;
  EXPECT_EQ(filter_noise_count(unscaled, {960, 720}), per_interval(p.filter_noise_hz, 960 * 720));
}

TEST(BackgroundActivityFilter, AnIntervalAfterAnEmptyOneIsNotNoisy) {
  constexpr TimeUs kInterval = TimeUs{1} << kFilterNoiseIntervalLog2;
  BackgroundActivityFilter f(kSensor, 10 * kInterval, 1, 0, /*noise_count=*/2);
  f.accept({0, 20, 20, 1});
  f.accept({1, 60, 20, 1});                                  // two unsupported in interval 0
  f.accept({2 * kInterval, 100, 100, 1});                    // interval 1 was empty
  EXPECT_TRUE(f.accept({2 * kInterval + 1, 101, 100, 1}));  // one neighbour is enough
}

// With a quiet count of 2 and a quiet window of 10 ms beside the 1 ms window: an interval that
// held fewer than 2 events no neighbour supported within 1 ms makes the next one judge by 10 ms;
// an interval that held 2 or more does not. The count is against the 1 ms window, so the long
// window cannot hide the noise that would end it.
TEST(BackgroundActivityFilter, AQuietIntervalMakesTheNextJudgeByTheQuietWindow) {
  constexpr TimeUs kInterval = TimeUs{1} << kFilterNoiseIntervalLog2;
  BackgroundActivityFilter f(kSensor, 1000, 1, 0, /*noise_count=*/0, /*quiet_count=*/2, /*quiet_window_us=*/10000);
  EXPECT_FALSE(f.accept({100, 20, 20, 1}));                       // interval 0: one unsupported event
  EXPECT_FALSE(f.accept({kInterval + 0, 100, 100, 1}));          // interval 0 is not judged quiet until it ends
  EXPECT_TRUE(f.accept({kInterval + 5000, 101, 100, 1}));        // 5 ms after its neighbour: within the quiet window
  // Interval 1 now holds 2 events unsupported within 1 ms (the second kept by the 10 ms), and a third:
  EXPECT_FALSE(f.accept({2 * kInterval - 5000, 60, 60, 1}));
  EXPECT_FALSE(f.accept({2 * kInterval + 0, 61, 60, 1}));        // so interval 2 is not quiet: 5 ms is too old again
  // Without the quiet count, 5 ms is too old for the 1 ms window.
  BackgroundActivityFilter plain(kSensor, 1000);
  plain.accept({100, 20, 20, 1});
  plain.accept({kInterval + 0, 100, 100, 1});
  EXPECT_FALSE(plain.accept({kInterval + 5000, 101, 100, 1}));
}

TEST(BackgroundActivityFilter, ZeroWindowKeepsEverything) {
  BackgroundActivityFilter f(kSensor, 0);
  EXPECT_TRUE(f.accept({0, 5, 5, 1}));
}

}  // namespace
}  // namespace evms::golden
