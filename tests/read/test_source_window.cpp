// --start-us, --duration-us, --limit, --roi and --hot-pixels: what of a source a run takes,
// with everything left out of the window's inside counted.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "host/read/source_window.h"
#include "tests/support/encoders.h"
#include "tests/support/read_all.h"
#include "tests/support/scenes.h"

namespace evms::test {
namespace {


std::string with_sensor(const std::vector<Event>& events) { return "# sensor 240x180\n" + csv(events); }

std::map<std::string, std::int64_t> skipped_of(read::EventSource& s) {
  std::map<std::string, std::int64_t> m;
  for (const auto& [k, n] : s.skipped()) m[k.substr(0, k.find(':'))] = n;
  return m;
}

TEST(SourceWindow, StartDurationAndLimitCutTheStream) {
  TempDir d;
  const std::vector<Event> events = sample_events(3000, kSensor);
  const std::string in = d.write("in.csv", with_sensor(events));
  read::SourceOptions o;
  o.window.start_us = 20000;
  o.window.duration_us = 30000;
  std::vector<Event> expected;
  for (const Event& e : events) {
    if (e.t >= events[0].t + 20000 && e.t < events[0].t + 50000) expected.push_back(e);
  }
  ASSERT_FALSE(expected.empty());
  ASSERT_LT(expected.size(), events.size());
  EXPECT_EQ(read_all(in, o), expected);
  o.window.limit = 17;
  EXPECT_EQ(read_all(in, o), std::vector<Event>(expected.begin(), expected.begin() + 17));
}

TEST(SourceWindow, RoiCropsAndCountsWhatItLeavesOut) {
  TempDir d;
  const std::vector<Event> events = sample_events(3000, kSensor);
  const std::string in = d.write("in.csv", with_sensor(events));
  read::SourceOptions o;
  o.window.roi = read::parse_roi("50,40,100,60");
  auto source = read::open_source(in, o);
  EXPECT_EQ(source->info().sensor, (SensorSize{100, 60}));
  std::vector<Event> expected;
  for (Event e : events) {
    if (e.x >= 50 && e.x < 150 && e.y >= 40 && e.y < 100) e.x = static_cast<std::uint16_t>(e.x - 50), e.y = static_cast<std::uint16_t>(e.y - 40), expected.push_back(e);
  }
  std::vector<Event> got;
  read_into(*source, got, 256);
  EXPECT_EQ(got, expected);
  EXPECT_EQ(skipped_of(*source)["events outside --roi"], static_cast<std::int64_t>(events.size() - expected.size()));
  o.window.roi = read::parse_roi("200,0,41,10");
  EXPECT_THROW(read::open_source(in, o), std::invalid_argument);
  for (const char* bad : {"1,2,3", "1,2,3,0", "a,2,3,4", "1,2,3,4,5", "-1,2,3,4"}) EXPECT_THROW(read::parse_roi(bad), std::invalid_argument) << bad;
}

TEST(SourceWindow, HotPixelsFromAListOrFoundAlone) {
  TempDir d;
  std::vector<Event> events = sample_events(3000, kSensor);
  // One pixel firing every 50 us throughout, far more than any pixel the dots pass over.
  const TimeUs first = events.front().t, last = events.back().t;
  for (TimeUs t = first; t <= last; t += 50) events.push_back({t, 7, 9, 1});
  std::stable_sort(events.begin(), events.end(), [](const Event& a, const Event& b) { return a.t < b.t; });
  const std::string in = d.write("in.csv", with_sensor(events));
  std::vector<Event> cool;
  std::copy_if(events.begin(), events.end(), std::back_inserter(cool), [](const Event& e) { return !(e.x == 7 && e.y == 9); });

  read::SourceOptions o;
  o.window.hot_pixels = "auto";
  auto source = read::open_source(in, o);
  std::vector<Event> got;
  read_into(*source, got, 512);
  EXPECT_EQ(got, cool);
  ASSERT_EQ(source->skipped().size(), 1u);
  EXPECT_EQ(source->skipped()[0].first, "events of 1 hot pixel masked: (7,9)");
  EXPECT_EQ(source->skipped()[0].second, static_cast<std::int64_t>(events.size() - cool.size()));

  o.window.hot_pixels = d.write("hot.txt", std::string("# x,y\n7,9\n\n"));
  EXPECT_EQ(read_all(in, o), cool);
  o.window.hot_pixels = d.write("bad.txt", std::string("7,9\n7;9\n"));
  const std::string message = read_error(in, o);
  EXPECT_EQ(message, o.window.hot_pixels + ": line 2: expected 'x,y', got '7;9'");
}

}  // namespace
}  // namespace evms::test
