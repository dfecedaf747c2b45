// Each reader decodes what a spec-based encoder wrote, event for event.
#include <gtest/gtest.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <functional>
#include <random>
#include <thread>

#include <sys/stat.h>

#include "tests/support/encoders.h"
#include "tests/support/read_all.h"
#include "host/read/event_source.h"
#include "host/read/input_error.h"

namespace evms::test {
namespace {

TEST(Formats, RpgTextRoundTrips) {
  TempDir dir;
  const auto events = sample_events(5000, {240, 180});
  EXPECT_EQ(read_all(dir.write("events.txt", rpg_text(events))), events);
}

TEST(Formats, RpgTextRoundsNanosecondsToTheNearestMicrosecond) {
  TempDir dir;
  const auto path = dir.write("e.txt", "0.000001499 1 2 1\n0.000001500 3 4 0\n12.5 5 6 1\n");
  const auto e = read_all(path);
  ASSERT_EQ(e.size(), 3u);
  EXPECT_EQ(e[0].t, 1);
  EXPECT_EQ(e[1].t, 2);
  EXPECT_EQ(e[2].t, 12500000);
}

// The usual line is read in one pass and any other through the field-by-field reader: over
// 20,000 random lines, fractions of 0 to 9 digits among them, the same line with blanks added
// (the other reader) gives the same event, and both give the time worked out here digit by digit.
TEST(Formats, TextLinesOfEveryFormReadTheSame) {
  TempDir dir;
  std::mt19937_64 rng(11);
  std::string compact, spaced, csv_compact, csv_spaced;
  std::vector<Event> want;
  for (int i = 0; i < 20000; ++i) {
    const std::uint64_t whole = i / 7;  // non-decreasing seconds, so the times stay in order
    const int digits = static_cast<int>(rng() % 10);
    std::string frac;
    for (int d = 0; d < digits; ++d) frac += static_cast<char>('0' + rng() % 10);
    TimeUs micro = 0;
    for (int d = 0; d < 6; ++d) micro = micro * 10 + (d < digits ? frac[static_cast<size_t>(d)] - '0' : 0);
    if (digits > 6 && frac[6] >= '5') ++micro;
    const TimeUs t = static_cast<TimeUs>(whole) * 1000000 + micro;
    if (!want.empty() && t < want.back().t) continue;
    const Event e{t, static_cast<std::uint16_t>(rng() % 240), static_cast<std::uint16_t>(rng() % 180), static_cast<std::uint8_t>(rng() % 2)};
    want.push_back(e);
    const std::string seconds = std::to_string(whole) + (digits ? "." + frac : "");
    const std::string xyp = std::to_string(e.x) + " " + std::to_string(e.y) + " " + std::to_string(e.p);
    compact += seconds + " " + xyp + "\n";
    spaced += "  " + seconds + " \t " + std::to_string(e.x) + "  " + std::to_string(e.y) + "\t" + (e.p ? "1" : "-1") + " \n";
    const std::string row = std::to_string(e.t) + "," + std::to_string(e.x) + "," + std::to_string(e.y) + "," + std::to_string(e.p);
    csv_compact += row + "," + std::to_string(static_cast<int>(rng() % 5) - 1) + "\n";
    csv_spaced += std::to_string(e.t) + ", " + std::to_string(e.x) + " ," + std::to_string(e.y) + "," + std::to_string(e.p) + "\n";
  }
  EXPECT_EQ(read_all(dir.write("compact.txt", compact)), want);
  EXPECT_EQ(read_all(dir.write("spaced.txt", spaced)), want);
  EXPECT_EQ(read_all(dir.write("compact.csv", "t_us,x,y,p,label\n" + csv_compact)), want);
  EXPECT_EQ(read_all(dir.write("spaced.csv", csv_spaced)), want);
  // A UTF-8 byte-order mark before the first line, as spreadsheets save a CSV, is not text.
  EXPECT_EQ(read_all(dir.write("bom.csv", "\xEF\xBB\xBFt_us,x,y,p,label\n" + csv_compact)), want);
  EXPECT_EQ(read_all(dir.write("bom.txt", "\xEF\xBB\xBF" + compact)), want);
}

TEST(Formats, CsvRoundTripsAndAcceptsALabelColumn) {
  TempDir dir;
  const auto events = sample_events(3000, {240, 180});
  EXPECT_EQ(read_all(dir.write("e.csv", csv(events))), events);
  const auto labelled = read_all(dir.write("l.csv", "t_us,x,y,p,label\n10,1,2,1,-1\n20,3,4,0,7\n"));
  ASSERT_EQ(labelled.size(), 2u);
  EXPECT_EQ(labelled[1], (Event{20, 3, 4, 0}));
}

// A header names a CSV's columns in any order, as pandas, spreadsheets and other tools write
// them; Metavision's CSV is "%geometry:W,H" and then x,y,p,t rows. Each reads the same events.
TEST(Formats, CsvColumnsGoByTheirHeader) {
  TempDir dir;
  const auto events = sample_events(3000, {320, 240});
  const auto rows = [&](const std::string& header, const std::function<std::string(const Event&)>& row) {
    std::string s = header.empty() ? "" : header + "\n";
    for (const Event& e : events) s += row(e) + "\n";
    return s;
  };
  const auto n = [](auto v) { return std::to_string(v); };
  const auto seconds = [](TimeUs t) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%lld.%06lld", static_cast<long long>(t / 1000000), static_cast<long long>(t % 1000000));
    return std::string(buf);
  };
  const read::SourceOptions vga = sized(320, 240, 1000);
  struct Case {
    const char* file;
    std::string text;
    const char* format;
  };
  const Case cases[] = {
      {"usual.csv", rows("t_us,x,y,p", [&](const Event& e) { return n(e.t) + "," + n(e.x) + "," + n(e.y) + "," + n(e.p); }),
       "CSV t_us,x,y,p"},
      {"xypt.csv", rows("x,y,p,t", [&](const Event& e) { return n(e.x) + "," + n(e.y) + "," + n(e.p) + "," + n(e.t); }),
       "CSV x,y,p,t"},
      {"named.csv",
       rows("\"Polarity\", Timestamp ,label,Y,X",
            [&](const Event& e) { return n(e.p) + "," + n(e.t) + ",-1," + n(e.y) + "," + n(e.x); }),
       "CSV polarity,timestamp,label,y,x"},
      {"seconds.csv", rows("t_s,x,y,pol", [&](const Event& e) { return seconds(e.t) + "," + n(e.x) + "," + n(e.y) + "," + n(e.p); }),
       "CSV t_s,x,y,pol"},
      // Semicolons (spreadsheets where the comma is the decimal mark) and tabs between the columns.
      {"semicolons.csv", rows("t;x;y;p", [&](const Event& e) { return n(e.t) + ";" + n(e.x) + ";" + n(e.y) + ";" + n(e.p); }), "CSV t,x,y,p"},
      {"bare semicolons.csv", rows("", [&](const Event& e) { return n(e.t) + ";" + n(e.x) + ";" + n(e.y) + ";" + n(e.p) + ";-1"; }),
       "CSV t_us,x,y,p"},
      {"tabs.tsv", rows("x\ty\tpolarity\tt_s", [&](const Event& e) { return n(e.x) + "\t" + n(e.y) + "\t" + n(e.p) + "\t" + seconds(e.t); }),
       "CSV x,y,polarity,t_s"},
      // Columns of names evms does not know are not read, whatever they hold, empty too.
      {"more.csv",
       rows("Object,t,x,y,p,Note", [&](const Event& e) { return std::string(e.x % 3 ? "2.5" : "") + "," + n(e.t) + "," + n(e.x) + "," + n(e.y) + "," + n(e.p) + "," + (e.p ? "a b" : ""); }),
       "CSV Object,t,x,y,p,Note (not read: Object,Note)"},
      // Fields in double quotes (RFC 4180) may hold the separator and "" for a quote; quoted
      // numbers read as numbers, and a quoted name may hold the separator too.
      {"quoted.csv",
       rows("\"Note, free\",t,x,y,\"p\"", [&](const Event& e) {
         return std::string(e.x % 2 ? "\"a, \"\"b\"\", c\"" : "\"\"") + "," + n(e.t) + ",\"" + n(e.x) + "\", " + n(e.y) + " ,\"" + n(e.p) + "\"";
       }),
       "CSV Note, free,t,x,y,p (not read: Note, free)"},
      {"quoted;.csv",
       rows("t;x;y;p;\"a;b\"", [&](const Event& e) { return n(e.t) + ";" + n(e.x) + ";" + n(e.y) + ";" + n(e.p) + ";\"1;2,3\""; }),
       "CSV t,x,y,p,a;b (not read: a;b)"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.file);
    const std::string path = dir.write(c.file, c.text);
    EXPECT_EQ(read_all(path, vga), events);
    EXPECT_EQ(read::open_source(path, vga)->info().format, c.format);
  }
  const std::string metavision =
      dir.write("mv.csv", rows("%geometry:320,240", [&](const Event& e) { return n(e.x) + "," + n(e.y) + "," + n(e.p) + "," + n(e.t); }));
  EXPECT_EQ(read_all(metavision), events);
  const auto source = read::open_source(metavision, {});
  EXPECT_EQ(source->info().format, "CSV x,y,p,t (Metavision)");
  EXPECT_EQ(source->info().sensor, (SensorSize{320, 240}));
  EXPECT_EQ(source->info().sensor_origin, "header");
}

// NumPy arrays: structured records named as CSV columns are (evms's own events.npy, tonic's
// x,y,p,t with a bool polarity, seconds as floats), and plain (N, 4) integer arrays as t_us,x,y,p.
// The sensor is the smallest usual one that holds every event, said to be assumed.
TEST(Formats, NpyStructuredAndPlainArraysReadTheSame) {
  TempDir dir;
  const auto events = sample_events(2000, {346, 260});
  const std::string n = std::to_string(events.size());
  Bytes ours, tonic, seconds, plain, more;
  for (const Event& e : events) {
    put_int(ours, static_cast<std::uint64_t>(e.t), 8), put_int(ours, e.x, 2), put_int(ours, e.y, 2), put_int(ours, e.p, 1), put_int(ours, 7, 4);
    put_int(tonic, e.x, 2), put_int(tonic, e.y, 2), put_int(tonic, e.p, 1), put_int(tonic, static_cast<std::uint64_t>(e.t), 8);
    put_int(more, e.x, 2), put_int(more, e.y, 2), put_int(more, e.p, 1), put_int(more, static_cast<std::uint64_t>(e.t), 8), put_int(more, 0x3fc00000u, 4);
    const double s = static_cast<double>(e.t) / 1e6;
    std::uint64_t bits = 0;
    std::memcpy(&bits, &s, 8);
    put_int(seconds, bits, 8, true), put_int(seconds, e.x, 4), put_int(seconds, e.y, 4), put_int(seconds, e.p, 1);
    for (std::int64_t v : {e.t, std::int64_t{e.x}, std::int64_t{e.y}, std::int64_t{e.p}}) put_int(plain, static_cast<std::uint64_t>(v), 4, true);
  }
  struct Case {
    const char* file;
    Bytes bytes;
    const char* format;
  };
  const Case cases[] = {
      {"ours.npy", npy("{'descr': [('t', '<i8'), ('x', '<u2'), ('y', '<u2'), ('p', 'u1'), ('label', '<i4')], 'fortran_order': False, 'shape': (" + n + ",), }", ours),
       "NPY t,x,y,p,label"},
      {"tonic.npy", npy("{'descr': [('x', '<i2'), ('y', '<i2'), ('p', '|b1'), ('t', '<i8')], 'fortran_order': False, 'shape': (" + n + ",), }", tonic, 2),
       "NPY x,y,p,t"},
      {"seconds.npy", npy("{'descr': [('t_s', '>f8'), ('x', '<i4'), ('y', '<i4'), ('polarity', '|i1')], 'fortran_order': False, 'shape': (" + n + ",), }", seconds, 3),
       "NPY t_s,x,y,polarity"},
      {"plain.npy", npy("{'descr': '>i4', 'fortran_order': False, 'shape': (" + n + ", 4), }", plain), "NPY (N, 4) >i4 as t_us,x,y,p"},
      // A field of a name evms does not know is not read (here tonic's x,y,p,t and a float after).
      {"more.npy", npy("{'descr': [('x', '<i2'), ('y', '<i2'), ('p', '|b1'), ('t', '<i8'), ('Weight', '<f4')], 'fortran_order': False, 'shape': (" + n + ",), }", more, 2),
       "NPY x,y,p,t,Weight (not read: Weight)"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.file);
    const std::string path = dir.write(c.file, c.bytes);
    EXPECT_EQ(read_all(path), events);
    const auto source = read::open_source(path, {});
    EXPECT_EQ(source->info().format, c.format);
    EXPECT_EQ(source->info().sensor, (SensorSize{346, 260}));
    EXPECT_TRUE(source->info().sensor_assumed());
    EXPECT_EQ(read::open_source(path, sized(640, 480, 1000))->info().sensor, (SensorSize{640, 480}));
  }
}

// A pipe has no size and cannot be read twice: its records are read as they come, and its
// sensor size must be given.
TEST(Formats, NpyFromAPipeNeedsItsSensorSize) {
  TempDir dir;
  const auto events = sample_events(500, {128, 128});
  Bytes records;
  for (const Event& e : events) {
    for (std::int64_t v : {e.t, std::int64_t{e.x}, std::int64_t{e.y}, std::int64_t{e.p}}) put_int(records, static_cast<std::uint64_t>(v), 8);
  }
  const Bytes file = npy("{'descr': '<i8', 'fortran_order': False, 'shape': (500, 4), }", records);
  const std::string fifo = dir.path("pipe.npy");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  // A reader that stops early closes the pipe under the writer: its write then fails, not the test.
  std::signal(SIGPIPE, SIG_IGN);
  const auto through_pipe = [&](const read::SourceOptions& o) {
    std::thread writer([&] {
      std::FILE* f = std::fopen(fifo.c_str(), "wb");
      if (f) std::fwrite(file.data(), 1, file.size(), f), std::fclose(f);
    });
    std::string error;
    std::vector<Event> got;
    try {
      got = read_all(fifo, o);
    } catch (const read::InputError& e) {
      error = e.what();
    }
    writer.join();
    return std::pair{got, error};
  };
  EXPECT_EQ(through_pipe({}).second, fifo + ": the file does not say the sensor size: pass --width and --height");
  EXPECT_EQ(through_pipe(sized(128, 128, 1000)).first, events);
}

// A text file that does not say its size (no "# sensor WxH", no --width/--height) takes the
// smallest usual sensor that holds its rows, found by a first pass, and says it was assumed;
// its events are those a sized read gives. A pipe cannot be read twice: 240x180 is assumed.
TEST(Formats, TextWithoutASizeTakesTheSmallestUsualSensorThatHoldsItsRows) {
  TempDir dir;
  struct Case {
    SensorSize sensor;
    SensorSize assumed;
  };
  // An extent of 240x180 or less, 346x260 and 640x480, and one between 346x260 and 640x480.
  for (const Case c : {Case{{128, 128}, {128, 128}}, Case{{240, 180}, {240, 180}}, Case{{346, 260}, {346, 260}},
                       Case{{640, 480}, {640, 480}}, Case{{400, 300}, {640, 480}}}) {
    const auto events = sample_events(3000, c.sensor);
    long width = 0, height = 0;
    for (const Event& e : events) width = std::max<long>(width, e.x + 1), height = std::max<long>(height, e.y + 1);
    SCOPED_TRACE(std::to_string(width) + "x" + std::to_string(height));
    for (const std::string& path : {dir.write("e.csv", csv(events)), dir.write("e.txt", rpg_text(events))}) {
      const auto source = read::open_source(path, {});
      EXPECT_EQ(source->info().sensor, c.assumed) << path;
      EXPECT_EQ(source->info().sensor_origin, read::kSensorAssumedFromExtent) << path;
      EXPECT_EQ(read_all(path), events) << path;
      EXPECT_EQ(read::open_source(path, sized(1280, 720, 1000))->info().sensor, (SensorSize{1280, 720})) << path;
    }
  }
  // The first pass stops at a bad row; the second names it after the events before it.
  const std::string bad = dir.write("bad.csv", "t_us,x,y,p\n1,300,10,1\n2,x,1,1\n3,500,1,1\n");
  EXPECT_EQ(read::open_source(bad, {})->info().sensor, (SensorSize{304, 240}));
  EXPECT_EQ(read_error(bad), bad + ": line 3: field 'x' = 'x' is not an integer");
  // Beyond any sensor: nothing is taken from the rows, and the row is named.
  const std::string far = dir.write("far.csv", "t_us,x,y,p\n1,10,10,1\n2,4096,1,1\n");
  EXPECT_EQ(read_error(far), far + ": line 3: event at x=4096 y=1 is outside the 240x180 sensor (set --width/--height if the size is wrong)");
  // Through a pipe.
  const std::string fifo = dir.path("pipe.csv");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  std::signal(SIGPIPE, SIG_IGN);
  const std::string rows = "1,10,10,1\n2,300,200,0\n";
  std::thread writer([&] {
    std::FILE* f = std::fopen(fifo.c_str(), "wb");
    if (f) std::fwrite(rows.data(), 1, rows.size(), f), std::fclose(f);
  });
  EXPECT_EQ(read_error(fifo), fifo + ": line 2: event at x=300 y=200 is outside the 240x180 sensor (set --width/--height if the size is wrong)");
  writer.join();
}

TEST(Formats, Aedat2Dvs128AndDavisRoundTrip) {
  TempDir dir;
  const auto small = sample_events(2000, {128, 128});
  auto dvs = read::open_source(dir.write("dvs.aedat", aedat2_dvs128(small)), {});
  EXPECT_EQ(dvs->info().sensor, (SensorSize{128, 128}));
  EXPECT_EQ(read_all(dir.path("dvs.aedat")), small);
  const auto davis = sample_events(2000, {240, 180});
  const auto path = dir.write("davis.aedat", aedat2_davis240(davis));
  EXPECT_EQ(read_all(path), davis);
  auto source = read::open_source(path, {});
  EXPECT_EQ(source->info().sensor, (SensorSize{240, 180}));
  std::vector<Event> sink(4096);
  while (source->read(sink)) {
  }
  ASSERT_EQ(source->skipped().size(), 1u);
  EXPECT_EQ(source->skipped()[0].second, 1);  // the APS sample is counted, not dropped silently
}

TEST(Formats, Aedat3RoundTripsAcrossPackets) {
  TempDir dir;
  const auto events = sample_events(1234, {240, 180});
  EXPECT_EQ(read_all(dir.write("e.aedat", aedat3_davis240(events))), events);
}

// Each event packet is followed by an IMU packet, which is counted as skipped by what it holds.
TEST(Formats, Aedat4RoundTripsWithEveryCompression) {
  TempDir dir;
  const auto events = sample_events(3210, {346, 260});
  for (auto c : {Aedat4Compression::kNone, Aedat4Compression::kLz4, Aedat4Compression::kZstd}) {
    SCOPED_TRACE(static_cast<int>(c));
    const auto path = dir.write("e.aedat4", aedat4(events, {346, 260}, c, 1000));
    EXPECT_EQ(read_all(path), events);
    auto source = read::open_source(path, {});
    EXPECT_EQ(source->info().sensor, (SensorSize{346, 260}));
    std::vector<Event> sink(4096);
    while (source->read(sink)) {
    }
    ASSERT_EQ(source->skipped().size(), 1u);
    EXPECT_EQ(source->skipped()[0].first, "IMU packets");
    EXPECT_EQ(source->skipped()[0].second, 4);
  }
}

TEST(Formats, Evt2RoundTripsAndSkipsTriggers) {
  TempDir dir;
  const auto events = sample_events(4000, {640, 480});
  EXPECT_EQ(read_all(dir.write("e.raw", evt2(events, {640, 480}))), events);
}

// EVT 2.1 in both orders of a word's halves; a row burst fills one word's mask.
TEST(Formats, Evt21RoundTripsInBothWordOrders) {
  TempDir dir;
  auto events = sample_events(4000, {1280, 720});
  const TimeUs t = events.back().t + 5;
  for (std::uint16_t x : {64, 65, 70, 95, 96}) events.push_back({t, x, 50, 0});
  for (const bool legacy : {true, false}) {
    SCOPED_TRACE(legacy ? "legacy" : "little");
    const Bytes raw = evt21(events, {1280, 720}, legacy);
    ASSERT_LT(raw.size(), 8 * (events.size() + events.size() / 2)) << "the burst shares words";
    const std::string path = dir.write("e.raw", raw);
    EXPECT_EQ(read_all(path), events);
    const auto source = read::open_source(path, {});
    EXPECT_EQ(source->info().format, "EVT 2.1 RAW");
    EXPECT_EQ(source->info().sensor, (SensorSize{1280, 720}));
  }
  // The IMX636's "% evt 2.1" header alone means its order, legacy.
  Bytes raw = evt21(events, {1280, 720}, true);
  const std::string header = "% evt 2.1\n% format EVT21;height=720;width=1280;endianness=legacy\n% end\n";
  ASSERT_EQ(std::string(raw.begin(), raw.begin() + static_cast<long>(header.size())), header);
  raw.erase(raw.begin() + 10, raw.begin() + static_cast<long>(header.size()) - 6);
  EXPECT_EQ(read_all(dir.write("old.raw", raw), sized(1280, 720, 1000)), events);
  // A header whose order is not the words' (its first word, a TIME_HIGH, says which they are).
  Bytes swapped = evt21(events, {1280, 720}, true);
  const std::string legacy_field = ";endianness=legacy";
  const auto field = std::search(swapped.begin(), swapped.end(), legacy_field.begin(), legacy_field.end());
  ASSERT_NE(field, swapped.end());
  std::copy_n(";endianness=little", legacy_field.size(), field);
  EXPECT_EQ(read_all(dir.write("swapped.raw", swapped)), events);
}

TEST(Formats, Evt3RoundTripsWithVectorWords) {
  TempDir dir;
  auto events = sample_events(3000, {1280, 720});
  // A row burst: 10 ON events at consecutive x, which the encoder packs into a VECT_12 word.
  const TimeUs t = events.back().t + 5;
  for (std::uint16_t i = 0; i < 10; ++i) events.push_back({t, static_cast<std::uint16_t>(100 + i), 50, 1});
  EXPECT_EQ(read_all(dir.write("e.raw", evt3(events, {1280, 720}))), events);
}

TEST(Formats, DatRoundTrips) {
  TempDir dir;
  const auto events = sample_events(2500, {304, 240});
  EXPECT_EQ(read_all(dir.write("e.dat", dat(events))), events);
}

TEST(Formats, GeneratedSceneIsASource) {
  auto source = read::open_source("gen://translation?duration-s=0.05&seed=3", {});
  EXPECT_EQ(source->info().sensor, (SensorSize{240, 180}));
  const auto events = read_all("gen://translation?duration-s=0.05&seed=3");
  EXPECT_GT(events.size(), 100u);
  for (size_t i = 1; i < events.size(); ++i) ASSERT_LE(events[i - 1].t, events[i].t);
}

TEST(Ordering, SmallJitterIsReorderedStably) {
  TempDir dir;
  // 30 us out of order, within the default 1000 us tolerance; equal times keep file order.
  const auto path = dir.write("e.csv", "t_us,x,y,p\n100,1,1,1\n200,2,2,1\n170,3,3,0\n200,4,4,0\n300,5,5,1\n");
  const auto e = read_all(path);
  ASSERT_EQ(e.size(), 5u);
  EXPECT_EQ(e[0].x, 1);
  EXPECT_EQ(e[1].x, 3);
  EXPECT_EQ(e[2].x, 2);
  EXPECT_EQ(e[3].x, 4);
  EXPECT_EQ(e[4].x, 5);
}

TEST(Ordering, ReorderingIsBoundedByTheTolerance) {
  TempDir dir;
  const auto path = dir.write("e.csv", "t_us,x,y,p\n100,1,1,1\n5000,2,2,1\n4800,3,3,0\n");
  EXPECT_EQ(read_error(path, sized(0, 0, 1000)), "");
  EXPECT_NE(read_error(path, sized(0, 0, 100)), "");
}

}  // namespace
}  // namespace evms::test
