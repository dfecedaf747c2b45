// K-means, chunking, tracking metrics, and the eval/sweep/metrics commands end to end.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "host/eval/chunks.h"
#include "host/eval/evaluation.h"
#include "host/eval/family_eval.h"
#include "host/eval/kmeans.h"
#include "host/eval/tracking_metrics.h"
#include "host/gen/family.h"
#include "tests/support/command.h"
#include "tests/support/encoders.h"
#include "tests/support/scenes.h"

namespace evms::eval {
namespace {

TEST(Chunks, ByCountAndByTime) {
  std::vector<Event> e;
  for (TimeUs t : {0, 10, 20, 30, 35, 100, 101}) e.push_back({t, 0, 0, 0});
  const auto by_count = chunk_ranges(e, {Chunking::Kind::kEvents, 3});
  ASSERT_EQ(by_count.size(), 3u);
  EXPECT_EQ(by_count[2], (std::pair<size_t, size_t>{6, 7}));
  const auto by_time = chunk_ranges(e, {Chunking::Kind::kTime, 25});
  ASSERT_EQ(by_time.size(), 3u);  // [0,25) [25,50) [100,125): the empty windows are skipped
  EXPECT_EQ(by_time[0], (std::pair<size_t, size_t>{0, 3}));
  EXPECT_EQ(by_time[1], (std::pair<size_t, size_t>{3, 5}));
  EXPECT_EQ(by_time[2], (std::pair<size_t, size_t>{5, 7}));
}

TEST(KMeans, SeparatesWellSeparatedGroupsDeterministically) {
  Eigen::Matrix<double, 4, Eigen::Dynamic> x(4, 9);
  for (int i = 0; i < 9; ++i) x.col(i) << (i / 3) * 1.0 + 0.01 * (i % 3), 0.5, 0, 1;
  const auto a = kmeans(x, 3, 7), b = kmeans(x, 3, 7);
  EXPECT_EQ(a, b);
  for (int g = 0; g < 3; ++g) {
    EXPECT_EQ(a[3 * g], a[3 * g + 1]);
    EXPECT_EQ(a[3 * g], a[3 * g + 2]);
  }
  EXPECT_NE(a[0], a[3]);
  EXPECT_NE(a[3], a[6]);
  EXPECT_NE(a[0], a[6]);
}

TEST(KMeans, BaselineUsesTheTrueObjectCountPerChunk) {
  std::vector<int> which;
  const auto events = test::blob_events({{40, 40}, {200, 140}}, 40000, 0, 50000, {240, 180}, 3, &which);
  std::vector<std::int32_t> truth(which.begin(), which.end());
  const auto labels = kmeans_labels(events, truth, {240, 180}, Params{}, {Chunking::Kind::kEvents, 256});
  // Two far blobs and k = 2: within every chunk, each blob's kept events share one label,
  // and the two labels differ. Filtered events are noise.
  for (const auto& [begin, end] : chunk_ranges(events, {Chunking::Kind::kEvents, 256})) {
    std::set<std::int32_t> of[2];
    for (size_t i = begin; i < end; ++i) {
      if (labels[i] >= 0) of[which[i]].insert(labels[i]);
    }
    ASSERT_EQ(of[0].size(), 1u);
    ASSERT_EQ(of[1].size(), 1u);
    EXPECT_NE(*of[0].begin(), *of[1].begin());
  }
}

TEST(TrackingMetrics, ErrorsWithinTauAndAssociation) {
  std::vector<gen::TruthSample> centres;
  for (TimeUs t = 0; t <= 100000; t += 1000) {
    centres.push_back({t, 0, 50.0 + t * 1e-4, 50, 10});  // object 0 moves at 100 px/s in x
    centres.push_back({t, 1, 150, 100, 10});
  }
  std::vector<TrackUpdate> updates;
  for (TimeUs t = 5000; t <= 95000; t += 10000) {
    updates.push_back({t, 7, 50.0 + t * 1e-4 + 3.0, 50, 100, 0, 50.0 + t * 1e-4 + 4.0, 50});  // 3 px off (raw 4)
    updates.push_back({t + 500, 9, 151, 100, 0, 30, 150, 100});                             // 1 px off (raw 0), 30 px/s off
    updates.push_back({t, 11, 10, 170, 0, 0, 10, 170});                                     // near nothing
  }
  const TrackingReport r = tracking_report(updates, centres, 2, 2.5);
  ASSERT_EQ(r.objects.size(), 2u);
  EXPECT_EQ(r.objects[0].tracks, (std::vector<std::int32_t>{7}));
  EXPECT_EQ(r.objects[1].tracks, (std::vector<std::int32_t>{9}));
  EXPECT_NEAR(r.objects[0].kalman.mean, 3.0, 1e-9);
  EXPECT_NEAR(r.objects[0].kalman.std, 0.0, 1e-6);
  EXPECT_DOUBLE_EQ(r.objects[0].kalman.within, 0.0);
  EXPECT_NEAR(r.objects[0].raw.mean, 4.0, 1e-9);
  EXPECT_NEAR(r.objects[0].velocity_error, 0.0, 1e-6);
  EXPECT_NEAR(r.objects[1].kalman.mean, 1.0, 1e-9);
  EXPECT_DOUBLE_EQ(r.objects[1].kalman.within, 1.0);
  EXPECT_DOUBLE_EQ(r.objects[1].raw.mean, 0.0);
  EXPECT_NEAR(r.objects[1].velocity_error, 30.0, 1e-6);
  EXPECT_EQ(r.spurious_updates, 10);
  EXPECT_EQ(r.all_kalman.samples, 20);
  EXPECT_DOUBLE_EQ(r.all_kalman.within, 0.5);
  EXPECT_EQ(r.all_velocity.samples, 20);
  EXPECT_NEAR(r.all_velocity.mean, 15.0, 1e-6);
}

// With the run's labels, a track belongs to the object whose events it labelled. Object 0 is a
// large shape whose outline reaches past the sensor's edge, so it has no true centre; object 1
// is a small shape 10 px from where object 0's track stands. By nearest centre, object 0's track
// would be scored against object 1's centre; by its events it is object 0's, which has no centre
// to score it against, while track 2 (object 1's) is, and track 3, mostly noise, is spurious.
TEST(TrackingMetrics, ATrackBelongsToTheObjectWhoseEventsItLabelled) {
  std::vector<gen::TruthSample> centres;
  for (TimeUs t = 0; t <= 50000; t += 1000) centres.push_back({t, 1, 40, 40, 3});
  std::vector<Event> events;
  std::vector<std::int32_t> truth, predicted;
  for (TimeUs t = 0; t <= 50000; t += 1000) {
    for (int k = 0; k < 6; ++k) {
      events.push_back({t + k, static_cast<std::uint16_t>(2 + 10 * k), 50, 1}), truth.push_back(0), predicted.push_back(1);
    }
    events.push_back({t + 10, 40, 40, 1}), truth.push_back(1), predicted.push_back(2);
    events.push_back({t + 11, 41, 41, 0}), truth.push_back(1), predicted.push_back(2);
    events.push_back({t + 12, 90, 10, 0}), truth.push_back(-1), predicted.push_back(3);
    events.push_back({t + 13, 91, 11, 0}), truth.push_back(-1), predicted.push_back(3);
    events.push_back({t + 14, 27, 50, 1}), truth.push_back(0), predicted.push_back(3);  // at object 0's mean
  }
  std::vector<TrackUpdate> updates;
  // 0.1 ms past the millisecond, so that no window's edge splits a millisecond's events.
  for (TimeUs t = 10100; t <= 45000; t += 10000) {
    updates.push_back({t, 1, 30, 48, 0, 0, 30, 48});   // on object 0's events, 8.2 px from object 1's centre
    updates.push_back({t, 2, 40.5, 40, 0, 0, 40.5, 40});
    updates.push_back({t, 3, 91, 10, 0, 0, 91, 10});
  }
  const TrackingReport by_centre = tracking_report(updates, centres, 2, 2.5);
  EXPECT_EQ(by_centre.objects[1].tracks, (std::vector<std::int32_t>{1, 2}));
  EXPECT_EQ(by_centre.all_kalman.samples, 8);

  const TrackingReport by_labels = tracking_report(updates, centres, 2, 2.5, 15.0, 20000, {events, truth, predicted});
  EXPECT_EQ(by_labels.objects[0].tracks, (std::vector<std::int32_t>{1}));
  EXPECT_EQ(by_labels.objects[1].tracks, (std::vector<std::int32_t>{2}));
  EXPECT_EQ(by_labels.spurious_updates, 4);  // track 3: two of its three events a millisecond are noise
  EXPECT_EQ(by_labels.all_kalman.samples, 4);
  EXPECT_NEAR(by_labels.all_kalman.mean, 0.5, 1e-9);
  EXPECT_EQ(by_labels.objects[0].kalman.samples, 0);
  // Object 0's events' centre (27, 50) is still the paper's ground truth for its track.
  EXPECT_EQ(by_labels.objects[0].kalman_events.samples, 4);
  EXPECT_NEAR(by_labels.objects[0].kalman_events.mean, std::hypot(3.0, 2.0), 1e-9);
}

// A track that follows object 0 and then object 1, 40 px away (an identity switch, IDF1's to
// count), is scored at each update against the object its events then came from: its estimates
// sit 0.5 px from each in turn, where the track's owner alone would put half of them 40 px off.
TEST(TrackingMetrics, EachEstimateIsScoredAgainstTheObjectItWasMeasuredFrom) {
  std::vector<gen::TruthSample> centres;
  std::vector<Event> events;
  std::vector<std::int32_t> truth, predicted;
  for (TimeUs t = 0; t <= 80000; t += 1000) {
    centres.push_back({t, 0, 20, 50, 3});
    centres.push_back({t, 1, 60, 50, 3});
    const int followed = t < 50000 ? 0 : 1;  // object 0 for 50 ms, then object 1 for 31 ms
    for (int k = 0; k < 4; ++k) {
      events.push_back({t + k, static_cast<std::uint16_t>(followed ? 60 : 20), static_cast<std::uint16_t>(49 + k % 2), 1});
      truth.push_back(followed), predicted.push_back(7);
    }
  }
  std::vector<TrackUpdate> updates;
  for (TimeUs t = 10100; t <= 75000; t += 10000) {
    const double x = t < 50000 ? 20.5 : 60.5;
    updates.push_back({t, 7, x, 50, 0, 0, x, 50});
  }
  const TrackingReport r = tracking_report(updates, centres, 2, 2.5, 15.0, 20000, {events, truth, predicted});
  EXPECT_EQ(r.objects[0].tracks, (std::vector<std::int32_t>{7}));  // the track's owner: most of its events
  EXPECT_EQ(r.objects[0].kalman.samples, 4);                         // 10.1 .. 40.1 ms
  EXPECT_EQ(r.objects[1].kalman.samples, 3);                         // 50.1 .. 70.1 ms
  EXPECT_NEAR(r.all_kalman.mean, 0.5, 1e-9);
  EXPECT_DOUBLE_EQ(r.all_kalman.within, 1.0);
}

// The paper's ground truth: the centre of mass of the object's labelled events over the last
// 10 ms. An object whose right edge fires three events for each of its left edge's has that
// centre 5 px right of its outline's centre (left edge at x = 40, right at 60: (40 + 3 * 60) / 4
// = 55); a track on the centre of mass is 5 px off the one and 0 px off the other.
TEST(TrackingMetrics, LabelledEventsCentreIsThePapersGroundTruth) {
  std::vector<gen::TruthSample> centres;
  std::vector<Event> events;
  std::vector<std::int32_t> truth;
  for (TimeUs t = 0; t <= 50000; t += 1000) {
    centres.push_back({t, 0, 50, 50, 10});
    for (int k = 0; k < 4; ++k) {
      events.push_back({t + 10 * k, static_cast<std::uint16_t>(k == 0 ? 40 : 60), static_cast<std::uint16_t>(46 + 2 * k), 1});
      truth.push_back(0);
    }
    events.push_back({t + 50, 200, 10, 0});  // noise: no object's
    truth.push_back(-1);
  }
  std::vector<TrackUpdate> updates;
  // 0.1 ms past the millisecond, so that no window's edge splits a millisecond's four events.
  for (TimeUs t = 20100; t <= 50000; t += 5000) updates.push_back({t, 3, 55, 49, 0, 0, 55, 49});
  // At 56 ms the window holds none of the object's events (fewer than kEventCentreMinEvents),
  // and the true centre is not known either.
  updates.push_back({56100, 3, 55, 49, 0, 0, 55, 49});
  const TrackingReport r = tracking_report(updates, centres, 1, 2.5, 15.0, 20000, {events, truth});
  ASSERT_EQ(r.objects.size(), 1u);
  EXPECT_EQ(r.all_kalman.samples, 6);
  EXPECT_NEAR(r.all_kalman.mean, std::hypot(5.0, 1.0), 1e-9);
  EXPECT_DOUBLE_EQ(r.all_kalman.within, 0.0);
  // y: the events' rows 46, 48, 50, 52 average to 49.
  EXPECT_EQ(r.all_kalman_events.samples, 6);
  EXPECT_NEAR(r.all_kalman_events.mean, 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(r.all_kalman_events.within, 1.0);
  EXPECT_EQ(r.objects[0].kalman_events.samples, 6);
  // The labelled events' centre (55, 49) is itself 5.1 px from the outline's centre at each of
  // the six estimates: all of the track's error against the outline.
  EXPECT_EQ(r.all_events_centre.samples, 6);
  EXPECT_NEAR(r.all_events_centre.mean, std::hypot(5.0, 1.0), 1e-9);
  EXPECT_DOUBLE_EQ(r.all_events_centre.within, 0.0);
  // Without the events the paper's statistics stay empty.
  EXPECT_EQ(tracking_report(updates, centres, 1).all_kalman_events.samples, 0);
  EXPECT_EQ(tracking_report(updates, centres, 1).all_events_centre.samples, 0);
}

// An estimate is timed at the mean timestamp of its events, so the labelled events' centre it is
// measured against is taken over a window centred on that time: for an object moving at 1 px/ms
// an estimate on its path is within a pixel of it, where the 10 ms before the estimate would put
// the centre 4.5 px behind.
TEST(TrackingMetrics, TheLabelledEventsCentreIsTakenAroundTheEstimatesTime) {
  std::vector<gen::TruthSample> centres;
  std::vector<Event> events;
  std::vector<std::int32_t> truth;
  for (TimeUs t = 0; t <= 60000; t += 1000) {
    const double x = 20.0 + static_cast<double>(t) / 1000.0;
    centres.push_back({t, 0, x, 50, 10});
    for (int k = 0; k < 4; ++k) {
      events.push_back({t, static_cast<std::uint16_t>(x), static_cast<std::uint16_t>(48 + k), 1});
      truth.push_back(0);
    }
  }
  std::vector<TrackUpdate> updates;
  for (TimeUs t = 20000; t <= 40000; t += 5000) updates.push_back({t, 3, 20.0 + static_cast<double>(t) / 1000.0, 49.5, 1000, 0});
  const TrackingReport r = tracking_report(updates, centres, 1, 2.5, 15.0, 20000, {events, truth});
  EXPECT_EQ(r.all_kalman_events.samples, 5);
  EXPECT_LT(r.all_kalman_events.mean, 1.0);
  EXPECT_NEAR(r.all_kalman.mean, 0.5, 1e-9);  // y: 49.5 against the true 50
}

// The true centre of one still object at (50, 50), sampled every millisecond up to `until_us`.
std::vector<gen::TruthSample> still_object_centres(TimeUs until_us) {
  std::vector<gen::TruthSample> centres;
  for (TimeUs t = 0; t <= until_us; t += 1000) centres.push_back({t, 0, 50, 50, 10});
  return centres;
}

// CLEAR MOT matches an object to one track at a time: a second track 10 px off the same object
// is a false positive in every frame, where the per-update error counts it as a second estimate.
TEST(TrackingMetrics, ClearMotCountsASecondTrackOnAnObjectAsAFalsePositive) {
  const std::vector<gen::TruthSample> centres = still_object_centres(100000);
  std::vector<TrackUpdate> updates;
  for (TimeUs t = 5000; t <= 100000; t += 5000) {
    updates.push_back({t, 1, 51, 50, 0, 0, 51, 50});
    updates.push_back({t, 2, 60, 50, 0, 0, 60, 50});
  }
  const TrackingReport r = tracking_report(updates, centres, 1, 2.5);
  EXPECT_NEAR(r.all_kalman.mean, 5.5, 1e-9);  // both tracks' updates, 1 and 10 px off
  const ClearMot& m = r.mot;
  EXPECT_EQ(m.frames, 11);  // 0, 10, ..., 100 ms
  EXPECT_EQ(m.objects, 11);
  EXPECT_EQ(m.misses, 1);  // at 0 ms no track has been updated yet
  EXPECT_EQ(m.matches, 10);
  EXPECT_EQ(m.false_positives, 10);
  EXPECT_EQ(m.mismatches, 0);
  EXPECT_NEAR(m.mota(), 1.0 - 11.0 / 11.0, 1e-12);
  EXPECT_NEAR(m.to_centres.mean, 1.0, 1e-9);
  EXPECT_DOUBLE_EQ(m.to_centres.within, 1.0);
}

// An object keeps its track while that track stays present and within the radius, even when a
// nearer one appears; when its track is gone, taking another is one mismatch.
TEST(TrackingMetrics, ClearMotKeepsAnObjectsTrackAndCountsTheSwitchWhenItEnds) {
  const std::vector<gen::TruthSample> centres = still_object_centres(150000);
  std::vector<TrackUpdate> updates;
  for (TimeUs t = 0; t <= 60000; t += 5000) updates.push_back({t, 4, 51, 50, 0, 0, 51, 50});
  for (TimeUs t = 50000; t <= 150000; t += 5000) updates.push_back({t, 5, 50.5, 50, 0, 0, 50.5, 50});
  const ClearMot m = tracking_report(updates, centres, 1, 2.5).mot;
  // Track 4 is present until 60 + 34 ms, so in the frames 0 .. 90 ms; track 5 from 50 ms.
  EXPECT_EQ(m.frames, 16);
  EXPECT_EQ(m.objects, 16);
  EXPECT_EQ(m.matches, 16);
  EXPECT_EQ(m.misses, 0);
  EXPECT_EQ(m.false_positives, 5);  // track 5 at 50 .. 90 ms, while the object keeps track 4
  EXPECT_EQ(m.mismatches, 1);       // at 100 ms
  EXPECT_NEAR(m.mota(), 1.0 - 6.0 / 16.0, 1e-12);
  EXPECT_NEAR(m.to_centres.mean, (10 * 1.0 + 6 * 0.5) / 16.0, 1e-9);
}

// With the labelled events given, an object is present only while it fires: an event camera
// cannot see a still object, so its frames without events are not misses.
TEST(TrackingMetrics, ClearMotCountsAnObjectOnlyWhileItFires) {
  const std::vector<gen::TruthSample> centres = still_object_centres(100000);
  std::vector<Event> events;  // four a millisecond until 50 ms, then none
  for (TimeUs t = 0; t <= 50000; t += 1000) {
    for (int k = 0; k < 4; ++k) events.push_back({t, 50, static_cast<std::uint16_t>(48 + k), 1});
  }
  const std::vector<std::int32_t> truth(events.size(), 0);
  const std::vector<TrackUpdate> none;
  EXPECT_EQ(tracking_report(none, centres, 1).mot.misses, 11);
  const ClearMot fired = tracking_report(none, centres, 1, 2.5, 15.0, 20000, {events, truth}).mot;
  EXPECT_EQ(fired.objects, 6);  // 0 .. 50 ms: the 10 ms window around 60 ms holds none of its events
  EXPECT_EQ(fired.misses, 6);
  EXPECT_EQ(fired.false_positives, 0);
}

// With the run's labels, a track measured from an object the truth has no centre for (its
// outline reaches past the sensor's edge) is ignored, as MOTChallenge ignores a track on a
// distractor; a track on noise stays a false positive, and so does the first track without labels.
TEST(TrackingMetrics, ClearMotIgnoresATrackOnAnObjectWithoutATrueCentre) {
  const std::vector<gen::TruthSample> centres = still_object_centres(100000);  // object 0 only
  std::vector<Event> events;
  std::vector<std::int32_t> truth, predicted;
  const auto fire = [&](TimeUs t, std::uint16_t x, std::int32_t object, std::int32_t track) {
    for (std::uint16_t y = 48; y < 52; ++y) events.push_back({t, x, y, 1}), truth.push_back(object), predicted.push_back(track);
  };
  std::vector<TrackUpdate> updates;
  for (TimeUs t = 0; t <= 100000; t += 1000) {
    fire(t, 50, 0, 1);    // object 0, tracked by track 1
    fire(t, 120, 1, 2);   // object 1, no true centre, tracked by track 2
    fire(t, 200, -1, 3);  // noise, tracked by track 3
    if (t % 5000 == 0) {
      updates.push_back({t, 1, 51, 50, 0, 0, 51, 50});
      updates.push_back({t, 2, 120, 50, 0, 0, 120, 50});
      updates.push_back({t, 3, 200, 50, 0, 0, 200, 50});
    }
  }
  const ClearMot labelled = tracking_report(updates, centres, 2, 2.5, 15.0, 20000, {events, truth, predicted}).mot;
  EXPECT_EQ(labelled.frames, 11);
  EXPECT_EQ(labelled.matches, 11);
  EXPECT_EQ(labelled.misses, 0);
  EXPECT_EQ(labelled.ignored, 11);          // track 2 in every frame
  EXPECT_EQ(labelled.false_positives, 11);  // track 3 in every frame
  EXPECT_NEAR(labelled.mota(), 0.0, 1e-12);
  const ClearMot by_position = tracking_report(updates, centres, 2, 2.5).mot;
  EXPECT_EQ(by_position.ignored, 0);
  EXPECT_EQ(by_position.false_positives, 22);  // without labels nothing says what track 2 measured
}

// A crossing member of the family scored in 10 ms chunks by golden, at the defaults with one rule
// by motion off and on.
struct RuleOffAndOn {
  Evaluation off, on;
};
template <class SetOff, class SetOn>
RuleOffAndOn crossing_member_with(std::uint64_t seed, SetOff rule_off, SetOn rule_on) {
  const Scene scene = generate_scene(gen::family_scene("crossing", seed));
  Params off = preset("evms"), on = preset("evms");
  rule_off(off);
  rule_on(on);
  const Chunking ten_ms{Chunking::Kind::kTime, 10000};
  return {evaluate(scene, off, "golden", ten_ms), evaluate(scene, on, "golden", ten_ms)};
}

TEST(Evaluation, TheMotionSplitPartsFastShapesFromTheSlowOnesTheyCross) {
  // A tuning member where two fast shapes cross slow ones (128x128, 46 k events): where two
  // tracks meet, the split by motion gives each its own events back (golden/cluster/motion_split.h).
  const auto [whole, parted] = crossing_member_with(3, [](Params& p) { p.motion_split = 0; }, [](Params& p) { p.motion_split = 0.6; });
  EXPECT_GT(parted.scores.f, whole.scores.f + 0.01);
  EXPECT_LT(parted.tracking.all_kalman.mean, whole.tracking.all_kalman.mean);
}

TEST(Evaluation, TheOutlineSplitPartsShapesWhereTheyCrossByTheirOwnOutlines) {
  // A tuning member where three shapes cross still ones (128x128, 6 shapes): where two tracks
  // meet in one cluster, each takes back the events its own recent outline explains
  // (golden/track/outline_split.h), and the tracks stay on their shapes.
  const auto [whole, parted] = crossing_member_with(7, [](Params&) {}, [](Params& p) { p.outline_split_us = 30000; });
  EXPECT_GT(parted.scores.f, whole.scores.f + 0.015);
  EXPECT_GT(parted.tracking.all_kalman.within, whole.tracking.all_kalman.within);
}

TEST(Evaluation, TheMotionMeasureTracksAFastShapeWithoutTheSlowOnesItPasses) {
  // A tuning member (640x480, 219 k events) where a fast shape passes slow ones: measured from the
  // pixels its own motion explains, its track stays nearer its centre (golden/track/motion_measure.h).
  const auto [pixel_centre, by_motion] = crossing_member_with(6, [](Params& p) { p.motion_measure = 0; }, [](Params& p) { p.motion_measure = 1000; });
  EXPECT_LT(by_motion.tracking.all_kalman.mean, pixel_centre.tracking.all_kalman.mean - 0.2);
  EXPECT_GT(by_motion.tracking.all_kalman.within, pixel_centre.tracking.all_kalman.within);
  EXPECT_EQ(by_motion.run.labels, pixel_centre.run.labels);  // the clusters are the same
}

TEST(Evaluation, OcclusionChunksAreRecognised) {
  Scene s;
  for (TimeUs t = 0; t < 4000; t += 10) s.events.push_back({t, 0, 0, 0}), s.truth.push_back(0);
  for (TimeUs ms = 0; ms < 4; ++ms) {
    s.centres.push_back({ms * 1000, 0, 10, 10, 5});
    s.centres.push_back({ms * 1000, 1, ms < 2 ? 30.0 : 18.0, 10, 5});  // overlapping from 2 ms
  }
  const auto overlap = overlap_by_ms(s);
  EXPECT_EQ(overlap, (std::vector<bool>{false, false, true, true}));
  std::int64_t all = 0, clear = 0;
  score_chunks(s, s.truth, {Chunking::Kind::kTime, 1000}, &all);
  score_chunks(s, s.truth, {Chunking::Kind::kTime, 1000}, &clear, true);
  EXPECT_EQ(all, 4);
  EXPECT_EQ(clear, 2);
}

TEST(MetricsCommand, PrintsOneLineOfScores) {
  test::TempDir dir;
  std::string truth = "t_us,x,y,p,label\n", pred = truth;
  const std::vector<int> t = {0, 0, 0, 0, 0, 1, 0, 1, 1, 1, 1, 2, 0, 0, 2, 2, 2};
  const std::vector<int> p = {0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1, 1, 2, 2, 2, 2, 2};
  for (size_t i = 0; i < t.size(); ++i) {
    const std::string row = std::to_string(i * 10) + "," + std::to_string(i) + ",1,1,";
    truth += row + std::to_string(t[i]) + "\n";
    pred += row + std::to_string(p[i]) + "\n";
  }
  const auto r = test::run_command(test::evms_binary() + " metrics --truth " + dir.write("t.csv", truth) + " --pred " +
                                   dir.write("p.csv", pred) + " --chunk-events 100");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  double ari, nmi, prec, rec, f;
  ASSERT_EQ(std::sscanf(r.out.c_str(), "%lf %lf %lf %lf %lf", &ari, &nmi, &prec, &rec, &f), 5) << r.out;
  EXPECT_NEAR(ari, 1920.0 / 7904.0, 1e-6);
  EXPECT_NEAR(nmi, 0.36, 0.005);
  EXPECT_NEAR(prec, 0.5, 1e-6);
  EXPECT_NEAR(rec, 20.0 / 44.0, 1e-6);
  EXPECT_NEAR(f, 2 * 0.5 * (20.0 / 44.0) / (0.5 + 20.0 / 44.0), 1e-6);
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1);
}

TEST(MetricsCommand, MismatchedFilesAreAnError) {
  test::TempDir dir;
  const auto a = dir.write("a.csv", "t_us,x,y,p,label\n1,2,3,1,0\n2,2,3,1,0\n");
  const auto b = dir.write("b.csv", "t_us,x,y,p,label\n1,2,3,1,0\n2,5,3,1,0\n");
  const auto r = test::run_command(test::evms_binary() + " metrics --truth " + a + " --pred " + b);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find(b + ": line 3: event"), std::string::npos) << r.err;
  const auto c = dir.write("c.csv", "t,x,y,p\n");
  const auto r2 = test::run_command(test::evms_binary() + " metrics --truth " + c + " --pred " + b);
  EXPECT_NE(r2.err.find(c + ": line 1: bad header"), std::string::npos) << r2.err;
}

TEST(EvalCommand, WritesTheReportWithEveryFigure) {
  test::TempDir dir;
  const auto r = test::run_command(test::evms_binary() + " eval --scenes translation,rotation --speeds 1,2 --duration-s 0.4 "
                                   "--bandwidths 0.06,0.08 --family-seeds 1 --family-types still --real-dir /nonexistent --out " + dir.path("ev"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::stringstream report;
  report << std::ifstream(dir.path("ev/report.md")).rdbuf();
  for (const char* section : {"Table I", "KM (true k)", "## Targets", "Clusters over time", "Cost against speed",
                              "F against bandwidth", "## Tracking", "Share", "Real recordings", "## The scene family", "| still |", "touching merged F",
                              "CLEAR MOT over the split", "one track per object at a time (CLEAR MOT's MOTP"}) {
    EXPECT_NE(report.str().find(section), std::string::npos) << section;
  }
  for (const char* fig : {"clusters_translation.svg", "ops_vs_speed.svg", "f_vs_speed.svg", "f_vs_bandwidth.svg",
                          "tracks_rotation.png", "within_tau_translation.svg"}) {
    const auto svg = dir.path(std::string("ev/fig/") + fig);
    ASSERT_TRUE(std::filesystem::exists(svg)) << svg;
    EXPECT_GT(std::filesystem::file_size(svg), 2000u) << svg;
  }
}

TEST(SweepCommand, PrintsATablePerParameter) {
  const auto r = test::run_command(test::evms_binary() + " sweep --types rotation,still --seeds 1 --vary bandwidth=0.04,0.06 "
                                   "--vary packet-size=1000,3000");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("## bandwidth"), std::string::npos);
  EXPECT_NE(r.out.find("| 0.04 |"), std::string::npos);
  EXPECT_NE(r.out.find("## packet-size"), std::string::npos);
  EXPECT_NE(r.out.find("| 1000 |"), std::string::npos);
  EXPECT_NE(r.out.find("| packet-size | rotation | still | mean F |"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("| track err px | within 2.5 px | events' centre's own err px | within 2.5 px | velocity err px/s |"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("| within 2.5 px | MOTA | MOTP px | MOTP to events' centre px | within 2.5 px |"), std::string::npos) << r.out;
}

// The line of `out` that starts with `start` (empty when there is none).
std::string row_line(const std::string& out, const std::string& start) {
  const auto at = out.find(start);
  return at == std::string::npos ? std::string() : out.substr(at, out.find('\n', at) - at);
}

// The cells of that line, a Markdown table's row.
std::vector<std::string> row_cells(const std::string& out, const std::string& start) {
  std::vector<std::string> cells;
  const std::string line = row_line(out, start);
  for (size_t from = 1, bar; (bar = line.find('|', from)) != std::string::npos; from = bar + 1) cells.push_back(line.substr(from, bar - from));
  return cells;
}

// --sensor, --objects and --noise-hz pin the family's members (not the paper's scenes).
TEST(SweepCommand, PinsTheMembersSensorShapesAndNoise) {
  const auto r = test::run_command(test::evms_binary() + " sweep --types rotation,paper-rotation --seeds 1 --per-scene --sensor 200x150 "
                                   "--objects 3 --noise-hz 0.5 --vary bandwidth=0.04");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("| rotation 1: rotation 200x150,  3 shapes (0 moving), speed"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("noise 0.50 Hz"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("| paper-rotation 1: rotation 240x180, poster of 9 shapes"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("| F 0.04 | IDF1 0.04 | track err px 0.04 | estimates 0.04 | beyond 2.5 px 0.04 | within 2.5 px 0.04 | centroid err px 0.04 | events' centre's own err px 0.04 | "
                       "err to events' centre px 0.04 | MOTA 0.04 | false tracks/frame 0.04 |"),
            std::string::npos)
      << r.out;
  // Each member's row: its estimates and those beyond 2.5 px are counts, and its share within
  // 2.5 px the fraction they leave.
  const std::string start = "| rotation 1: rotation 200x150";
  const auto cells = row_cells(r.out, start);
  ASSERT_EQ(cells.size(), 3u + 11u) << r.out;
  const std::string line = row_line(r.out, start);
  const long estimates = std::stol(cells[6]);
  const long beyond = std::stol(cells[7]);
  const double within = std::stod(cells[8]);
  EXPECT_GT(estimates, 0) << line;
  EXPECT_GE(beyond, 0) << line;
  EXPECT_LE(beyond, estimates) << line;
  EXPECT_NEAR(within, 1.0 - static_cast<double>(beyond) / static_cast<double>(estimates), 0.005) << line;
  const auto bad = test::run_command(test::evms_binary() + " sweep --types rotation --seeds 1 --sensor 200");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("--sensor: expected WxH"), std::string::npos) << bad.err;
}

// --per-scene ends with each sensor's members together: their count, mean F and pooled
// estimates, the sums of the members' own rows.
TEST(SweepCommand, PoolsEachSensorsMembers) {
  const auto r = test::run_command(test::evms_binary() + " sweep --types rotation,still,paper-rotation --seeds 1 --per-scene --sensor 200x150 "
                                   "--preset evms --split tuning");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rotation = row_cells(r.out, "| rotation 1: "), still = row_cells(r.out, "| still 1: "), poster = row_cells(r.out, "| paper-rotation 1: ");
  ASSERT_EQ(rotation.size(), 14u) << r.out;
  ASSERT_EQ(still.size(), 14u) << r.out;
  ASSERT_EQ(poster.size(), 14u) << r.out;
  const auto small = row_cells(r.out, "| 200x150 |"), paper = row_cells(r.out, "| 240x180 |");
  ASSERT_EQ(small.size(), 6u) << r.out;
  ASSERT_EQ(paper.size(), 6u) << r.out;
  EXPECT_LT(r.out.find("| 200x150 |"), r.out.find("| 240x180 |")) << "the smaller sensor first";
  EXPECT_EQ(std::stoi(small[1]), 2);
  EXPECT_EQ(std::stoi(paper[1]), 1);
  EXPECT_NEAR(std::stod(small[2]), (std::stod(rotation[3]) + std::stod(still[3])) / 2, 0.0015);
  EXPECT_NEAR(std::stod(paper[2]), std::stod(poster[3]), 0.0005);
  const long estimates = std::stol(rotation[6]) + std::stol(still[6]), beyond = std::stol(rotation[7]) + std::stol(still[7]);
  EXPECT_EQ(std::stol(small[3]), estimates);
  EXPECT_EQ(std::stol(small[4]), beyond);
  ASSERT_GT(estimates, 0);
  EXPECT_NEAR(std::stod(small[5]), 1.0 - static_cast<double>(beyond) / static_cast<double>(estimates), 0.0005);
  EXPECT_EQ(std::stol(paper[3]), std::stol(poster[6]));
  EXPECT_EQ(std::stol(paper[4]), std::stol(poster[7]));
}

// Without --split the presets are compared on both splits; with it, on that split alone.
TEST(SweepCommand, ComparesThePresetsOnTheSplitGiven) {
  const auto both = test::run_command(test::evms_binary() + " sweep --types still --seeds 1 --preset evms");
  ASSERT_EQ(both.exit_code, 0) << both.err;
  EXPECT_NE(both.out.find("## Tuning split"), std::string::npos) << both.out;
  EXPECT_NE(both.out.find("## Validation split"), std::string::npos) << both.out;
  const auto one = test::run_command(test::evms_binary() + " sweep --types still --seeds 1 --preset evms --split validation");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  EXPECT_EQ(one.out.find("## Tuning split"), std::string::npos) << one.out;
  EXPECT_NE(one.out.find("## Validation split"), std::string::npos) << one.out;
}

TEST(SweepCommand, UnknownTypesAndParametersAreOneLine) {
  const auto type = test::run_command(test::evms_binary() + " sweep --types spin --seeds 1");
  EXPECT_NE(type.exit_code, 0);
  EXPECT_NE(type.err.find("unknown scene type 'spin'"), std::string::npos) << type.err;
  const auto param = test::run_command(test::evms_binary() + " sweep --types rotation --seeds 1 --vary bandwith=0.1");
  EXPECT_NE(param.exit_code, 0);
  EXPECT_NE(param.err.find("unknown parameter 'bandwith'"), std::string::npos) << param.err;
  // A value that is not a number is refused before anything is printed.
  const auto value = test::run_command(test::evms_binary() + " sweep --types rotation --seeds 1 --vary bandwidth=0.04,nan");
  EXPECT_NE(value.exit_code, 0);
  EXPECT_NE(value.err.find("--bandwidth: 'nan' is not a number"), std::string::npos) << value.err;
  EXPECT_EQ(value.out, "");
}

// What `evms sweep` prints is the family's pooling of its members: F the mean over members,
// the worst type the lowest of the types' means, and the tracking errors (position, velocity)
// pooled over every estimate of every member, so that a member with many estimates weighs
// more. Two short members of two types, run by the defaults.
TEST(FamilyEval, ThePooledScoresAreTheMembersScoresPooled) {
  std::vector<eval::FamilyScene> family = eval::generate_family(gen::Split::kValidation, 1, {"still", "rotation"}, 2,
                                                                gen::FamilyPins{128, 128, 3, 0.1});
  ASSERT_EQ(family.size(), 2u);
  const eval::FamilyResult r = eval::evaluate_family(family, Method{}, "golden", 2);
  ASSERT_EQ(r.scenes.size(), 2u);
  ASSERT_EQ(r.types.size(), 2u);
  EXPECT_NEAR(r.mean_f, (r.scenes[0].scores.f + r.scenes[1].scores.f) / 2, 1e-12);
  EXPECT_NEAR(r.worst_type_f, std::min(r.scenes[0].scores.f, r.scenes[1].scores.f), 1e-12);
  std::int64_t positions = 0, velocities = 0;
  double position_sum = 0, velocity_sum = 0;
  for (const eval::SceneResult& s : r.scenes) {
    ASSERT_GT(s.tracking.all_velocity.samples, 0) << "each member's confirmed tracks have velocities to score";
    positions += s.tracking.all_kalman.samples;
    velocities += s.tracking.all_velocity.samples;
    position_sum += s.tracking.all_kalman.mean * static_cast<double>(s.tracking.all_kalman.samples);
    velocity_sum += s.tracking.all_velocity.mean * static_cast<double>(s.tracking.all_velocity.samples);
  }
  EXPECT_EQ(r.tracking.samples, positions);
  EXPECT_EQ(r.velocity.samples, velocities);
  EXPECT_NEAR(r.tracking.mean, position_sum / static_cast<double>(positions), 1e-9);
  EXPECT_NEAR(r.velocity.mean, velocity_sum / static_cast<double>(velocities), 1e-9);
  EXPECT_GT(r.velocity.mean, 0) << "no estimate's velocity is exactly the truth";
}

}  // namespace

}  // namespace evms::eval
