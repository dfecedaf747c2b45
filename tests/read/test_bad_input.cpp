// Bad input: one line naming the file, the line or byte offset, and what is wrong. Never a
// crash, never a silent drop.
#include <gtest/gtest.h>
#include <zstd.h>

#include <cstdint>

#include "tests/support/encoders.h"
#include "tests/support/read_all.h"
#include "host/read/input_error.h"

namespace evms::test {
namespace {

// The error must name the file, the position and the problem, on one line.
void expect_error(const std::string& path, const std::string& position, const std::string& what,
                  const read::SourceOptions& o = {}) {
  const std::string message = read_error(path, o);
  SCOPED_TRACE(message);
  const std::string prefix = path + ": " + position;
  EXPECT_EQ(message.rfind(prefix, 0), 0u) << "expected '" << prefix << "...'";
  if (position.back() != ' ') {
    EXPECT_EQ(message.substr(prefix.size(), 2), ": ");
  }
  EXPECT_NE(message.find(what), std::string::npos) << "expected the message to say '" << what << "'";
  EXPECT_EQ(message.find('\n'), std::string::npos);
}

Bytes truncated(Bytes b, size_t drop) {
  b.resize(b.size() - drop);
  return b;
}

const std::vector<Event> kEvents = sample_events(300, {128, 128});

TEST(BadInput, TruncatedRecords) {
  TempDir d;
  {
    const Bytes b = aedat2_dvs128(kEvents);
    expect_error(d.write("a2.aedat", truncated(b, 3)), "byte " + std::to_string(b.size() - 8), "truncated record (5 of 8 bytes)");
  }
  {
    const Bytes b = aedat3_davis240(kEvents);
    expect_error(d.write("a3.aedat", truncated(b, 2)), "byte " + std::to_string(b.size() - 8), "truncated record (6 of 8 bytes)");
  }
  {
    const Bytes b = aedat4(kEvents, {128, 128}, Aedat4Compression::kLz4, 1000);
    expect_error(d.write("a4.aedat4", truncated(b, 30)), "byte ", "truncated packet");
  }
  {
    const Bytes b = evt2(kEvents, {128, 128});
    expect_error(d.write("e2.raw", truncated(b, 1)), "byte " + std::to_string(b.size() - 4), "truncated word (3 of 4 bytes)");
  }
  {
    const Bytes b = evt21(kEvents, {128, 128}, true);
    expect_error(d.write("e21.raw", truncated(b, 3)), "byte " + std::to_string(b.size() - 8), "truncated word (5 of 8 bytes)");
    Bytes reserved = b;
    reserved[reserved.size() - 5] = 0x30;  // the last word's EVT 2.0 half: type 0x3
    expect_error(d.write("e21r.raw", reserved), "byte " + std::to_string(b.size() - 8),
                 "reserved EVT 2.1 word type 0x3 (is the header's endianness, legacy, the file's?)");
  }
  {
    Bytes b = evt3(kEvents, {128, 128});
    b.push_back(0x12);
    expect_error(d.write("e3.raw", b), "byte " + std::to_string(b.size() - 1), "truncated word");
  }
  {
    const Bytes b = dat(kEvents);
    expect_error(d.write("d.dat", truncated(b, 4)), "byte " + std::to_string(b.size() - 8), "truncated record (4 of 8 bytes)");
  }
  expect_error(d.write("t.txt", "0.000010000 1 2 1\n0.000020000 3 4\n"), "line 2", "missing field 'p' (truncated record)");
  expect_error(d.write("c.csv", "t_us,x,y,p\n10,1,2,1\n20,3\n"), "line 3", "missing field 'y' (truncated record)");
}

TEST(BadInput, BadHeaders) {
  TempDir d;
  expect_error(d.write("v5.aedat", "#!AER-DAT5.0\r\n"), "byte 0", "bad header: unsupported AEDAT version");
  expect_error(d.write("a3.aedat", "#!AER-DAT3.1\r\n#Format: RAW\r\n"), "byte ", "bad header: no '#!END-HEADER' line");
  expect_error(d.write("a3f.aedat", "#!AER-DAT3.1\r\n#Format: SerializedTS\r\n#!END-HEADER\r\n"), "line 2", "only '#Format: RAW'");
  {
    Bytes b = aedat4(kEvents, {128, 128}, Aedat4Compression::kNone);
    b[20] ^= 0xFF;  // inside the IOHeader flatbuffer's identifier
    expect_error(d.write("a4.aedat4", b), "byte 18", "bad header: the IOHeader flatbuffer does not verify");
  }
  expect_error(d.write("e4.raw", "% evt 4.0\n"), "line 1", "bad header: unsupported encoding 'evt 4.0'");
  expect_error(d.write("x.raw", "% date 2020\n"), "line 1", "bad header");
  {
    Bytes b = dat(kEvents);
    b[b.size() - kEvents.size() * 8 - 2] = 7;  // event type byte
    expect_error(d.write("d.dat", b), "byte ", "bad header: event type 7");
  }
  // A CSV header names its columns (Formats.CsvColumnsGoByTheirHeader): each of t, x, y and p
  // once, by a name evms knows; a column of another name is not read.
  expect_error(d.write("c.csv", "time,x,y,pixel\n1,2,3,1\n"), "line 1",
               "bad header: no polarity column (the columns are time,x,y,pixel; the names evms reads: t_us, t, ts");
  expect_error(d.write("c.csv", "t,x,y,p,a,b,c,d,e,f,g,h,i,j,k,l,m\n"), "line 1", "bad header: more than 16 columns");
  expect_error(d.write("c.csv", "t,x,y\n1,2,3\n"), "line 1", "bad header: no polarity column (the columns are t,x,y)");
  expect_error(d.write("c.csv", "t,x,y,p,ts\n"), "line 1", "bad header: column 'ts' repeats the time");
  expect_error(d.write("c.csv", ",t,x,y,p\n0,1,2,3,1\n"), "line 1", "bad header: column 1 has no name (pandas writes its index so");
  // A quote that opens a field must close it, with nothing but blanks before the separator.
  expect_error(d.write("c.csv", "t,x,y,p,\"note\n"), "line 1", "bad header: column 5: a quoted field does not close before the end of the row");
  expect_error(d.write("c.csv", "t,x,y,p,note\n1,2,3,1,\"a,b\n"), "line 2", "field 'note': a quoted field does not close before the end of the row");
  expect_error(d.write("c.csv", "t,x,y,p\n1,\"2\"3,3,1\n"), "line 2", "field 'x': a quoted field does not close before the end of the row, or has more than blanks after");
  expect_error(d.write("c.csv", "# sensor 64x64\n\nt,x,y,p\n0.5,1,2,1\n"), "line 4",
               "field 't' = '0.5' is not an integer number of microseconds (a column named t_s holds seconds)");
  expect_error(d.write("c.csv", "%geometry:320x240\n1,2,1,3\n"), "line 1", "bad header: expected '%geometry:W,H'");
  // Metavision's rows without their geometry line or a header read as t,x,y,p, whose polarity
  // is then the time.
  expect_error(d.write("c.csv", "10,20,1,100\n"), "line 1",
               "polarity 100 is not 0, 1 or -1; rows of x,y,p,t, as Metavision's tools write them, need the header line 'x,y,p,t'");
  // After the header, a word is a bad record, not a second header.
  expect_error(d.write("nan.csv", "t_us,x,y,p\nnan,2,3,1\n"), "line 2", "field 't_us' = 'nan' is not an integer");
  expect_error(d.write("huge.csv", "t_us,x,y,p\n18446744073709551615,2,3,1\n"), "line 2",
               "field 't_us' = '18446744073709551615' is out of range (at most 9223372036854775807)");
  expect_error(d.write("bin.bin", Bytes{0x00, 0xFF, 0x13, 0x00, 0x42}), "byte 0", "bad header: not a known event format");
  // NumPy files: the header's dict says what each record holds (Formats.NpyStructuredAndPlainArraysReadTheSame).
  {
    const std::string fields = "[('t', '<i8'), ('x', '<u2'), ('y', '<u2'), ('p', '|u1')]";
    const auto header = [](const std::string& descr, const std::string& shape, const char* order = "False") {
      return "{'descr': " + descr + ", 'fortran_order': " + order + ", 'shape': " + shape + ", }";
    };
    Bytes record;
    put_int(record, 10, 8), put_int(record, 1, 2), put_int(record, 2, 2), put_int(record, 1, 1);  // 13 bytes
    expect_error(d.write("n.npy", npy(header("[('t', '<i8'), ('x', '<u2'), ('y', '<u2'), ('q', '|u1')]", "(1,)"), record)), "byte ",
                 "bad NPY header: no polarity field (the fields are t,x,y,q; the names evms reads:");
    expect_error(d.write("n.npy", npy(header("[('t', '<f8'), ('x', '<u2'), ('y', '<u2'), ('p', '|u1')]", "(1,)"), record)), "byte ",
                 "field 't' is an integer number of microseconds (a float field named t_s holds seconds)");
    expect_error(d.write("n.npy", npy(header("[('t', '<i8'), ('x', '<u2'), ('p', '|u1')]", "(1,)"), record)), "byte ",
                 "bad NPY header: no y field (the fields are t,x,p)");
    expect_error(d.write("n.npy", npy(header("'<f8'", "(1, 4)"), record)), "byte ", "bad NPY header: a plain array's columns t_us,x,y,p are integers, not '<f8'");
    expect_error(d.write("n.npy", npy(header("'<i8'", "(1, 3)"), record)), "byte ", "bad NPY header: a plain array of events has shape (N, 4) or (N, 5)");
    expect_error(d.write("n.npy", npy(header("'<i8'", "(1, 4)", "True"), record)), "byte ", "bad NPY header: a plain array in Fortran order");
    expect_error(d.write("n.npy", npy(header(fields, "(2,)"), record)), "byte 141", "truncated: the header says 2 records, the file holds 1");
    Bytes more = record;
    more.push_back(0);
    expect_error(d.write("n.npy", npy(header(fields, "(1,)"), more)), "byte 141", "1 byte after the header's 1 records");
    Bytes bad_polarity;
    put_int(bad_polarity, 10, 8), put_int(bad_polarity, 1, 2), put_int(bad_polarity, 2, 2), put_int(bad_polarity, 3, 1);
    expect_error(d.write("n.npy", npy(header(fields, "(1,)"), bad_polarity)), "byte 140", "polarity 3 is not 0, 1 or -1");
    // DVS Gesture's arrays are x,y,p,t: as a plain array's t_us,x,y,p, the time is the polarity.
    Bytes gesture;
    for (int v : {1, 2, 1, 5000}) put_int(gesture, static_cast<std::uint64_t>(v), 8);
    expect_error(d.write("n.npy", npy(header("'<i8'", "(1, 4)"), gesture)), "byte 152",
                 "polarity 5000 is not 0, 1 or -1; a plain array's columns are t_us,x,y,p: save a structured array");
    // A coordinate beyond any sensor: no size is assumed, and none is given.
    Bytes far;
    put_int(far, 10, 8), put_int(far, ~std::uint64_t{0} >> 1, 8), put_int(far, 2, 8), put_int(far, 1, 8);
    const std::string far_file = d.write("far.npy", npy(header("[('t', '<i8'), ('x', '<i8'), ('y', '<i8'), ('p', '<i8')]", "(1,)"), far));
    EXPECT_EQ(read_error(far_file), far_file + ": the file does not say the sensor size: pass --width and --height");
    Bytes v9 = npy(header(fields, "(1,)"), record);
    v9[6] = 9;
    expect_error(d.write("n.npy", v9), "byte 6", "bad NPY header: version 9");
    expect_error(d.write("n.npy", npy("{'descr': " + fields + ", 'shape': (1,), }", record)), "byte ",
                 "bad NPY header: the header lacks 'descr', 'fortran_order' or 'shape'");
  }
  expect_error(d.write("empty.txt", ""), "byte 0", "empty file");
}

TEST(BadInput, CoordinatesOutsideTheSensor) {
  TempDir d;
  expect_error(d.write("t.txt", "0.000001000 1 2 1\n0.000002000 240 5 0\n"), "line 2", "x=240 y=5 is outside the 240x180 sensor",
               sized(240, 180, 1000));
  expect_error(d.write("c.csv", "t_us,x,y,p\n5,7,200,1\n"), "line 2", "x=7 y=200 is outside the 240x180 sensor", sized(240, 180, 1000));
  // Without a size, the text formats take the smallest usual sensor that holds every row.
  expect_error(d.write("s.csv", "# sensor 240x180\nt_us,x,y,p\n5,7,200,1\n"), "line 3", "x=7 y=200 is outside the 240x180 sensor");
  EXPECT_EQ(read_error(d.path("c.csv")), "");
  // The same CSV is fine on a taller sensor given on the command line.
  EXPECT_EQ(read_error(d.path("c.csv"), sized(240, 260, 1000)), "");
  auto wide = kEvents;
  wide[10].x = 200;
  const Bytes e3 = evt3(wide, {128, 128});
  expect_error(d.write("e3.raw", e3), "byte ", "x=200");
  auto tall = kEvents;
  tall[5].y = 300;
  expect_error(d.write("a4.aedat4", aedat4(tall, {128, 128}, Aedat4Compression::kZstd)), "byte ", "y=300 is outside the 128x128 sensor");
}

TEST(BadInput, TimestampsGoingBackwardsBeyondTheTolerance) {
  TempDir d;
  expect_error(d.write("t.txt", "1.000000000 1 2 1\n1.000500000 1 2 1\n0.500000000 3 4 0\n"), "line 3", "goes back 500500 us");
  auto events = kEvents;
  events.push_back({events.back().t - 5000, 1, 1, 1});
  expect_error(d.write("e2.raw", evt2(events, {128, 128})), "byte ", "more than the reorder tolerance");
  expect_error(d.write("d.dat", dat(events)), "byte " + std::to_string(dat(events).size() - 8), "goes back 5000 us");
}

TEST(BadInput, MalformedFields) {
  TempDir d;
  expect_error(d.write("t.txt", "0.1 1 2 1\nabc 1 2 1\n"), "line 2", "is not a non-negative decimal number of seconds");
  expect_error(d.write("p.txt", "0.1 1 2 5\n"), "line 1", "polarity 5 is not 0, 1 or -1");
  expect_error(d.write("f.txt", "0.1 1 2 1 9\n"), "line 1", "more than 4 fields");
  // A header of names separated by blanks: only a CSV names its columns.
  expect_error(d.write("h.txt", "# from a script\nt x y p\n0.1 2 3 1\n"), "line 2",
               "'t x y p' is not a row of time (s), x, y and polarity; a header naming the columns is read in a CSV file, whose columns are separated by "
               "commas, semicolons or tabs");
  // RPG times are seconds: a whole number of a million or more, before any time with a decimal
  // point, is a count of microseconds, refused on either reading path (blanks send a line to the second).
  for (const char* line : {"5 1 2 1\n1317888 1 2 1\n", "5 1 2 1\n 1317888  1 2 1\n"}) {
    expect_error(d.write("us.txt", line), "line 2",
                 "timestamp '1317888' has no decimal point and would be 15 days as seconds, the RPG format's unit; for microseconds write a CSV "
                 "whose header names the column t_us");
  }
  EXPECT_EQ(read_all(d.write("s.txt", "999999 1 2 1\n")).front().t, TimeUs{999999000000});
  EXPECT_EQ(read_all(d.write("s.txt", "0.5 1 2 1\n1317888 1 2 1\n")).back().t, TimeUs{1317888000000});
  expect_error(d.write("x.csv", "t_us,x,y,p\n10,1.5,2,1\n"), "line 2", "field 'x' = '1.5' is not an integer");
  {
    Bytes b = evt3(kEvents, {128, 128});
    b.push_back(0x00);
    b.push_back(0x90);  // word type 0x9 is reserved
    expect_error(d.write("r.raw", b), "byte " + std::to_string(b.size() - 2), "reserved EVT 3.0 word type 0x9");
  }
}

TEST(BadInput, MissingFilesAndUnknownSources) {
  EXPECT_NE(read_error("/nonexistent/file.raw").find("/nonexistent/file.raw: cannot open"), std::string::npos);
  EXPECT_NE(read_error("gen://spiral").find("unknown scene 'spiral'"), std::string::npos);
  EXPECT_NE(read_error("ftp://x").find("unknown source scheme"), std::string::npos);
}

TEST(BadInput, TimestampsOutsideTheirRange) {
  TempDir d;
  // 2^63 - 1 followed by -1 would overflow a difference of the two.
  expect_error(d.write("max.csv", "t_us,x,y,p\n9223372036854775807,0,0,0\n-1,0,0,0\n"), "line 2",
               "timestamp 9223372036854775807 us is beyond 2^62 us");
  expect_error(d.write("neg.csv", "t_us,x,y,p\n0,1,1,1\n-5,1,1,1\n"), "line 3", "timestamp -5 us is negative");
}

TEST(BadInput, HeaderSensorSizesBeyondTheLargestSensor) {
  TempDir d;
  expect_error(d.write("huge.raw", "% evt 3.0\n% format EVT3;height=70000;width=70000\n% end\n"), "byte 0",
               "a sensor of 70000x70000 (from the header) is outside 1x1 to 4096x4096");
  expect_error(d.write("huge.aedat4", aedat4(kEvents, {70000, 70000}, Aedat4Compression::kNone)), "byte 0",
               "a sensor of 70000x70000 (from the header)");
}

// A 33 kB ZSTD frame that expands to 129 MiB is refused when its output reaches the 128 MiB
// cap, with a message that says so.
TEST(BadInput, ADecompressionBombIsRefusedAtTheCap) {
  Bytes b = aedat4({}, {128, 128}, Aedat4Compression::kZstd);
  const size_t at = b.size();
  const std::vector<std::uint8_t> zeros((size_t{129} << 20), 0);
  Bytes frame(ZSTD_compressBound(zeros.size()));
  frame.resize(ZSTD_compress(frame.data(), frame.size(), zeros.data(), zeros.size(), 1));
  for (std::uint32_t v : {std::uint32_t{0}, static_cast<std::uint32_t>(frame.size())}) {
    for (int k = 0; k < 4; ++k) b.push_back(static_cast<std::uint8_t>(v >> (8 * k)));
  }
  b.insert(b.end(), frame.begin(), frame.end());
  TempDir d;
  expect_error(d.write("bomb.aedat4", b), "byte " + std::to_string(at),
               "packet of more than 128 MiB, stored or decompressed (a corrupt frame or a decompression bomb)");
}

TEST(ErrorMessages, ControlAndMalformedUtf8BytesAreEscaped) {
  EXPECT_EQ(read::printable("plain text, 1.5 us"), "plain text, 1.5 us");
  EXPECT_EQ(read::printable("a\x1b[2Jb"), "a\\x1b[2Jb");
  EXPECT_EQ(read::printable("\x7f\n\t"), "\\x7f\\x0a\\x09");
  EXPECT_EQ(read::printable("caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80"), "caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80");  // é, €, an emoji
  EXPECT_EQ(read::printable("\xff\xc3"), "\\xff\\xc3");              // not UTF-8; a lead byte at the end
  EXPECT_EQ(read::printable("\xc0\xaf"), "\\xc0\\xaf");              // an overlong '/'
  EXPECT_EQ(read::printable("\xed\xa0\x80"), "\\xed\\xa0\\x80");  // a surrogate
  EXPECT_EQ(read::printable(std::string("a\0b", 3)), "a\\x00b");
}

}  // namespace
}  // namespace evms::test
