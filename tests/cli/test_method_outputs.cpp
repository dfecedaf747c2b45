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

// `evms run` of a short scene with `options` exits with 1 and one line that holds `message`.
void expect_refused(const std::string& options, const std::string& message) {
  const auto r = run_command(evms_binary() + " run gen://rotation?duration-s=0.05 " + options + " --quiet");
  EXPECT_EQ(r.exit_code, 1) << options;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << options << ": " << r.err;
  EXPECT_NE(r.err.find(message), std::string::npos) << options << ": " << r.err;
}

// `evms run` of a short scene with `options` runs.
void expect_runs(const std::string& options) {
  const auto r = run_command(evms_binary() + " run gen://rotation?duration-s=0.05 " + options + " --quiet");
  EXPECT_EQ(r.exit_code, 0) << options << ": " << r.err;
}

TEST(MethodOutputs, TheRtlRefusesTheMethodItLacksInOneLine) {
  expect_refused("--backend rtl --coast-packets 3", "the RTL core does not implement --coast-packets 3 (add --coast-packets 0)");
  // No RTL build labels the events its filter dropped, which they run without unless told it;
  // nor does the fixed core of a board's build.
  expect_refused("--backend rtl --rescue-px 1", "the RTL core does not implement --rescue-px 1 (add --rescue-px 0)");
  expect_refused("--backend fixed --core arty --rescue-px 1",
                 "this build's core does not label the events its filter dropped, not --rescue-px 1 (add --rescue-px 0)");
  // The boards' builds do not hold the edge join, which they run without unless told it.
  expect_refused("--backend rtl --core arty --edge-join 5", "the RTL build 'arty' does not hold the edge join, not --edge-join 5 (add --edge-join 0)");
  // Nor the polarity split.
  expect_refused("--backend rtl --core arty --split-balance 0.3",
                 "the RTL build 'arty' does not hold the polarity split, not --split-balance 0.3 (add --split-balance 0)");
  // Nor the polarity midpoint.
  expect_refused("--backend rtl --core arty --measure polarity-midpoint",
                 "the RTL build 'arty' does not hold the polarity midpoint, not --measure polarity-midpoint (add --measure centroid)");
  // Nor the pixel centre, which the core takes from the links' pixel map.
  expect_refused("--backend rtl --core ice40 --measure pixel-centre",
                 "the RTL build 'ice40' does not hold the pixel centre, not --measure pixel-centre (add --measure centroid)");
  expect_refused("--backend fixed --link-px 0", "--measure pixel-centre needs --link-px 1 or more");
  expect_refused("--backend fixed --measure box-centre",
                 "measures a cluster by its centroid, or with seeded climbs by the polarity midpoint or the pixel centre, not --measure box-centre");
  for (const std::string build : {"arty", "ice40"}) {
    expect_refused("--backend rtl --core " + build + " --preset gaussian",
                   "the RTL build '" + build + "' clusters by seeded climbs only, not --seeding every");
  }
  expect_refused("--backend fixed --kernel epanechnikov", "flat kernel only");
  // The core compares event counts by a shift: a ratio that is not a power of two is refused.
  expect_refused("--backend fixed --size-ratio 3", "compares sizes by a power of two from 2 to 32768, not --size-ratio 3");
  expect_runs("--backend fixed --size-ratio 8");
  expect_runs("--backend fixed --filter-warm-up-us 30000");  // the core keeps the stream's first events too (hls/filter/ba_filter.h)
  expect_refused("--backend fixed --filter-look-ahead-us 10000", "does not implement --filter-look-ahead-us 10000 (only --filter-look-ahead-us 0)");
  expect_refused("--backend rtl --warm-reach 1.5", "does not implement --warm-reach 1.5 (only --warm-reach 0)");
  expect_refused("--backend fixed --packet-span-edge-px 5", "does not implement --packet-span-edge-px 5 (only --packet-span-edge-px 0)");
  expect_refused("--backend fixed --outline-split-us 30000", "does not implement --outline-split-us 30000 (only --outline-split-us 0)");
  // The fixed-point core holds the split by motion; no RTL build and no board's core does.
  expect_runs("--backend fixed --motion-split 0.6");
  expect_refused("--backend rtl --motion-split 0.6", "does not split a cluster by its events' motions, not --motion-split 0.6 (add --motion-split 0)");
  expect_refused("--backend fixed --core arty --motion-split 0.6",
                 "this build's core does not split a cluster by its events' motions, not --motion-split 0.6 (add --motion-split 0)");
  // The fixed-point core keeps a cluster's concentric groups whole or not; no RTL build keeps them whole.
  expect_runs("--backend fixed --split-concentric false");
  expect_refused("--backend rtl --split-concentric true",
                 "splits a cluster's concentric groups of parts, not --split-concentric true (add --split-concentric false)");
  // The fixed-point core times the pixel centre either way; no RTL build by its pixels.
  expect_runs("--backend fixed --time-by-pixels false");
  expect_refused("--backend rtl --time-by-pixels true", "times the pixel centre by all its events, not --time-by-pixels true (add --time-by-pixels false)");
  // The fixed-point core holds the motion measure; no RTL build and no board's core does.
  expect_runs("--backend fixed --motion-measure 1000");
  expect_refused("--backend rtl --motion-measure 1000", "does not implement --motion-measure 1000 (add --motion-measure 0)");
  expect_refused("--backend fixed --core arty --motion-measure 1000",
                 "this build's core does not measure a fast track's cluster by its motion, not --motion-measure 1000 (add --motion-measure 0)");
  // Nor the measurement noise from the clusters' spreads, which the host build and the C++
  // cores hold.
  expect_refused("--backend rtl --core arty --meas-noise-from-spread true",
                 "the RTL build 'arty' does not hold the measurement noise from the spread, not --meas-noise-from-spread true "
                 "(add --meas-noise-from-spread false)");
  expect_runs("--backend fixed --core arty --meas-noise-from-spread true");
  // Nor the gate's boxes, which only the host build's tracker holds.
  expect_refused("--backend rtl --core arty --gate-boxes true",
                 "the RTL build 'arty' does not hold the gate's boxes, not --gate-boxes true (add --gate-boxes false)");
  // Nor the least density on the linked sets, which only the host build's controller holds.
  expect_refused("--backend rtl --core arty --density-after-links true",
                 "the RTL build 'arty' does not hold the least density on the linked sets, not --density-after-links true "
                 "(add --density-after-links false)");
  expect_runs("--backend fixed --core arty --density-after-links true");
  expect_runs("--backend fixed --split-balance 0.3");
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
  // No RTL build labels the events its filter dropped (--rescue-px) or times the pixel centre by
  // its pixels (--time-by-pixels), which the RTL backend leaves out of its default method.
  const std::string rtl = run("rtl", "rtl", ""), fixed = run("fixed", "fixed", " --rescue-px 0 --time-by-pixels false");
  const std::string unsplit = run("unsplit", "rtl", " --split-balance 0");
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
