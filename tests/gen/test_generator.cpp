#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "host/gen/family.h"
#include "host/gen/scene_generator.h"
#include "host/read/generated_source.h"
#include "host/read/input_error.h"

namespace evms::gen {
namespace {

struct Scene {
  std::vector<LabelledEvent> events;
  std::vector<TruthSample> truth;
};

Scene generate(SceneConfig c) {
  SceneGenerator g(c);
  Scene s;
  while (g.next(s.events, s.truth)) {
  }
  return s;
}

SceneConfig short_scene(Motion m, std::uint64_t seed) {
  SceneConfig c;
  c.motion = m;
  c.seed = seed;
  c.duration_s = 0.3;
  return c;
}

TEST(SceneGenerator, TheSameSeedGivesTheSameScene) {
  for (Motion m : {Motion::kTranslation, Motion::kRotation, Motion::kSixDof}) {
    const Scene a = generate(short_scene(m, 11)), b = generate(short_scene(m, 11));
    ASSERT_EQ(a.events.size(), b.events.size());
    EXPECT_TRUE(a.events == b.events);
    ASSERT_EQ(a.truth.size(), b.truth.size());
    for (size_t i = 0; i < a.truth.size(); ++i) {
      EXPECT_EQ(a.truth[i].x, b.truth[i].x);
      EXPECT_EQ(a.truth[i].object, b.truth[i].object);
    }
  }
}

TEST(SceneGenerator, ADifferentSeedGivesADifferentScene) {
  const Scene a = generate(short_scene(Motion::kRotation, 1)), b = generate(short_scene(Motion::kRotation, 2));
  EXPECT_FALSE(a.events == b.events);
}

TEST(SceneGenerator, EventsAreOrderedInsideTheSensorAndLabelled) {
  const Scene s = generate(short_scene(Motion::kSixDof, 3));
  ASSERT_GT(s.events.size(), 10000u);
  std::map<int, int> per_label;
  for (size_t i = 0; i < s.events.size(); ++i) {
    const Event& e = s.events[i].event;
    if (i) {
      ASSERT_LE(s.events[i - 1].event.t, e.t);
    }
    ASSERT_LT(e.x, 240);
    ASSERT_LT(e.y, 180);
    ++per_label[s.events[i].label];
  }
  EXPECT_GE(per_label.size(), 6u) << "several objects and noise";
  EXPECT_GT(per_label[kNoiseLabel], 0);
  // 0.2 Hz a pixel over 0.3 s on 43,200 pixels is about 2,600 noise events.
  EXPECT_NEAR(per_label[kNoiseLabel], 0.2 * 0.3 * 240 * 180, 300);
}

TEST(SceneGenerator, ObjectEventsLieOnTheirObjectNearItsTrueCentre) {
  const Scene s = generate(short_scene(Motion::kTranslation, 5));
  // Truth every ms per visible object; events of an object lie within its outline's reach.
  std::map<std::pair<TimeUs, int>, TruthSample> truth;
  for (const TruthSample& t : s.truth) truth[{t.t, t.object}] = t;
  int checked = 0, near = 0;
  for (const LabelledEvent& e : s.events) {
    if (e.label < 0) continue;
    auto it = truth.find({(e.event.t / 1000) * 1000, e.label});
    if (it == truth.end()) continue;
    ++checked;
    near += std::hypot(e.event.x - it->second.x, e.event.y - it->second.y) < 30;
  }
  ASSERT_GT(checked, 5000);
  EXPECT_GT(near, checked * 99 / 100);
}

TEST(SceneGenerator, SpeedScalesTheMotion) {
  SceneConfig slow = short_scene(Motion::kTranslation, 4), fast = slow;
  fast.speed = 3.0;
  fast.noise_hz = slow.noise_hz = 0;
  // Faster motion crosses more edges per second: more events in the same time.
  EXPECT_GT(generate(fast).events.size(), 2 * generate(slow).events.size());
}

TEST(SceneFamily, AMemberIsItsTypeAndSeedAndNothingElse) {
  const SceneConfig a = family_scene("crossing", 7), b = family_scene("crossing", 7);
  EXPECT_EQ(a.seed, b.seed);
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.objects, b.objects);
  EXPECT_NE(family_scene("crossing", 8).seed, a.seed);
  EXPECT_NE(family_scene("rotation", 7).seed, a.seed) << "seed 7 of two types are unrelated scenes";
  EXPECT_THROW(family_scene("spin", 1), std::invalid_argument);
}

// Pins replace the sensor, the shape count and the noise of a member; its other draws stay the
// seed's, and the shapes' sizes follow the pinned sensor.
TEST(SceneFamily, PinsReplaceOnlyWhatTheyName) {
  for (std::uint64_t seed : {1000, 1001, 1002, 1003}) {
    const SceneConfig drawn = family_scene("rotation", seed);
    const SceneConfig pinned = family_scene("rotation", seed, {240, 180, 7, 0.1});
    EXPECT_EQ(pinned.width, 240);
    EXPECT_EQ(pinned.height, 180);
    EXPECT_EQ(pinned.objects, 7);
    EXPECT_DOUBLE_EQ(pinned.noise_hz, 0.1);
    EXPECT_DOUBLE_EQ(pinned.size_max_px, 60.0);
    EXPECT_DOUBLE_EQ(pinned.duration_s, 1.0);
    EXPECT_EQ(pinned.seed, drawn.seed);
    EXPECT_DOUBLE_EQ(pinned.speed, drawn.speed);
    EXPECT_DOUBLE_EQ(pinned.threshold_sigma, drawn.threshold_sigma);
    EXPECT_EQ(pinned.hot_pixels, drawn.hot_pixels);
  }
  // A zero noise pin is a noiseless member; no pins is the drawn member.
  EXPECT_DOUBLE_EQ(family_scene("still", 5, {0, 0, 0, 0.0}).noise_hz, 0.0);
  EXPECT_DOUBLE_EQ(family_scene("still", 5, {}).noise_hz, family_scene("still", 5).noise_hz);
  // Crossing members keep no more movers than shapes.
  const SceneConfig two = family_scene("crossing", 1002, {0, 0, 2, -1});
  EXPECT_EQ(two.objects, 2);
  EXPECT_LE(two.movers, 2);
}

TEST(SceneFamily, AFamilyUriTakesThePins) {
  const SceneConfig c = read::parse_scene_uri("gen://family/rotation?seed=1001&width=240&height=180&objects=7&noise-hz=0.1");
  const SceneConfig d = family_scene("rotation", 1001, {240, 180, 7, 0.1});
  EXPECT_EQ(c.seed, d.seed);
  EXPECT_EQ(c.width, 240);
  EXPECT_EQ(c.objects, 7);
  EXPECT_DOUBLE_EQ(c.noise_hz, 0.1);
  for (const char* bad : {"gen://family/rotation?width=240", "gen://family/rotation?width=32&height=32",
                          "gen://family/rotation?objects=17", "gen://family/rotation?noise-hz=-1", "gen://family/rotation?size=3"}) {
    EXPECT_THROW(read::parse_scene_uri(bad), read::InputError) << bad;
  }
}

// A scene's numbers are finite and in the ranges `evms gen` takes, each refused with what is
// wrong: a NaN passes every comparison, and an infinite duration never ends.
TEST(SceneFamily, AUriRefusesNumbersThatAreNotFiniteOrOutOfRange) {
  const std::pair<const char*, const char*> cases[] = {
      {"gen://rotation?duration-s=inf", "gen://rotation?duration-s=inf: 'duration-s' needs a number, got 'inf'"},
      {"gen://rotation?speed=nan", "gen://rotation?speed=nan: 'speed' needs a number, got 'nan'"},
      {"gen://rotation?noise-hz=nan", "gen://rotation?noise-hz=nan: 'noise-hz' needs a number, got 'nan'"},
      {"gen://rotation?noise-hz=-1", "gen://rotation?noise-hz=-1: noise-hz must be from 0 to 1000"},
      {"gen://rotation?speed=200", "gen://rotation?speed=200: speed must be from 0.01 to 100, the sensor between 64 and 4096 px, and movers 0 to 9"},
      {"gen://family/still?duration-s=4000", "gen://family/still?duration-s=4000: duration-s must be from 0.001 to 3600"},
      {"gen://family/still?noise-hz=inf", "gen://family/still?noise-hz=inf: 'noise-hz' needs a number, got 'inf'"},
  };
  for (const auto& [uri, message] : cases) {
    try {
      read::parse_scene_uri(uri);
      ADD_FAILURE() << uri << " was taken";
    } catch (const read::InputError& e) {
      EXPECT_STREQ(e.what(), message);
    }
  }
  EXPECT_DOUBLE_EQ(read::parse_scene_uri("gen://rotation?duration-s=3600&speed=100&noise-hz=1000").duration_s, 3600.0);
}

TEST(SceneFamily, TheSplitsAreDisjointBySeed) {
  EXPECT_EQ(split_of(split_seed(Split::kTuning, 0)), Split::kTuning);
  EXPECT_EQ(split_of(split_seed(Split::kTuning, 998)), Split::kTuning);
  EXPECT_EQ(split_of(split_seed(Split::kValidation, 0)), Split::kValidation);
}

TEST(SceneFamily, MembersSpanWhatTheFamilyPromises) {
  std::set<int> widths, counts;
  double speed_lo = 1e9, speed_hi = 0, noise_lo = 1e9, noise_hi = 0;
  int hot = 0, moving = 0, crossing = 0, low_contrast = 0;
  for (const char* type : family_types()) {
    for (std::uint64_t seed = 1; seed <= 40; ++seed) {
      const SceneConfig c = family_scene(type, seed);
      widths.insert(c.width);
      counts.insert(c.objects);
      speed_lo = std::min(speed_lo, c.speed), speed_hi = std::max(speed_hi, c.speed);
      noise_lo = std::min(noise_lo, c.noise_hz), noise_hi = std::max(noise_hi, c.noise_hz);
      hot += c.hot_pixels > 0, moving += c.movers > 0, crossing += c.crossing, low_contrast += c.low_contrast_share > 0;
      EXPECT_GE(c.objects, 1);
      EXPECT_LE(c.objects, 12);
      if (std::string(type) == "still") {
        EXPECT_GE(c.movers, 1);
      }
    }
  }
  EXPECT_EQ(widths, (std::set<int>{128, 240, 346, 640}));
  EXPECT_GE(counts.size(), 11u);
  EXPECT_LT(speed_lo, 0.1) << "crossing drifts slowly";
  EXPECT_GT(speed_hi, 3.0);
  EXPECT_LT(noise_lo, 0.1);
  EXPECT_GT(noise_hi, 1.5);
  EXPECT_GT(hot, 100);
  EXPECT_GT(moving, 60);
  EXPECT_EQ(crossing, 40);
  EXPECT_EQ(low_contrast, 280);
}

TEST(SceneFamily, ShapesOfEveryKindAppearAndHotPixelsFireNoise) {
  std::set<std::string> kinds;
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    SceneConfig c = family_scene("still", seed);
    c.duration_s = 0.001;
    SceneGenerator g(c);
    for (int i = 0; i < g.object_count(); ++i) kinds.insert(g.object_name(i));
  }
  for (const char* kind : {"bar", "L", "cross", "ring", "chevron", "circle", "star"}) EXPECT_TRUE(kinds.count(kind)) << kind;
  // One hot pixel at 500 Hz and no background activity: about 150 noise events on one pixel
  // in 0.3 s (the faint rims of shapes give the few other events labelled -1).
  SceneConfig c = short_scene(Motion::kTranslation, 9);
  c.noise_hz = 0;
  c.hot_pixels = 1;
  c.hot_pixel_hz = 500;
  const Scene s = generate(c);
  std::map<std::pair<int, int>, int> noise_pixels;
  int noise = 0;
  for (const LabelledEvent& e : s.events) {
    if (e.label != kNoiseLabel) continue;
    ++noise;
    ++noise_pixels[{e.event.x, e.event.y}];
  }
  const auto hot = std::max_element(noise_pixels.begin(), noise_pixels.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
  EXPECT_NEAR(hot->second, 0.3 * 500, 40);
  EXPECT_LT(noise - hot->second, hot->second);
}

TEST(SceneFamily, CrossingMoversPassOverOtherShapes) {
  // Some millisecond has two objects' true centres closer than their radii (240x180 members).
  for (std::uint64_t seed : {1001, 1003, 1004}) {
    const SceneConfig c = family_scene("crossing", seed);
    ASSERT_EQ(c.width, 240);
    const Scene s = generate(c);
    bool overlap = false;
    std::map<TimeUs, std::vector<TruthSample>> by_ms;
    for (const TruthSample& t : s.truth) by_ms[t.t].push_back(t);
    for (const auto& [t, v] : by_ms) {
      for (size_t a = 0; a < v.size(); ++a) {
        for (size_t b = a + 1; b < v.size(); ++b) overlap |= std::hypot(v[a].x - v[b].x, v[a].y - v[b].y) < v[a].radius + v[b].radius;
      }
    }
    EXPECT_TRUE(overlap) << "seed " << seed;
  }
}

}  // namespace
}  // namespace evms::gen
