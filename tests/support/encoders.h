// Byte-level encoders of every input format, written from the format specifications (not
// from the readers), so that tests can build files with known contents and then corrupt
// them on purpose.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "types/event.h"

namespace evms::test {

using Bytes = std::vector<std::uint8_t>;

std::string rpg_text(const std::vector<Event>& events);
std::string csv(const std::vector<Event>& events);
Bytes aedat2_dvs128(const std::vector<Event>& events);
Bytes aedat2_davis240(const std::vector<Event>& events);
Bytes aedat3_davis240(const std::vector<Event>& events);
enum class Aedat4Compression { kNone = 0, kLz4 = 1, kZstd = 3 };
Bytes aedat4(const std::vector<Event>& events, SensorSize sensor, Aedat4Compression c, size_t events_per_packet = 100);
Bytes evt2(const std::vector<Event>& events, SensorSize sensor);
// EVT 2.1 RAW: events of one time, row and polarity at ascending x within 32 share a word;
// `legacy` stores each word's halves as the IMX636 does ("endianness=legacy"), else the whole
// word little-endian.
Bytes evt21(const std::vector<Event>& events, SensorSize sensor, bool legacy);
Bytes evt3(const std::vector<Event>& events, SensorSize sensor);
Bytes dat(const std::vector<Event>& events);
// A NumPy .npy file of format version `major` (1, 2 or 3): the magic, the version, the length
// of `dict` padded with blanks and a newline to a multiple of 64, then `data` as it is.
Bytes npy(const std::string& dict, const Bytes& data, int major = 1);
// Little- or big-endian bytes of the low `bytes` bytes of v.
void put_int(Bytes& b, std::uint64_t v, int bytes, bool big_endian = false);

// ROS 2 messages in CDR (little endian), or with `ros1` in ROS 1's serialization, and bags that
// hold them.
Bytes evt3_words(const std::vector<Event>& events);  // the words of evt3() without its header
Bytes event_packet_cdr(const std::string& encoding, std::uint64_t time_base_ns, SensorSize sensor, const Bytes& events, bool ros1 = false);
Bytes libcaer_events(const std::vector<Event>& events);  // t relative to the packet's time base
Bytes mono_events(const std::vector<Event>& events, std::uint64_t time_base_ns);
Bytes dvs_event_array_cdr(const std::vector<Event>& events, SensorSize sensor, bool ros1 = false);
struct BagTopic {
  std::string name, type;
  std::vector<Bytes> messages;
};
// Writes the sqlite3 storage file `db3` of a bag with these topics, messages 1 ms apart.
void write_db3(const std::string& db3, const std::vector<BagTopic>& topics);
// A bag folder `dir` with metadata.yaml and dir/NAME_0.db3 (or NAME_0.mcap, by `storage`: "sqlite3"
// or "mcap"); returns the folder.
std::string write_ros2_bag(const std::string& dir, const std::vector<BagTopic>& topics, const std::string& storage = "sqlite3");
// An MCAP file (https://mcap.dev/spec) of these topics, as rosbag2 writes one: a schema (the
// type) and a cdr channel for each topic, its messages 1 ms apart in turn, in chunks of
// `messages_per_chunk` compressed with `compression` ("", "lz4" or "zstd"; 0 messages a chunk:
// no chunks), then Data End, a summary (each channel's schema and channel, and the statistics
// with each channel's message count; none with `summary` false) and the footer. Each chunk, the
// data section and the summary carry their CRC-32.
// `encoding` is the channels' message encoding: "cdr" (ROS 2) or "ros1" (`mcap convert` of a ROS 1 bag).
Bytes mcap_file(const std::vector<BagTopic>& topics, const std::string& compression = "zstd", size_t messages_per_chunk = 4,
                const std::string& encoding = "cdr", bool summary = true);
// A ROS 1 bag (format 2.0) of these topics, their messages in ROS 1's serialization, in chunks
// of `messages_per_chunk` compressed with `compression` ("none", "lz4" or "bz2"), and its index.
Bytes ros1_bag(const std::vector<BagTopic>& topics, const std::string& compression, size_t messages_per_chunk = 4);

// A temporary directory removed at the end of the test.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  std::string path(const std::string& name) const { return dir_ + "/" + name; }
  std::string write(const std::string& name, const std::string& text) const;
  std::string write(const std::string& name, const Bytes& bytes) const;

 private:
  std::string dir_;
};

// One word of what iniVation cameras send: a DVS128 event (address LE, timestamp LE), a DVS128
// word with only its flag byte (0x80 wrap, 0x40 timestamp reset), a 16-bit DAVIS word.
void dvs128_event(Bytes& b, int x, int y, int p, int ts);
void dvs128_flag(Bytes& b, std::uint8_t byte3);
void davis_word(Bytes& b, unsigned w);
// What iniVation cameras send on their bulk IN endpoint (facts.md, Live USB cameras), in time
// order from t = 0: timestamp wraps where they fall, then each event.
Bytes dvs128_usb_words(const std::vector<Event>& events);  // 4-byte address + timestamp words
Bytes davis_usb_words(const std::vector<Event>& events);   // 16-bit timestamp, row and column words

// Events of a few moving dots, deterministic, in time order.
std::vector<Event> sample_events(size_t n, SensorSize sensor, std::uint64_t seed = 1);

}  // namespace evms::test
