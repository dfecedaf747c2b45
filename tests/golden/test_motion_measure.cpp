// Time-surface slopes (golden/cluster/time_surface_slopes.h) and a fast track's cluster measured
// from the pixels its motion explains (golden/track/motion_measure.h): straight edges swept at
// known velocities.
#include <gtest/gtest.h>

#include <cmath>

#include "golden/cluster/time_surface_slopes.h"
#include "golden/track/motion_measure.h"
#include "tests/support/scenes.h"

namespace evms::golden {
namespace {

using test::kSensor;

// An edge swept over the pixels [x0, x1) x [y0, y1) at (vx, vy) px/s: each pixel fires once, when
// the edge, at angle atan2(vy, vx) to the x axis, reaches it.
std::vector<Event> edge_at_velocity(int x0, int x1, int y0, int y1, double vx, double vy, std::uint8_t polarity = 1) {
  std::vector<Event> e;
  const double speed2 = vx * vx + vy * vy;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      const double s = ((x - x0) * vx + (y - y0) * vy) / speed2;  // when the edge's normal line reaches it
      e.push_back({static_cast<TimeUs>(std::lround(s * 1e6)) + 100000, static_cast<std::uint16_t>(x), static_cast<std::uint16_t>(y), polarity});
    }
  }
  return e;
}

TEST(TimeSurfaceSlopes, AnEdgeAtVelocityVHasSlopeVOverItsSpeedSquared) {
  // Dense over directions and speeds: slope · v = 1 and the slope lies along v (their cross
  // product, the sine of the angle between them, is 0), within what the events' times rounded to
  // the microsecond allow: a slope off by 1e-6 s/px moves both by 1e-6 times the speed.
  for (double angle = 0; angle < 2 * M_PI; angle += M_PI / 12) {
    for (double speed : {50.0, 400.0, 3000.0}) {
      const double vx = speed * std::cos(angle), vy = speed * std::sin(angle);
      const std::vector<Event> events = edge_at_velocity(40, 60, 40, 60, vx, vy);
      TimeSurfaceSlopes slopes(kSensor);
      slopes.add(events);
      const std::optional<Eigen::Vector2d> g = slopes.at(events[10 * 20 + 10]);
      ASSERT_TRUE(g.has_value()) << angle << " " << speed;
      EXPECT_NEAR(misfit(*g, {vx, vy}), 0.0, 1e-6 * speed) << angle << " " << speed;
      EXPECT_NEAR(g->x() * vy - g->y() * vx, 0.0, 1e-6 * speed) << angle << " " << speed;
      slopes.clear();
    }
  }
}

TEST(TimeSurfaceSlopes, OneLineOfPixelsOrTooFewEventsGiveNoSlope) {
  TimeSurfaceSlopes slopes(kSensor);
  const std::vector<Event> row = edge_at_velocity(10, 30, 50, 51, 500, 0);  // one row: the slope across it unknown
  slopes.add(row);
  EXPECT_FALSE(slopes.at(row[10]).has_value());
  slopes.clear();
  const std::vector<Event> five = edge_at_velocity(10, 15, 50, 51, 500, 0);
  slopes.add(five);
  EXPECT_FALSE(slopes.at(five[2]).has_value());
  slopes.clear();
  // Cleared: the next packet's events alone count.
  const std::vector<Event> square = edge_at_velocity(10, 20, 50, 60, 500, 0);
  slopes.add(square);
  ASSERT_TRUE(slopes.at(square[55]).has_value());
  EXPECT_NEAR(misfit(*slopes.at(square[55]), {500, 0}), 0.0, 1e-3);
}

TEST(TimeSurfaceSlopes, PolaritiesDoNotMix) {
  // An ON edge and an OFF edge on the same pixels, moving apart: each event's slope is its own
  // edge's.
  const std::vector<Event> on = edge_at_velocity(10, 30, 20, 40, 1000, 0, 1), off = edge_at_velocity(10, 30, 20, 40, -250, 0, 0);
  TimeSurfaceSlopes slopes(kSensor);
  const std::vector<Event> both = test::concat(on, off);
  slopes.add(both);
  EXPECT_NEAR(misfit(*slopes.at(on[210]), {1000, 0}), 0.0, 1e-3);
  EXPECT_NEAR(misfit(*slopes.at(off[210]), {-250, 0}), 0.0, 1e-3);
}

struct MeasuredPacket {
  std::vector<Event> events;
  std::vector<int> cluster_of;
  std::vector<Measurement> measurements;  // one cluster, its box and pixel centre
};

// A fast edge (x 100-119, 2,000 px/s) and a slow one beside it (x 122-141, 100 px/s) in one cluster.
MeasuredPacket fast_beside_slow() {
  MeasuredPacket p;
  p.events = test::concat(edge_at_velocity(100, 120, 50, 70, 2000, 0), edge_at_velocity(122, 142, 50, 70, 100, 0));
  p.cluster_of.assign(p.events.size(), 0);
  Measurement m;
  m.x_min = 100, m.x_max = 141, m.y_min = 50, m.y_max = 69;
  m.x = (109.5 + 131.5) / 2, m.y = 59.5;  // the pixel centre: both edges' 400 pixels
  m.events = static_cast<int>(p.events.size());
  p.measurements = {m};
  return p;
}

// The slow edge's own track, coasting in the box beside the fast one.
const TrackPrediction kSlowTrack{{132, 60}, {100, 0}, false};

Params measuring_fast(double speed) {
  Params p;
  p.motion_measure = speed;
  return p;
}

TEST(MotionMeasure, AFastTracksClusterIsMeasuredFromThePixelsItsVelocityExplains) {
  MeasuredPacket p = fast_beside_slow();
  const std::vector<TrackPrediction> tracks = {{{110, 60}, {2000, 0}}, kSlowTrack};
  MotionMeasure(measuring_fast(1000), kSensor).measure(p.events, p.cluster_of, tracks, p.measurements);
  EXPECT_NEAR(p.measurements[0].x, 109.5, 1e-9);  // the fast edge's pixels alone
  EXPECT_NEAR(p.measurements[0].y, 59.5, 1e-9);
}

TEST(MotionMeasure, ASlowTrackOrNoTrackInTheBoxOrAFastTrackAloneLeavesThePixelCentre) {
  for (const std::vector<TrackPrediction>& tracks : {std::vector<TrackPrediction>{{{110, 60}, {900, 0}}, kSlowTrack},  // slower than asked
                                                     std::vector<TrackPrediction>{{{180, 60}, {2000, 0}}, kSlowTrack},  // outside the box
                                                     std::vector<TrackPrediction>{{{110, 60}, {2000, 0}, false}, kSlowTrack},  // coasting
                                                     std::vector<TrackPrediction>{{{110, 60}, {2000, 0}}},  // no other track beside it
                                                     std::vector<TrackPrediction>{{{110, 60}, {2000, 0}}, {{180, 60}, {100, 0}}},  // nor in the box
                                                     std::vector<TrackPrediction>{}}) {
    MeasuredPacket p = fast_beside_slow();
    MotionMeasure(measuring_fast(1000), kSensor).measure(p.events, p.cluster_of, tracks, p.measurements);
    EXPECT_DOUBLE_EQ(p.measurements[0].x, (109.5 + 131.5) / 2);
  }
}

TEST(MotionMeasure, FewerThanHalfThePixelsExplainedLeavesThePixelCentre) {
  // The track's velocity explains neither edge (it moves along y): no pixels kept.
  MeasuredPacket p = fast_beside_slow();
  MotionMeasure(measuring_fast(1000), kSensor).measure(p.events, p.cluster_of, {{{{110, 60}, {0, 2000}}, kSlowTrack}}, p.measurements);
  EXPECT_DOUBLE_EQ(p.measurements[0].x, (109.5 + 131.5) / 2);
  // A slow edge three times the fast one's pixels: the fast edge's are a quarter of the cluster's.
  MeasuredPacket wide = fast_beside_slow();
  wide.events = test::concat(edge_at_velocity(100, 120, 50, 70, 2000, 0), edge_at_velocity(122, 182, 50, 70, 100, 0));
  wide.cluster_of.assign(wide.events.size(), 0);
  wide.measurements[0].x_max = 181, wide.measurements[0].x = 140;
  MotionMeasure(measuring_fast(1000), kSensor).measure(wide.events, wide.cluster_of, {{{{110, 60}, {2000, 0}}, kSlowTrack}}, wide.measurements);
  EXPECT_DOUBLE_EQ(wide.measurements[0].x, 140);
}

}  // namespace
}  // namespace evms::golden
