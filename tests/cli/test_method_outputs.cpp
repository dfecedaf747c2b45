// What the method's outputs promise a user, end to end through evms: every label is a track of
// tracks.csv, the sensor size survives evms's own files, presets and refusals are one line.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "tests/support/command.h"
#include "tests/support/encoders.h"
#include "tests/support/read_all.h"

namespace evms::test {
namespace {

std::vector<std::vector<std::string>> csv_rows(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#' || !std::isdigit(static_cast<unsigned char>(line[0]))) continue;
    std::vector<std::string> row;
    std::stringstream fields(line);
    for (std::string f; std::getline(fields, f, ',');) row.push_back(f);
    rows.push_back(row);
  }
  return rows;
}

// Runs evms on `source` and checks that every label of events.csv is -1 or a track of tracks.csv
// with a row in the same packet's time range; returns the number of labelled events.
std::int64_t expect_labels_are_tracks(const TempDir& dir, const std::string& source, const std::string& options = "") {
  const std::string out = dir.path("out" + std::to_string(std::hash<std::string>{}(source + options)));
  const auto r = run_command(evms_binary() + " run \"" + source + "\" --quiet --out " + out + " " + options);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  std::set<std::int64_t> track_ids;
  for (const auto& row : csv_rows(out + "/tracks.csv")) {
    EXPECT_TRUE(row[2] == "tentative" || row[2] == "confirmed") << row[2];
    track_ids.insert(std::stoll(row[1]));
  }
  std::int64_t labelled = 0;
  std::set<std::int64_t> missing;
  for (const auto& row : csv_rows(out + "/events.csv")) {
    const std::int64_t label = std::stoll(row[4]);
    if (label < 0) continue;
    ++labelled;
    if (!track_ids.count(label)) missing.insert(label);
  }
  EXPECT_TRUE(missing.empty()) << source << ": " << missing.size() << " labels have no row in tracks.csv, e.g. " << *missing.begin();
  return labelled;
}

TEST(MethodOutputs, EveryLabelIsATrackOfTracksCsv) {
  TempDir dir;
  EXPECT_GT(expect_labels_are_tracks(dir, "gen://family/crossing?seed=1006"), 1000);
  EXPECT_GT(expect_labels_are_tracks(dir, "gen://rotation?duration-s=0.3"), 1000);
}

TEST(MethodOutputs, EveryLabelIsATrackOnTheRealRecordings) {
  const std::string real = shared_data_dir();
  if (real.empty()) GTEST_SKIP() << "../shared/data/real is absent";
  TempDir dir;
  for (const char* f : {"dvxplorer_indoor.aedat4", "gen3_moving_blob.evt2.raw", "gen41_dense_scene.evt3.raw", "atis_ncars_sample.dat"}) {
    EXPECT_GT(expect_labels_are_tracks(dir, real + "/" + f), 0) << f;
  }
}

// With the least density tested on each mode (the default) and on the linked sets
// (--density-after-links true, where a set must also hold a dense ball's events: without that,
// 36 scattered events beside the blob make two tentative tracks).
TEST(MethodOutputs, TheSingleBlobOfTheGen3RecordingKeepsOneId) {
  const std::string real = shared_data_dir();
  if (real.empty()) GTEST_SKIP() << "../shared/data/real is absent";
  TempDir dir;
  for (const std::string& density : {std::string(), std::string(" --density-after-links true")}) {
    SCOPED_TRACE(density);
    const auto r = run_command(evms_binary() + " run " + real + "/gen3_moving_blob.evt2.raw --quiet --out " + dir.path("o") + density);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    // In every 4 ms of the 50 ms recording the ID most events carry is the same one.
    std::map<std::int64_t, std::map<std::int64_t, std::int64_t>> votes;  // window -> id -> events
    std::set<std::int64_t> ids_seen;
    std::int64_t t0 = -1;
    for (const auto& row : csv_rows(dir.path("o/events.csv"))) {
      const std::int64_t t = std::stoll(row[0]), label = std::stoll(row[4]);
      if (t0 < 0) t0 = t;
      if (label >= 0) ++votes[(t - t0) / 4000][label], ids_seen.insert(label);
    }
    std::set<std::int64_t> dominant;
    for (const auto& [window, ids] : votes) {
      dominant.insert(std::max_element(ids.begin(), ids.end(), [](const auto& a, const auto& b) { return a.second < b.second; })->first);
    }
    EXPECT_GE(votes.size(), 12u);
    EXPECT_EQ(dominant.size(), 1u) << "the blob changed its ID";
    // No event carries another ID: a climb that ends within a bandwidth of the blob's mode, among
    // the blob's trailing events, joins the blob (--merge-radius) instead of starting a track.
    EXPECT_EQ(ids_seen.size(), 1u) << "events outside the blob's track";
    // And the blob is the one confirmed track: its scattered events make no track of their own.
    std::set<std::string> confirmed;
    for (const auto& row : csv_rows(dir.path("o/tracks.csv"))) {
      if (row[2] == "confirmed") confirmed.insert(row[1]);
    }
    EXPECT_EQ(confirmed.size(), 1u);
  }
}

TEST(MethodOutputs, TheSensorSizeSurvivesEvmssOwnFiles) {
  TempDir dir;
  // A 346x260 family member: written with its size, read back with it.
  const auto gen = run_command(evms_binary() + " gen --family translation --seed 2 --duration-s 0.1 --out " + dir.path("g"));
  ASSERT_EQ(gen.exit_code, 0) << gen.err;
  ASSERT_NE(gen.out.find("346x260"), std::string::npos) << gen.out;
  const auto first = run_command(evms_binary() + " run " + dir.path("g/events.txt") + " --quiet --out " + dir.path("a"));
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_NE(first.out.find("(RPG events.txt, 346x260)"), std::string::npos) << first.out;
  const auto again = run_command(evms_binary() + " run " + dir.path("a/events.csv") + " --quiet --out " + dir.path("b"));
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.out.find("346x260)"), std::string::npos) << again.out;
  EXPECT_TRUE(same_text(read_file(dir.path("a/events.csv")), read_file(dir.path("b/events.csv")))) << "the same size, the same labels";
}

TEST(MethodOutputs, ATextFileWithoutASizeSaysWhatWasAssumed) {
  TempDir dir;
  // The smallest usual sensor that holds every row: 240x180 for x up to 239 and y up to 179,
  // 346x260 beyond.
  const std::string in = dir.write("plain.txt", "0.000001 10 10 1\n0.000002 239 179 1\n");
  const auto r = run_command(evms_binary() + " run " + in + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("240x180 assumed: the file does not say; the smallest usual sensor that holds every event"), std::string::npos) << r.out;
  const auto info = run_command(evms_binary() + " info " + in);
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("sensor      240x180 (assumed: the file does not say"), std::string::npos) << info.out;
  const auto wider = run_command(evms_binary() + " info " + dir.write("wider.csv", "t,x,y,p\n1,10,10,1\n2,345,259,0\n"));
  ASSERT_EQ(wider.exit_code, 0) << wider.err;
  EXPECT_NE(wider.out.find("sensor      346x260 (assumed: the file does not say"), std::string::npos) << wider.out;
  const auto bad = run_command(evms_binary() + " run " + dir.write("bad.txt", "# sensor 240by180\n0.1 1 1 1\n") + " --quiet");
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("line 1: bad sensor comment"), std::string::npos) << bad.err;
}

TEST(MethodOutputs, TheRtlRefusesTheMethodItLacksInOneLine) {
  const auto r = run_command(evms_binary() + " run gen://rotation?duration-s=0.05 --backend rtl --coast-packets 3 --quiet");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("the RTL core does not implement --coast-packets 3 (add --coast-packets 0)"), std::string::npos) << r.err;
  // The boards' builds do not hold the edge join, which they run without unless told it.
  const auto board_edges = run_command(evms_binary() + " run gen://rotation?duration-s=0.05 --backend rtl --core arty --edge-join 5 --quiet");
  EXPECT_EQ(board_edges.exit_code, 1);
  EXPECT_EQ(std::count(board_edges.err.begin(), board_edges.err.end(), '\n'), 1) << board_edges.err;
  EXPECT_NE(board_edges.err.find("the RTL build 'arty' does not hold the edge join, not --edge-join 5 (add --edge-join 0)"), std::string::npos)
      << board_edges.err;
  // Nor the polarity split.
  const auto split = run_command(evms_binary() + " run gen://rotation?duration-s=0.05 --backend rtl --core arty --split-balance 0.3 --quiet");
  EXPECT_EQ(split.exit_code, 1);
  EXPECT_NE(split.err.find("the RTL build 'arty' does not hold the polarity split, not --split-balance 0.3 (add --split-balance 0)"), std::string::npos)
      << split.err;
  // Nor the polarity midpoint.
  const auto midpoint = run_command(evms_binary() + " run gen://rotation?duration-s=0.05 --backend rtl --core arty --measure polarity-midpoint --quiet");
  EXPECT_EQ(midpoint.exit_code, 1);
  EXPECT_NE(midpoint.err.find("the RTL build 'arty' does not hold the polarity midpoint, not --measure polarity-midpoint (add --measure centroid)"),
            std::string::npos)
      << midpoint.err;
  // Nor the pixel centre, which the core takes from the links' pixel map.
  const auto pixels = run_command(evms_binary() + " run gen://rotation?duration-s=0.05 --backend rtl --core ice40 --measure pixel-centre --quiet");
  EXPECT_EQ(pixels.exit_code, 1);
  EXPECT_NE(pixels.err.find("the RTL build 'ice40' does not hold the pixel centre, not --measure pixel-centre (add --measure centroid)"),
            std::string::npos)
      << pixels.err;
  const auto unlinked = run_command(evms_binary() + " run gen://rotation?duration-s=0.05 --backend fixed --link-px 0 --quiet");
  EXPECT_EQ(unlinked.exit_code, 1);
  EXPECT_EQ(std::count(unlinked.err.begin(), unlinked.err.end(), '\n'), 1) << unlinked.err;
  EXPECT_NE(unlinked.err.find("--measure pixel-centre needs --link-px 1 or more"), std::string::npos) << unlinked.err;
  const auto box = run_command(evms_binary() + " run gen://rotation?duration-s=0.05 --backend fixed --measure box-centre --quiet");
  EXPECT_EQ(box.exit_code, 1);
  EXPECT_NE(box.err.find("measures a cluster by its centroid, or with seeded climbs by the polarity midpoint or the pixel centre, not --measure box-centre"),
            std::string::npos)
      << box.err;
  for (const std::string build : {"arty", "ice40"}) {
    const auto board = run_command(evms_binary() + " run gen://rotation?duration-s=0.05 --backend rtl --core " + build + " --preset gaussian --quiet");
    EXPECT_EQ(board.exit_code, 1);
    EXPECT_NE(board.err.find("the RTL build '" + build + "' clusters by seeded climbs only, not --seeding every"), std::string::npos) << board.err;
  }
  const auto fixed = run_command(evms_binary() + " run gen://rotation?duration-s=0.05 --backend fixed --kernel epanechnikov --quiet");
  EXPECT_EQ(fixed.exit_code, 1);
  EXPECT_NE(fixed.err.find("flat kernel only"), std::string::npos) << fixed.err;
  // The core compares event counts by a shift: a ratio that is not a power of two is refused.
  const auto ratio = run_command(evms_binary() + " run gen://rotation?duration-s=0.05 --backend fixed --size-ratio 3 --quiet");
  EXPECT_EQ(ratio.exit_code, 1);
  EXPECT_NE(ratio.err.find("compares sizes by a power of two from 2 to 32768, not --size-ratio 3"), std::string::npos) << ratio.err;
  const auto eight = run_command(evms_binary() + " run gen://rotation?duration-s=0.05 --backend fixed --size-ratio 8 --quiet");
  EXPECT_EQ(eight.exit_code, 0) << eight.err;
  const auto warm = run_command(evms_binary() + " run gen://rotation?duration-s=0.05 --backend fixed --filter-warm-up-us 30000 --quiet");
  EXPECT_EQ(warm.exit_code, 0) << warm.err;  // the core keeps the stream's first events too (hls/filter/ba_filter.h)
  const auto ahead = run_command(evms_binary() + " run gen://rotation?duration-s=0.05 --backend fixed --filter-look-ahead-us 10000 --quiet");
  EXPECT_EQ(ahead.exit_code, 1);
  EXPECT_NE(ahead.err.find("does not implement --filter-look-ahead-us 10000 (only --filter-look-ahead-us 0)"), std::string::npos) << ahead.err;
  // Nor the measurement noise from the clusters' spreads, which the host build and the C++
  // cores hold.
  const auto spread = run_command(evms_binary() + " run gen://rotation?duration-s=0.05 --backend rtl --core arty --meas-noise-from-spread true --quiet");
  EXPECT_EQ(spread.exit_code, 1);
  EXPECT_EQ(std::count(spread.err.begin(), spread.err.end(), '\n'), 1) << spread.err;
  EXPECT_NE(spread.err.find("the RTL build 'arty' does not hold the measurement noise from the spread, not --meas-noise-from-spread true "
                            "(add --meas-noise-from-spread false)"),
            std::string::npos)
      << spread.err;
  const auto fixed_spread = run_command(evms_binary() + " run gen://rotation?duration-s=0.05 --backend fixed --core arty --meas-noise-from-spread true --quiet");
  EXPECT_EQ(fixed_spread.exit_code, 0) << fixed_spread.err;
  // Nor the gate's boxes, which only the host build's tracker holds.
  const auto boxes = run_command(evms_binary() + " run gen://rotation?duration-s=0.05 --backend rtl --core arty --gate-boxes true --quiet");
  EXPECT_EQ(boxes.exit_code, 1);
  EXPECT_EQ(std::count(boxes.err.begin(), boxes.err.end(), '\n'), 1) << boxes.err;
  EXPECT_NE(boxes.err.find("the RTL build 'arty' does not hold the gate's boxes, not --gate-boxes true (add --gate-boxes false)"),
            std::string::npos)
      << boxes.err;
  // Nor the least density on the linked sets, which only the host build's controller holds.
  const auto after_links =
      run_command(evms_binary() + " run gen://rotation?duration-s=0.05 --backend rtl --core arty --density-after-links true --quiet");
  EXPECT_EQ(after_links.exit_code, 1);
  EXPECT_EQ(std::count(after_links.err.begin(), after_links.err.end(), '\n'), 1) << after_links.err;
  EXPECT_NE(after_links.err.find("the RTL build 'arty' does not hold the least density on the linked sets, not --density-after-links true "
                                 "(add --density-after-links false)"),
            std::string::npos)
      << after_links.err;
  const auto fixed_split = run_command(evms_binary() + " run gen://rotation?duration-s=0.05 --backend fixed --split-balance 0.3 --quiet");
  EXPECT_EQ(fixed_split.exit_code, 0) << fixed_split.err;
}

// The host RTL build runs the default method in its sizes, the polarity split, the edge join and
// the measurement noise from the spread included; its labels and tracks are the fixed-point core's.
TEST(MethodOutputs, TheRtlRunsTheDefaultMethodAsTheFixedCore) {
  TempDir dir;
  // Packets of 256 events hold few clusters of twice the default 64 events a part, so the parts
  // counted here are smaller, which also sets the register to a value other than its default.
  const std::string scene = " run 'gen://SCENE' --packet-size 256 --max-clusters 16 --max-tracks 16 --split-min-events 16 --quiet";
  auto run = [&](const std::string& name, const std::string& backend, const std::string& extra) {
    const std::string out = dir.path(name);
    std::string command = scene;
    command.replace(command.find("SCENE"), 5, "family/shake?duration-s=0.1&seed=4&width=240&height=180");
    const auto r = run_command(evms_binary() + command + " --backend " + backend + extra + " --out " + out);
    EXPECT_EQ(r.exit_code, 0) << backend << extra << ": " << r.err;
    return out;
  };
  const std::string rtl = run("rtl", "rtl", ""), fixed = run("fixed", "fixed", ""), unsplit = run("unsplit", "rtl", " --split-balance 0");
  const std::string unjoined = run("unjoined", "rtl", " --edge-join 0");
  const std::string one_noise = run("one_noise", "rtl", " --meas-noise-from-spread false");
  EXPECT_GT(csv_rows(rtl + "/tracks.csv").size(), 10u);
  EXPECT_TRUE(same_text(read_file(rtl + "/events.csv"), read_file(fixed + "/events.csv"))) << "the labels";
  // Every column: the RTL's track words carry the measurement's count and box and the variances.
  EXPECT_TRUE(same_text(read_file(rtl + "/tracks.csv"), read_file(fixed + "/tracks.csv"))) << "the tracks";
  // The scene has clusters that the split parts and edges that the join makes one, and the
  // clusters' spreads move the tracks, so the equality covers all three in the RTL.
  EXPECT_FALSE(same_text(read_file(rtl + "/events.csv"), read_file(unsplit + "/events.csv"))) << "the split changed no label: the scene does not test it";
  EXPECT_FALSE(same_text(read_file(rtl + "/events.csv"), read_file(unjoined + "/events.csv"))) << "the edge join changed no label: the scene does not test it";
  EXPECT_FALSE(same_text(read_file(rtl + "/tracks.csv"), read_file(one_noise + "/tracks.csv"))) << "the measurement noise changed no track";
}

TEST(MethodOutputs, ThePaperPresetRunsTheAuthorsRule) {
  TempDir dir;
  const auto r = run_command(evms_binary() + " run gen://rotation?duration-s=0.2 --preset paper --quiet --out " + dir.path("p"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The authors' code keeps every cluster, however small, and confirms every ID at once.
  for (const auto& row : csv_rows(dir.path("p/tracks.csv"))) EXPECT_EQ(row[2], "confirmed");
  const auto unknown = run_command(evms_binary() + " run gen://rotation --preset fast --quiet");
  EXPECT_NE(unknown.exit_code, 0);
  EXPECT_NE(unknown.err.find("--preset"), std::string::npos) << unknown.err;
}

}  // namespace
}  // namespace evms::test
