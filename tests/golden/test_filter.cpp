#include <gtest/gtest.h>

#include "golden/filter/background_activity_filter.h"

namespace evms::golden {
namespace {

constexpr SensorSize kSensor{240, 180};

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

TEST(BackgroundActivityFilter, ZeroWindowKeepsEverything) {
  BackgroundActivityFilter f(kSensor, 0);
  EXPECT_TRUE(f.accept({0, 5, 5, 1}));
}

}  // namespace
}  // namespace evms::golden
