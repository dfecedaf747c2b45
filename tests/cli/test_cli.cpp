// The evms program end to end: exit codes, one-line errors, outputs and memory.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "host/cli/bounded_queue.h"
#include "host/cli/run_stages.h"
#include "tests/support/command.h"
#include "tests/support/encoders.h"

namespace evms::test {
namespace {

size_t count_lines(const std::string& path) {
  std::ifstream in(path);
  size_t n = 0;
  std::string line;
  while (std::getline(in, line)) ++n;
  return n;
}

TEST(Cli, EverySubcommandHasHelp) {
  for (const char* sub : {"", "run", "info", "gen"}) {
    const auto r = run_command(evms_binary() + " " + sub + " --help");
    EXPECT_EQ(r.exit_code, 0) << sub;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << sub;
  }
}

// An option a subcommand lists is one it acts on: pacing means nothing to info or cycles, live
// always paces a recording, and view chooses its default and takes either flag.
TEST(Cli, SubcommandsListOnlyTheOptionsTheyUse) {
  struct Expect {
    const char* sub;
    std::vector<std::string> listed;
    std::vector<std::string> absent;
  };
  const std::vector<Expect> table = {
      {"run", {"--realtime", "--speed", "--live-buffer", "--format", "--baud"}, {"--no-realtime", "--fps", "--headless"}},
      {"view", {"--realtime", "--no-realtime", "--speed", "--fps", "--headless"}, {"--format", "--baud"}},
      {"live", {"--speed", "--live-buffer", "--fps"}, {"--realtime", "--no-realtime", "--format"}},
      {"info", {"--width", "--roi", "--hot-pixels"}, {"--realtime", "--speed", "--live-buffer", "--preset", "--backend"}},
      {"cycles", {"--build", "--preset", "--limit"}, {"--realtime", "--speed", "--live-buffer", "--backend"}},
      {"gen", {"--family", "--seed"}, {"--preset", "--realtime", "--backend"}},
      {"metrics", {"--truth", "--pred"}, {"--preset", "--realtime", "--limit"}},
  };
  for (const Expect& e : table) {
    const auto r = run_command(evms_binary() + " " + e.sub + " --help");
    ASSERT_EQ(r.exit_code, 0) << e.sub;
    std::vector<std::string> options;
    std::istringstream lines(r.out);
    for (std::string line; std::getline(lines, line);) {
      const size_t at = line.find("--");
      if (at == std::string::npos || line.find_first_not_of(' ') != at) continue;
      options.push_back(line.substr(at, line.find_first_of(" ,", at) - at));
    }
    const auto has = [&](const std::string& o) { return std::find(options.begin(), options.end(), o) != options.end(); };
    for (const auto& o : e.listed) EXPECT_TRUE(has(o)) << e.sub << " --help does not list " << o;
    for (const auto& o : e.absent) EXPECT_FALSE(has(o)) << e.sub << " --help lists " << o;
  }
  // The help groups its options under headings, the method's last.
  const auto run = run_command(evms_binary() + " run --help");
  const size_t input = run.out.find("\nInput:"), replay = run.out.find("\nReplay:"), method = run.out.find("\nMethod parameters:");
  ASSERT_NE(input, std::string::npos);
  ASSERT_NE(replay, std::string::npos);
  ASSERT_NE(method, std::string::npos);
  EXPECT_LT(replay, method);
}

TEST(Cli, RunWritesOneRowPerEventAndATrackFile) {
  TempDir dir;
  const auto events = sample_events(3000, {240, 180});
  const std::string in = dir.write("in.csv", csv(events));
  const auto r = run_command(evms_binary() + " run " + in + " --out " + dir.path("out"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The sensor comment, the header and one row per event.
  EXPECT_EQ(count_lines(dir.path("out/events.csv")), events.size() + 2);
  std::ifstream labelled(dir.path("out/events.csv"));
  std::string sensor;
  std::getline(labelled, sensor);
  EXPECT_EQ(sensor, "# sensor 240x180");
  std::ifstream tracks(dir.path("out/tracks.csv"));
  std::string header;
  std::getline(tracks, header);
  EXPECT_EQ(header, "t_us,track_id,state,x,y,vx,vy,events,x_min,y_min,x_max,y_max,var_x,cov_xy,var_y");
  EXPECT_NE(r.out.find("events in   3,000"), std::string::npos) << r.out;
}

// The summary's "time" line splits the wall clock into reading, the method (for golden: its
// clustering, tracking and the rest) and writing, and golden counts its kernel evaluations.
TEST(Cli, RunSummarySaysWhereTheTimeWent) {
  TempDir dir;
  // A scene with objects: uniformly random events are a noisy sensor's, and the filter's noise
  // check leaves nothing of them to cluster.
  const std::string events = "\"gen://rotation?duration-s=0.2\"";
  const auto golden = run_command(evms_binary() + " run " + events + " --out " + dir.path("g"));
  ASSERT_EQ(golden.exit_code, 0) << golden.err;
  double read = -1, method = -1, cluster = -1, track = -1, rest = -1, write = -1, kernel = -1;
  const size_t at = golden.out.find("time        ");
  ASSERT_NE(at, std::string::npos) << golden.out;
  ASSERT_EQ(std::sscanf(golden.out.c_str() + at, "time        read %lf s, method %lf s (cluster %lf, track %lf, filter and the rest %lf), write %lf s",
                        &read, &method, &cluster, &track, &rest, &write),
            6)
      << golden.out;
  EXPECT_GE(read, 0);
  EXPECT_GE(write, 0);
  EXPECT_GT(cluster, 0);
  EXPECT_NEAR(cluster + track + rest, method, 0.0021) << "the method's parts add up to it (to the printed digits)";
  const size_t k = golden.out.find(" kernel evaluations per event");
  ASSERT_NE(k, std::string::npos) << golden.out;
  ASSERT_EQ(std::sscanf(golden.out.c_str() + golden.out.rfind(", ", k) + 2, "%lf", &kernel), 1);
  EXPECT_GT(kernel, 0);
  // The fixed core counts no kernel evaluations and does not time its stages: neither is printed.
  const auto fixed = run_command(evms_binary() + " run " + events + " --backend fixed");
  ASSERT_EQ(fixed.exit_code, 0) << fixed.err;
  EXPECT_EQ(fixed.out.find("kernel evaluations"), std::string::npos) << fixed.out;
  EXPECT_NE(fixed.out.find("time        read "), std::string::npos) << fixed.out;
  EXPECT_EQ(fixed.out.find("(cluster "), std::string::npos) << fixed.out;
}

TEST(Cli, RunsOnTheEmbeddedDefaultScene) {
  const auto r = run_command(evms_binary() + " run gen://translation?duration-s=0.2 --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("tracks"), std::string::npos);
}

TEST(Cli, BadInputIsOneLineNamingFileAndPosition) {
  TempDir dir;
  const std::string in = dir.write("bad.txt", "0.1 1 2 1\n0.2 1 2\n");
  for (const char* sub : {"run", "info"}) {
    const auto r = run_command(evms_binary() + " " + sub + " " + in);
    EXPECT_EQ(r.exit_code, 1) << sub;
    EXPECT_EQ(r.err, "evms: " + in + ": line 2: missing field 'p' (truncated record)\n") << sub;
  }
}

// A file that is not events at all (a text file given by mistake) gets its error and no summary
// of zero events; one that fails later keeps the summary of what was read before.
TEST(Cli, ASourceThatFailsBeforeItsFirstEventPrintsOnlyItsError) {
  TempDir dir;
  const std::string prose = dir.write("LICENSE.txt", "GNU GENERAL PUBLIC LICENSE\nVersion 3\n");
  const auto r = run_command(evms_binary() + " run " + prose + " --quiet");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, "evms: " + prose + ": line 1: timestamp 'GNU' is not a non-negative decimal number of seconds\n");
  const std::string later = dir.write("later.txt", "0.1 1 2 1\n0.2 1 2\n");
  const auto l = run_command(evms_binary() + " run " + later + " --quiet");
  EXPECT_EQ(l.exit_code, 1);
  EXPECT_NE(l.out.find("events in   1 "), std::string::npos) << l.out;
}

// A file cannot put terminal escapes on the screen through an error message that quotes it.
TEST(Cli, ErrorMessagesEscapeTheInputsControlBytes) {
  TempDir dir;
  const std::string in = dir.write("esc.csv", "t_us,x,y,p\n10,\x1b[2J\x07,2,1\n");
  const auto r = run_command(evms_binary() + " info " + in);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("\\x1b[2J\\x07"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\x1b'), std::string::npos);
  EXPECT_EQ(r.err.find('\x07'), std::string::npos);
}

// Events a little out of time order are put back in order, and both commands say how many.
TEST(Cli, RunAndInfoSayHowManyEventsWerePutBackInOrder) {
  TempDir dir;
  const std::string in = dir.write("late.csv", "t_us,x,y,p\n10,1,1,1\n30,2,1,0\n20,3,1,1\n40,4,1,1\n35,5,1,0\n");
  const auto info = run_command(evms_binary() + " info " + in + " --width 8 --height 8");
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("reordered   2 events moved back into time order"), std::string::npos) << info.out;
  const auto run = run_command(evms_binary() + " run " + in + " --width 8 --height 8 --quiet --out " + dir.path("out"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("reordered   2 events moved back into time order"), std::string::npos) << run.out;
  const auto in_order = run_command(evms_binary() + " run gen://rotation?duration-s=0.01 --quiet --out " + dir.path("out2"));
  ASSERT_EQ(in_order.exit_code, 0) << in_order.err;
  EXPECT_EQ(in_order.out.find("reordered"), std::string::npos) << in_order.out;
}

// Peak rate windows step over a gap of any length at once.
TEST(Cli, InfoStepsOverAGapOfCenturies) {
  TempDir dir;
  const std::string in = dir.write("gap.csv", "t_us,x,y,p\n0,1,1,1\n4611686018427387904,1,1,1\n");
  const auto r = run_command(evms_binary() + " info " + in + " --reorder-us 0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("events      2"), std::string::npos) << r.out;
}

// A recording shorter than a 10 ms window reports its mean as its peak, never a peak below it
// (the 8.8 ms Gen4.1 clip read 22 M against a mean of 25 M).
TEST(Cli, InfoPeakRateOfAClipShorterThanAWindowIsItsMean) {
  TempDir dir;
  const std::string in = dir.write("short.csv", "t_us,x,y,p\n0,1,1,1\n1000,2,1,0\n2000,3,1,1\n");
  const auto r = run_command(evms_binary() + " info " + in + " --width 8 --height 8");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("mean rate   1.5 kevents/s"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("peak rate   1.5 kevents/s (the mean"), std::string::npos) << r.out;
}

TEST(Cli, BadParametersAreRejected) {
  const auto r = run_command(evms_binary() + " run gen://rotation --bandwidth -1");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("--bandwidth"), std::string::npos) << r.err;
  const auto b = run_command(evms_binary() + " run gen://rotation?duration-s=0.01 --backend nope");
  EXPECT_EQ(b.exit_code, 1);
  EXPECT_NE(b.err.find("unknown backend 'nope'"), std::string::npos) << b.err;
  const auto m = run_command(evms_binary() + " run gen://rotation?duration-s=0.01 --motion-measure -5");
  EXPECT_NE(m.exit_code, 0);
  EXPECT_NE(m.err.find("motion-measure"), std::string::npos) << m.err;
}

TEST(Cli, VersionNamesTheCommitAndTheCoreBuilds) {
  const auto r = run_command(evms_binary() + " --version");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("evms ", 0), 0u) << r.out;
  EXPECT_NE(r.out.substr(5, r.out.find('\n') - 5), "") << r.out;
  for (const char* build : {"host ", "arty ", "ice40"}) EXPECT_NE(r.out.find(build), std::string::npos) << r.out;
}

// The width study runs the host core and its variants by the method given: the rows of the
// seeded path's words by default, the Gaussian path's kernel weights and exp table only under
// its preset, and a method the core lacks is refused in one line.
TEST(Cli, WidthsStudiesTheWordsOfTheMethodsPath) {
  const auto table_rows = [](const std::string& out) {
    std::map<std::string, std::vector<double>> rows;  // core -> its figures
    std::istringstream lines(out);
    for (std::string line; std::getline(lines, line);) {
      if (line.rfind("| ", 0) != 0 || line.rfind("| core ", 0) == 0) continue;
      std::vector<std::string> cells;
      std::istringstream cols(line.substr(2));
      for (std::string cell; std::getline(cols, cell, '|');) cells.push_back(cell.substr(0, cell.find_last_not_of(' ') + 1));
      std::vector<double> figures;
      for (size_t i = 1; i + 1 < cells.size(); ++i) figures.push_back(std::stod(cells[i]));
      rows[cells[0]] = figures;
    }
    return rows;
  };
  const auto named = [](const std::map<std::string, std::vector<double>>& rows, const std::string& prefix) {
    for (const auto& [name, figures] : rows)
      if (name.rfind(prefix, 0) == 0) return &figures;
    return static_cast<const std::vector<double>*>(nullptr);
  };
  const auto seeded = run_command(evms_binary() + " widths --duration-s 0.03 --jobs 2");
  ASSERT_EQ(seeded.exit_code, 0) << seeded.err;
  const auto rows = table_rows(seeded.out);
  for (const char* core : {"golden (double)", "host core", "features 5.7", "positions .4", "16-bit 128 us timestamps",
                           "the arty build's words", "the ice40 build's words"})
    EXPECT_NE(named(rows, core), nullptr) << core << " is not a row of\n" << seeded.out;
  for (const char* core : {"weights 1.8", "exp table 2^6 entries"}) EXPECT_EQ(named(rows, core), nullptr) << seeded.out;
  const std::vector<double>* host = named(rows, "host core");
  const std::vector<double>* golden = named(rows, "golden (double)");
  ASSERT_TRUE(host && golden && host->size() == 4 && golden->size() == 4) << seeded.out;
  EXPECT_GE((*host)[2], 0.99) << "the host core's labels against golden's, the lowest over the scenes";
  EXPECT_NEAR((*host)[0], (*golden)[0], 0.01) << "F against the truth";

  const auto gaussian = run_command(evms_binary() + " widths --duration-s 0.03 --jobs 2 --preset gaussian");
  ASSERT_EQ(gaussian.exit_code, 0) << gaussian.err;
  const auto gaussian_rows = table_rows(gaussian.out);
  for (const char* core : {"weights 1.8", "exp table 2^6 entries", "features 5.7"})
    EXPECT_NE(named(gaussian_rows, core), nullptr) << core << " is not a row of\n" << gaussian.out;
  EXPECT_EQ(named(gaussian_rows, "the arty build's words"), nullptr) << "the board builds do not hold the Gaussian path";

  const auto refused = run_command(evms_binary() + " widths --duration-s 0.03 --kernel gaussian");
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_EQ(refused.err, "evms: the fixed-point core climbs from seeds with the flat kernel only, not --kernel gaussian\n");
}

TEST(Cli, AMistypedCommandIsNamedWithTheNearestOne) {
  const auto r = run_command(evms_binary() + " runn gen://rotation");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "evms: unknown command 'runn'; did you mean 'run'? (evms --help lists them)\n");
  const auto far = run_command(evms_binary() + " frobnicate");
  EXPECT_EQ(far.exit_code, 2);
  EXPECT_EQ(far.err, "evms: unknown command 'frobnicate' (evms --help lists them)\n");
}

// A mistyped option is named with the nearest one, and every other refusal of the command line
// is one line too, with exit 2.
TEST(Cli, ARefusedCommandLineIsOneLineAndAMistypedOptionNamesTheNearest) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"run gen://rotation?duration-s=0.01 --bandwith 0.1",
       "unknown option '--bandwith' for evms run; did you mean '--bandwidth'? (evms run --help lists the options)"},
      {"sweep --seedz=3", "unknown option '--seedz' for evms sweep; did you mean '--seeds'? (evms sweep --help lists the options)"},
      {"run --threads 0", "--threads: Value 0 not in range 1 to 256 (evms run --help lists the options)"},
      {"run gen://rotation --backend board --baud -5", "--baud: Value -5 not in range 0 to 12000000 (evms run --help lists the options)"},
      {"run --bandwidth -1", "--bandwidth: -1 is outside [0.0001, 10] (evms run --help lists the options)"},
      {"run --coast-us -5", "--coast-us: -5 is outside [0, 1e+12] us (evms run --help lists the options)"},
      {"metrics", "--truth is required (evms metrics --help lists the options)"},
      // Every floating-point option refuses NaN and infinity (finite_in, host/cli/common.h):
      // a NaN passes CLI11's own range checks, and a NaN duration never ends.
      {"gen --scene rotation --duration-s nan --out x", "--duration-s: 'nan' is not a number (evms gen --help lists the options)"},
      {"metrics --truth a --pred b --touching-px inf", "--touching-px: 'inf' is not a number (evms metrics --help lists the options)"},
      {"eval --speeds 1,nan", "--speeds: 'nan' is not a number (evms eval --help lists the options)"},
      {"run gen://rotation --speed nan", "--speed: 'nan' is not a number (evms run --help lists the options)"},
      {"run gen://rotation --hot-factor NaN", "--hot-factor: 'NaN' is not a number (evms run --help lists the options)"},
      {"view --hold-s -1", "--hold-s: -1 is outside [0, 86400] (evms view --help lists the options)"},
      {"--bandwidth 0.1 run", "unknown option '--bandwidth': options follow the command, as in 'evms run --help' (evms --help lists the commands)"},
  };
  for (const auto& [args, line] : cases) {
    const auto r = run_command(evms_binary() + " " + args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_EQ(r.err, "evms: " + line + "\n") << args;
  }
}

TEST(Cli, FilesystemErrorsAreOneLineNamingThePath) {
  TempDir dir;
  const std::string file = dir.write("plain", std::string("x"));
  // A folder cannot be made under a plain file.
  const auto r = run_command(evms_binary() + " run gen://rotation?duration-s=0.01 --out " + file + "/out");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err.rfind("evms: " + file + "/out: ", 0), 0u) << r.err;
  EXPECT_EQ(r.err.find("filesystem error"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

// The rows of an events.csv without its two header lines, each split at the last comma:
// "t,x,y,p" and the label.
std::vector<std::pair<std::string, std::string>> event_rows_and_labels(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::getline(in, line);
  std::vector<std::pair<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    const size_t comma = line.rfind(',');
    rows.emplace_back(line.substr(0, comma), line.substr(comma + 1));
  }
  return rows;
}

TEST(Cli, NpyOutputHoldsTheSameRowsAsCsv) {
  TempDir dir;
  const std::string scene = " run 'gen://family/crossing?seed=3&duration-s=0.1' --quiet";
  ASSERT_EQ(run_command(evms_binary() + scene + " --out " + dir.path("csv")).exit_code, 0);
  const auto r = run_command(evms_binary() + scene + " --format npy --out " + dir.path("npy"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = event_rows_and_labels(dir.path("csv/events.csv"));
  const std::string npy = read_file(dir.path("npy/events.npy"));
  // NPY 1.0: magic, version, a little-endian header length, the header dict, then the data.
  ASSERT_GT(npy.size(), 10u);
  ASSERT_EQ(npy.substr(0, 8), std::string("\x93NUMPY\x01\x00", 8));
  const size_t header = 10 + static_cast<unsigned char>(npy[8]) + 256 * static_cast<unsigned char>(npy[9]);
  EXPECT_EQ(header % 64, 0u);
  const std::string dict = npy.substr(10, header - 10);
  EXPECT_NE(dict.find("'descr': [('t', '<i8'), ('x', '<u2'), ('y', '<u2'), ('p', 'u1'), ('label', '<i4')]"), std::string::npos) << dict;
  EXPECT_NE(dict.find("'shape': (" + std::to_string(rows.size()) + ",)"), std::string::npos) << dict;
  ASSERT_EQ(npy.size(), header + 17 * rows.size());
  const auto le = [&](size_t at, int bytes) {
    std::int64_t v = 0;
    for (int i = 0; i < bytes; ++i) v |= static_cast<std::int64_t>(static_cast<unsigned char>(npy[at + static_cast<size_t>(i)])) << (8 * i);
    return bytes == 4 ? static_cast<std::int64_t>(static_cast<std::int32_t>(v)) : v;
  };
  for (size_t i = 0; i < rows.size(); ++i) {
    const size_t at = header + 17 * i;
    const std::string event = std::to_string(le(at, 8)) + "," + std::to_string(le(at + 8, 2)) + "," + std::to_string(le(at + 10, 2)) +
                              "," + std::to_string(le(at + 12, 1));
    ASSERT_EQ(event, rows[i].first) << "row " << i;
    ASSERT_EQ(std::to_string(le(at + 13, 4)), rows[i].second) << "row " << i;
  }
  // numpy itself, where it is installed.
  const auto numpy = run_command("python3 -c \"import numpy; a = numpy.load('" + dir.path("npy/events.npy") +
                                 "'); print(len(a), int(a['label'].max()), int(a['t'][-1]))\"");
  if (numpy.exit_code == 0) {
    int max_label = -1;
    for (const auto& row : rows) max_label = std::max(max_label, std::stoi(row.second));
    EXPECT_EQ(numpy.out, std::to_string(rows.size()) + " " + std::to_string(max_label) + " " +
                             rows.back().first.substr(0, rows.back().first.find(',')) + "\n");
  }
}

// The camera-file outputs: evms reads each back to the same events, and labels.csv beside it
// holds their labels in order.
TEST(Cli, CameraFileOutputsReadBackToTheSameEventsWithTheirLabelsBeside) {
  TempDir dir;
  // Timestamps far above EVT 3.0's 24 bits, a gap longer than a 2^24 us epoch, and more events
  // than an AEDAT 4.0 packet holds.
  std::vector<Event> events = sample_events(10000, {240, 180});
  for (size_t i = 0; i < events.size(); ++i) events[i].t += 1605537493718345 + (i >= 5000 ? 40000000 : 0);
  const std::string in = dir.write("in.csv", csv(events));
  ASSERT_EQ(run_command(evms_binary() + " run " + in + " --quiet --out " + dir.path("csv")).exit_code, 0);
  const auto original = event_rows_and_labels(dir.path("csv/events.csv"));
  ASSERT_EQ(original.size(), events.size());
  for (const auto& [format, file, description] : {std::tuple{"evt3", "events.raw", "EVT 3.0"}, {"aedat4", "events.aedat4", "AEDAT 4.0"}}) {
    SCOPED_TRACE(format);
    const std::string out = dir.path(format);
    const auto r = run_command(evms_binary() + " run " + in + " --quiet --format " + format + " --out " + out);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto info = run_command(evms_binary() + " info " + out + "/" + file);
    EXPECT_NE(info.out.find(std::string("format      ") + description), std::string::npos) << info.out;
    EXPECT_NE(info.out.find("sensor      240x180 (from header)"), std::string::npos) << info.out;
    const auto again = run_command(evms_binary() + " run " + out + "/" + file + " --quiet --out " + out + "/again");
    ASSERT_EQ(again.exit_code, 0) << again.err;
    const auto decoded = event_rows_and_labels(out + "/again/events.csv");
    ASSERT_EQ(decoded.size(), original.size());
    std::ifstream labels(out + "/labels.csv");
    std::string line;
    std::getline(labels, line);
    EXPECT_EQ(line.rfind("# one label per event of ", 0), 0u);
    std::getline(labels, line);
    EXPECT_EQ(line, "label");
    for (size_t i = 0; i < original.size(); ++i) {
      ASSERT_EQ(decoded[i].first, original[i].first) << "event " << i;
      ASSERT_TRUE(std::getline(labels, line));
      ASSERT_EQ(line, original[i].second) << "label " << i;
    }
    EXPECT_FALSE(std::getline(labels, line));
  }
}

TEST(Cli, OutDashWritesTheRowsToStandardOutput) {
  TempDir dir;
  const std::string scene = " run gen://rotation?duration-s=0.05 --quiet";
  ASSERT_EQ(run_command(evms_binary() + scene + " --out " + dir.path("file")).exit_code, 0);
  const auto r = run_command(evms_binary() + scene + " --out -");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, read_file(dir.path("file/events.csv")));
  EXPECT_NE(r.err.find("events in"), std::string::npos) << r.err;
  const auto npy = run_command(evms_binary() + scene + " --out - --format npy");
  EXPECT_EQ(npy.exit_code, 1);
  EXPECT_EQ(npy.err, "evms: --out - writes CSV only (--format npy needs a folder)\n");
}

TEST(Cli, ConfigFilesSetParametersAndTheCommandLineWins) {
  TempDir dir;
  const std::string scene = " run 'gen://rotation?duration-s=0.15' --quiet --out ";
  const auto run_to = [&](const std::string& name, const std::string& options) {
    const auto r = run_command(evms_binary() + scene + dir.path(name) + " " + options);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return read_file(dir.path(name + "/events.csv"));
  };
  // Every default, written by params --config, changes nothing.
  const auto defaults = run_command(evms_binary() + " params --config");
  ASSERT_EQ(defaults.exit_code, 0);
  EXPECT_EQ(run_to("all", "--config " + dir.write("all.yaml", defaults.out)), run_to("none", ""));
  // A preset and a value from the file act as they do on the command line.
  const std::string paper = dir.write("paper.yaml", std::string("# the authors' settings, wider\npreset: paper\nbandwidth: 0.2\n"));
  const std::string by_file = run_to("file", "--config " + paper);
  EXPECT_EQ(by_file, run_to("flags", "--preset paper --bandwidth 0.2"));
  EXPECT_NE(by_file, run_to("paper", "--preset paper"));
  // The command line wins, before or after --config.
  EXPECT_EQ(run_to("after", "--config " + paper + " --bandwidth 0.15"), run_to("plain", "--preset paper --bandwidth 0.15"));
  EXPECT_EQ(run_to("before", "--preset evms --config " + paper), run_to("evms", "--bandwidth 0.2"));
  // Bad files: one line, the file, the line, what is wrong.
  for (const auto& [text, said] : std::vector<std::pair<std::string, std::string>>{
           {"bandwidth: 0.1\nbandwith: 0.2\n", ": line 2: unknown parameter 'bandwith'"},
           {"kernel: round\n", ": line 1: --kernel: 'round' is not one of"},
           {"preset: fast\n", ": line 1: unknown preset 'fast'"},
           {"a: [1,\n", ": line 2: bad YAML"},
           // Found by tests/fuzz/fuzz_config.cpp: a key that is a list once ended evms with yaml-cpp's exception.
           {"bandwidth: 0.1\n? [a, b]\n: 3000\n", ": line 2: expected a parameter name before ':'"}}) {
    const std::string path = dir.write("bad.yaml", text);
    const auto r = run_command(evms_binary() + scene + dir.path("bad") + " --config " + path);
    EXPECT_EQ(r.exit_code, 1) << text;
    EXPECT_EQ(r.err.rfind("evms: " + path + said, 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

TEST(Cli, EvalNamesTheRecordingsItSkipsAndWhy) {
  TempDir dir;
  const auto events = sample_events(4000, {240, 180});
  std::filesystem::create_directories(dir.path("real"));
  dir.write("real/dots.csv", "# sensor 240x180\n" + csv(events));
  dir.write("real/notes.txt", std::string("GNU GENERAL PUBLIC LICENSE\n"));
  dir.write("real/README.md", std::string("# recordings\n"));
  write_ros2_bag(dir.path("real/ros2/bag"), {{"/events", "event_camera_msgs/msg/EventPacket",
                                             {event_packet_cdr("evt3", 0, {240, 180}, evt3_words(events))}}});
  const auto r = run_command(evms_binary() + " eval --out " + dir.path("eval") + " --real-dir " + dir.path("real") +
                             " --family-seeds 0 --speeds 1 --duration-s 0.3 --scenes rotation --bandwidths 0.04");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string report = read_file(dir.path("eval/report.md"));
  EXPECT_NE(report.find("| dots.csv | CSV"), std::string::npos) << report;
  EXPECT_NE(report.find("| bag | ROS 2 bag"), std::string::npos) << report;
  EXPECT_NE(report.find("- README.md: not an event file (extension .md)"), std::string::npos) << report;
  EXPECT_NE(report.find("- notes.txt: " + dir.path("real/notes.txt") + ": line 1: "), std::string::npos) << report;
  EXPECT_NE(r.err.find("eval: skipped notes.txt: "), std::string::npos) << r.err;
}

// Without method options, sweep measures the three presets; with them, the method they give
// alone, so that an option is never silently left out of the measurement.
TEST(Cli, SweepMeasuresTheMethodTheCommandLineGives) {
  // One still member (about 0.4 s a preset): the paper's 3 s scenes cost a minute under the sanitizers.
  const std::string base = evms_binary() + " sweep --seeds 1 --types still";
  const auto presets = run_command(base);
  ASSERT_EQ(presets.exit_code, 0) << presets.err;
  for (const char* row : {"\n| evms |", "\n| paper |", "\n| gaussian |"}) EXPECT_NE(presets.out.find(row), std::string::npos) << row;
  const auto given = run_command(base + " --bandwidth 0.15");
  ASSERT_EQ(given.exit_code, 0) << given.err;
  EXPECT_EQ(given.out.find("\n| paper |"), std::string::npos);
  const size_t row = given.out.find("\n| --preset evms --bandwidth 0.15 |");
  ASSERT_NE(row, std::string::npos) << given.out;
  // The row's F differs from the defaults' row: the option took effect.
  const auto f_of = [](const std::string& out, size_t at) { return out.substr(out.find('|', at + 2), 8); };
  EXPECT_NE(f_of(given.out, row), f_of(presets.out, presets.out.find("\n| evms |"))) << given.out;
}

TEST(Cli, GenIsDeterministicOnDisk) {
  TempDir dir;
  for (const char* d : {"a", "b"}) {
    const auto r = run_command(evms_binary() + " gen --scene 6dof --duration-s 0.1 --seed 7 --out " + dir.path(d));
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  for (const char* f : {"events.txt", "labels.csv", "gt_tracks.csv"}) {
    const auto r = run_command("cmp " + dir.path("a/") + f + " " + dir.path("b/") + f);
    EXPECT_EQ(r.exit_code, 0) << f;
  }
}

// A batch the writers handed back holds the batch after next, with none of its old rows.
TEST(Stages, ARecycledBatchHoldsTheBatchAfterNextAndNothingOfItsOwn) {
  const auto events_from = [](TimeUs t0) {
    std::vector<LabelledEvent> v;
    for (TimeUs t = t0; t < t0 + 1000; ++t) v.push_back({{t, 1, 2, 1}, 7});
    return v;
  };
  cli::Collector sink(true);
  sink.on_events(events_from(0));
  sink.on_track({});
  cli::OutputBatch first = sink.take();
  const LabelledEvent* memory = first.events.data();
  sink.recycle(std::move(first));
  sink.on_events(events_from(1000));
  EXPECT_NE(sink.take().events.data(), memory);  // the batch being filled when it came back
  const std::vector<LabelledEvent> third = events_from(2000);
  sink.on_events(third);
  const cli::OutputBatch reused = sink.take();
  EXPECT_EQ(reused.events.data(), memory);
  EXPECT_EQ(reused.events, third);
  EXPECT_TRUE(reused.tracks.empty());
  EXPECT_EQ(sink.events, 3000);
}

// The stages hand spent batches back without waiting: a full or closed queue refuses one and
// leaves it with the caller, an empty one gives none.
TEST(Stages, TheQueuesTryWithoutWaiting) {
  cli::BoundedQueue<std::vector<int>> q(1);
  std::vector<int> item{1, 2, 3}, out;
  EXPECT_FALSE(q.try_pop(out));
  EXPECT_TRUE(q.try_push(item));
  std::vector<int> second{4};
  EXPECT_FALSE(q.try_push(second));  // full
  EXPECT_EQ(second, std::vector<int>{4});
  EXPECT_TRUE(q.try_pop(out));
  EXPECT_EQ(out, (std::vector<int>{1, 2, 3}));
  q.close();
  EXPECT_FALSE(q.try_push(second));  // closed
  EXPECT_EQ(second, std::vector<int>{4});
}

// Reading, the method and writing in threads of their own write the same bytes as one thread,
// on every backend that runs on the host, in every output format. The scene spans several
// batches of the stages, so that batches whose memory was handed back are written too.
TEST(Cli, ThreadsWriteTheSameBytesAsOne) {
  TempDir dir;
  const std::string scene = dir.write("e.csv", "# sensor 128x128\n" + csv(sample_events(100000, {128, 128})));
  for (const char* backend : {"golden", "fixed", "rtl"}) {
    const std::string method = std::string(backend) == "rtl" ? " --preset gaussian" : "";
    const std::string limit = std::string(backend) == "rtl" ? " --limit 3000" : "";
    for (const char* format : {"csv", "npy", "evt3"}) {
      std::vector<std::string> outputs;
      for (const char* threads : {"1", "4"}) {
        const std::string out = dir.path(std::string(backend) + "_" + format + "_" + threads);
        const auto r = run_command(evms_binary() + " run " + scene + " --quiet --backend " + backend + method + limit + " --format " +
                                   format + " --threads " + threads + " --out " + out);
        ASSERT_EQ(r.exit_code, 0) << backend << " " << r.err;
        outputs.push_back(out);
      }
      for (const auto& entry : std::filesystem::directory_iterator(outputs[0])) {
        const std::string name = entry.path().filename();
        const std::string one = read_file(outputs[0] + "/" + name), four = read_file(outputs[1] + "/" + name);
        EXPECT_GT(one.size(), 100u) << backend << " " << name;
        EXPECT_TRUE(one == four) << backend << " " << format << ": " << name << " differs between 1 and 4 threads";
      }
    }
  }
}

// evms metrics reads the files evms itself writes (their first line is "# sensor WxH"): the
// truth against itself scores 1, and a run of the method scores between 0 and 1.
TEST(Cli, MetricsScoresWhatGenAndRunWrite) {
  TempDir dir;
  const auto gen = run_command(evms_binary() + " gen --scene rotation --duration-s 0.1 --seed 3 --out " + dir.path("g"));
  ASSERT_EQ(gen.exit_code, 0) << gen.err;
  const auto run = run_command(evms_binary() + " run " + dir.path("g/events.txt") + " --quiet --out " + dir.path("r"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  auto f_of = [&](const std::string& pred) {
    const auto r = run_command(evms_binary() + " metrics --chunk-us 10000 --truth " + dir.path("g/labels.csv") + " --pred " + pred);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    double ari = -1, nmi = -1, p = -1, rc = -1, f = -1;
    EXPECT_EQ(std::sscanf(r.out.c_str(), "%lf %lf %lf %lf %lf", &ari, &nmi, &p, &rc, &f), 5) << r.out;
    return f;
  };
  EXPECT_DOUBLE_EQ(f_of(dir.path("g/labels.csv")), 1.0);
  const double f = f_of(dir.path("r/events.csv"));
  EXPECT_GT(f, 0.5);
  EXPECT_LT(f, 1.0);
  // A board run writes -2 for a label its link lost: scored as unclustered, as noise is. A
  // label below that is refused with its line.
  std::string lost = read_file(dir.path("r/events.csv"));
  const size_t row = lost.find('\n', lost.find("t_us,")) + 1;
  const size_t label = lost.rfind(',', lost.find('\n', row)) + 1;
  lost.replace(label, lost.find('\n', row) - label, "-1");
  const double f_noise = f_of(dir.write("noise.csv", lost));
  lost.replace(label, 2, "-2");
  EXPECT_DOUBLE_EQ(f_of(dir.write("lost.csv", lost)), f_noise);
  lost.replace(label, 2, "-3");
  const auto bad = run_command(evms_binary() + " metrics --truth " + dir.path("g/labels.csv") + " --pred " + dir.write("bad.csv", lost));
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("bad.csv: line 3: label -3 is not a track ID, -1 (noise) or -2 (lost on the board's link)"), std::string::npos)
      << bad.err;
  // Truth from another tool, its columns in another order and its times in seconds, scores the
  // same: the header names the columns (host/read/csv_columns.h), a column of another name is
  // not read, and tabs may separate them; a field in quotes may hold the separator.
  std::istringstream truth(read_file(dir.path("g/labels.csv")));
  std::string line, reordered = "Label\tX\tY\tpolarity\tt_s\tkind\n", quoted = "\"kind, of shape\",t_us,x,y,p,label\n";
  while (std::getline(truth, line)) {
    long long t = 0;
    int x = 0, y = 0, p = 0, object = 0;
    if (std::sscanf(line.c_str(), "%lld,%d,%d,%d,%d", &t, &x, &y, &p, &object) != 5) continue;
    char row[96];
    std::snprintf(row, sizeof row, "%d\t%d\t%d\t%d\t%lld.%06lld\t%s\n", object, x, y, p, t / 1000000, t % 1000000, object < 0 ? "" : "shape 2");
    reordered += row;
    quoted += std::string(object < 0 ? "" : "\"a \"\"shape\"\", 2\"") + "," + std::to_string(t) + "," + std::to_string(x) + "," +
              std::to_string(y) + "," + std::to_string(p) + "," + std::to_string(object) + "\n";
  }
  const auto other = run_command(evms_binary() + " metrics --chunk-us 10000 --truth " + dir.write("other.csv", reordered) +
                                 " --pred " + dir.path("r/events.csv"));
  const auto ours = run_command(evms_binary() + " metrics --chunk-us 10000 --truth " + dir.path("g/labels.csv") + " --pred " +
                                dir.path("r/events.csv"));
  ASSERT_EQ(other.exit_code, 0) << other.err;
  EXPECT_EQ(other.out, ours.out);
  const auto commas = run_command(evms_binary() + " metrics --chunk-us 10000 --truth " + dir.write("quoted.csv", quoted) + " --pred " +
                                  dir.path("r/events.csv"));
  ASSERT_EQ(commas.exit_code, 0) << commas.err;
  EXPECT_EQ(commas.out, ours.out);
  // Without a header the rows are t_us,x,y,p,label, as evms run reads them, and score the same.
  std::string headerless = read_file(dir.path("g/labels.csv"));
  const size_t header = headerless.find("t_us,");
  headerless.erase(header, headerless.find('\n', header) - header + 1);
  const auto bare = run_command(evms_binary() + " metrics --chunk-us 10000 --truth " + dir.write("bare.csv", headerless) +
                                " --pred " + dir.path("r/events.csv"));
  ASSERT_EQ(bare.exit_code, 0) << bare.err;
  EXPECT_EQ(bare.out, ours.out);
  std::string semicolons = headerless;  // and so do they separated by ';'
  std::replace(semicolons.begin(), semicolons.end(), ',', ';');
  const auto semi = run_command(evms_binary() + " metrics --chunk-us 10000 --truth " + dir.write("semi.csv", semicolons) +
                                " --pred " + dir.path("r/events.csv"));
  ASSERT_EQ(semi.exit_code, 0) << semi.err;
  EXPECT_EQ(semi.out, ours.out);
  const auto four = run_command(evms_binary() + " metrics --truth " + dir.write("four.csv", "1,2,3,1\n") + " --pred " +
                                dir.path("r/events.csv"));
  EXPECT_EQ(four.exit_code, 1);
  EXPECT_NE(four.err.find("four.csv: line 1: truncated row: expected 5 fields"), std::string::npos) << four.err;
  const auto unlabelled = run_command(evms_binary() + " metrics --truth " + dir.write("u.csv", "t,x,y,p\n1,2,3,1\n") + " --pred " +
                                      dir.path("r/events.csv"));
  EXPECT_EQ(unlabelled.exit_code, 1);
  EXPECT_NE(unlabelled.err.find("u.csv: line 1: bad header: no label column (the columns are t,x,y,p; the labels are read from a column named label)"), std::string::npos) << unlabelled.err;
}

// evms metrics --touching-px adds a line: the truth scored with the objects that touch in a
// chunk merged. Objects 1 and 2 are 2 px apart in the first 10 ms chunk and 20 px apart in the
// second, so the merged truth loses precision in the first chunk only; at a reach below 2 px
// it is the truth.
TEST(Cli, MetricsScoresTheTruthWithTouchingObjectsMerged) {
  TempDir dir;
  std::string truth = "# sensor 64x64\nt_us,x,y,p,label\n";
  for (int i = 0; i < 4; ++i) truth += std::to_string(100 + i) + ",10," + std::to_string(10 + i) + ",1,1\n";
  for (int i = 0; i < 4; ++i) truth += std::to_string(200 + i) + ",12," + std::to_string(10 + i) + ",0,2\n";
  for (int i = 0; i < 4; ++i) truth += std::to_string(10100 + i) + ",10," + std::to_string(10 + i) + ",1,1\n";
  for (int i = 0; i < 4; ++i) truth += std::to_string(10200 + i) + ",30," + std::to_string(10 + i) + ",0,2\n";
  const std::string path = dir.write("truth.csv", truth);
  auto touching_line = [&](const std::string& reach) {
    const auto r = run_command(evms_binary() + " metrics --chunk-us 10000 --truth " + path + " --pred " + path + " --touching-px " + reach);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const size_t at = r.out.find("touching-merged ");
    EXPECT_NE(at, std::string::npos) << r.out;
    double ari = -1, nmi = -1, p = -1, rc = -1, f = -1;
    EXPECT_EQ(std::sscanf(r.out.c_str() + at, "touching-merged %lf %lf %lf %lf %lf", &ari, &nmi, &p, &rc, &f), 5) << r.out;
    return std::array<double, 2>{p, rc};
  };
  // Chunk 1 merged: 12 of 28 pairs true; chunk 2 as true. Means over the two chunks.
  const auto merged = touching_line("2");
  EXPECT_NEAR(merged[0], (12.0 / 28.0 + 1.0) / 2.0, 1e-6);  // printed to 6 decimals
  EXPECT_DOUBLE_EQ(merged[1], 1.0);
  EXPECT_DOUBLE_EQ(touching_line("1.9")[0], 1.0);
  const auto plain = run_command(evms_binary() + " metrics --chunk-us 10000 --truth " + path + " --pred " + path);
  EXPECT_EQ(plain.out.find("touching-merged"), std::string::npos) << plain.out;
  const auto negative = run_command(evms_binary() + " metrics --truth " + path + " --pred " + path + " --touching-px -1");
  EXPECT_NE(negative.exit_code, 0);
}

// evms metrics --least adds a line: the scores of the chunk of the least ARI, and where it
// starts. Two objects in two 10 ms chunks; the prediction holds them apart in the first and as
// one in the second, so the second is the least (ARI 0), from its first event's time and line.
TEST(Cli, MetricsNamesTheChunkOfTheLeastAri) {
  TempDir dir;
  std::string truth = "t_us,x,y,p,label\n", pred = truth;
  for (int chunk = 0; chunk < 2; ++chunk) {
    for (int i = 0; i < 8; ++i) {
      const std::string row = std::to_string(chunk * 10000 + 100 + i) + "," + std::to_string(i < 4 ? 10 : 40) + ",20,1,";
      truth += row + (i < 4 ? "1\n" : "2\n");
      pred += row + (chunk == 1 || i < 4 ? "5\n" : "6\n");
    }
  }
  const std::string files = " --truth " + dir.write("truth.csv", truth) + " --pred " + dir.write("pred.csv", pred);
  const auto r = run_command(evms_binary() + " metrics --chunk-us 10000 --least" + files);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const size_t at = r.out.find("least-chunk ");
  ASSERT_NE(at, std::string::npos) << r.out;
  double ari = -1, nmi = -1, p = -1, rc = -1, f = -1;
  long long t = -1, line = -1;
  ASSERT_EQ(std::sscanf(r.out.c_str() + at, "least-chunk %lf %lf %lf %lf %lf (the chunk of the least ARI, from t_us %lld, line %lld", &ari,
                        &nmi, &p, &rc, &f, &t, &line),
            7)
      << r.out;
  EXPECT_NEAR(ari, 0, 1e-6);
  EXPECT_NEAR(rc, 1, 1e-6);
  EXPECT_LT(p, 1);
  EXPECT_EQ(t, 10100);
  EXPECT_EQ(line, 10);  // the header, 8 rows of the first chunk, then the second's first
  double mean_ari = -1;
  ASSERT_EQ(std::sscanf(r.out.c_str(), "%lf", &mean_ari), 1);
  EXPECT_NEAR(mean_ari, 0.5, 1e-6);  // the first chunk agrees (1), the second not (0)
  const auto same = run_command(evms_binary() + " metrics --chunk-us 10000 --least --truth " + dir.path("truth.csv") + " --pred " +
                                dir.path("truth.csv"));
  ASSERT_EQ(same.exit_code, 0) << same.err;
  EXPECT_NE(same.out.find("least-chunk 1.000000"), std::string::npos) << same.out;
  const auto plain = run_command(evms_binary() + " metrics --chunk-us 10000" + files);
  EXPECT_EQ(plain.out.find("least-chunk"), std::string::npos) << plain.out;
}

// evms metrics --tracks scores identity and the confirmed tracks against the labelled events'
// centre. Object 7 fires at x = 10 and x = 30 in turn (its centre x = 20, y = 50) for 60 ms,
// labelled track 3; the confirmed updates stand 1 px right of that centre, and a tentative one
// far away does not count. Bad rows of the tracks file stop with the file and line.
TEST(Cli, MetricsScoresTracksAgainstTheLabelledEvents) {
  TempDir dir;
  std::string truth = "t_us,x,y,p,label\n", pred = truth;
  for (int t = 0; t < 60000; t += 100) {
    const std::string row = std::to_string(t) + "," + (t % 200 ? "30" : "10") + ",50,1,";
    truth += row + "7\n", pred += row + "3\n";
  }
  const std::string header = "t_us,track_id,state,x,y,vx,vy,events\n";
  std::string tracks = header;
  for (int t = 10050; t <= 50050; t += 10000) tracks += std::to_string(t) + ",3,confirmed,21,50,0,0,100\n";
  tracks += "55050,3,tentative,90,10,0,0,100\n";
  const std::string files = " --truth " + dir.write("truth.csv", truth) + " --pred " + dir.write("pred.csv", pred);
  const auto r = run_command(evms_binary() + " metrics --chunk-us 10000" + files + " --tracks " + dir.write("tracks.csv", tracks));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  double f[5], idf1 = 0, err = -1, within = -1;
  long long switches = -1, objects = -1, estimates = -1;
  const size_t second = r.out.find('\n') + 1, third = r.out.find('\n', second) + 1;
  ASSERT_EQ(std::sscanf(r.out.c_str(), "%lf %lf %lf %lf %lf", &f[0], &f[1], &f[2], &f[3], &f[4]), 5) << r.out;
  EXPECT_DOUBLE_EQ(f[4], 1.0);
  ASSERT_EQ(std::sscanf(r.out.c_str() + second, "IDF1 %lf ID-precision %*f ID-recall %*f ID-switches %lld objects %lld", &idf1, &switches,
                        &objects), 3) << r.out;
  EXPECT_DOUBLE_EQ(idf1, 1.0);
  EXPECT_EQ(switches, 0);
  EXPECT_EQ(objects, 1);
  ASSERT_EQ(std::sscanf(r.out.c_str() + third, "tracking %lf px within-2.5px %lf estimates %lld", &err, &within, &estimates), 3) << r.out;
  EXPECT_NEAR(err, 1.0, 1e-6);
  EXPECT_DOUBLE_EQ(within, 1.0);
  EXPECT_EQ(estimates, 5);
  // A truth of noise alone holds no object, so nothing is an estimate.
  std::string noise = truth;
  for (size_t at = noise.find(",7\n"); at != std::string::npos; at = noise.find(",7\n", at)) noise.replace(at, 3, ",-1\n");
  const auto none = run_command(evms_binary() + " metrics --truth " + dir.write("noise.csv", noise) + " --pred " + dir.path("pred.csv") +
                                " --tracks " + dir.path("tracks.csv"));
  ASSERT_EQ(none.exit_code, 0) << none.err;
  EXPECT_NE(none.out.find("estimates 0 "), std::string::npos) << none.out;

  const auto bad = [&](const std::string& name, const std::string& text) {
    const auto b = run_command(evms_binary() + " metrics" + files + " --tracks " + dir.write(name, text));
    EXPECT_EQ(b.exit_code, 1) << name;
    EXPECT_EQ(std::count(b.err.begin(), b.err.end(), '\n'), 1) << b.err;
    return b.err;
  };
  EXPECT_NE(bad("h.csv", "t_us,id,x,y\n").find("h.csv: line 1: bad header: expected 't_us,track_id,state,x,y,vx,vy' first"), std::string::npos);
  EXPECT_NE(bad("s.csv", header + "10050,3,lost,21,50,0,0,100\n").find("s.csv: line 2: state 'lost' is neither tentative nor confirmed"),
            std::string::npos);
  EXPECT_NE(bad("n.csv", header + "10050,3,confirmed,21,50,0,0\n").find("n.csv: line 2: 7 fields where the header has 8"), std::string::npos);
  EXPECT_NE(bad("x.csv", header + "10050,3,confirmed,nan,50,0,0,1\n").find("x.csv: line 2: x 'nan' is not a finite number"), std::string::npos);
  EXPECT_NE(bad("i.csv", header + "10050,-4,confirmed,21,50,0,0,1\n").find("i.csv: line 2: track_id '-4' is not a track ID"), std::string::npos);
}

// A source that fails part way (a corrupt record; a camera unplugged, which reaches the run
// the same way as a paced replay's failure does): the events before the failure are labelled
// and written, the summary printed, and the cause is one line with a non-zero exit.
TEST(Cli, ASourceThatFailsPartWayKeepsWhatCameBefore) {
  TempDir dir;
  const auto events = sample_events(5000, {240, 180});
  const std::string in = dir.write("in.csv", csv(events) + "999999999,4,4\n");  // a header line, 5,000 rows, a bad one
  for (const char* pacing : {"", " --realtime --speed 1000"}) {
    SCOPED_TRACE(pacing);
    const auto r = run_command(evms_binary() + " run " + in + " --quiet --width 240 --height 180 --out " + dir.path("o") + pacing);
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.err, "evms: " + in + ": line 5002: missing field 'p' (truncated record)\n");
    EXPECT_NE(r.out.find("events in   5,000"), std::string::npos) << r.out;
    EXPECT_EQ(count_lines(dir.path("o/events.csv")), events.size() + 2);
  }
}

// Ctrl-C ends any source as if its input had ended: the outputs are complete files holding
// every event read until then, and the summary is printed. A recording cut short exits 130; a
// live source (here a paced replay, and a UDP port nobody sends to) ends normally.
TEST(Cli, CtrlCLeavesCompleteOutputs) {
  struct Case {
    std::string source;
    std::string ready;  // a shell test that is true once evms is in its loop
    int exit_code;
  };
  TempDir dir;
  const std::string out = dir.path("o"), log = dir.path("log");
  const std::vector<Case> cases = {
      {"'gen://rotation?duration-s=60'", "[ -s " + out + "/events.csv ]", 130},
      {"'gen://rotation?duration-s=60' --realtime", "[ -s " + out + "/events.csv ]", 0},
      {"udp://127.0.0.1:47193", "grep -q listening " + log, 0},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.source);
    std::filesystem::remove_all(out);
    const auto r = run_command(evms_binary() + " run " + c.source + " --quiet --out " + out + " > " + log +
                               " 2>&1 & pid=$!; for i in $(seq 600); do " + c.ready + " && break; sleep 0.05; done; sleep 0.3; "
                               "kill -INT $pid; wait $pid; echo $?");
    ASSERT_EQ(r.out, std::to_string(c.exit_code) + "\n") << read_file(log);
    const std::string summary = read_file(log);
    const std::int64_t events = number_after(summary, "events in   ");
    ASSERT_NE(events, -1) << summary;
    // Ctrl-C ends the source, even one that never falls quiet (the replay): the run does not
    // go on to the end of the generated minute.
    const size_t over = summary.find(" over ", summary.find("events in   ")), span_end = summary.find(" s of sensor time");
    ASSERT_TRUE(over != std::string::npos && span_end != std::string::npos) << summary;
    EXPECT_LT(std::stod(summary.substr(over + 6, span_end - over - 6)), 30.0) << summary;
    EXPECT_NE(summary.find("outputs     "), std::string::npos) << summary;
    EXPECT_EQ(summary.find("interrupted before the end") != std::string::npos, c.exit_code == 130) << summary;
    const std::string rows = read_file(out + "/events.csv"), tracks = read_file(out + "/tracks.csv");
    EXPECT_EQ(static_cast<std::int64_t>(count_lines(out + "/events.csv")), events + 2);
    ASSERT_FALSE(rows.empty());
    EXPECT_EQ(rows.back(), '\n');
    const std::string last = rows.substr(rows.rfind('\n', rows.size() - 2) + 1);
    EXPECT_EQ(std::count(last.begin(), last.end(), ','), 4) << last;
    EXPECT_EQ(tracks.rfind("t_us,track_id,state,", 0), 0u);
    EXPECT_EQ(tracks.back(), '\n');
    if (c.exit_code == 130) {
      EXPECT_GT(events, 0);
    }
  }
}

TEST(Cli, MemoryIsFlatInTheInputLength) {
  // The same scene, 4x longer: peak memory must not grow with it. The filter window is
  // minimal and the stream's first events are judged too, so that almost nothing reaches the
  // clustering and the test stays quick (a packet left open holds every dropped event after it
  // until a kept one closes it: golden/pipeline.cpp). The
  // shorter input is long enough for every buffer to have reached its working size (a few
  // MB are allocated once, between 200 k and 400 k events).
#ifdef __SANITIZE_ADDRESS__
  GTEST_SKIP() << "AddressSanitizer's quarantine holds freed memory, so peak RSS grows with the input; measured in the release build";
#endif
  TempDir dir;
  auto small = sample_events(400000, {240, 180}, 3), large = sample_events(1600000, {240, 180}, 3);
  const std::string a = dir.write("a.txt", rpg_text(small)), b = dir.write("b.txt", rpg_text(large));
  small.clear(), large.clear();
  const std::string cmd = evms_binary() + " run --quiet --filter-window-us 1 --filter-warm-up-us 0 --out " + dir.path("o") + " ";
  const auto ra = run_command(cmd + a), rb = run_command(cmd + b);
  ASSERT_EQ(ra.exit_code, 0) << ra.err;
  ASSERT_EQ(rb.exit_code, 0) << rb.err;
  EXPECT_LT(rb.max_rss_kb, ra.max_rss_kb + 4096) << "peak RSS " << ra.max_rss_kb << " kB for 400k events, " << rb.max_rss_kb << " kB for 1.6M";
}

}  // namespace
}  // namespace evms::test

namespace evms::test {
namespace {

TEST(Cli, ParameterDocsAreCurrent) {
  const auto r = run_command(evms_binary() + " params --markdown");
  ASSERT_EQ(r.exit_code, 0);
  std::ifstream doc(std::string(EVMS_SOURCE_DIR) + "/docs/parameters.md");
  std::stringstream ss;
  ss << doc.rdbuf();
  EXPECT_EQ(ss.str(), r.out) << "docs/parameters.md is stale: regenerate it with 'evms params --markdown'";
  // Every row has its four cells: a '|' in a meaning ("|ON - OFF|") is escaped, not a cell's end.
  std::istringstream rows(r.out);
  int table_rows = 0;
  for (std::string row; std::getline(rows, row);) {
    if (row.rfind("| `--", 0) != 0) continue;
    ++table_rows;
    int ends = 0;
    for (size_t i = 0; i < row.size(); ++i) ends += row[i] == '|' && (i == 0 || row[i - 1] != '\\');
    EXPECT_EQ(ends, 5) << row;
  }
  EXPECT_GT(table_rows, 50);
}

}  // namespace
}  // namespace evms::test
