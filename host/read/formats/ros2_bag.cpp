// ROS 2 bags (rosbag2, sqlite3 storage): a folder with metadata.yaml and its .db3 files, or one
// .db3 file. Each .db3 holds the tables topics(id, name, type, serialization_format, ...) and
// messages(id, topic_id, timestamp, data); data is the CDR-serialized message (cdr.h). One topic
// is read, in the order of the messages' receive timestamps.
//
// Message types (the layouts are the .msg definitions):
//   event_camera_msgs/msg/EventPacket
//       std_msgs/Header header, uint32 height, uint32 width, uint64 seq, uint64 time_base,
//       string encoding, bool is_bigendian, uint8[] events
//     encodings: "evt3"    Prophesee EVT 3.0 words (evt3_decoder.h), state kept across
//                          packets; sensor time, time_base unused
//                "libcaer" 8 bytes an event: uint32 address (bit 1 polarity, y in 2..16, x in
//                          17..31) and int32 t_us; t = time_base (ns) + t_us * 1000, and t_us
//                          going down inside a packet is a roll-over of 2^31 us
//                "mono"    uint64: dt in 0..31 (ns), x in 32..47, y in 48..62, polarity in 63;
//                          t = time_base + dt
//                "trigger" uint64 trigger records: counted and skipped
//   dvs_msgs/msg/EventArray, prophesee_event_msgs/msg/EventArray
//       std_msgs/Header header, uint32 height, uint32 width, Event[] events with
//       Event = {uint16 x, uint16 y, builtin_interfaces/Time ts, bool polarity}
// Times become microseconds (floor). The sensor size is the first message's height and width.
// Bags compressed per message with zstd are read; file-compressed bags are refused.
#include <sqlite3.h>
#include <yaml-cpp/yaml.h>
#include <zstd.h>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <optional>

#include "host/read/bytes.h"
#include "host/read/event_source.h"
#include "host/read/formats/cdr.h"
#include "host/read/formats/evt3_decoder.h"

namespace evms::read {
namespace {

namespace fs = std::filesystem;

constexpr const char* kEventPacket = "event_camera_msgs/msg/EventPacket";
constexpr const char* kDvsArray = "dvs_msgs/msg/EventArray";
constexpr const char* kPropheseeArray = "prophesee_event_msgs/msg/EventArray";
// A decompressed message larger than this is corrupt (a packet of 16 M events in 8 bytes each).
constexpr size_t kMaxMessageBytes = size_t{128} << 20;

bool is_event_type(const std::string& type) { return type == kEventPacket || type == kDvsArray || type == kPropheseeArray; }

struct BagLayout {
  std::vector<std::string> files;  // .db3 paths in recording order
  bool zstd_messages = false;
};

// The files of a bag folder, from its metadata.yaml.
BagLayout layout_of_folder(const std::string& folder) {
  const fs::path meta = fs::path(folder) / "metadata.yaml";
  if (!fs::exists(meta)) {
    // A user who names the folder above a bag (ros2 bag record writes one folder a run) is told
    // which bags it holds.
    std::vector<std::string> bags;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(folder, ec)) {
      if (entry.is_directory(ec) && fs::exists(entry.path() / "metadata.yaml", ec)) bags.push_back(entry.path().string());
    }
    std::sort(bags.begin(), bags.end());
    std::string what = "a folder without metadata.yaml is not a ROS 2 bag";
    if (!bags.empty()) what += bags.size() > 1 ? "; the bags in it: " : "; the bag in it: ";
    for (size_t i = 0; i < bags.size() && i < 4; ++i) what += (i ? ", " : "") + printable(bags[i]);
    if (bags.size() > 4) what += ", ...";
    fail(folder, {}, what);
  }
  YAML::Node root;
  try {
    root = YAML::LoadFile(meta.string())["rosbag2_bagfile_information"];
  } catch (const YAML::Exception& e) {
    fail(meta.string(), InputPosition::line(static_cast<std::uint64_t>(e.mark.line + 1)), "bad YAML: " + e.msg);
  }
  if (!root || !root.IsMap()) fail(meta.string(), {}, "no rosbag2_bagfile_information section");
  BagLayout layout;
  try {
    const std::string storage = root["storage_identifier"] ? root["storage_identifier"].as<std::string>() : "sqlite3";
    if (storage != "sqlite3") fail(meta.string(), {}, "storage '" + printable(storage) + "' is not supported (sqlite3 bags only)");
    const std::string format = root["compression_format"] ? root["compression_format"].as<std::string>() : "";
    const std::string mode = root["compression_mode"] ? root["compression_mode"].as<std::string>() : "";
    if (!format.empty() && format != "zstd") fail(meta.string(), {}, "compression '" + printable(format) + "' is not supported (zstd only)");
    if (!format.empty() && mode != "MESSAGE" && mode != "message") {
      fail(meta.string(), {}, "file-compressed bags are not supported: decompress it first (ros2 bag decompress)");
    }
    layout.zstd_messages = !format.empty();
    for (const YAML::Node& f : root["relative_file_paths"]) layout.files.push_back((fs::path(folder) / f.as<std::string>()).string());
  } catch (const YAML::Exception& e) {
    fail(meta.string(), InputPosition::line(static_cast<std::uint64_t>(e.mark.line + 1)), "bad metadata: " + e.msg);
  }
  if (layout.files.empty()) fail(meta.string(), {}, "relative_file_paths lists no storage file");
  return layout;
}

// One .db3 file, read-only, with the chosen topic's messages in receive order. The handle and
// statements are released however a read ends, errors included.
class Db3 {
 public:
  explicit Db3(const std::string& path) : path_(path) {
    if (!fs::exists(path)) fail(path, {}, "cannot open: no such file (listed in the bag's metadata.yaml)");
    sqlite3* db = nullptr;
    const int rc = sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr);
    db_.reset(db);  // sqlite allocates a handle even when opening fails
    if (rc != SQLITE_OK) error("cannot open");
  }

  struct Topic {
    std::int64_t id;
    std::string name, type, serialization;
  };
  std::vector<Topic> topics() {
    Statement s = prepare("SELECT id, name, type, serialization_format FROM topics ORDER BY id");
    std::vector<Topic> out;
    while (step(s.get())) out.push_back({sqlite3_column_int64(s.get(), 0), text(s.get(), 1), text(s.get(), 2), text(s.get(), 3)});
    return out;
  }
  std::int64_t count(std::int64_t topic) {
    Statement s = prepare("SELECT COUNT(*) FROM messages WHERE topic_id = ?");
    sqlite3_bind_int64(s.get(), 1, topic);
    return step(s.get()) ? sqlite3_column_int64(s.get(), 0) : 0;
  }
  void select(std::int64_t topic) {
    messages_ = prepare("SELECT id, data FROM messages WHERE topic_id = ? ORDER BY timestamp, id");
    sqlite3_bind_int64(messages_.get(), 1, topic);
  }
  // The next message's row id and bytes (valid until the next call); false at the end.
  bool next(std::int64_t& id, std::span<const unsigned char>& data) {
    if (!step(messages_.get())) return false;
    id = sqlite3_column_int64(messages_.get(), 0);
    const void* blob = sqlite3_column_blob(messages_.get(), 1);
    const int n = sqlite3_column_bytes(messages_.get(), 1);
    data = {static_cast<const unsigned char*>(blob), static_cast<size_t>(n)};
    return true;
  }
  const std::string& path() const { return path_; }

 private:
  struct CloseDb {
    void operator()(sqlite3* db) const { sqlite3_close(db); }
  };
  struct Finalize {
    void operator()(sqlite3_stmt* s) const { sqlite3_finalize(s); }
  };
  using Statement = std::unique_ptr<sqlite3_stmt, Finalize>;

  [[noreturn]] void error(const char* what) const {
    fail(path_, {}, std::string(what) + ": " + (db_ ? sqlite3_errmsg(db_.get()) : "out of memory") + " (not a readable sqlite3 bag file)");
  }
  Statement prepare(const char* sql) {
    sqlite3_stmt* s = nullptr;
    const int rc = sqlite3_prepare_v2(db_.get(), sql, -1, &s, nullptr);
    Statement owned(s);
    if (rc != SQLITE_OK) error("cannot read the bag's tables");
    return owned;
  }
  bool step(sqlite3_stmt* s) {
    const int rc = sqlite3_step(s);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    error("cannot read the bag's tables");
  }
  static std::string text(sqlite3_stmt* s, int column) {
    const unsigned char* t = sqlite3_column_text(s, column);
    return t ? reinterpret_cast<const char*>(t) : "";
  }

  std::string path_;
  std::unique_ptr<sqlite3, CloseDb> db_;
  Statement messages_;
};

class Ros2BagSource final : public DecodedEventSource {
 public:
  Ros2BagSource(const std::string& name, BagLayout layout, const std::string& topic, const SourceOptions& options)
      : layout_(std::move(layout)), options_(options) {
    info_.name = name;
    choose_topic(topic);
    if (!next_message()) fail(name, {}, "topic '" + printable(topic_) + "' has no messages");
    const std::optional<SensorSize> size = sensor_of_first_message();
    if (options_.width > 0 && options_.height > 0) {
      info_.sensor = {options_.width, options_.height};
      info_.sensor_origin = "--width/--height";
    } else if (size) {
      info_.sensor = *size;
      info_.sensor_origin = "message header";
    } else {
      fail(name, {}, "the messages do not say the sensor size (height and width are 0): pass --width and --height");
    }
    if (info_.sensor.width > kMaxSensorSide || info_.sensor.height > kMaxSensorSide) {
      fail(name, InputPosition::message(message_id_, 0), "a sensor of " + std::to_string(info_.sensor.width) + "x" +
                                                             std::to_string(info_.sensor.height) + " is larger than " +
                                                             std::to_string(kMaxSensorSide) + "x" + std::to_string(kMaxSensorSide));
    }
    start_ordering(db_->path(), options_.reorder_us);
    decode_current();
  }

  double progress() const override { return total_ ? static_cast<double>(decoded_) / static_cast<double>(total_) : -1.0; }

 private:
  bool decode_more() override {
    if (!next_message()) return false;
    decode_current();
    return true;
  }

  void choose_topic(const std::string& wanted) {
    db_ = std::make_unique<Db3>(layout_.files[0]);
    const std::vector<Db3::Topic> topics = db_->topics();
    const Db3::Topic* chosen = nullptr;
    std::string listed;
    for (const Db3::Topic& t : topics) {
      listed += (listed.empty() ? "" : ", ") + t.name + " (" + t.type + ")";
      if (wanted.empty() ? (!chosen && is_event_type(t.type)) : t.name == wanted) chosen = &t;
    }
    if (!chosen) {
      fail(info_.name, {}, printable(wanted.empty() ? "no event topic" : "no topic '" + wanted + "'") +
                               " in the bag (its topics: " + printable(listed.empty() ? "none" : listed) +
                               "; event types: " + kEventPacket + ", " + kDvsArray + ", " + kPropheseeArray + ")");
    }
    if (!is_event_type(chosen->type)) {
      fail(info_.name, {}, "topic " + printable(chosen->name) + " has type " + printable(chosen->type) + ", not an event type (" +
                               kEventPacket + ", " + kDvsArray + ", " + kPropheseeArray + ")");
    }
    if (chosen->serialization != "cdr") {
      fail(info_.name, {}, "topic " + printable(chosen->name) + " is serialized as '" + printable(chosen->serialization) + "', not cdr");
    }
    topic_ = chosen->name;
    type_ = chosen->type;
    for (const Db3::Topic& t : topics) {
      if (t.name == topic_) total_ += db_->count(t.id);
    }
    for (size_t f = 1; f < layout_.files.size(); ++f) {
      Db3 db(layout_.files[f]);
      for (const Db3::Topic& t : db.topics()) {
        if (t.name == topic_) total_ += db.count(t.id);
      }
    }
    open_file(0);
  }

  void open_file(size_t index) {
    file_ = index;
    if (!db_ || db_->path() != layout_.files[index]) db_ = std::make_unique<Db3>(layout_.files[index]);
    for (const Db3::Topic& t : db_->topics()) {
      if (t.name == topic_) {
        db_->select(t.id);
        has_topic_ = true;
        return;
      }
    }
    has_topic_ = false;
  }

  // Moves to the next message of the topic, across files; false at the end of the bag.
  bool next_message() {
    for (;;) {
      std::span<const unsigned char> data;
      if (has_topic_ && db_->next(message_id_, data)) {
        ++decoded_;
        message_ = layout_.zstd_messages ? decompress(data) : data;
        return true;
      }
      if (file_ + 1 >= layout_.files.size()) return false;
      open_file(file_ + 1);
    }
  }

  std::span<const unsigned char> decompress(std::span<const unsigned char> data) {
    const unsigned long long size = ZSTD_getFrameContentSize(data.data(), data.size());
    if (size == ZSTD_CONTENTSIZE_ERROR || size == ZSTD_CONTENTSIZE_UNKNOWN) fail_message(0, "not a zstd frame with its size");
    if (size > kMaxMessageBytes) fail_message(0, "a zstd frame of " + std::to_string(size) + " bytes (more than 128 MiB)");
    unpacked_.resize(size);
    const size_t got = ZSTD_decompress(unpacked_.data(), unpacked_.size(), data.data(), data.size());
    if (ZSTD_isError(got) || got != size) fail_message(0, "corrupt zstd frame");
    return unpacked_;
  }

  [[noreturn]] void fail_message(std::uint64_t byte, const std::string& what) const {
    fail(db_->path(), InputPosition::message(static_cast<std::uint64_t>(message_id_), byte), what);
  }

  std::optional<SensorSize> sensor_of_first_message() {
    try {
      CdrReader r(message_);
      skip_header(r);
      const std::uint32_t height = r.u32(), width = r.u32();
      if (width == 0 || height == 0) return std::nullopt;
      if (width > static_cast<std::uint32_t>(kMaxSensorSide) || height > static_cast<std::uint32_t>(kMaxSensorSide)) {
        fail_message(r.offset(), "a sensor of " + std::to_string(width) + "x" + std::to_string(height) + " is larger than " +
                                     std::to_string(kMaxSensorSide) + "x" + std::to_string(kMaxSensorSide));
      }
      return SensorSize{static_cast<int>(width), static_cast<int>(height)};
    } catch (const CdrReader::Error& e) {
      fail_message(e.offset, e.what);
    }
  }

  static void skip_header(CdrReader& r) {
    r.i32();     // stamp.sec
    r.u32();     // stamp.nanosec
    r.string();  // frame_id
  }

  void decode_current() {
    try {
      CdrReader r(message_);
      skip_header(r);
      r.u32();  // height
      r.u32();  // width
      if (type_ == kEventPacket) {
        decode_packet(r);
      } else {
        decode_array(r);
      }
    } catch (const CdrReader::Error& e) {
      fail_message(e.offset, e.what);
    }
  }

  void emit_at(TimeUs t, std::uint64_t x, std::uint64_t y, int p, std::uint64_t at) {
    emit(t, static_cast<long>(x), static_cast<long>(y), p, InputPosition::message(static_cast<std::uint64_t>(message_id_), at));
  }

  // Times in ns become us; a time that does not fit is corrupt input.
  TimeUs us_of_ns(unsigned __int128 ns, std::uint64_t at) const {
    const unsigned __int128 us = ns / 1000;
    if (us > static_cast<unsigned __int128>(kMaxTimestampUs)) fail_message(at, "a timestamp beyond 2^62 us");
    return static_cast<TimeUs>(us);
  }

  void decode_packet(CdrReader& r) {
    r.u64();  // seq
    const std::uint64_t time_base = r.u64();
    const std::uint64_t encoding_at = r.offset();
    const std::string encoding(r.string());
    r.boolean();  // is_bigendian: every encoding fixes its own byte order
    const std::uint32_t n = r.sequence_length(1);
    const std::uint64_t start = r.offset();
    const std::span<const unsigned char> events = r.bytes(n);
    if (info_.format.empty()) info_.format = "ROS 2 bag, " + std::string(kEventPacket) + " (" + printable(encoding) + ")";
    if (encoding == "evt3") {
      if (n % 2) fail_message(start, "an evt3 packet of " + std::to_string(n) + " bytes (not whole 16-bit words)");
      struct Sink {
        Ros2BagSource& source;
        std::uint64_t at;
        void event(TimeUs t, unsigned x, unsigned y, int p) { source.emit_at(t, x, y, p, at); }
        void skipped(const char* kind) { source.count_skipped(kind); }
      } sink{*this, start};
      for (size_t i = 0; i < n; i += 2, sink.at += 2) {
        if (!evt3_.word(le16(&events[i]), sink)) {
          fail_message(sink.at, "reserved EVT 3.0 word type " + std::to_string(le16(&events[i]) >> 12));
        }
      }
    } else if (encoding == "libcaer" || encoding == "mono" || encoding == "trigger") {
      if (n % 8) fail_message(start, "a " + encoding + " packet of " + std::to_string(n) + " bytes (not whole 8-byte events)");
      if (encoding == "trigger") {
        count_skipped("trigger events", n / 8);
        return;
      }
      const bool libcaer = encoding == "libcaer";
      std::uint64_t high = time_base;  // libcaer: ns, raised by 2^31 us at each roll-over
      std::uint32_t last_low = 0;
      for (size_t i = 0; i < n; i += 8) {
        const std::uint64_t at = start + i;
        if (libcaer) {
          const std::uint32_t address = le32(&events[i]);
          const std::int32_t low = static_cast<std::int32_t>(le32(&events[i + 4]));
          if (low < 0) fail_message(at + 4, "a negative libcaer timestamp (" + std::to_string(low) + ")");
          if (static_cast<std::uint32_t>(low) < last_low) high += (std::uint64_t{1} << 31) * 1000;
          last_low = static_cast<std::uint32_t>(low);
          emit_at(us_of_ns(static_cast<unsigned __int128>(high) + static_cast<unsigned __int128>(low) * 1000, at), (address >> 17) & 0x7FFF,
               (address >> 2) & 0x7FFF, static_cast<int>((address >> 1) & 1), at);
        } else {
          const std::uint64_t word = std::uint64_t{le32(&events[i])} | (std::uint64_t{le32(&events[i + 4])} << 32);
          emit_at(us_of_ns(static_cast<unsigned __int128>(time_base) + (word & 0xFFFFFFFFu), at), (word >> 32) & 0xFFFF,
               (word >> 48) & 0x7FFF, static_cast<int>(word >> 63), at);
        }
      }
    } else {
      fail_message(encoding_at, "encoding '" + printable(encoding) + "' is not supported (evt3, libcaer, mono, trigger)");
    }
  }

  void decode_array(CdrReader& r) {
    if (info_.format.empty()) info_.format = "ROS 2 bag, " + type_;
    const std::uint32_t n = r.sequence_length(13);
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::uint64_t at = r.offset();
      const std::uint16_t x = r.u16(), y = r.u16();
      const std::int32_t sec = r.i32();
      const std::uint32_t nanosec = r.u32();
      const bool polarity = r.boolean();
      if (sec < 0 || nanosec >= 1000000000u) fail_message(at, "a bad event time (" + std::to_string(sec) + " s, " + std::to_string(nanosec) + " ns)");
      emit_at(static_cast<TimeUs>(sec) * 1000000 + nanosec / 1000, x, y, polarity ? 1 : 0, at);
    }
  }

  BagLayout layout_;
  SourceOptions options_;
  std::string topic_, type_;
  std::unique_ptr<Db3> db_;
  size_t file_ = 0;
  bool has_topic_ = false;
  std::int64_t message_id_ = 0;
  std::span<const unsigned char> message_;
  std::vector<unsigned char> unpacked_;
  std::int64_t total_ = 0, decoded_ = 0;
  Evt3Decoder evt3_;
};

}  // namespace

std::unique_ptr<EventSource> open_ros2_bag(const std::string& name, const std::string& path, const std::string& topic,
                                          const SourceOptions& options) {
  std::error_code ec;
  BagLayout layout = fs::is_directory(path, ec) ? layout_of_folder(path) : BagLayout{{path}, false};
  return std::make_unique<Ros2BagSource>(name, std::move(layout), topic, options);
}

}  // namespace evms::read
