// The backends behind the CLI produce the same files: the Verilated RTL equals the fixed-point
// core of its build, and the board backend, through the virtual board's pseudo-terminal and
// the framed UART link, equals the fixed-point core of the board's build (tracks.csv in the
// columns the RTL's track words carry): the iCEBreaker's, whose core stops after the climbs and
// whose verdicts and climbs the host completes, and the Arty's, which holds the whole core.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "hls/core/configs.h"
#include "host/backend/core_backend.h"
#include "host/backend/core_config.h"
#include "host/link/find_bridge.h"
#include "host/link/line_rate.h"
#include "tests/support/command.h"
#include "tests/support/encoders.h"
#include "tests/support/core_words.h"

namespace evms::test {
namespace {

// Runs `evms run` on one source with one backend and returns (events.csv, tracks.csv).
std::pair<std::string, std::string> run_backend(const TempDir& dir, const std::string& name, const std::string& source,
                                                const std::string& options) {
  const std::string out = dir.path(name);
  const auto r = run_command(evms_binary() + " run \"" + source + "\" --quiet --out " + out + " " + options);
  EXPECT_EQ(r.exit_code, 0) << name << ": " << r.err;
  return {read_file(out + "/events.csv"), read_file(out + "/tracks.csv")};
}

TEST(BackendsAgree, RtlEqualsFixedFileForFile) {
  TempDir dir;
  const std::string scene = "gen://translation?duration-s=0.15&seed=8";
  const auto fixed = run_backend(dir, "fixed", scene, "--backend fixed --preset gaussian");
  const auto rtl = run_backend(dir, "rtl", scene, "--backend rtl --preset gaussian");
  EXPECT_GT(fixed.first.size(), 1000u);
  EXPECT_TRUE(same_text(rtl.first, fixed.first)) << "events.csv";
  EXPECT_TRUE(same_text(rtl.second, fixed.second)) << "tracks.csv";
  // A board build whose fixed core is its RTL's (the Arty's; the ice40 build's fixed core is the
  // iCEBreaker's whole method, and its RTL core is checked against hls::Core<Ice40Shape> by the
  // cosimulation, tests/sim/test_cosim.cpp).
  const std::string arty_scene = "gen://rotation?duration-s=0.1&seed=9";
  const auto rtl_arty = run_backend(dir, "rtl_arty", arty_scene, "--backend rtl --core arty");
  const auto fixed_arty = run_backend(dir, "fixed_arty", arty_scene, "--backend fixed --core arty");
  EXPECT_TRUE(same_text(rtl_arty.first, fixed_arty.first)) << "events.csv";
  EXPECT_TRUE(same_text(rtl_arty.second, fixed_arty.second)) << "tracks.csv";
}

// --backend rtl --core ice40 alone runs that RTL build's packet size, cluster and track counts
// (hls/core/configs.h), and so does evms cycles --build ice40, which also counts its board's core;
// a size set by hand beyond the build's is refused.
TEST(BackendsAgree, ACoreBuildAppliesItsOwnSizes) {
  TempDir dir;
  const std::string small = "gen://rotation?duration-s=0.1&seed=9&width=128&height=128";
  const auto by_build = run_backend(dir, "by_build", small, "--backend rtl --core ice40");
  const auto by_hand =
      run_backend(dir, "by_hand", small, "--backend rtl --core ice40 --packet-size 256 --max-clusters 8 --max-tracks 8");
  EXPECT_GT(by_build.first.size(), 1000u);
  EXPECT_EQ(by_build, by_hand);
  const auto refused = run_command(evms_binary() + " run \"" + small + "\" --quiet --backend rtl --core ice40 --packet-size 300 --out " +
                                   dir.path("refused"));
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_NE(refused.err.find("--packet-size"), std::string::npos) << refused.err;
  const auto cycles = run_command(evms_binary() + " cycles \"" + small + "\" --build ice40");
  ASSERT_EQ(cycles.exit_code, 0) << cycles.err;
  EXPECT_NE(cycles.out.find("packets of 256, 8 clusters, 8 tracks"), std::string::npos) << cycles.out;
  // Below the whole core's cycles, the board's core cut after its climbs, on the same events,
  // with the board's registers: within the 180 clocks an event (100 k events/s at the
  // board's 18 MHz).
  EXPECT_NE(cycles.out.find("its registers: packets of 1024, no warm seeds"), std::string::npos) << cycles.out;
  const size_t at = cycles.out.find("board core       ");
  ASSERT_NE(at, std::string::npos) << cycles.out;
  const double clocks = std::stod(cycles.out.substr(at + 17));
  EXPECT_GT(clocks, 10.0) << cycles.out;
  EXPECT_LT(clocks, 180.0) << cycles.out;
}

// A build that runs the method otherwise than golden does says so in the summary, naming each
// setting it changed with the method's value; what the command line set, or a build that holds
// the method as it is, is not named.
TEST(BackendsAgree, TheSummarySaysWhatACoreBuildChangesOfTheMethod) {
  TempDir dir;
  const std::string small = "gen://rotation?duration-s=0.05&seed=9&width=128&height=128";
  const auto note = [&](const std::string& options) {
    const auto r = run_command(evms_binary() + " run \"" + small + "\" --quiet --out " + dir.path("out") + " " + options);
    EXPECT_EQ(r.exit_code, 0) << options << ": " << r.err;
    const size_t at = r.out.find("            the ");
    return at == std::string::npos ? std::string() : r.out.substr(at + 12, r.out.find('\n', at) - at - 12);
  };
  const std::string ice40 = note("--backend rtl --core ice40");
  EXPECT_EQ(ice40.rfind("the ice40 build runs --packet-size 256 (the method's ", 0), 0u) << ice40;
  for (const char* changed : {"--max-clusters 8 (the method's ", "--max-tracks 8 (the method's ", "--split-balance 0 (the method's ",
                              "--edge-join 0 (the method's ", "--measure centroid (the method's pixel-centre)",
                              "--meas-noise-from-spread false (the method's true)", "--gate-boxes false (the method's true)",
                              "--density-after-links false (the method's true)", "--rescue-px 0 (the method's 1)"}) {
    EXPECT_NE(ice40.find(changed), std::string::npos) << changed << " in: " << ice40;
  }
  const std::string by_hand = note("--backend rtl --core ice40 --packet-size 256 --max-clusters 8 --max-tracks 8 --edge-join 0");
  EXPECT_EQ(by_hand.find("--packet-size"), std::string::npos) << by_hand;
  EXPECT_EQ(by_hand.find("--edge-join"), std::string::npos) << by_hand;
  EXPECT_NE(by_hand.find("--split-balance 0"), std::string::npos) << by_hand;
  EXPECT_EQ(note("--backend golden"), "");
  EXPECT_EQ(note("--backend fixed"), "") << "the host build's C++ core holds the method's sizes";
  EXPECT_EQ(note("--backend fixed --core ice40"), "the ice40 build runs --packet-size 1024 (the method's 3000), --warm-start false (the method's true)")
      << "the iCEBreaker's fixed core (its board's filter and climbs, then the host core) holds every step after the climbs";
}

// The Arty build runs the seeded path, which the cycle model does not count: evms cycles measures
// it on the RTL without being asked (the same figures as with --rtl), gives the rate that total
// sustains at the build's clock, and refuses only --table, which sweeps the model.
TEST(BackendsAgree, CyclesOfTheSeededArtyBuildAreMeasuredOnTheRtl) {
  const std::string scene = " cycles \"gen://rotation?duration-s=0.1&seed=9\" --build arty";
  const auto plain = run_command(evms_binary() + scene);
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_NE(plain.out.find("measured on the RTL"), std::string::npos) << plain.out;
  const auto asked = run_command(evms_binary() + scene + " --rtl");
  ASSERT_EQ(asked.exit_code, 0) << asked.err;
  EXPECT_EQ(plain.out, asked.out);
  const size_t total = plain.out.find("\ntotal");
  ASSERT_NE(total, std::string::npos) << plain.out;
  const double per_event = std::stod(plain.out.substr(total + 6));
  EXPECT_GT(per_event, 10.0) << plain.out;
  const size_t rate = plain.out.find("\nrate");
  ASSERT_NE(rate, std::string::npos) << plain.out;
  const double clock_hz = static_cast<double>(backend::board_of("arty").clock_hz);
  EXPECT_NEAR(std::stod(plain.out.substr(rate + 5)) * 1e6, clock_hz / per_event, 0.006e6) << plain.out;
  EXPECT_NE(plain.out.find(" M events/s at the build's 100 MHz clock (the RTL's cycles)"), std::string::npos) << plain.out;
  const auto table = run_command(evms_binary() + scene + " --table");
  EXPECT_NE(table.exit_code, 0);
  EXPECT_NE(table.err.find("--table"), std::string::npos) << table.err;
}

// The host build holds the edge join: its cycles are those of the default method with it, whose
// pass adds clocks to the "merge" stage. The Arty build does not hold it: it counts the default
// method without it, and asking for it is refused in one line.
TEST(BackendsAgree, CyclesOfTheHostBuildCountTheEdgeJoinAndTheArtyBuildRefusesIt) {
  const std::string scene = " cycles \"gen://rotation?duration-s=0.03&seed=9\" --build ";
  auto merge_cycles = [](const std::string& out) {  // the "merge" row's cycles an event
    const size_t at = out.find("\nmerge ");
    if (at == std::string::npos) return -1.0;
    const std::string row = out.substr(at + 1, out.find('\n', at + 1) - at - 1);
    return std::stod(row.substr(row.find_last_of(' ') + 1));
  };
  const auto with = run_command(evms_binary() + scene + "host");
  ASSERT_EQ(with.exit_code, 0) << with.err;
  EXPECT_EQ(with.out.find("without"), std::string::npos) << with.out;
  const auto without = run_command(evms_binary() + scene + "host --edge-join 0");
  ASSERT_EQ(without.exit_code, 0) << without.err;
  EXPECT_GT(merge_cycles(with.out), merge_cycles(without.out)) << with.out << without.out;
  const auto arty = run_command(evms_binary() + scene + "arty --edge-join 5");
  EXPECT_NE(arty.exit_code, 0);
  EXPECT_NE(arty.err.find("the RTL build 'arty' does not hold the edge join, not --edge-join 5 (add --edge-join 0)"), std::string::npos) << arty.err;
}

TEST(BackendsAgree, ACoreBuildRefusesParametersBeyondItsLimits) {
  const auto r = run_command(evms_binary() + " run gen://rotation?duration-s=0.05 --backend fixed --core ice40 --quiet");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("128x128"), std::string::npos) << r.err;
  const auto bad = run_command(evms_binary() + " run gen://rotation?duration-s=0.05 --backend fixed --core zynq --quiet");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("unknown core build 'zynq'"), std::string::npos) << bad.err;
}

// The iCEBreaker's board (the ice40 build, its core cut after the climbs) with the rest of the
// core on the host.
TEST(BackendsAgree, TheBoardThroughTheVirtualBoardEqualsTheFixedCore) {
  TempDir dir;
  VirtualBoardProcess board(dir);
  ASSERT_FALSE(board.device().empty()) << "evms vboard did not start";
  const std::string scene = "gen://rotation?duration-s=0.1&seed=5&width=128&height=128";
  const auto fixed = run_backend(dir, "fixed", scene, "--backend fixed --core ice40");
  const auto on_board = run_backend(dir, "board", scene, "--backend board --device " + board.device());
  EXPECT_GT(fixed.first.size(), 1000u);
  EXPECT_TRUE(same_text(on_board.first, fixed.first)) << "events.csv";
  EXPECT_EQ(link_track_columns(on_board.second), link_track_columns(fixed.second)) << "tracks.csv differs";
  // A second run on the same board starts from the reset frame: the same files again. Its
  // summary says where the work was done.
  const auto again = run_backend(dir, "board2", scene, "--backend board --device " + board.device());
  EXPECT_EQ(again, on_board);
  const auto said = run_command(evms_binary() + " run \"" + scene + "\" --out " + dir.path("board3") + " --backend board --device " + board.device());
  EXPECT_NE(said.out.find("board       filtered and climbed (its core stops after the climbs): "), std::string::npos) << said.out;
  EXPECT_NE(said.out.find(" packets climbed; linked, measured and tracked on the host\n"), std::string::npos)
      << "every packet's climbs from the board: " << said.out;
  // The host runs any setting of the rest: fewer tracks, and the least density on each mode
  // (tested on the board's climbs), for some.
  const std::string rest = "--max-tracks 2 --density-after-links false";
  const auto fixed_rest = run_backend(dir, "fixed_rest", scene, "--backend fixed --core ice40 " + rest);
  const auto board_rest = run_backend(dir, "board_rest", scene, "--backend board --device " + board.device() + " " + rest);
  EXPECT_NE(fixed_rest.first, fixed.first) << "other clusters, other labels";
  EXPECT_TRUE(same_text(board_rest.first, fixed_rest.first)) << "events.csv";
  // What its registers hold is the board's: other packets are refused.
  const auto other_packets = run_command(evms_binary() + " run \"" + scene + "\" --quiet --out " + dir.path("board4") +
                                         " --backend board --packet-size 256 --device " + board.device());
  EXPECT_NE(other_packets.exit_code, 0);
  EXPECT_NE(other_packets.err.find("runs its build's filter, packet and climbs settings, without warm seeds (the host runs any other), "
                                   "but --packet-size is 256, the board's 1024"),
            std::string::npos)
      << other_packets.err;
  // A scene that is mostly noise: the filtered events wait in the core with their packet's, and
  // the host's window holds more than the core can, so the run goes through.
  const std::string noisy = "gen://family/still?seed=1005&width=128&height=128&noise-hz=4&duration-s=0.1";
  const auto noisy_fixed = run_backend(dir, "noisy_fixed", noisy, "--backend fixed --core ice40");
  const auto noisy_board = run_backend(dir, "noisy_board", noisy, "--backend board --device " + board.device());
  EXPECT_GT(std::count(noisy_fixed.first.begin(), noisy_fixed.first.end(), '\n'), 2000) << "a scene of some length";
  EXPECT_TRUE(same_text(noisy_board.first, noisy_fixed.first)) << "events.csv";
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// evms vectors (the words of the vector testbench, sim/tb/evms_core_vectors_tb.sv): one register
// a line, the event words with their count and the closing flush, and output words that are the
// C++ core of the build's RTL Shape: the labels `evms run --backend rtl` gives, one a line, in
// input order.
TEST(BackendsAgree, VectorsHoldTheCoresWordsAsTheRtlBackendLabelsThem) {
  TempDir dir;
  const std::string scene = "gen://rotation?duration-s=0.05&width=128&height=128&seed=3";
  const auto r = run_command(evms_binary() + " vectors \"" + scene + "\" --core ice40 --out " + dir.path("v"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rtl = run_backend(dir, "rtl", scene, "--backend rtl --core ice40");
  const std::vector<std::string> rows = lines_of(rtl.first);  // "# sensor", the header, then t_us,x,y,p,label
  ASSERT_GT(rows.size(), 1002u);
  const std::vector<std::string> words = lines_of(read_file(dir.path("v/events.hex")));
  EXPECT_EQ(words.size(), rows.size() - 2 + 1) << "an event word a row, and the flush";
  EXPECT_EQ(std::stoul(read_file(dir.path("v/count.hex")), nullptr, 16), words.size());
  for (const std::string& w : words) ASSERT_EQ(w.find_first_not_of("0123456789abcdef"), std::string::npos) << w;
  EXPECT_EQ(words.back(), std::string(words.back().size() - 1, '0') + "1") << "the last word flushes";
  EXPECT_EQ(lines_of(read_file(dir.path("v/cfg.hex"))).size(), static_cast<size_t>(hls::kRtlRegisterCount));
  const std::vector<std::string> labels = lines_of(read_file(dir.path("v/expected_labels.txt")));
  ASSERT_EQ(labels.size(), rows.size() - 2);
  for (size_t i = 0; i < labels.size(); ++i) {
    // "t x y p label" against the row's x, y, p and label (its t is the host's, not the core's).
    std::istringstream word(labels[i]), row(rows[i + 2]);
    long long t, x, y, p, label, rt, rx, ry, rp, rlabel;
    char c;
    word >> t >> x >> y >> p >> label;
    row >> rt >> c >> rx >> c >> ry >> c >> rp >> c >> rlabel;
    ASSERT_EQ(std::vector<long long>({x, y, p, label}), std::vector<long long>({rx, ry, rp, rlabel})) << "word " << i;
  }
  EXPECT_FALSE(lines_of(read_file(dir.path("v/expected_tracks.txt"))).empty());
  EXPECT_FALSE(lines_of(read_file(dir.path("v/expected_packets.txt"))).empty());
  // What the RTL does not hold is refused, as --backend rtl refuses it.
  const auto refused = run_command(evms_binary() + " vectors \"" + scene + "\" --core ice40 --preset gaussian --out " + dir.path("g"));
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_EQ(refused.err, "evms: the RTL build 'ice40' clusters by seeded climbs only, not --seeding every\n");
}

// Every row of `rows` is a row of `all`, in the same order (a board in tracks mode sends whole
// packets' track updates, and skips some packets whole when its line is busy).
void expect_rows_in_order(const std::vector<std::string>& rows, const std::vector<std::string>& all) {
  size_t at = 0;
  for (const std::string& row : rows) {
    while (at < all.size() && all[at] != row) ++at;
    ASSERT_LT(at, all.size()) << "a track row the fixed core did not write: " << row;
    ++at;
  }
}

struct CsvEvent {
  long long t;
  int x, y, p;
  std::string label;
};
std::vector<CsvEvent> events_csv_rows(const std::string& text) {
  std::vector<CsvEvent> rows;
  for (const std::string& line : lines_of(text)) {
    if (line.empty() || line[0] == '#' || line[0] == 't') continue;  // the sensor line and the header
    CsvEvent e;
    char label[32] = {};
    EXPECT_EQ(std::sscanf(line.c_str(), "%lld,%d,%d,%d,%31s", &e.t, &e.x, &e.y, &e.p, label), 5) << line;
    e.label = label;
    rows.push_back(e);
  }
  return rows;
}

// A line that flips, drops and repeats bytes both ways (evms vboard --error-rate), to the
// iCEBreaker's board: the run ends cleanly, every event has one row, and each verdict the line
// destroyed is reported (-2, counted in the summary). The host clusters such an event as noise
// (and climbs the packets after a loss itself), so every other label, and the number of track
// rows, is what the ice40 build gives with exactly those events' verdicts noise: the line changes
// nothing it does not report.
TEST(BackendsAgree, TheBoardOverAnUnreliableLineLosesOnlyWhatItReports) {
  using S = hls::Ice40Shape;          // the board's filter
  using Rest = hls::Ice40ClimbsShape;  // the rest, on the host
  const std::string scene = "gen://rotation?duration-s=0.12&seed=5&width=128&height=128";
  TempDir dir;
  const auto fixed = run_backend(dir, "fixed", scene, "--backend fixed --core ice40");
  const std::vector<CsvEvent> fixed_rows = events_csv_rows(fixed.first);
  ASSERT_GT(fixed_rows.size(), 1000u);
  for (const char* rate : {"1e-4", "1e-3"}) {
    SCOPED_TRACE(std::string("error rate ") + rate);
    TempDir run_dir;
    VirtualBoardProcess board(run_dir, {"--error-rate", rate, "--seed", "11"});
    ASSERT_FALSE(board.device().empty()) << "evms vboard did not start";
    const std::string out = run_dir.path("board");
    const auto r = run_command(evms_binary() + " run \"" + scene + "\" --quiet --out " + out + " --backend board --device " + board.device());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::vector<CsvEvent> rows = events_csv_rows(read_file(out + "/events.csv"));
    ASSERT_EQ(rows.size(), fixed_rows.size());
    size_t lost = 0;
    for (const CsvEvent& e : rows) lost += e.label == "-2";
    if (std::string(rate) == "1e-3") {
      EXPECT_GT(lost, 0u) << "at this rate the line destroys some verdicts";
    }
    EXPECT_NE(r.out.find(", " + std::to_string(lost) + " labels lost (labelled -2)"), std::string::npos) << r.out;
    const long bad_frames = number_after(r.out, "link        ");  // "1,140 frames failed their check"
    ASSERT_NE(bad_frames, -1) << r.out;
    EXPECT_GT(bad_frames, 0) << "the line made no errors: " << r.out;

    // The ice40 build with the lost verdicts noise: the board's filter and the rest on the
    // host, on the words the backend made (its mapper's core times).
    const hls::Config cfg = backend::core_config<S>(backend::build_default_params<S>(), {S::kMaxWidth, S::kMaxHeight});
    const hls::Config rest_cfg = backend::core_config<Rest>(backend::build_default_params<Rest>(), {S::kMaxWidth, S::kMaxHeight});
    std::vector<hls::EventWord> words;
    backend::CoreWordMapper<S> mapper;
    for (const CsvEvent& e : rows) {
      words.push_back(mapper.to_word({e.t, static_cast<std::uint16_t>(e.x), static_cast<std::uint16_t>(e.y), static_cast<std::uint8_t>(e.p)}));
    }
    std::vector<hls::LabelWord> verdicts = test::filter_core_verdicts<S>(words, cfg);
    ASSERT_EQ(verdicts.size(), rows.size());
    for (size_t i = 0; i < rows.size(); ++i) {
      if (rows[i].label == "-2") verdicts[i].label = -1;
    }
    const test::CoreWords completed = test::completed_on_the_host<Rest>(verdicts, rest_cfg);
    std::vector<std::int32_t> want;
    for (const hls::LabelWord& l : completed.labels) want.push_back(l.label);
    const size_t want_tracks = completed.tracks.size();
    ASSERT_EQ(want.size(), rows.size());
    for (size_t i = 0; i < rows.size(); ++i) {
      if (rows[i].label != "-2") {
        ASSERT_EQ(rows[i].label, std::to_string(want[i])) << "row " << i;
      }
    }
    EXPECT_EQ(lines_of(read_file(out + "/tracks.csv")).size(), want_tracks + 1) << "the header and one row a track update";
  }
}

TEST(BackendsAgree, TheBoardBackendNamesWhatIsWrong) {
  const auto no_device = run_command(evms_binary() + " run gen://rotation?width=128\\&height=128 --backend board --quiet");
  EXPECT_NE(no_device.exit_code, 0);
  EXPECT_NE(no_device.err.find("--device"), std::string::npos) << no_device.err;
  const auto missing = run_command(evms_binary() + " run gen://rotation?width=128\\&height=128 --backend board --device /dev/evms-no-such-tty --quiet");
  EXPECT_NE(missing.exit_code, 0);
  EXPECT_NE(missing.err.find("/dev/evms-no-such-tty: cannot open the serial device"), std::string::npos) << missing.err;
  // The board's registers are its build's: on the Arty every setting's, so a packet size set by
  // hand is refused; on the iCEBreaker, whose core stops after the climbs, the filter's, the
  // packets' and the climbs'.
  const auto params = run_command(evms_binary() +
                                  " run gen://rotation --backend board --core arty --device /dev/null --packet-size 32 --quiet");
  EXPECT_NE(params.exit_code, 0);
  EXPECT_NE(params.err.find("the arty board runs its build's settings: --packet-size 512 "), std::string::npos) << params.err;
  EXPECT_NE(params.err.find(", but --packet-size is 32, the board's 512\n"), std::string::npos) << params.err;
  const auto filter = run_command(evms_binary() +
                                  " run gen://rotation?width=128\\&height=128 --backend board --device /dev/null --filter-window-us 10000 --quiet");
  EXPECT_NE(filter.exit_code, 0);
  EXPECT_NE(filter.err.find("the ice40 board runs its build's filter, packet and climbs settings, without warm seeds (the host runs "
                            "any other), but --filter-window-us is 10000, the board's 30000\n"),
            std::string::npos)
      << filter.err;
  // So is a source of another size, named with the --roi that takes a part of it.
  const auto size = run_command(evms_binary() + " run gen://rotation?duration-s=0.05 --backend board --device /dev/null --quiet");
  EXPECT_NE(size.exit_code, 0);
  EXPECT_NE(size.err.find(", but the source is 240x180 (--roi X,Y,128,128 takes a part of it)\n"), std::string::npos) << size.err;
  // Tracks mode is the board backend's.
  const auto link_mode = run_command(evms_binary() + " run gen://rotation?duration-s=0.05 --backend fixed --board-link tracks --quiet");
  EXPECT_NE(link_mode.exit_code, 0);
  EXPECT_NE(link_mode.err.find("--board-link tracks is the board backend's"), std::string::npos) << link_mode.err;
  // The iCEBreaker's core is cut: its verdicts must cross the link.
  const auto cut = run_command(evms_binary() +
                               " run gen://rotation?width=128\\&height=128 --backend board --board-link tracks --device /dev/null --quiet");
  EXPECT_NE(cut.exit_code, 0);
  EXPECT_NE(cut.err.find("the ice40 board's core is cut and the host completes its verdicts"), std::string::npos) << cut.err;
}

// Without --device the board backend takes the one board's UART connected: an FT2232H's channel
// B (USB 0403:6010, interface 01), as sysfs shows it. Here a sysfs tree laid out as Linux's: each
// /sys/class/tty/ttyUSB*'s device a link to its usb-serial port, below the USB interface, below the
// USB device. Channel A, another vendor's bridge and a non-USB tty are passed over; none, or two
// boards, is an error that says so.
TEST(BackendsAgree, TheBoardsUartIsFoundInSysfsWithoutDevice) {
  namespace fs = std::filesystem;
  TempDir dir;
  const fs::path root = dir.path("sys");
  auto text = [](const fs::path& file, const std::string& line) {
    fs::create_directories(file.parent_path());
    std::ofstream(file) << line << "\n";
  };
  auto usb_device = [&](const std::string& at, const std::string& vendor, const std::string& product) {
    const fs::path d = root / "devices/pci0000:00/usb1" / at;
    text(d / "idVendor", vendor);
    text(d / "idProduct", product);
    return d;
  };
  auto tty = [&](const std::string& name, const fs::path& usb, const std::string& interface) {
    const fs::path intf = usb / (usb.filename().string() + ":1." + std::to_string(std::stoi(interface)));
    text(intf / "bInterfaceNumber", interface);
    fs::create_directories(intf / name / "tty" / name);
    fs::create_directories(root / "class/tty");
    fs::create_directory_symlink(intf / name / "tty" / name, root / "class/tty" / name);
    fs::create_directory_symlink(intf / name, intf / name / "tty" / name / "device");
  };
  EXPECT_TRUE(link::ft2232h_uarts(root).empty());
  try {
    link::the_board_uart(root);
    ADD_FAILURE() << "no UART in the tree, yet one was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no board's UART is connected"), std::string::npos) << e.what();
  }
  const fs::path board = usb_device("1-1", "0403", "6010");
  tty("ttyUSB0", board, "00");
  tty("ttyUSB1", board, "01");
  tty("ttyUSB2", usb_device("1-2", "10c4", "ea60"), "00");
  fs::create_directories(root / "class/tty/ttyS0");
  EXPECT_EQ(link::ft2232h_uarts(root), std::vector<std::string>{"/dev/ttyUSB1"});
  EXPECT_EQ(link::the_board_uart(root), "/dev/ttyUSB1");
  const fs::path second = usb_device("1-3", "0403", "6010");
  tty("ttyUSB3", second, "00");
  tty("ttyUSB4", second, "01");
  EXPECT_EQ(link::ft2232h_uarts(root), (std::vector<std::string>{"/dev/ttyUSB1", "/dev/ttyUSB4"}));
  try {
    link::the_board_uart(root);
    ADD_FAILURE() << "two boards, yet one was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("(/dev/ttyUSB1, /dev/ttyUSB4): name the one to use with --device"), std::string::npos) << e.what();
  }
}

// The count of "events in   N" in a run's summary; -1 when it has none.
long events_in_summary(const std::string& out) { return number_after(out, "events in   "); }

// The count in "(N labelled noise" of a run's summary.
long noise_in_summary(const std::string& out) {
  const size_t at = out.find(" labelled noise");
  long n = 0, scale = 1;
  for (size_t i = at; i-- > 0 && (std::isdigit(static_cast<unsigned char>(out[i])) || out[i] == ',');) {
    if (out[i] != ',') n += (out[i] - '0') * scale, scale *= 10;
  }
  return at == std::string::npos ? -1 : n;
}

// The line rate a terminal is set to, as the host left it (the virtual board holds the terminal
// open, so its settings outlast the host's run); -1 when it cannot be read.
int line_rate_of(const std::string& device) {
  const int fd = ::open(device.c_str(), O_RDWR | O_NOCTTY);
  if (fd < 0) return -1;
  const int rate = link::line_rate(fd);
  ::close(fd);
  return rate;
}

// The board backend opens the line at the rate of the board its --core names (EVMS_BOARD_BUILDS:
// the Arty's UART runs at 100 MHz / 50 = 2 Mbaud, the iCEBreaker's at 18 MHz / 3 = 6 Mbaud, a
// rate without a Bnnn constant), and --baud sets another.
TEST(BackendsAgree, TheBoardBackendOpensTheLineAtItsBoardsRate) {
  static_assert(backend::board_of("arty").baud() == 2000000 && backend::board_of("ice40").baud() == 6000000);
  TempDir dir;
  for (const std::string build : {"arty", "ice40"}) {
    VirtualBoardProcess board(dir, {"--build", build});
    ASSERT_FALSE(board.device().empty()) << "evms vboard did not start";
    const std::string scene = build == "ice40" ? "gen://rotation?duration-s=0.005&seed=5&width=128&height=128" : "gen://rotation?duration-s=0.005&seed=5";
    const std::string run = evms_binary() + " run \"" + scene + "\" --quiet --backend board --core " + build + " --device " + board.device() +
                            " --out " + dir.path("out");
    const auto own = run_command(run);
    ASSERT_EQ(own.exit_code, 0) << own.err;
    EXPECT_EQ(line_rate_of(board.device()), backend::board_of(build).baud()) << build;
    const auto set = run_command(run + " --baud 1000000");
    ASSERT_EQ(set.exit_code, 0) << set.err;
    EXPECT_EQ(line_rate_of(board.device()), 1000000) << build;
  }
}

// Tracks mode (--board-link tracks, the Arty's board): the board keeps the labels and counts
// them, events.csv has no rows, and tracks.csv holds whole packets' updates, each row one of the
// fixed core's, in order. The events still come over the link, acknowledged by progress frames.
TEST(BackendsAgree, TheBoardInTracksModeKeepsTheLabelsAndSendsTheFixedCoresTracks) {
  TempDir dir;
  VirtualBoardProcess board(dir, {"--build", "arty"});
  ASSERT_FALSE(board.device().empty()) << "evms vboard did not start";
  const std::string scene = "gen://rotation?duration-s=0.1&seed=5";
  const std::string fixed_out = dir.path("fixed"), board_out = dir.path("board");
  const auto fixed = run_command(evms_binary() + " run \"" + scene + "\" --quiet --backend fixed --core arty --out " + fixed_out);
  ASSERT_EQ(fixed.exit_code, 0) << fixed.err;
  const auto on_board = run_command(evms_binary() + " run \"" + scene + "\" --quiet --backend board --core arty --board-link tracks --device " +
                                    board.device() + " --out " + board_out);
  ASSERT_EQ(on_board.exit_code, 0) << on_board.err;
  EXPECT_EQ(lines_of(read_file(board_out + "/events.csv")).size(), 2u) << "the sensor line and the header only";
  EXPECT_NE(on_board.out.find("board       kept the labels (tracks mode)"), std::string::npos) << on_board.out;
  EXPECT_GT(noise_in_summary(fixed.out), 0) << fixed.out;
  EXPECT_EQ(noise_in_summary(on_board.out), noise_in_summary(fixed.out)) << on_board.out;
  const auto tracks = lines_of(link_track_columns(read_file(board_out + "/tracks.csv")));
  EXPECT_GT(tracks.size(), 2u);
  expect_rows_in_order(tracks, lines_of(link_track_columns(read_file(fixed_out + "/tracks.csv"))));
}

// Listening: the events enter at the Arty's board's AER pins (the virtual board plays a
// recording into them, as a DVS128 would), the host sends none, and the track updates that
// come are the fixed core's on the events as the board stamped them.
TEST(BackendsAgree, ListeningToTheBoardsAerPinsGivesTheFixedCoresTracks) {
  TempDir dir;
  const std::string scene = "gen://translation?duration-s=0.1&seed=3&width=128&height=128";
  const std::string stamped = dir.path("stamped.txt");
  VirtualBoardProcess board(dir, {"--build", "arty", "--aer", scene, "--aer-stamped", stamped});
  ASSERT_FALSE(board.device().empty()) << "evms vboard did not start";
  const std::string listen = evms_binary() + " run --listen --backend board --core arty --board-link tracks --quiet --device " + board.device();
  const auto listened = run_command(listen + " --limit 4000 --out " + dir.path("listen"));
  ASSERT_EQ(listened.exit_code, 0) << listened.err;
  EXPECT_NE(listened.out.find("source      the board's AER pins (DVS128 AER, listening, 240x180)"), std::string::npos) << listened.out;
  EXPECT_GE(events_in_summary(listened.out), 4000) << "the board labelled at least --limit events: " << listened.out;
  EXPECT_EQ(lines_of(read_file(dir.path("listen/events.csv"))).size(), 2u) << "no event rows: the labels stay on the board";

  for (int i = 0; i < 1200 && !std::filesystem::exists(stamped); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ASSERT_TRUE(std::filesystem::exists(stamped)) << "the virtual board did not finish playing the recording";
  const auto fixed = run_command(evms_binary() + " run " + stamped + " --quiet --backend fixed --core arty --out " + dir.path("fixed"));
  ASSERT_EQ(fixed.exit_code, 0) << fixed.err;
  const auto tracks = lines_of(link_track_columns(read_file(dir.path("listen/tracks.csv"))));
  EXPECT_GT(tracks.size(), 10u);
  expect_rows_in_order(tracks, lines_of(link_track_columns(read_file(dir.path("fixed/tracks.csv")))));

  // Ctrl-C ends listening as it ends a live source: exit 0, the summary, whole files.
  const std::string out = dir.path("interrupted"), log = dir.path("interrupted.log");
  const auto interrupted = run_command(listen + " --out " + out + " > " + log + " 2>&1 & pid=$!; for i in $(seq 600); do [ -s " + out +
                                       "/tracks.csv ] && break; sleep 0.05; done; sleep 0.3; kill -INT $pid; wait $pid; echo $?");
  EXPECT_EQ(interrupted.out, "0\n") << read_file(log);
  EXPECT_NE(read_file(log).find("outputs     "), std::string::npos) << read_file(log);
  const std::string interrupted_tracks = read_file(out + "/tracks.csv");
  EXPECT_EQ(interrupted_tracks.rfind("t_us,track_id,state,", 0), 0u) << interrupted_tracks;
  EXPECT_EQ(interrupted_tracks.back(), '\n');

  // Listening is the board's, in tracks mode, without a source on the host: one line otherwise.
  const auto golden = run_command(evms_binary() + " run --listen --quiet");
  EXPECT_EQ(golden.exit_code, 1);
  EXPECT_EQ(golden.err, "evms: --listen takes the board's own input: add --backend board, and --board-link tracks for a board with the whole "
                        "core (--core arty), whose labels stay on it\n");
  const auto with_source = run_command(listen + " \"" + scene + "\"");
  EXPECT_EQ(with_source.exit_code, 1);
  EXPECT_EQ(with_source.err, "evms: --listen takes the events at the board's AER pins: name no SOURCE\n");
  const auto too_large = run_command(evms_binary() + " vboard --build arty --aer gen://rotation?duration-s=0.01");
  EXPECT_EQ(too_large.exit_code, 1);
  EXPECT_NE(too_large.err.find("a 240x180 sensor; the board's AER pins take a DVS128's 7-bit addresses (128x128 at most)"), std::string::npos)
      << too_large.err;
}

// Listening to the iCEBreaker's board, whose core stops after the climbs: every event that
// enters at its AER pins comes back with its verdict (the sensor waits for the line), each packet
// with its climbs, and the host completes them, so the rows of both files are the fixed ice40
// core's on the events as the board stamped them, byte for byte.
TEST(BackendsAgree, ListeningToTheIcebreakersAerPinsGivesTheFixedCoresLabels) {
  TempDir dir;
  const std::string scene = "gen://translation?duration-s=0.1&seed=3&width=128&height=128";
  const auto info = run_command(evms_binary() + " info \"" + scene + "\"");
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const long recording_events = number_after(info.out, "events      ");
  ASSERT_NE(recording_events, -1) << info.out;
  const std::string count = std::to_string(recording_events);
  const std::string stamped = dir.path("stamped.txt");
  VirtualBoardProcess board(dir, {"--build", "ice40", "--aer", scene, "--aer-stamped", stamped});
  ASSERT_FALSE(board.device().empty()) << "evms vboard did not start";
  // Until every event of the recording came: the sensor waits for the line, so the board takes
  // the last of them only while the host reads.
  const auto listened = run_command("timeout 120 " + evms_binary() + " run --listen --backend board --core ice40 --device " + board.device() +
                                    " --limit " + count + " --out " + dir.path("listen"));
  ASSERT_EQ(listened.exit_code, 0) << listened.err;
  EXPECT_EQ(events_in_summary(listened.out), recording_events) << listened.out;
  EXPECT_NE(listened.out.find("0 labels lost"), std::string::npos) << listened.out;
  EXPECT_NE(listened.out.find("packets climbed; linked, measured and tracked on the host"), std::string::npos) << listened.out;

  for (int i = 0; i < 1200 && !std::filesystem::exists(stamped); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ASSERT_TRUE(std::filesystem::exists(stamped)) << "the virtual board did not finish playing the recording";
  const auto fixed = run_command(evms_binary() + " run " + stamped + " --quiet --backend fixed --core ice40 --out " + dir.path("fixed"));
  ASSERT_EQ(fixed.exit_code, 0) << fixed.err;
  const std::string events = read_file(dir.path("listen/events.csv"));
  EXPECT_EQ(lines_of(events).size(), static_cast<size_t>(recording_events) + 2) << "a row for every event, under the two header lines";
  EXPECT_EQ(events, read_file(dir.path("fixed/events.csv")));
  const std::string tracks = read_file(dir.path("listen/tracks.csv"));
  EXPECT_GT(lines_of(tracks).size(), 10u);
  EXPECT_EQ(tracks, read_file(dir.path("fixed/tracks.csv")));
}

// --limit takes at most that many of the sensor's events, though the board's frames bring
// them 32 at a time and the sensor goes on.
TEST(BackendsAgree, ListeningWithALimitTakesExactlyThatManyEvents) {
  TempDir dir;
  const std::string scene = "gen://translation?duration-s=0.1&seed=3&width=128&height=128";
  VirtualBoardProcess board(dir, {"--build", "ice40", "--aer", scene});
  ASSERT_FALSE(board.device().empty()) << "evms vboard did not start";
  const long limit = 1001;
  const auto listened = run_command("timeout 120 " + evms_binary() + " run --listen --backend board --core ice40 --device " + board.device() +
                                    " --limit " + std::to_string(limit) + " --out " + dir.path("listen"));
  ASSERT_EQ(listened.exit_code, 0) << listened.err;
  EXPECT_EQ(events_in_summary(listened.out), limit) << listened.out;
  EXPECT_EQ(lines_of(read_file(dir.path("listen/events.csv"))).size(), static_cast<size_t>(limit) + 2) << "a row for each event taken";
}

}  // namespace
}  // namespace evms::test
