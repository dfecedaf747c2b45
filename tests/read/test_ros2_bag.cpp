// ROS 2 bags: every encoding of event_camera_msgs/EventPacket and dvs_msgs/EventArray decodes to
// the events encoded, the shared recording to the figures in its README, and a bad bag to one
// line that names the file and the message.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "host/read/bytes.h"
#include "host/read/event_source.h"
#include "tests/support/encoders.h"
#include "tests/support/read_all.h"

namespace evms::test {
namespace {

constexpr SensorSize kDavis346{346, 260};
constexpr const char* kPacket = "event_camera_msgs/msg/EventPacket";

// `events` cut into `parts` messages by `encode`.
template <class Encode>
std::vector<Bytes> packets(const std::vector<Event>& events, size_t parts, Encode encode) {
  std::vector<Bytes> out;
  for (size_t k = 0; k < parts; ++k) {
    const auto a = events.begin() + static_cast<long>(events.size() * k / parts);
    const auto b = events.begin() + static_cast<long>(events.size() * (k + 1) / parts);
    out.push_back(encode(std::vector<Event>(a, b)));
  }
  return out;
}

std::vector<Event> shifted(std::vector<Event> events, TimeUs by) {
  for (Event& e : events) e.t += by;
  return events;
}

TEST(Ros2Bag, EveryEncodingDecodesToTheEventsEncoded) {
  TempDir d;
  const std::vector<Event> events = sample_events(900, kDavis346);
  const std::uint64_t base_ns = 1702309120000000000;  // ROS time of the driver's start
  const TimeUs base_us = static_cast<TimeUs>(base_ns / 1000);
  struct Case {
    const char* name;
    std::vector<Bytes> messages;
    std::vector<Event> expected;
    std::string type = kPacket;
  };
  const std::vector<Case> cases = {
      {"evt3", packets(events, 3, [](const std::vector<Event>& p) { return event_packet_cdr("evt3", 0, kDavis346, evt3_words(p)); }), events},
      {"libcaer", packets(events, 3, [&](const std::vector<Event>& p) { return event_packet_cdr("libcaer", base_ns, kDavis346, libcaer_events(p)); }),
       shifted(events, base_us)},
      {"mono", packets(events, 3, [&](const std::vector<Event>& p) { return event_packet_cdr("mono", base_ns, kDavis346, mono_events(shifted(p, base_us), base_ns)); }),
       shifted(events, base_us)},
      {"dvs", packets(events, 3, [&](const std::vector<Event>& p) { return dvs_event_array_cdr(shifted(p, base_us), kDavis346); }),
       shifted(events, base_us), "dvs_msgs/msg/EventArray"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string bag = write_ros2_bag(d.path(c.name), {{"/events", c.type, c.messages}});
    auto source = read::open_source(bag, {});
    EXPECT_EQ(source->info().sensor, kDavis346);
    EXPECT_NE(source->info().format.find(c.type), std::string::npos) << source->info().format;
    EXPECT_EQ(read_all(bag), c.expected);
    // The storage file alone reads the same.
    EXPECT_EQ(read_all(bag + "/" + c.name + "_0.db3"), c.expected);
    // And so does the bag in MCAP storage, rosbag2's default since ROS 2 Iron.
    const std::string mcap = write_ros2_bag(d.path(std::string(c.name) + "_mcap"), {{"/events", c.type, c.messages}}, "mcap");
    EXPECT_EQ(read::open_source(mcap, {})->info().sensor, kDavis346);
    EXPECT_EQ(read_all(mcap), c.expected);
    EXPECT_EQ(read_all(mcap + "/" + c.name + "_mcap_0.mcap"), c.expected);
  }
}

// An MCAP file's messages read the same in chunks of every compression and outside chunks, with
// other topics' channels and messages between them.
TEST(Ros2Bag, McapFilesReadTheSameInEveryChunkCompression) {
  TempDir d;
  const std::vector<Event> events = sample_events(2000, kDavis346);
  const std::vector<Bytes> messages = packets(events, 10, [](const std::vector<Event>& p) { return event_packet_cdr("evt3", 0, kDavis346, evt3_words(p)); });
  const std::vector<BagTopic> topics = {{"/imu", "sensor_msgs/msg/Imu", std::vector<Bytes>(7, Bytes{0, 1, 0, 0})}, {"/events", kPacket, messages}};
  struct Case {
    const char* compression;
    size_t per_chunk;
  };
  for (const Case c : {Case{"", 3}, Case{"lz4", 4}, Case{"zstd", 5}, Case{"zstd", 100}, Case{"", 0}}) {
    SCOPED_TRACE(std::string(c.compression) + ", " + std::to_string(c.per_chunk) + " messages a chunk");
    const std::string file = d.write("e.mcap", mcap_file(topics, c.compression, c.per_chunk));
    const auto source = read::open_source(file, {});
    EXPECT_EQ(source->info().format, "MCAP, /events: event_camera_msgs/msg/EventPacket (evt3)");
    EXPECT_EQ(read_all(file), events);
    EXPECT_EQ(read_all(file + "?topic=/events"), events);
    EXPECT_NE(read_error(file + "?topic=/imu").find("sensor_msgs/msg/Imu, not an event type"), std::string::npos);
  }
  // A ROS 1 bag converted to MCAP (`mcap convert`) keeps ROS 1's types and serialization.
  const std::vector<Bytes> ros1 = packets(events, 10, [](const std::vector<Event>& p) { return dvs_event_array_cdr(p, kDavis346, true); });
  const std::string converted = d.write("converted.mcap", mcap_file({{"/dvs/events", "dvs_msgs/EventArray", ros1}}, "lz4", 4, "ros1"));
  EXPECT_EQ(read::open_source(converted, {})->info().format, "MCAP, /dvs/events: dvs_msgs/EventArray");
  EXPECT_EQ(read_all(converted), events);
  const std::string json = d.write("json.mcap", mcap_file({{"/dvs/events", "dvs_msgs/msg/EventArray", {Bytes{1}}}}, "", 0, "json"));
  EXPECT_EQ(read_error(json), json + ": topic /dvs/events is serialized as 'json', not cdr or ros1");
}

// An MCAP file's topics and counts come from its summary when it holds schemas, channels and
// statistics that pass its CRC, so the data section is read once; otherwise a first pass over
// the data finds them. The count of the topic's messages is what the reading's progress goes by.
TEST(Ros2Bag, McapSummariesGiveTheTopicsAndCountsWhenWhole) {
  TempDir d;
  const std::vector<Event> events = sample_events(2000, kDavis346);
  const std::vector<Bytes> messages = packets(events, 10, [](const std::vector<Event>& p) { return event_packet_cdr("evt3", 0, kDavis346, evt3_words(p)); });
  const std::vector<BagTopic> topics = {{"/imu", "sensor_msgs/msg/Imu", std::vector<Bytes>(7, Bytes{0, 1, 0, 0})}, {"/events", kPacket, messages}};
  // The progress after the last event: the messages read over the messages counted.
  const auto progress_at_end = [&](const std::string& file) {
    const auto source = read::open_source(file, {});
    std::vector<Event> got;
    read_into(*source, got);
    EXPECT_EQ(got.size(), events.size());
    return source->progress();
  };
  for (const bool summary : {true, false}) {
    for (const char* compression : {"", "zstd"}) {
      SCOPED_TRACE(std::string(summary ? "summary, " : "no summary, ") + compression);
      const std::string file = d.write("e.mcap", mcap_file(topics, compression, 3, "cdr", summary));
      EXPECT_EQ(read_all(file), events);
      EXPECT_DOUBLE_EQ(progress_at_end(file), 1.0);
      EXPECT_NE(read_error(file + "?topic=/imu").find("sensor_msgs/msg/Imu, not an event type"), std::string::npos);
    }
  }
  // The statistics' count of /events (channel 1) doubled: with the CRC cleared the summary is
  // taken, and the progress ends at one half; with the CRC left as it was, the summary fails it
  // and the first pass counts.
  Bytes doubled = mcap_file(topics, "zstd", 3);
  const size_t footer_at = doubled.size() - 8 - 29;
  ASSERT_EQ(doubled[footer_at], 0x02);
  size_t at = static_cast<size_t>(read::le64(&doubled[footer_at + 9]));
  while (doubled[at] != 0x0B) at += 9 + static_cast<size_t>(read::le64(&doubled[at + 1]));
  const size_t pair_at = at + 9 + static_cast<size_t>(read::le64(&doubled[at + 1])) - 10;
  ASSERT_EQ(read::le16(&doubled[pair_at]), 1);
  ASSERT_EQ(read::le64(&doubled[pair_at + 2]), messages.size());
  doubled[pair_at + 2] = static_cast<unsigned char>(2 * messages.size());
  EXPECT_DOUBLE_EQ(progress_at_end(d.write("crc.mcap", doubled)), 1.0);
  std::fill(doubled.begin() + static_cast<long>(footer_at + 25), doubled.begin() + static_cast<long>(footer_at + 29), 0);
  EXPECT_DOUBLE_EQ(progress_at_end(d.write("trusted.mcap", doubled)), 0.5);
  // Statistics that count a channel the summary does not define: the first pass counts.
  doubled[pair_at + 2] = static_cast<unsigned char>(messages.size());
  doubled[at + 9 + 8 + 2] = 3;  // channels: 3
  EXPECT_DOUBLE_EQ(progress_at_end(d.write("channels.mcap", doubled)), 1.0);
  doubled[at + 9 + 8 + 2] = 2;
  doubled[pair_at + 2] = static_cast<unsigned char>(2 * messages.size());
  EXPECT_DOUBLE_EQ(progress_at_end(d.write("again.mcap", doubled)), 0.5);
}

TEST(Ros2Bag, LibcaerTimestampsRollOverInsideAPacket) {
  TempDir d;
  std::vector<Event> events = {{(TimeUs{1} << 31) - 3, 5, 6, 1}, {(TimeUs{1} << 31) - 1, 7, 8, 0}};
  Bytes words = libcaer_events(events);
  const Bytes after = libcaer_events({{2, 9, 10, 1}});  // the 31-bit counter wrapped
  words.insert(words.end(), after.begin(), after.end());
  const std::string bag = write_ros2_bag(d.path("rollover"), {{"/events", kPacket, {event_packet_cdr("libcaer", 0, kDavis346, words)}}});
  events.push_back({(TimeUs{1} << 31) + 2, 9, 10, 1});
  EXPECT_EQ(read_all(bag), events);
}

TEST(Ros2Bag, TriggerPacketsAreCountedAndSkipped) {
  TempDir d;
  const std::vector<Event> events = sample_events(50, kDavis346);
  const std::string bag = write_ros2_bag(
      d.path("trig"), {{"/triggers", kPacket, {event_packet_cdr("trigger", 0, kDavis346, Bytes(8 * 4, 0))}},
                       {"/events", kPacket, {event_packet_cdr("evt3", 0, kDavis346, evt3_words(events))}}});
  // The first event topic is the trigger topic: it has no events, and says so.
  auto source = read::open_source(bag, {});
  std::vector<Event> out(100);
  EXPECT_EQ(source->read(out), 0u);
  ASSERT_EQ(source->skipped().size(), 1u);
  EXPECT_EQ(source->skipped()[0], std::make_pair(std::string("trigger events"), std::int64_t{4}));
  EXPECT_EQ(read_all(bag + "?topic=/events"), events);
}

TEST(Ros2Bag, TheFirstEventTopicIsTheDefaultAndQueryChoosesAnother) {
  TempDir d;
  const std::vector<Event> a = sample_events(40, kDavis346, 1), b = sample_events(60, kDavis346, 2);
  const std::string bag = write_ros2_bag(d.path("two"), {{"/imu", "sensor_msgs/msg/Imu", {Bytes{0, 1, 0, 0}}},
                                                         {"/left/events", kPacket, {event_packet_cdr("evt3", 0, kDavis346, evt3_words(a))}},
                                                         {"/right/events", kPacket, {event_packet_cdr("evt3", 0, kDavis346, evt3_words(b))}}});
  EXPECT_EQ(read_all(bag), a);
  EXPECT_EQ(read_all(bag + "?topic=/right/events"), b);
  // The format names the topic read.
  EXPECT_EQ(read::open_source(bag, {})->info().format,
            "ROS 2 bag, /left/events: event_camera_msgs/msg/EventPacket (evt3) (other event topics, which ?topic= picks: /right/events)");
  EXPECT_EQ(read::open_source(bag + "?topic=/right/events", {})->info().format,
            "ROS 2 bag, /right/events: event_camera_msgs/msg/EventPacket (evt3) (other event topics, which ?topic= picks: /left/events)");
  const std::string missing = read_error(bag + "?topic=/nope");
  EXPECT_NE(missing.find("no topic '/nope'"), std::string::npos) << missing;
  EXPECT_NE(missing.find("/left/events (event_camera_msgs/msg/EventPacket)"), std::string::npos) << missing;
  const std::string not_events = read_error(bag + "?topic=/imu");
  EXPECT_NE(not_events.find("sensor_msgs/msg/Imu, not an event type"), std::string::npos) << not_events;
}

// One line, naming the storage file (or folder) and, inside a message, the message and byte.
void expect_bag_error(const std::string& name, const std::string& prefix, const std::string& what) {
  const std::string message = read_error(name);
  SCOPED_TRACE(message);
  EXPECT_EQ(message.rfind(prefix, 0), 0u) << "expected '" << prefix << "...'";
  EXPECT_NE(message.find(what), std::string::npos);
  EXPECT_EQ(message.find('\n'), std::string::npos);
}

TEST(Ros2Bag, BadBagsGetOneLineThatSaysWhereAndWhat) {
  TempDir d;
  const std::vector<Event> events = sample_events(3000, kDavis346);
  {
    const std::string bag = write_ros2_bag(d.path("enc"), {{"/e", kPacket, {event_packet_cdr("evt5", 0, kDavis346, Bytes(16, 0))}}});
    expect_bag_error(bag, bag + "/enc_0.db3: message 1, byte ", "encoding 'evt5' is not supported");
  }
  {
    Bytes cut = event_packet_cdr("libcaer", 0, kDavis346, libcaer_events(events));
    cut.resize(cut.size() - 5);
    const std::string bag = write_ros2_bag(d.path("cut"), {{"/e", kPacket, {cut}}});
    expect_bag_error(bag, bag + "/cut_0.db3: message 1, byte 6", "runs past the end of the message");
  }
  {
    const std::string bag = write_ros2_bag(d.path("odd"), {{"/e", kPacket, {event_packet_cdr("libcaer", 0, kDavis346, Bytes(12, 0))}}});
    expect_bag_error(bag, bag + "/odd_0.db3: message 1, byte ", "not whole 8-byte events");
  }
  {
    std::filesystem::create_directories(d.path("nometa"));
    write_db3(d.path("nometa/x_0.db3"), {{"/e", kPacket, {event_packet_cdr("evt3", 0, kDavis346, evt3_words(events))}}});
    expect_bag_error(d.path("nometa"), d.path("nometa") + ": ", "without metadata.yaml");
  }
  {
    // The folder above a bag, as `ros2 bag record` leaves it: the error names the bag inside.
    const std::string bag = write_ros2_bag(d.path("runs/first"), {{"/e", kPacket, {event_packet_cdr("evt3", 0, kDavis346, evt3_words(events))}}});
    expect_bag_error(d.path("runs"), d.path("runs") + ": ", "not a ROS 2 bag; the bag in it: " + bag);
  }
  {
    // A storage file cut short: sqlite finds its pages missing.
    std::vector<Bytes> many = packets(events, 30, [](const std::vector<Event>& p) { return event_packet_cdr("libcaer", 0, kDavis346, libcaer_events(p)); });
    const std::string bag = write_ros2_bag(d.path("trunc"), {{"/e", kPacket, many}});
    const std::string db3 = bag + "/trunc_0.db3";
    std::filesystem::resize_file(db3, std::filesystem::file_size(db3) / 2);
    expect_bag_error(db3, db3 + ": ", "not a readable sqlite3 bag file");
  }
  {
    // sqlite's magic and then nothing it can use (fuzz_ros2 found that this leaked the handle).
    Bytes junk(4096, 0xFF);
    const std::string magic = "SQLite format 3";
    std::copy(magic.begin(), magic.end(), junk.begin());
    junk[15] = 0;
    const std::string db3 = d.write("junk.db3", junk);
    expect_bag_error(db3, db3 + ": ", "not a readable sqlite3 bag file");
  }
  {
    const std::string bag = write_ros2_bag(d.path("lost"), {{"/e", kPacket, {}}});
    std::filesystem::remove(bag + "/lost_0.db3");
    expect_bag_error(bag, bag + "/lost_0.db3: ", "no such file");
  }
  {
    const std::string bag = write_ros2_bag(d.path("empty"), {{"/e", kPacket, {}}});
    expect_bag_error(bag, bag + ": ", "has no messages");
  }
}

// The events a file gives before its first error, or all of them.
std::vector<Event> read_until_error(const std::string& file) {
  const auto source = read::open_source(file, {});
  std::vector<Event> got;
  try {
    read_into(*source, got);
  } catch (const read::InputError&) {
  }
  return got;
}

// A bad MCAP file: one line that names the file and the byte of the record (a chunk's, for a
// record inside it), or the message and its byte, and what is wrong.
TEST(Ros2Bag, BadMcapFilesGetOneLineThatSaysWhereAndWhat) {
  TempDir d;
  const std::vector<Event> events = sample_events(600, kDavis346);
  const std::vector<BagTopic> topics = {{"/e", kPacket, packets(events, 6, [](const std::vector<Event>& p) {
                                           return event_packet_cdr("evt3", 0, kDavis346, evt3_words(p));
                                         })}};
  const Bytes good = mcap_file(topics, "zstd", 2);
  const size_t header_end = 8 + 9 + 4 + 4 + 4 + 9;  // magic, then the header: "ros2" and "evms test"
  const size_t first_chunk_length = good[header_end + 1] | (good[header_end + 2] << 8) | (good[header_end + 3] << 16);
  const std::string at_chunk = ": byte " + std::to_string(header_end) + ": ";
  {
    Bytes cut(good.begin(), good.begin() + static_cast<long>(header_end + 9 + first_chunk_length / 2));
    const std::string f = d.write("cut.mcap", cut);
    expect_bag_error(f, f + at_chunk, "a record of " + std::to_string(first_chunk_length) + " bytes runs past the end of the file");
  }
  {
    // A recording cut short after its first chunk: that chunk's two messages come out, then the error.
    Bytes cut(good.begin(), good.begin() + static_cast<long>(header_end + 9 + first_chunk_length));
    const std::string f = d.write("short.mcap", cut);
    expect_bag_error(f, f + ": byte " + std::to_string(cut.size()) + ": ", "the file ends without its Data End and Footer records");
    EXPECT_EQ(read_until_error(f), std::vector<Event>(events.begin(), events.begin() + static_cast<long>(events.size() * 2 / 6)));
  }
  {
    Bytes corrupt = good;
    corrupt[header_end + 9 + first_chunk_length - 3] ^= 0xFF;
    const std::string f = d.write("corrupt.mcap", corrupt);
    expect_bag_error(f, f + at_chunk, "a corrupt zstd chunk, or one that does not hold the ");
  }
  {
    // A changed byte inside an uncompressed chunk's records: its CRC-32 refuses it at the chunk,
    // after the messages of the chunk before it.
    Bytes flipped = mcap_file(topics, "", 2);
    const size_t second_chunk_at = header_end + 9 + (flipped[header_end + 1] | (flipped[header_end + 2] << 8) | (flipped[header_end + 3] << 16));
    ASSERT_EQ(flipped[second_chunk_at], 0x06);
    const size_t second_chunk_end = second_chunk_at + 9 + (flipped[second_chunk_at + 1] | (flipped[second_chunk_at + 2] << 8) | (flipped[second_chunk_at + 3] << 16));
    flipped[second_chunk_end - 4] ^= 0x01;  // the last EVT 3.0 word's lowest bit: an address or a time
    const std::string f = d.write("flipped.mcap", flipped);
    expect_bag_error(f, f + ": byte " + std::to_string(second_chunk_at) + ": ", "the chunk's records fail their CRC-32 (stored 0x");
    EXPECT_EQ(read_until_error(f), std::vector<Event>(events.begin(), events.begin() + static_cast<long>(events.size() * 2 / 6)));
    // A CRC of 0 is none: the same change then reads, into other events.
    const size_t crc_at = second_chunk_at + 9 + 8 + 8 + 8;
    std::fill(flipped.begin() + static_cast<long>(crc_at), flipped.begin() + static_cast<long>(crc_at + 4), 0);
    const std::vector<Event> unchecked = read_until_error(d.write("unchecked.mcap", flipped));
    EXPECT_EQ(unchecked.size(), events.size());
    EXPECT_NE(unchecked, events);
  }
  {
    // Without chunks the data section's CRC-32 finds the change, at the Data End record.
    Bytes flipped = mcap_file(topics, "", 0, "cdr", false);
    const size_t data_end_at = flipped.size() - 8 - (9 + 20) - (9 + 4);
    ASSERT_EQ(flipped[data_end_at], 0x0F);
    flipped[data_end_at - 20] ^= 0x01;
    const std::string f = d.write("section.mcap", flipped);
    expect_bag_error(f, f + ": byte " + std::to_string(data_end_at) + ": ", "the data section fails its CRC-32 (stored 0x");
  }
  {
    Bytes other = mcap_file(topics, "lz4", 2);
    const std::string lz4 = "lz4";
    const size_t name_at = header_end + 9 + 8 + 8 + 8 + 4 + 4;
    ASSERT_TRUE(std::equal(lz4.begin(), lz4.end(), other.begin() + static_cast<long>(name_at)));
    other[name_at] = 'x';
    const std::string f = d.write("xz4.mcap", other);
    expect_bag_error(f, f + at_chunk, "a chunk compressed with 'xz4': evms reads uncompressed, 'lz4' and 'zstd' chunks");
  }
  {
    // A message on a channel no record defines: outside chunks, the message's own record is named.
    Bytes loose = mcap_file(topics, "", 0);
    const size_t schema_length = loose[header_end + 1], channel_at = header_end + 9 + schema_length;
    const size_t message_at = channel_at + 9 + loose[channel_at + 1];
    ASSERT_EQ(loose[message_at], 0x05);
    loose[message_at + 9] = 7;
    const std::string f = d.write("loose.mcap", loose);
    expect_bag_error(f, f + ": byte " + std::to_string(message_at) + ": ", "message 1 is on channel 7, which no channel record before it defines");
  }
  {
    // A message that does not decode: the message and its byte.
    Bytes cut = event_packet_cdr("libcaer", 0, kDavis346, libcaer_events(events));
    cut.resize(cut.size() - 5);
    const std::string f = d.write("message.mcap", mcap_file({{"/e", kPacket, {cut}}}, "lz4", 2));
    expect_bag_error(f, f + ": message 1, byte 6", "runs past the end of the message");
  }
  {
    const std::string bag = write_ros2_bag(d.path("storage"), topics, "mcap");
    std::ofstream(bag + "/metadata.yaml") << "rosbag2_bagfile_information:\n  storage_identifier: rocksdb\n  relative_file_paths:\n    - storage_0.mcap\n";
    expect_bag_error(bag, bag + "/metadata.yaml: ", "storage 'rocksdb' is not supported (sqlite3 and mcap)");
  }
}

TEST(Ros2Bag, TheSharedRecordingMatchesItsReadme) {
  const std::string dir = shared_data_dir();
  if (dir.empty()) GTEST_SKIP() << "../shared/data/real is absent: the shared ROS 2 bag is not checked";
  const std::string bag = dir + "/ros2/libcaer_rollover";
  auto source = read::open_source(bag, {});
  EXPECT_EQ(source->info().sensor, (SensorSize{640, 480}));
  EXPECT_NE(source->info().format.find("libcaer"), std::string::npos);
  std::int64_t n = 0, sum_x = 0, sum_y = 0, on = 0;
  TimeUs last = 0;
  bool ordered = true;
  std::vector<Event> batch(4096);
  while (size_t got = source->read(batch)) {
    for (size_t i = 0; i < got; ++i) {
      ++n, sum_x += batch[i].x, sum_y += batch[i].y, on += batch[i].p;
      ordered = ordered && batch[i].t >= last;
      last = batch[i].t;
    }
  }
  // README.md of ../shared/data/real: 334,331 events, sums of x and y, ON count.
  EXPECT_EQ(n, 334331);
  EXPECT_EQ(sum_x, 111651612);
  EXPECT_EQ(sum_y, 82801007);
  EXPECT_EQ(on, 181908);
  EXPECT_TRUE(ordered) << "the roll-over must not send time backwards";
}

}  // namespace
}  // namespace evms::test
