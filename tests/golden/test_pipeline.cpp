// The method end to end on inputs with known answers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "golden/pipeline.h"
#include "host/gen/random.h"
#include "tests/support/scenes.h"

namespace evms::golden {
namespace {

using test::Blob;
using test::CollectingSink;

using test::kSensor;

CollectingSink run(const std::vector<Event>& events, const Params& p) {
  Pipeline pipeline(p, kSensor);
  CollectingSink sink;
  for (const Event& e : events) pipeline.push(e, sink);
  pipeline.finish(sink);
  return sink;
}

TEST(Pipeline, OneLabelledEventPerInputInInputOrder) {
  std::vector<int> which;
  const auto events = test::blob_events({{60, 90}, {180, 90}}, 50000, 0, 100000, kSensor, 1, &which);
  const CollectingSink out = run(events, Params{});
  ASSERT_EQ(out.events.size(), events.size());
  for (size_t i = 0; i < events.size(); ++i) ASSERT_EQ(out.events[i].event, events[i]) << i;
}

TEST(Pipeline, TwoSeparatedBlobsGiveTwoClusters) {
  std::vector<int> which;
  const auto events = test::blob_events({{60, 90}, {180, 90}}, 50000, 0, 100000, kSensor, 2, &which);
  const CollectingSink out = run(events, Params{});
  for (const PacketSummary& s : out.packets) EXPECT_EQ(s.clusters, 2);
  // Every non-noise event of a blob carries its blob's label, and the two labels differ.
  std::map<int, std::set<std::int32_t>> labels;
  for (size_t i = 0; i < events.size(); ++i) {
    if (out.events[i].label != kNoiseLabel) labels[which[i]].insert(out.events[i].label);
  }
  ASSERT_EQ(labels[0].size(), 1u);
  ASSERT_EQ(labels[1].size(), 1u);
  EXPECT_NE(*labels[0].begin(), *labels[1].begin());
}

TEST(Pipeline, ABlobAtConstantVelocityGivesItsVelocityWithin2Percent) {
  const double vx = 120.0, vy = -45.0;
  const auto events = test::blob_events({{40, 150, vx, vy, 2.5}}, 40000, 0, 1500000, kSensor, 3);
  const double speed = std::hypot(vx, vy);
  // The error of the mean velocity over the second half of the track (converged), and of the last.
  const auto velocity_errors = [&](Measure measure) {
    Params p;
    p.packet_size = 256;  // many updates, so that the velocity converges
    p.accel_psd = 1000;   // a smooth filter: the last estimate too is close
    p.measure = measure;
    const CollectingSink out = run(events, p);
    EXPECT_GT(out.tracks.size(), 100u);
    std::set<std::int32_t> ids;
    for (const TrackUpdate& u : out.tracks) ids.insert(u.id);
    EXPECT_EQ(ids.size(), 1u) << "one object, one track";
    double sx = 0, sy = 0;
    size_t n = 0;
    for (size_t i = out.tracks.size() / 2; i < out.tracks.size(); ++i, ++n) sx += out.tracks[i].vx, sy += out.tracks[i].vy;
    const TrackUpdate& last = out.tracks.back();
    return std::pair{std::hypot(sx / n - vx, sy / n - vy) / speed, std::hypot(last.vx - vx, last.vy - vy) / speed};
  };
  const auto [mean_error, last_error] = velocity_errors(Measure::kCentroid);
  EXPECT_LT(mean_error, 0.02);
  EXPECT_LT(last_error, 0.02);
  // A blob of random events is not an outline: its 256 events a packet fall on about 100 pixels,
  // so each pixel once (the default) measures it from fewer samples, and the last estimate is
  // noisier; the converged mean is as close.
  const auto [pixels_mean_error, pixels_last_error] = velocity_errors(Measure::kPixelCentre);
  EXPECT_LT(pixels_mean_error, 0.02);
  EXPECT_LT(pixels_last_error, 0.03);
}

// A band of ON events at x 100..102 that fires three times as often as a band of OFF events
// at x 104..106 beside it, both y 80..100: one cluster, whose centre of mass (102) leans to the
// ON band and whose polarity midpoint and pixel centre (103) do not. Every `off_every` rounds hold
// (off_every + 1) x 63 events, so packets of a multiple of that size see whole rounds.
std::vector<Event> two_bands(int off_every, int rounds) {
  std::vector<Event> e;
  TimeUs t = 0;
  for (int round = 0; round < rounds; ++round) {
    for (int y = 80; y <= 100; ++y) {
      for (int x = 100; x <= 106; ++x) {
        if (x == 103) continue;
        const bool on = x <= 102;
        if (!on && round % off_every != 0) continue;
        e.push_back({t += 20, static_cast<std::uint16_t>(x), static_cast<std::uint16_t>(y), static_cast<std::uint8_t>(on)});
      }
    }
  }
  return e;
}

TEST(Pipeline, ThePolarityMidpointAndThePixelCentreDoNotLeanToTheBusierEdge) {
  const auto events = two_bands(3, 240);
  Params p;
  p.packet_size = 4 * 4 * 63;  // four blocks of three rounds, (3 + 1) x 63 events each
  p.filter_window_us = 0;      // every event reaches the packets, so they stay aligned to rounds
  auto measured_x = [&](Measure measure, int min_events) {
    p.measure = measure;
    p.midpoint_min_events = min_events;
    const CollectingSink out = run(events, p);
    EXPECT_GT(out.tracks.size(), 5u);
    double worst = 0, sum = 0;
    for (const TrackUpdate& u : out.tracks) sum += u.zx, worst = std::max(worst, std::abs(u.zy - 90.0));
    EXPECT_LT(worst, 0.5) << "the bands are symmetric about y = 90";
    return sum / static_cast<double>(out.tracks.size());
  };
  EXPECT_NEAR(measured_x(Measure::kPolarityMidpoint, 16), 103.0, 0.1);
  EXPECT_NEAR(measured_x(Measure::kCentroid, 16), 102.0, 0.1);
  // Each packet holds every pixel of both bands: each pixel once, the ON band weighs no more.
  EXPECT_NEAR(measured_x(Measure::kPixelCentre, 16), 103.0, 0.1);
  // A polarity with fewer events than the minimum: the centre of mass.
  EXPECT_NEAR(measured_x(Measure::kPolarityMidpoint, 100000 / 3), 102.0, 0.1);
}

// A vertical bar (x .. x + 2, y 80..100) moving right at 1,000 px/s: each pixel fires when the
// bar's leading edge reaches it and twice more over the next millisecond, as a pixel under a
// strong edge fires a burst. The pixel centre is timed at its pixels' first events, so each
// measurement lies on the edge's trajectory; timed at the mean of all its events
// (--time-by-pixels false), it trails it by about 0.5 ms, half a pixel.
TEST(Pipeline, ThePixelCentreIsTimedWhenItsPixelsFired) {
  constexpr double kSpeed = 1000e-6;  // px/us
  std::vector<Event> events;
  for (int x = 20; x < 200; ++x) {
    for (int burst = 0; burst < 3; ++burst) {
      for (int y = 80; y <= 100; ++y) {
        const TimeUs t = static_cast<TimeUs>(x / kSpeed) + 500 * burst + (y - 80);
        events.push_back({t, static_cast<std::uint16_t>(x), static_cast<std::uint16_t>(y), 1});
      }
    }
  }
  std::stable_sort(events.begin(), events.end(), [](const Event& a, const Event& b) { return a.t < b.t; });
  Params p;
  p.packet_size = 1000;
  p.filter_window_us = 0;
  const CollectingSink out = run(events, p);
  ASSERT_GT(out.tracks.size(), 5u);
  double off = 0;
  for (const TrackUpdate& u : out.tracks) {
    // The pixels of column x fired first at x / speed (+ 10 us on average along the column).
    off += std::abs(u.zx - kSpeed * (static_cast<double>(u.t) - 10));
  }
  // A packet's first pixels may be a burst's later events (its first fell in the packet before).
  EXPECT_LT(off / static_cast<double>(out.tracks.size()), 0.1) << "the measurements lie on the edge's trajectory";
  p.time_by_pixels = false;  // timed at the mean of all its events
  double lag = 0;
  const CollectingSink by_events = run(events, p);
  ASSERT_GT(by_events.tracks.size(), 5u);
  for (const TrackUpdate& u : by_events.tracks) lag += kSpeed * (static_cast<double>(u.t) - 10) - u.zx;
  EXPECT_GT(lag / static_cast<double>(by_events.tracks.size()), 0.3) << "a burst's later events time the pixels later";
}

TEST(Pipeline, IsolatedNoiseIsLabelledNoise) {
  // Scattered single events, far apart in space or time: none has a recent neighbour.
  std::vector<Event> events;
  for (int i = 0; i < 500; ++i) {
    events.push_back({i * 20000, static_cast<std::uint16_t>((i * 37) % 240), static_cast<std::uint16_t>((i * 53) % 180), 1});
  }
  const CollectingSink out = run(events, Params{});
  ASSERT_EQ(out.events.size(), events.size());
  for (const LabelledEvent& e : out.events) EXPECT_EQ(e.label, kNoiseLabel);
  EXPECT_TRUE(out.tracks.empty());
}

TEST(Pipeline, NoiseAmongABlobIsLabelledNoise) {
  std::vector<int> which;
  auto events = test::blob_events({{120, 90}}, 40000, 0, 50000, kSensor, 5, &which);
  std::vector<bool> noise(events.size(), false);
  for (size_t i = 7; i < events.size(); i += 50) {
    events[i].x = static_cast<std::uint16_t>(10 + (i * 13) % 40);
    events[i].y = static_cast<std::uint16_t>(10 + (i * 7) % 30);
    noise[i] = true;
  }
  const CollectingSink out = run(events, Params{});
  int noise_labelled = 0, noise_total = 0;
  for (size_t i = 0; i < events.size(); ++i) {
    if (noise[i]) ++noise_total, noise_labelled += out.events[i].label == kNoiseLabel;
  }
  EXPECT_EQ(noise_labelled, noise_total);
}

// Background activity alone on a 640x480 sensor, at a rate below the noise check's 0.7 Hz a pixel:
// with the rate unscaled, noise that passed the filter gathers in kernel balls of 1,500 pixels
// and wider, holds clusters from packet to packet and confirms tracks; with the rate scaled to
// the sensor's pixels (types/params.h, filter_noise_count) the check asks two neighbours and no
// track is confirmed.
TEST(Pipeline, BackgroundActivityOnALargeSensorConfirmsNoTrack) {
  const SensorSize vga{640, 480};
  const double hz = 0.45;
  ASSERT_LT(hz, Params{}.filter_noise_hz);
  gen::Random rng(12);
  std::vector<Event> events;
  for (double t = 0; t < 1e6;) {
    t += rng.exponential(hz * vga.width * vga.height * 1e-6);
    events.push_back({static_cast<TimeUs>(t), static_cast<std::uint16_t>(rng.below(static_cast<std::uint64_t>(vga.width))),
                      static_cast<std::uint16_t>(rng.below(static_cast<std::uint64_t>(vga.height))),
                      static_cast<std::uint8_t>(rng.below(2))});
  }
  const auto confirmed_tracks = [&](const Params& p) {
    Pipeline pipeline(p, vga);
    CollectingSink sink;
    for (const Event& e : events) pipeline.push(e, sink);
    pipeline.finish(sink);
    EXPECT_EQ(sink.events.size(), events.size());
    std::set<std::int32_t> ids;
    for (const TrackUpdate& u : sink.tracks) {
      if (u.state == TrackState::kConfirmed) ids.insert(u.id);
    }
    return ids.size();
  };
  Params unscaled;
  unscaled.filter_noise_pixels = 0;
  EXPECT_GE(confirmed_tracks(unscaled), 10u) << "the scene no longer shows what the scaling is for";
  EXPECT_EQ(confirmed_tracks(Params{}), 0u);
}

// The first event of an edge has no neighbour's history to be judged by, so the filter drops it;
// with the look-ahead its neighbours that fire after it bring it back into its cluster, while an
// event whose neighbours stay quiet stays noise, and every label still leaves in input order.
TEST(Pipeline, LookAheadKeepsAnEdgesFirstEventAndStillDropsALoneOne) {
  std::vector<Event> events;
  TimeUs t = 0;
  for (int round = 0; round < 3; ++round) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) events.push_back({t++, static_cast<std::uint16_t>(100 + dx), static_cast<std::uint16_t>(50 + dy), 1});
    }
    if (round == 0) events.push_back({t++, 200, 150, 1});  // alone
  }
  Params cold;
  cold.filter_warm_up_us = 0;  // the stream's first events are judged too
  Params look = cold;
  look.filter_look_ahead_us = 10000;
  const CollectingSink plain = run(events, cold);
  const CollectingSink ahead = run(events, look);
  ASSERT_EQ(plain.events.size(), events.size());
  ASSERT_EQ(ahead.events.size(), events.size());
  for (size_t i = 0; i < events.size(); ++i) EXPECT_EQ(ahead.events[i].event.t, events[i].t);
  EXPECT_EQ(plain.events[0].label, kNoiseLabel);  // the edge's first event: no history
  EXPECT_NE(plain.events[1].label, kNoiseLabel);
  EXPECT_EQ(ahead.events[0].label, ahead.events[1].label);
  EXPECT_EQ(plain.events[9].label, kNoiseLabel);  // the lone event, either way
  EXPECT_EQ(ahead.events[9].label, kNoiseLabel);
}

// An event the filter dropped while a packet was open takes the label of the packet's labelled
// event beside it (--rescue-px): the first event of an edge, whose neighbours fire after it, and
// one two pixels off the edge with a reach of two; a lone event stays noise, and the labels
// still leave in input order.
TEST(Pipeline, ADroppedEventTakesTheLabelOfItsPacketsEventBesideIt) {
  std::vector<Event> events;
  TimeUs t = 0;
  const auto block = [&](std::uint16_t x, std::uint16_t y) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) events.push_back({t++, static_cast<std::uint16_t>(x + dx), static_cast<std::uint16_t>(y + dy), 1});
    }
  };
  block(30, 30);  // opens the packet
  const size_t edge_first = events.size();
  for (int round = 0; round < 3; ++round) block(100, 50);
  events.push_back({t++, 200, 150, 1});  // alone
  const size_t lone = events.size() - 1;
  events.push_back({t++, 103, 50, 1});   // two pixels right of the edge's last column
  const size_t two_off = events.size() - 1;
  for (int round = 0; round < 2; ++round) block(30, 30);
  const auto labels = [&](int rescue_px) {
    Params p;
    p.filter_warm_up_us = 0;  // the stream's first events are judged too
    p.rescue_px = rescue_px;
    const CollectingSink out = run(events, p);
    EXPECT_EQ(out.events.size(), events.size());
    std::vector<std::int32_t> l;
    for (size_t i = 0; i < out.events.size(); ++i) {
      EXPECT_EQ(out.events[i].event.t, events[i].t);
      l.push_back(out.events[i].label);
    }
    return l;
  };
  const std::vector<std::int32_t> off = labels(0), one = labels(1), two = labels(2);
  ASSERT_NE(one[edge_first + 1], kNoiseLabel);
  EXPECT_EQ(off[edge_first], kNoiseLabel);  // no history: dropped
  EXPECT_EQ(one[edge_first], one[edge_first + 1]);
  EXPECT_EQ(off[two_off], kNoiseLabel);
  EXPECT_EQ(one[two_off], kNoiseLabel);
  EXPECT_EQ(two[two_off], two[edge_first + 1]);
  for (const auto& l : {off, one, two}) EXPECT_EQ(l[lone], kNoiseLabel);
  // Nothing else moves: the rescued events join no cluster.
  for (size_t i = 0; i < events.size(); ++i) {
    if (i != edge_first && i != two_off) {
      EXPECT_EQ(one[i], off[i]) << i;
    }
  }
}

// While no packet is open, a dropped event waits out its look-ahead before it leaves as noise.
TEST(Pipeline, LookAheadHoldsADroppedEventOnlyForItsLookAhead) {
  Params look;
  look.filter_warm_up_us = 0;  // the stream's first events are judged too
  look.filter_look_ahead_us = 10000;
  Pipeline pipeline(look, kSensor);
  CollectingSink sink;
  pipeline.push({0, 10, 10, 1}, sink);
  pipeline.push({10000, 100, 100, 1}, sink);  // its look-ahead is not over yet
  EXPECT_TRUE(sink.events.empty());
  pipeline.push({10001, 200, 100, 1}, sink);  // now it is: the first leaves
  ASSERT_EQ(sink.events.size(), 1u);
  EXPECT_EQ(sink.events[0].event.t, 0);
  EXPECT_EQ(sink.events[0].label, kNoiseLabel);
  pipeline.finish(sink);
  EXPECT_EQ(sink.events.size(), 3u);
}

TEST(Pipeline, LaterPacketsLabelTheirOwnEvents) {
  // The authors' code read events of later packets from the wrong index. A blob that jumps
  // between packets must be labelled where it is, in every packet.
  Params p;
  p.packet_size = 200;
  std::vector<Event> events;
  auto a = test::blob_events({{40, 40}}, 40000, 0, 20000, kSensor, 7);
  auto b = test::blob_events({{200, 140}}, 40000, 20000, 20000, kSensor, 8);
  events.insert(events.end(), a.begin(), a.end());
  events.insert(events.end(), b.begin(), b.end());
  const CollectingSink out = run(events, p);
  ASSERT_GE(out.packets.size(), 6u);
  for (const TrackUpdate& u : out.tracks) {
    const bool near_a = std::hypot(u.x - 40, u.y - 40) < 5, near_b = std::hypot(u.x - 200, u.y - 140) < 5;
    EXPECT_TRUE(near_a || near_b) << "track at " << u.x << "," << u.y;
  }
}

TEST(Pipeline, APartialLastPacketMakesNoClusterAtTheOrigin) {
  // The authors left unfilled feature columns at zero, which formed a cluster at (0, 0).
  Params p;
  p.packet_size = 256;
  p.confirm_hits = 1;
  p.min_cluster_size = 1;
  const auto events = test::blob_events({{150, 120}}, 40000, 0, 2000, kSensor, 9);  // 80 events
  const CollectingSink out = run(events, p);
  ASSERT_EQ(out.packets.size(), 1u);
  EXPECT_LT(out.packets[0].events, 256);
  for (const TrackUpdate& u : out.tracks) EXPECT_GT(std::hypot(u.x, u.y), 100.0);
}

TEST(Pipeline, PacketSpanLimitClosesPacketsEarly) {
  Params p;
  p.packet_max_span_us = 1000;
  const auto events = test::blob_events({{100, 100}}, 20000, 0, 20000, kSensor, 10);
  const CollectingSink out = run(events, p);
  for (const PacketSummary& s : out.packets) EXPECT_LE(s.t_last - s.t_first, 1000);
  EXPECT_GE(out.packets.size(), 19u);
}

// A vertical bar, rows 20 to 160, whose edge crosses a column every `us_per_px` from x = 20 to
// x = 200: each pixel fires once as the edge reaches it, its column's pixels in order at once.
std::vector<Event> moving_bar(TimeUs us_per_px) {
  std::vector<Event> events;
  for (int x = 20; x <= 200; ++x) {
    for (int y = 20; y <= 160; ++y) {
      events.push_back({static_cast<TimeUs>(x - 20) * us_per_px, static_cast<std::uint16_t>(x), static_cast<std::uint16_t>(y), 1});
    }
  }
  return events;
}

TimeUs longest_span(const CollectingSink& out) {
  TimeUs longest = 0;
  for (const PacketSummary& s : out.packets) longest = std::max(longest, s.t_last - s.t_first);
  return longest;
}

TEST(Pipeline, ASlowEdgeStretchesThePacketSpanAndAFastOneDoesNot) {
  Params p;
  p.packet_max_span_us = 33333;
  // 40 px/s: 141 events every 25 ms, whose time map slopes 25 ms a pixel across the bar.
  const auto slow = moving_bar(25000);
  EXPECT_LE(longest_span(run(slow, p)), 33333);
  p.packet_span_edge_px = 5;
  // The span to move 5 px at 40 px/s is 125 ms, within 4 times 33,333 us; the packet closes
  // when the next event would reach past it, so its last event lies a column (25 ms) earlier.
  const CollectingSink stretched = run(slow, p);
  EXPECT_GE(longest_span(stretched), 100000);
  EXPECT_LE(longest_span(stretched), 125000);
  // To move 10 px the span would be 250 ms: it stops at 4 times 33,333 us.
  p.packet_span_edge_px = 10;
  const CollectingSink capped = run(slow, p);
  EXPECT_GE(longest_span(capped), 100000);
  EXPECT_LE(longest_span(capped), 4 * 33333);
  // 1,000 px/s: 10 px take 10 ms, and packets keep the usual span. The packets are large enough
  // that only the span closes them (the bar's 25,521 events take 180 ms).
  p.packet_size = 30000;
  const CollectingSink fast = run(moving_bar(1000), p);
  EXPECT_LE(longest_span(fast), 33333);
  EXPECT_GE(fast.packets.size(), 5u);
}

}  // namespace
}  // namespace evms::golden
