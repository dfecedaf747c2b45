#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "golden/track/kalman_filter.h"
#include "golden/track/tracker.h"
#include "host/gen/random.h"

namespace evms::golden {
namespace {

Params tracker_params() {
  Params p = preset("gaussian");
  p.report_tentative = true;
  p.confirm_hits = 2;
  p.gate_px = 10;
  p.coast_us = 100000;
  p.max_tracks = 4;
  return p;
}

TEST(KalmanFilter, CovarianceStartsAtP0AndIsUsedByTheFirstUpdate) {
  // The authors' code set P where predict() overwrote it: P0 had no effect.
  Params a, b;
  a.init_sigma_px = 1.0;
  b.init_sigma_px = 10.0;
  KalmanFilter fa(0, 0, 0, a), fb(0, 0, 0, b);
  EXPECT_DOUBLE_EQ(fa.covariance()(0, 0), 1.0);
  EXPECT_DOUBLE_EQ(fb.covariance()(0, 0), 100.0);
  fa.predict(1000), fb.predict(1000);
  fa.update(4, 0), fb.update(4, 0);
  EXPECT_LT(fa.state()(0), fb.state()(0));  // a confident start moves less towards z
  EXPECT_GT(fb.state()(0), 3.5);
}

TEST(KalmanFilter, StaysSymmetricAndPositiveOverManyUpdates) {
  Params p = preset("gaussian");
  KalmanFilter f(10, 10, 0, p);
  gen::Random rng(4);
  for (int k = 1; k <= 20000; ++k) {
    const TimeUs t = k * 1000;
    f.predict(t);
    f.update(10 + 0.1 * k + rng.normal(), 10 - 0.05 * k + rng.normal());
  }
  const auto& c = f.covariance();
  EXPECT_LT((c - c.transpose()).cwiseAbs().maxCoeff(), 1e-9 * c.cwiseAbs().maxCoeff());
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(c);
  EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0);
}

TEST(KalmanFilter, TheFilteredEstimateIsSmootherThanTheMeasurements) {
  // The authors computed the filtered estimate and then reported the raw centroid.
  Params p = preset("gaussian");
  p.meas_sigma_px = 2.0;
  p.accel_psd = 100;
  KalmanFilter f(0, 0, 0, p);
  gen::Random rng(9);
  double raw_error = 0, filtered_error = 0;
  for (int k = 1; k <= 2000; ++k) {
    const TimeUs t = k * 2000;
    const double truth = 100.0 * t * 1e-6;
    const double z = truth + 2.0 * rng.normal();
    f.predict(t);
    f.update(z, 0);
    if (k > 200) {
      raw_error += (z - truth) * (z - truth);
      filtered_error += (f.state()(0) - truth) * (f.state()(0) - truth);
    }
  }
  EXPECT_LT(filtered_error, 0.25 * raw_error);
}

TEST(Tracker, IdsAreOneToOneAndNeverReused) {
  MultiTargetTracker tracker(tracker_params());
  std::vector<TrackUpdate> updates;
  auto ids = tracker.step(1000, std::vector<Measurement>{{1000, 50, 50}}, updates);
  ASSERT_EQ(ids[0], 0);
  // Two clusters near the one track: only the nearer keeps its ID, the other gets a new one
  // (the authors' many-to-one matching gave both the same ID).
  ids = tracker.step(2000, std::vector<Measurement>{{2000, 53, 50}, {2000, 51, 50}}, updates);
  EXPECT_EQ(ids[1], 0);
  EXPECT_EQ(ids[0], 1);
  // Track 1 is tentative and misses a packet: it ends, and its ID does not come back.
  ids = tracker.step(3000, std::vector<Measurement>{{3000, 51, 50}, {3000, 150, 150}}, updates);
  EXPECT_EQ(ids[0], 0);
  EXPECT_EQ(ids[1], 2);
}

TEST(Tracker, ConfirmedTracksCoastThroughMissedPacketsThenEnd) {
  // The authors' tracks died after one missed packet.
  MultiTargetTracker tracker(tracker_params());
  std::vector<TrackUpdate> updates;
  tracker.step(0, std::vector<Measurement>{{0, 50, 50}}, updates);
  tracker.step(10000, std::vector<Measurement>{{10000, 50, 50}}, updates);
  ASSERT_EQ(updates.size(), 2u);  // tentative at the first hit, confirmed at the second
  EXPECT_EQ(updates[0].state, TrackState::kTentative);
  EXPECT_EQ(updates[1].state, TrackState::kConfirmed);
  for (TimeUs t = 20000; t <= 100000; t += 10000) tracker.step(t, {}, updates);
  EXPECT_EQ(tracker.live_tracks(), 1);
  auto ids = tracker.step(105000, std::vector<Measurement>{{105000, 51, 50}}, updates);
  EXPECT_EQ(ids[0], 0);  // the same object, the same ID
  for (TimeUs t = 110000; t <= 210000; t += 10000) tracker.step(t, {}, updates);
  EXPECT_EQ(tracker.live_tracks(), 0);
  ids = tracker.step(220000, std::vector<Measurement>{{220000, 51, 50}}, updates);
  EXPECT_EQ(ids[0], 1);
}

TEST(Tracker, MeasurementsBeyondTheGateStartNewTracks) {
  MultiTargetTracker tracker(tracker_params());
  std::vector<TrackUpdate> updates;
  tracker.step(0, std::vector<Measurement>{{0, 50, 50}}, updates);
  auto ids = tracker.step(1000, std::vector<Measurement>{{1000, 70, 50}}, updates);
  EXPECT_EQ(ids[0], 1);
}

// A cluster at (x, y) with the bounding box [x0, x1] x [y0, y1] and `events` events.
Measurement boxed(TimeUs t, double x, double y, int x0, int y0, int x1, int y1, int events = 100) {
  Measurement z{t, x, y, events};
  z.x_min = x0, z.y_min = y0, z.x_max = x1, z.y_max = y1;
  return z;
}

// A head and a body 50 px apart, one cluster for a packet, then two again: the merged cluster's
// centre is 25 px from either (beyond the 10 px gate), and with gate_boxes it takes the ID of a
// track whose last centre its box holds (the nearer; a tie goes to the lower slot); when it splits,
// the head's cluster lies in the box of that track's last cluster and takes its ID back, and the
// body's track, coasting, takes the body. Without the rule the merged cluster starts a third
// track.
TEST(Tracker, AClusterThatMergesOrSplitsKeepsTheIdOfATrackItCovers) {
  for (const bool boxes : {true, false}) {
    Params p = tracker_params();
    p.confirm_hits = 1;
    p.gate_boxes = boxes;
    MultiTargetTracker tracker(p);
    std::vector<TrackUpdate> updates;
    const auto apart = [](TimeUs t) {
      return std::vector<Measurement>{boxed(t, 50, 30, 40, 20, 60, 40), boxed(t, 50, 80, 30, 60, 70, 100)};
    };
    EXPECT_EQ(tracker.step(0, apart(0), updates), (std::vector<std::int32_t>{0, 1}));
    const auto merged = tracker.step(1000, std::vector<Measurement>{boxed(1000, 50, 55, 30, 20, 70, 100, 200)}, updates);
    const auto split = tracker.step(2000, apart(2000), updates);
    if (boxes) {
      EXPECT_EQ(merged, (std::vector<std::int32_t>{0}));
      EXPECT_EQ(split, (std::vector<std::int32_t>{0, 1}));
      EXPECT_EQ(tracker.tracks_started(), 2);
    } else {
      EXPECT_EQ(merged, (std::vector<std::int32_t>{2})) << "a third track for the merged cluster";
      EXPECT_EQ(split, (std::vector<std::int32_t>{0, 1})) << "the coasting tracks take their parts back";
      EXPECT_EQ(tracker.tracks_started(), 3);
    }
  }
}

// A pair beyond the gate comes after every pair within it, even one whose sizes are far apart:
// the track takes the bright cluster within its gate, and the faint one its box holds starts a
// track of its own.
TEST(Tracker, PairsWithinTheGateComeBeforePairsByTheBoxes) {
  Params p = tracker_params();
  p.confirm_hits = 1;
  p.gate_boxes = true;
  p.size_ratio = 4;
  MultiTargetTracker tracker(p);
  std::vector<TrackUpdate> updates;
  tracker.step(0, std::vector<Measurement>{boxed(0, 50, 50, 20, 20, 80, 80, 100)}, updates);
  const auto ids = tracker.step(1000, std::vector<Measurement>{boxed(1000, 70, 50, 65, 45, 75, 55, 100),
                                                               boxed(1000, 55, 50, 50, 45, 60, 55, 1000)}, updates);
  EXPECT_EQ(ids, (std::vector<std::int32_t>{1, 0}));
}

TEST(Tracker, FullSlotsLeaveClustersUnassigned) {
  Params p = tracker_params();
  p.max_tracks = 2;
  MultiTargetTracker tracker(p);
  std::vector<TrackUpdate> updates;
  auto ids = tracker.step(0, std::vector<Measurement>{{0, 10, 10}, {0, 100, 100}, {0, 200, 150}}, updates);
  EXPECT_EQ(ids, (std::vector<std::int32_t>{0, 1, kNoiseLabel}));
  EXPECT_EQ(tracker.unassigned_clusters(), 1);
}

TEST(Tracker, TentativeUpdatesAreReportedOnlyWhenAsked) {
  Params p = tracker_params();
  p.report_tentative = false;
  MultiTargetTracker tracker(p);
  std::vector<TrackUpdate> updates;
  const auto ids = tracker.step(0, std::vector<Measurement>{{0, 50, 50}}, updates);
  EXPECT_EQ(ids[0], 0);
  EXPECT_TRUE(updates.empty());
}

TEST(Tracker, LastMeasurementAssociationFollowsWhatTheFilterLagsBehind) {
  // A target that turns sharply: the Kalman prediction overshoots beyond the gate, the last
  // measurement does not.
  Params kalman = tracker_params();
  kalman.gate_px = 5;
  kalman.accel_psd = 1;
  Params last = kalman;
  last.association = Association::kLastMeasurement;
  for (const Params& p : {kalman, last}) {
    MultiTargetTracker tracker(p);
    std::vector<TrackUpdate> updates;
    std::vector<std::int32_t> ids;
    // Along x at 400 px/s, 4 px a packet ...
    for (int k = 0; k < 10; ++k) ids = tracker.step(k * 10000, std::vector<Measurement>{{k * 10000, 10.0 + 4 * k, 50}}, updates);
    ASSERT_EQ(ids[0], 0);
    // ... then straight up from (46, 50).
    for (int k = 1; k <= 5; ++k) ids = tracker.step((9 + k) * 10000, std::vector<Measurement>{{(9 + k) * 10000, 46, 50.0 + 4 * k}}, updates);
    if (p.association == Association::kLastMeasurement) {
      EXPECT_EQ(ids[0], 0) << "one target, one ID";
    } else {
      EXPECT_NE(ids[0], 0) << "the prediction ran on along x and lost the target";
    }
  }
}

TEST(Tracker, WithEverySlotTakenANewClusterTakesTheStalestUnmatchedSlot) {
  Params p = tracker_params();
  p.max_tracks = 2;
  p.confirm_hits = 1;
  p.evict_stale = true;
  MultiTargetTracker tracker(p);
  std::vector<TrackUpdate> updates;
  tracker.step(0, std::vector<Measurement>{{0, 10, 10}}, updates);       // ID 0, measured at 0
  tracker.step(1000, std::vector<Measurement>{{1000, 100, 100}}, updates);  // ID 1, measured at 1000
  // A third object while 0 and 1 coast: it takes the slot of 0, measured longest ago.
  auto ids = tracker.step(2000, std::vector<Measurement>{{2000, 200, 150}}, updates);
  EXPECT_EQ(ids[0], 2);
  EXPECT_EQ(tracker.unassigned_clusters(), 0);
  ids = tracker.step(3000, std::vector<Measurement>{{3000, 10, 10}, {3000, 100, 100}}, updates);
  EXPECT_EQ(ids[0], 3) << "track 0 was evicted: its object gets a new ID";
  EXPECT_EQ(ids[1], 1) << "track 1 kept its slot";
}

TEST(Tracker, CoastingCanEndAfterMissedPackets) {
  Params p = tracker_params();
  p.coast_packets = 3;
  MultiTargetTracker tracker(p);
  std::vector<TrackUpdate> updates;
  tracker.step(0, std::vector<Measurement>{{0, 50, 50}}, updates);
  tracker.step(100, std::vector<Measurement>{{100, 50, 50}}, updates);
  for (TimeUs t = 200; t <= 400; t += 100) tracker.step(t, {}, updates);  // three misses, well inside coast-us
  EXPECT_EQ(tracker.live_tracks(), 1);
  tracker.step(500, {}, updates);
  EXPECT_EQ(tracker.live_tracks(), 0);
}

TEST(Tracker, TheGateWidensWithTheClusterSpread) {
  Params p = tracker_params();
  p.gate_px = 10;
  p.gate_spread = 2;
  p.association = Association::kLastMeasurement;
  MultiTargetTracker tracker(p);
  std::vector<TrackUpdate> updates;
  Measurement big{0, 50, 50};
  big.spread = 12;
  tracker.step(0, std::vector<Measurement>{big}, updates);
  big.t = 1000, big.x = 70;  // 20 px: outside 10 px, inside 2 x 12 px
  EXPECT_EQ(tracker.step(1000, std::vector<Measurement>{big}, updates)[0], 0);
  Measurement small{2000, 90, 50};
  small.spread = 2;  // 20 px again, but the gate is 10 px
  EXPECT_EQ(tracker.step(2000, std::vector<Measurement>{small}, updates)[0], 1);
}

// A faint object's track (10 events a packet) and a bright one's (500), both confirmed: the
// bright cluster passes 1 px from the faint track's last measurement and 14 px from its own.
// Without the size ratio the faint track takes it (nearest first); with it, the bright track
// does, as its sizes match.
TEST(Tracker, TheSizeRatioKeepsAFaintTrackFromTakingABrightCluster) {
  for (const double ratio : {0.0, 8.0}) {
    SCOPED_TRACE(ratio);
    Params p = tracker_params();
    p.association = Association::kLastMeasurement;
    p.gate_px = 20;
    p.size_ratio = ratio;
    MultiTargetTracker tracker(p);
    std::vector<TrackUpdate> updates;
    Measurement faint{0, 50, 50}, bright{0, 20, 50};
    faint.events = 10, bright.events = 500;
    EXPECT_EQ(tracker.step(0, std::vector<Measurement>{faint, bright}, updates), (std::vector<std::int32_t>{0, 1}));
    faint.t = bright.t = 1000, bright.x = 35;
    EXPECT_EQ(tracker.step(1000, std::vector<Measurement>{faint, bright}, updates), (std::vector<std::int32_t>{0, 1}));
    bright.t = 2000, bright.x = 49;
    EXPECT_EQ(tracker.step(2000, std::vector<Measurement>{bright}, updates)[0], ratio > 0 ? 1 : 0);
    // Within the ratio sizes do not matter: 40 events take the faint track (10) again.
    Measurement fainter{3000, 50, 50};
    fainter.events = 40;
    EXPECT_EQ(tracker.step(3000, std::vector<Measurement>{fainter}, updates)[0], 0);
  }
}

// The size ratio ranks pairs; it does not forbid them. An object that grows fast (entering the
// view, say) keeps its track when no track of its own size claims its cluster.
TEST(Tracker, TheSizeRatioStillGivesAMismatchedClusterItsTrackWhenNoOtherClaimsIt) {
  Params p = tracker_params();
  p.association = Association::kLastMeasurement;
  p.gate_px = 20;
  p.size_ratio = 4;
  MultiTargetTracker tracker(p);
  std::vector<TrackUpdate> updates;
  Measurement entering{0, 5, 50};
  entering.events = 10;
  EXPECT_EQ(tracker.step(0, std::vector<Measurement>{entering}, updates), (std::vector<std::int32_t>{0}));
  entering.t = 1000, entering.x = 12, entering.events = 400;
  EXPECT_EQ(tracker.step(1000, std::vector<Measurement>{entering}, updates), (std::vector<std::int32_t>{0}));
  Measurement faint{2000, 30, 50}, bright{2000, 12, 50};
  faint.events = 10, bright.events = 400;
  EXPECT_EQ(tracker.step(2000, std::vector<Measurement>{bright, faint}, updates), (std::vector<std::int32_t>{0, 1}));
  // Two tracks near one bright cluster: the one of its size takes it, though farther (12 px
  // against 6).
  bright.t = 3000, bright.x = 24;
  EXPECT_EQ(tracker.step(3000, std::vector<Measurement>{bright}, updates), (std::vector<std::int32_t>{0}));
}

// The defaults' process noise is given for a 240-pixel-wide sensor and grows with the square of
// the width: on a 480-wide sensor the tracks are those of four times the noise without scaling.
TEST(Tracker, TheProcessNoiseScalesWithTheSquareOfTheSensorWidth) {
  const Params p;
  ASSERT_GT(p.accel_psd_width, 0);
  EXPECT_DOUBLE_EQ(accel_psd_at(p, {240, 180}), p.accel_psd);
  EXPECT_DOUBLE_EQ(accel_psd_at(p, {480, 360}), 4 * p.accel_psd);
  EXPECT_DOUBLE_EQ(accel_psd_at(p, {120, 90}), p.accel_psd / 4);
  Params unscaled = p;
  unscaled.accel_psd = 4 * p.accel_psd;
  unscaled.accel_psd_width = 0;
  EXPECT_DOUBLE_EQ(accel_psd_at(unscaled, {128, 128}), unscaled.accel_psd) << "width 0: the same on every sensor";

  const auto scaled = make_tracker(p, {480, 360}), given = make_tracker(unscaled, {128, 128});
  const auto at_240 = make_tracker(p, {240, 180});
  std::vector<TrackUpdate> a, b, c;
  gen::Random rng(5);
  double x = 100, vx = 0;
  for (TimeUs t = 10000; t < 1000000; t += 10000) {
    vx += 300 * rng.normal();  // a jerky target, so that the process noise shows
    x += vx * 0.01;
    const std::vector<Measurement> z{{t, x + rng.normal(), 200, 50, 3}};
    scaled->step(t, z, a), given->step(t, z, b), at_240->step(t, z, c);
  }
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GT(a.size(), 90u);
  double apart_from_240 = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].x, b[i].x) << i;
    ASSERT_EQ(a[i].vx, b[i].vx) << i;
    apart_from_240 = std::max(apart_from_240, std::abs(a[i].vx - c[i].vx));
  }
  EXPECT_GT(apart_from_240, 1.0) << "px/s: the 240-wide sensor's filter is another filter";
}

// A track born at (50, 50), then measured 4 px to the right by a tight cluster of 400 events
// (spread 4 px: a centre of mass known to 0.2 px) or by 10 scattered events (spread 8 px: known
// to 2.5 px). With the measurement noise from the spread the tight cluster moves the estimate
// nearly all the way and the scattered one less than half; with one noise for every cluster
// both move it alike.
TEST(Tracker, TheMeasurementNoiseFromTheSpreadTrustsATightClusterMoreThanAScatteredOne) {
  const auto moved_by = [](bool from_spread, int events, double spread) {
    Params p = tracker_params();
    p.association = Association::kLastMeasurement;
    p.meas_noise_from_spread = from_spread;
    p.meas_sigma_px = 1;
    MultiTargetTracker tracker(p);
    std::vector<TrackUpdate> updates;
    Measurement z{0, 50, 50, events, spread};
    tracker.step(0, std::vector<Measurement>{z}, updates);
    z.t = 1000, z.x = 54;
    EXPECT_EQ(tracker.step(1000, std::vector<Measurement>{z}, updates)[0], 0);
    return updates.back();
  };
  const TrackUpdate tight = moved_by(true, 400, 4), scattered = moved_by(true, 10, 8);
  EXPECT_GT(tight.x, 53.9);
  EXPECT_LT(scattered.x, 52.0);
  EXPECT_GT(scattered.x, 50.5);
  // The posterior variance is P R / (P + R), with R = sigma^2 (spread^2 + 1/6) / events.
  const double r_tight = (16.0 + 1.0 / 6) / 400, prior = tight.var_x * r_tight / (r_tight - tight.var_x);
  EXPECT_NEAR(prior, 4.04, 1e-3) << "P0's (2 px)^2, and its velocity's (200 px/s)^2 over 1 ms";
  EXPECT_EQ(moved_by(false, 400, 4).x, moved_by(false, 10, 8).x);
}

TEST(NearestCentreIds, ClustersTakeTheNearestPreviousCentreEvenTwice) {
  Params p = preset("paper");
  NearestCentreIds ids_of(p);
  std::vector<TrackUpdate> updates;
  EXPECT_EQ(ids_of.step(0, std::vector<Measurement>{{0, 50, 50}, {0, 150, 50}}, updates), (std::vector<std::int32_t>{0, 1}));
  // Two clusters near the first centre both take its ID (the authors' many-to-one rule); one
  // beyond sqrt(500) px of every centre gets a new one.
  EXPECT_EQ(ids_of.step(1000, std::vector<Measurement>{{1000, 55, 50}, {1000, 45, 52}, {1000, 100, 120}}, updates),
            (std::vector<std::int32_t>{0, 0, 2}));
}

}  // namespace
}  // namespace evms::golden
