#include <gtest/gtest.h>

#include <map>

#include "host/gen/scene_generator.h"

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

}  // namespace
}  // namespace evms::gen
