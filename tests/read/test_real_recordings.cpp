// Every reader against the reference figures of ../shared/data/real/README.md, which were
// decoded independently from the format specifications. The expected values are parsed from
// that README at test time.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>

#include "tests/support/read_all.h"

namespace evms::test {
namespace {

struct Reference {
  std::string file;
  std::int64_t events = 0, t_first = 0, t_last = 0, on = 0, off = 0;
  int x_min = 0, x_max = 0, y_min = 0, y_max = 0;
  struct First {
    std::string t_suffix;
    int x, y, p;
  };
  std::vector<First> first;
};

std::int64_t number(std::string s) {
  s.erase(std::remove(s.begin(), s.end(), ','), s.end());
  return std::stoll(s);
}

std::vector<std::string> cells(const std::string& row) {
  std::vector<std::string> out;
  std::stringstream ss(row);
  std::string cell;
  std::getline(ss, cell, '|');  // before the first bar
  while (std::getline(ss, cell, '|')) {
    const size_t b = cell.find_first_not_of(' '), e = cell.find_last_not_of(' ');
    out.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
  }
  return out;
}

std::vector<Reference> references(const std::string& dir) {
  std::ifstream readme(dir + "/README.md");
  std::vector<Reference> out;
  std::string line;
  const std::regex range(R"(([\d,]+)\s*\.\.\s*([\d,]+))");
  const std::regex first(R"(\(([.\d]+),(\d+),(\d+),(\d)\))");
  while (std::getline(readme, line)) {
    const auto c = cells(line);
    if (c.size() < 9 || c[0] == "file" || c[0].find("---") != std::string::npos) continue;
    Reference r;
    r.file = c[0];
    r.events = number(c[3]);
    std::smatch m;
    if (!std::regex_search(c[4], m, range)) continue;
    r.t_first = number(m[1]), r.t_last = number(m[2]);
    if (!std::regex_search(c[5], m, range)) continue;
    r.x_min = static_cast<int>(number(m[1])), r.x_max = static_cast<int>(number(m[2]));
    if (!std::regex_search(c[6], m, range)) continue;
    r.y_min = static_cast<int>(number(m[1])), r.y_max = static_cast<int>(number(m[2]));
    const size_t slash = c[7].find('/');
    r.on = number(c[7].substr(0, slash)), r.off = number(c[7].substr(slash + 1));
    for (std::sregex_iterator it(c[8].begin(), c[8].end(), first), end; it != end; ++it) {
      std::string t = (*it)[1];
      t.erase(0, t.find_first_not_of('.'));
      r.first.push_back({t, std::stoi((*it)[2]), std::stoi((*it)[3]), std::stoi((*it)[4])});
    }
    out.push_back(r);
  }
  return out;
}

TEST(RealRecordings, EveryReaderReproducesTheReferenceFigures) {
  const std::string dir = shared_data_dir();
  if (dir.empty()) GTEST_SKIP() << "../shared/data/real is absent: the real-recording reference test needs it";
  const auto refs = references(dir);
  ASSERT_GE(refs.size(), 4u) << "could not parse the reference table of " << dir << "/README.md";
  for (const Reference& r : refs) {
    SCOPED_TRACE(r.file);
    const auto events = read_all(dir + "/" + r.file);
    ASSERT_EQ(static_cast<std::int64_t>(events.size()), r.events);
    EXPECT_EQ(events.front().t, r.t_first);
    EXPECT_EQ(events.back().t, r.t_last);
    std::int64_t on = 0;
    int x0 = 1 << 20, x1 = -1, y0 = 1 << 20, y1 = -1;
    for (const Event& e : events) {
      on += e.p;
      x0 = std::min<int>(x0, e.x), x1 = std::max<int>(x1, e.x);
      y0 = std::min<int>(y0, e.y), y1 = std::max<int>(y1, e.y);
    }
    EXPECT_EQ(on, r.on);
    EXPECT_EQ(static_cast<std::int64_t>(events.size()) - on, r.off);
    EXPECT_EQ(x0, r.x_min);
    EXPECT_EQ(x1, r.x_max);
    EXPECT_EQ(y0, r.y_min);
    EXPECT_EQ(y1, r.y_max);
    ASSERT_EQ(r.first.size(), 3u);
    for (size_t i = 0; i < r.first.size(); ++i) {
      const std::string t = std::to_string(events[i].t);
      EXPECT_EQ(t.substr(t.size() - std::min(t.size(), r.first[i].t_suffix.size())), r.first[i].t_suffix) << "event " << i;
      EXPECT_EQ(events[i].x, r.first[i].x) << "event " << i;
      EXPECT_EQ(events[i].y, r.first[i].y) << "event " << i;
      EXPECT_EQ(events[i].p, r.first[i].p) << "event " << i;
    }
    for (size_t i = 1; i < events.size(); ++i) ASSERT_LE(events[i - 1].t, events[i].t) << "time order at " << i;
  }
}

TEST(RealRecordings, SensorSizesComeFromTheHeaders) {
  const std::string dir = shared_data_dir();
  if (dir.empty()) GTEST_SKIP() << "../shared/data/real is absent";
  EXPECT_EQ(read::open_source(dir + "/dvxplorer_indoor.aedat4", {})->info().sensor, (SensorSize{320, 240}));
  EXPECT_EQ(read::open_source(dir + "/gen3_moving_blob.evt2.raw", {})->info().sensor, (SensorSize{640, 480}));
  EXPECT_EQ(read::open_source(dir + "/gen41_dense_scene.evt3.raw", {})->info().sensor, (SensorSize{1280, 720}));
}

}  // namespace
}  // namespace evms::test
