// ROS 2 bags (rosbag2): a folder with metadata.yaml and its storage files, or one storage file.
// The storage is sqlite3 (.db3) or MCAP (.mcap, mcap_storage.cpp), told apart by their first
// bytes. Each .db3 holds the tables topics(id, name, type, serialization_format, ...) and
// messages(id, topic_id, timestamp, data); data is the CDR-serialized message. One topic
// is read, in the order of the messages' receive timestamps (MCAP: the order the file holds
// them, which is the order rosbag2 received them).
//
// The event messages are decoded by event_messages.h.
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
#include "host/read/decompress.h"
#include "host/read/event_source.h"
#include "host/read/formats/bag_storage.h"
#include "host/read/formats/event_messages.h"

namespace evms::read {
namespace {

namespace fs = std::filesystem;

// A decompressed message larger than this is corrupt (a packet of 16 M events in 8 bytes each).
constexpr size_t kMaxMessageBytes = size_t{128} << 20;


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
    if (storage != "sqlite3" && storage != "mcap") fail(meta.string(), {}, "storage '" + printable(storage) + "' is not supported (sqlite3 and mcap)");
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
class Db3 final : public BagStorage {
 public:
  explicit Db3(const std::string& path) : path_(path) {
    sqlite3* db = nullptr;
    const int rc = sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr);
    db_.reset(db);  // sqlite allocates a handle even when opening fails
    if (rc != SQLITE_OK) error("cannot open");
  }

  std::vector<Topic> topics() override {
    Statement s = prepare("SELECT id, name, type, serialization_format FROM topics ORDER BY id");
    std::vector<Topic> out;
    while (step(s.get())) out.push_back({sqlite3_column_int64(s.get(), 0), text(s.get(), 1), text(s.get(), 2), text(s.get(), 3)});
    return out;
  }
  std::int64_t count(std::int64_t topic) override {
    Statement s = prepare("SELECT COUNT(*) FROM messages WHERE topic_id = ?");
    sqlite3_bind_int64(s.get(), 1, topic);
    return step(s.get()) ? sqlite3_column_int64(s.get(), 0) : 0;
  }
  void select(std::int64_t topic) override {
    messages_ = prepare("SELECT id, data FROM messages WHERE topic_id = ? ORDER BY timestamp, id");
    sqlite3_bind_int64(messages_.get(), 1, topic);
  }
  // The next message's row id and bytes (valid until the next call); false at the end.
  bool next(std::int64_t& id, std::span<const unsigned char>& data) override {
    if (!step(messages_.get())) return false;
    id = sqlite3_column_int64(messages_.get(), 0);
    const void* blob = sqlite3_column_blob(messages_.get(), 1);
    const int n = sqlite3_column_bytes(messages_.get(), 1);
    data = {static_cast<const unsigned char*>(blob), static_cast<size_t>(n)};
    return true;
  }
  const std::string& path() const override { return path_; }
  const char* container() const override { return "ROS 2 bag"; }

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

// A storage file of either kind, by its first bytes.
std::unique_ptr<BagStorage> open_storage(const std::string& path) {
  if (!fs::exists(path)) fail(path, {}, "cannot open: no such file (listed in the bag's metadata.yaml)");
  {
    ByteReader in(path);
    if (in.peek(kMcapMagic.size()) == kMcapMagic) return open_mcap_storage(path);
  }
  return std::make_unique<Db3>(path);
}

class Ros2BagSource final : public DecodedEventSource, EventMessageSink {
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
    db_ = open_storage(layout_.files[0]);
    const std::vector<BagStorage::Topic> topics = db_->topics();
    const BagStorage::Topic* chosen = nullptr;
    std::string listed;
    for (const BagStorage::Topic& t : topics) {
      listed += (listed.empty() ? "" : ", ") + t.name + " (" + t.type + ")";
      if (wanted.empty() ? (!chosen && EventMessages::is_event_type(t.type)) : t.name == wanted) chosen = &t;
    }
    if (!chosen) {
      fail(info_.name, {}, printable(wanted.empty() ? "no event topic" : "no topic '" + wanted + "'") +
                               " in the bag (its topics: " + printable(listed.empty() ? "none" : listed) +
                               "; event types: " + EventMessages::types_known() + ")");
    }
    if (!EventMessages::is_event_type(chosen->type)) {
      fail(info_.name, {}, "topic " + printable(chosen->name) + " has type " + printable(chosen->type) + ", not an event type (" +
                               EventMessages::types_known() + ")");
    }
    // ROS 2 writes cdr; an MCAP file converted from a ROS 1 bag (`mcap convert`) keeps ROS 1's
    // serialization, "ros1".
    if (chosen->serialization != "cdr" && chosen->serialization != "ros1") {
      fail(info_.name, {}, "topic " + printable(chosen->name) + " is serialized as '" + printable(chosen->serialization) + "', not cdr or ros1");
    }
    topic_ = chosen->name;
    for (const BagStorage::Topic& t : topics) {
      if (t.name != topic_ && EventMessages::is_event_type(t.type) && other_event_topics_.find(t.name) == std::string::npos) {
        other_event_topics_ += (other_event_topics_.empty() ? "" : ", ") + t.name;
      }
    }
    messages_.emplace(chosen->type, chosen->serialization == "ros1" ? EventMessages::Serialization::kRos1 : EventMessages::Serialization::kCdr);
    for (const BagStorage::Topic& t : topics) {
      if (t.name == topic_) total_ += db_->count(t.id);
    }
    for (size_t f = 1; f < layout_.files.size(); ++f) {
      const std::unique_ptr<BagStorage> db = open_storage(layout_.files[f]);
      for (const BagStorage::Topic& t : db->topics()) {
        if (t.name == topic_) total_ += db->count(t.id);
      }
    }
    open_file(0);
  }

  void open_file(size_t index) {
    file_ = index;
    if (!db_ || db_->path() != layout_.files[index]) db_ = open_storage(layout_.files[index]);
    for (const BagStorage::Topic& t : db_->topics()) {
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
    if (!zstd_frame_into(data, size, unpacked_)) fail_message(0, "corrupt zstd frame");
    return unpacked_;
  }

  [[noreturn]] void fail_message(std::uint64_t byte, const std::string& what) const {
    fail(db_->path(), InputPosition::message(static_cast<std::uint64_t>(message_id_), byte), what);
  }

  std::optional<SensorSize> sensor_of_first_message() { return messages_->sensor(message_, *this); }

  void decode_current() {
    messages_->decode(message_, *this);
    if (info_.format.empty()) {
      info_.format = std::string(db_->container()) + ", " + printable(topic_) + ": " + messages_->format() +
                     (other_event_topics_.empty() ? "" : " (other event topics, which ?topic= picks: " + printable(other_event_topics_) + ")");
    }
  }

  void event(TimeUs t, std::uint64_t x, std::uint64_t y, int p, std::uint64_t at) override {
    emit(t, static_cast<long>(x), static_cast<long>(y), p, InputPosition::message(static_cast<std::uint64_t>(message_id_), at));
  }
  void skipped_records(const char* kind, std::int64_t n) override { count_skipped(kind, n); }
  [[noreturn]] void refuse(std::uint64_t at, const std::string& what) override { fail_message(at, what); }

  BagLayout layout_;
  SourceOptions options_;
  std::string topic_;
  std::string other_event_topics_;  // for the format line
  std::optional<EventMessages> messages_;
  std::unique_ptr<BagStorage> db_;
  size_t file_ = 0;
  bool has_topic_ = false;
  std::int64_t message_id_ = 0;
  std::span<const unsigned char> message_;
  std::vector<unsigned char> unpacked_;
  std::int64_t total_ = 0, decoded_ = 0;
};

}  // namespace

std::unique_ptr<EventSource> open_ros2_bag(const std::string& name, const std::string& path, const std::string& topic,
                                          const SourceOptions& options) {
  std::error_code ec;
  BagLayout layout = fs::is_directory(path, ec) ? layout_of_folder(path) : BagLayout{{path}, false};
  return std::make_unique<Ros2BagSource>(name, std::move(layout), topic, options);
}

}  // namespace evms::read
