// ROS 1 bags (format 2.0, as `rosbag record` writes them; the authors' code read dvs_msgs from
// ROS 1): each event message type decodes to the events encoded, in uncompressed, lz4 and bz2
// chunks, and a bad bag gets one line that names the file and where.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>

#include "host/read/event_source.h"
#include "tests/support/encoders.h"
#include "tests/support/read_all.h"

namespace evms::test {
namespace {

constexpr SensorSize kDavis240{240, 180};

std::vector<Bytes> in_messages(const std::vector<Event>& events, size_t parts, const std::function<Bytes(const std::vector<Event>&)>& encode) {
  std::vector<Bytes> out;
  for (size_t k = 0; k < parts; ++k) {
    out.push_back(encode(std::vector<Event>(events.begin() + static_cast<long>(events.size() * k / parts),
                                            events.begin() + static_cast<long>(events.size() * (k + 1) / parts))));
  }
  return out;
}

TEST(Ros1Bag, EventArraysAndPacketsDecodeToTheEventsEncodedInEveryChunkCompression) {
  TempDir d;
  const std::vector<Event> events = sample_events(1500, kDavis240);
  const auto arrays = in_messages(events, 10, [](const std::vector<Event>& p) { return dvs_event_array_cdr(p, kDavis240, true); });
  const auto packets = in_messages(events, 10, [](const std::vector<Event>& p) { return event_packet_cdr("evt3", 0, kDavis240, evt3_words(p), true); });
  struct Case {
    const char* type;
    const std::vector<Bytes>& messages;
    const char* format;
  };
  const Case cases[] = {{"dvs_msgs/EventArray", arrays, "ROS 1 bag, /dvs/events: dvs_msgs/EventArray"},
                        {"prophesee_event_msgs/EventArray", arrays, "ROS 1 bag, /dvs/events: prophesee_event_msgs/EventArray"},
                        {"event_camera_msgs/EventPacket", packets, "ROS 1 bag, /dvs/events: event_camera_msgs/EventPacket (evt3)"}};
  for (const Case& c : cases) {
    for (const char* compression : {"none", "lz4", "bz2"}) {
      SCOPED_TRACE(std::string(c.type) + ", " + compression);
      const std::string bag = d.write("events.bag", ros1_bag({{"/dvs/events", c.type, c.messages}}, compression));
      EXPECT_EQ(read_all(bag), events);
      const auto source = read::open_source(bag, {});
      EXPECT_EQ(source->info().format, c.format);
      EXPECT_EQ(source->info().sensor, kDavis240);
      EXPECT_EQ(read::open_source(bag, sized(346, 260, 1000))->info().sensor, (SensorSize{346, 260}));  // as for ROS 2 bags
    }
  }
  // A chunk that bzip2 shrinks more than 64 times (one event repeated): it grows as it is read.
  const std::vector<Event> repeated(100000, events.front());
  const Bytes message = dvs_event_array_cdr(repeated, kDavis240, true);
  const Bytes bag = ros1_bag({{"/dvs/events", "dvs_msgs/EventArray", {message}}}, "bz2");
  ASSERT_LT(bag.size() * 64, message.size());
  EXPECT_EQ(read_all(d.write("repeated.bag", bag)), repeated);
}

TEST(Ros1Bag, TheFirstEventTopicIsTheDefaultAndQueryChoosesAnother) {
  TempDir d;
  const std::vector<Event> a = sample_events(300, kDavis240, 1), b = sample_events(200, kDavis240, 2);
  const std::string bag = d.write(
      "two.bag", ros1_bag({{"/dvs/imu", "sensor_msgs/Imu", {Bytes(40, 0), Bytes(40, 0)}},
                           {"/left/events", "dvs_msgs/EventArray", in_messages(a, 3, [](const auto& p) { return dvs_event_array_cdr(p, kDavis240, true); })},
                           {"/right/events", "dvs_msgs/EventArray", in_messages(b, 5, [](const auto& p) { return dvs_event_array_cdr(p, kDavis240, true); })}},
                          "none", 3));
  EXPECT_EQ(read_all(bag), a);
  EXPECT_EQ(read_all(bag + "?topic=/right/events"), b);
  const std::string missing = read_error(bag + "?topic=/nope");
  EXPECT_EQ(missing, bag + "?topic=/nope: no topic '/nope' in the bag (its topics: /dvs/imu (sensor_msgs/Imu), /left/events (dvs_msgs/EventArray), "
                           "/right/events (dvs_msgs/EventArray); event types: event_camera_msgs/EventPacket, dvs_msgs/EventArray, "
                           "prophesee_event_msgs/EventArray)");
  EXPECT_EQ(read_error(bag + "?topic=/dvs/imu"), bag + "?topic=/dvs/imu: topic /dvs/imu has type sensor_msgs/Imu, not an event type "
                                                       "(event_camera_msgs/EventPacket, dvs_msgs/EventArray, prophesee_event_msgs/EventArray)");
}

TEST(Ros1Bag, BadBagsGetOneLineThatSaysWhereAndWhat) {
  TempDir d;
  const std::vector<Event> events = sample_events(100, kDavis240);
  const auto bag_of = [&](const Bytes& message, const std::string& compression) {
    return ros1_bag({{"/dvs/events", "dvs_msgs/EventArray", {message}}}, compression);
  };
  const Bytes message = dvs_event_array_cdr(events, kDavis240, true);
  // What follows the file's name: the position, then what is wrong.
  const auto error_of = [&](const Bytes& bag) {
    const std::string path = d.write("bad.bag", bag);
    const std::string text = read_error(path);
    EXPECT_EQ(text.rfind(path + ": ", 0), 0u) << text;
    EXPECT_EQ(text.find('\n'), std::string::npos) << text;
    return text.substr(std::min(text.size(), path.size() + 2));
  };
  const auto expect_error = [&](const Bytes& bag, const std::string& where, const std::string& what) {
    const std::string text = error_of(bag);
    EXPECT_EQ(text.rfind(where, 0), 0u) << text;
    EXPECT_NE(text.find(what), std::string::npos) << text << " (expected: " << what << ")";
  };
  expect_error(bag_of(message, "zstd"), "byte ", "a chunk compressed with 'zstd': evms reads 'none', 'lz4' and 'bz2'");
  Bytes bz2 = bag_of(message, "bz2");
  const Bytes stream_magic = {'B', 'Z', 'h', '9'};
  const auto stream = std::search(bz2.begin(), bz2.end(), stream_magic.begin(), stream_magic.end());
  ASSERT_NE(stream, bz2.end());
  stream[20] ^= 0xFF;  // inside the first block
  expect_error(bz2, "byte ", "a corrupt bz2 chunk");
  // A chunk whose stream holds more or fewer bytes than its size field says.
  for (const std::int64_t wrong : {-1, 1}) {
    Bytes resized = bag_of(message, "bz2");
    const Bytes size_field = {'s', 'i', 'z', 'e', '='};
    const auto field = std::search(resized.begin(), resized.end(), size_field.begin(), size_field.end());
    ASSERT_NE(field, resized.end());
    field[5] = static_cast<unsigned char>(field[5] + wrong);
    expect_error(resized, "byte ", "a corrupt bz2 chunk, or one that does not hold the");
  }
  Bytes lz4 = bag_of(message, "lz4");
  const Bytes frame_magic = {0x04, 0x22, 0x4D, 0x18};
  const auto magic = std::search(lz4.begin(), lz4.end(), frame_magic.begin(), frame_magic.end());
  ASSERT_NE(magic, lz4.end());
  magic[8] ^= 0xFF;  // inside the frame
  expect_error(lz4, "byte ", "a corrupt lz4 chunk");
  const Bytes whole = bag_of(message, "none");
  expect_error(Bytes(whole.begin(), whole.end() - 10), "byte ", "runs past the end of the file");
  // A message whose event count runs past its bytes: the message (counted from 1) and the byte.
  expect_error(bag_of(Bytes(message.begin(), message.end() - 13), "none"), "message 1, byte 30",
               "a sequence of 100 elements runs past the end of the message");
  expect_error(bag_of(dvs_event_array_cdr(events, {0, 0}, true), "none"), "", "the file does not say the sensor size: pass --width and --height");
  Bytes v1 = whole;
  v1[9] = '1';  // "#ROSBAG V1.0"
  expect_error(v1, "byte 0", "bad header: ROS bag version '#ROSBAG V1.0' (2.0 is read)");
  EXPECT_EQ(error_of(ros1_bag({{"/dvs/imu", "sensor_msgs/Imu", {Bytes(40, 0)}}}, "none")),
            "no event topic in the bag (its topics: /dvs/imu (sensor_msgs/Imu); event types: event_camera_msgs/EventPacket, "
            "dvs_msgs/EventArray, prophesee_event_msgs/EventArray)");
}

}  // namespace
}  // namespace evms::test
