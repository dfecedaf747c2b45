// The truth with touching objects merged (host/eval/touching_objects.h), on hand-made windows.
#include <gtest/gtest.h>

#include <stdexcept>

#include "host/eval/clustering_metrics.h"
#include "host/eval/touching_objects.h"

namespace evms::eval {
namespace {

using Labels = std::vector<std::int32_t>;

Event at(std::uint16_t x, std::uint16_t y) { return Event{0, x, y, 1}; }

TEST(TouchingObjects, ObjectsTouchWithinTheReachAndNotBeyondIt) {
  // Object 4 at x 10..11, object 7 at x 14: a gap of 3 px, on a row and then on a diagonal.
  const std::vector<Event> row = {at(10, 5), at(11, 5), at(14, 5)};
  const Labels truth = {4, 4, 7};
  EXPECT_EQ(merge_touching_objects(row, truth, 2.99), truth);
  EXPECT_EQ(merge_touching_objects(row, truth, 3.0), (Labels{4, 4, 4}));
  // (11, 5) to (13, 7) is sqrt(8) = 2.83 px: a reach of 2.8 keeps them apart, 2.9 joins them.
  const std::vector<Event> diagonal = {at(10, 5), at(11, 5), at(13, 7)};
  EXPECT_EQ(merge_touching_objects(diagonal, truth, 2.8), truth);
  EXPECT_EQ(merge_touching_objects(diagonal, truth, 2.9), (Labels{4, 4, 4}));
}

TEST(TouchingObjects, TouchingIsTransitiveAndEachGroupTakesItsSmallestLabel) {
  // 9 touches 3, 3 touches 5; 8 is far from all of them; noise beside them stays noise.
  const std::vector<Event> events = {at(0, 0), at(2, 0), at(4, 0), at(50, 50), at(3, 1), at(1, 0)};
  const Labels truth = {9, 3, 5, 8, -1, -1};
  EXPECT_EQ(merge_touching_objects(events, truth, 2.0), (Labels{3, 3, 3, 8, -1, -1}));
  EXPECT_EQ(merge_touching_objects(events, truth, 0.0), truth);  // no two objects on one pixel
}

TEST(TouchingObjects, TwoObjectsOnOnePixelTouchAtAnyReach) {
  const std::vector<Event> events = {at(3, 3), at(3, 3), at(9, 9)};
  EXPECT_EQ(merge_touching_objects(events, Labels{2, 1, 2}, 0.0), (Labels{1, 1, 1}));
}

TEST(TouchingObjects, MergingTouchingObjectsCostsPrecisionOnlyWhereTheyTouch) {
  // Two 3-event objects side by side: merged, their 9 cross pairs become false positives.
  const std::vector<Event> events = {at(0, 0), at(1, 0), at(2, 0), at(3, 0), at(4, 0), at(5, 0)};
  const Labels truth = {0, 0, 0, 1, 1, 1};
  const ClusteringScores s = score(truth, merge_touching_objects(events, truth, 1.0));
  EXPECT_DOUBLE_EQ(s.recall, 1.0);
  EXPECT_DOUBLE_EQ(s.precision, 6.0 / 15.0);
  EXPECT_DOUBLE_EQ(score(truth, merge_touching_objects(events, truth, 0.5)).f, 1.0);
}

TEST(TouchingObjects, ChunkByChunkObjectsTouchOnlyWhereTheyMeetInOneChunk) {
  // 10 ms chunks: objects 0 and 1 side by side in the first, 40 px apart in the second. Object
  // 1's second-chunk events lie where object 0 was in the first, which does not join them.
  const std::vector<Event> events = {{100, 10, 10, 1}, {200, 11, 10, 0}, {10100, 10, 10, 1}, {10200, 50, 10, 0}, {10300, 11, 10, 0}};
  const Labels truth = {0, 1, 0, 1, 2};
  const Chunking ten_ms{Chunking::Kind::kTime, 10000};
  EXPECT_EQ(merge_touching_objects(events, truth, ten_ms, 1.0), (Labels{0, 0, 0, 1, 0}));
  // In chunks of 2 events the pairs are (0, 1), (0, 1) and (2): only the first touches.
  EXPECT_EQ(merge_touching_objects(events, truth, Chunking{Chunking::Kind::kEvents, 2}, 1.0), (Labels{0, 0, 0, 1, 2}));
}

TEST(TouchingObjects, RefusesMismatchedLengthsAndANegativeReach) {
  const std::vector<Event> events = {at(0, 0)};
  EXPECT_THROW(merge_touching_objects(events, Labels{0, 1}, 1.0), std::invalid_argument);
  EXPECT_THROW(merge_touching_objects(events, Labels{0}, -1.0), std::invalid_argument);
}

}  // namespace
}  // namespace evms::eval
