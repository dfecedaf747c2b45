// ROS 1 bags (format 2.0; `rosbag record`): "#ROSBAG V2.0\n", then records. A record is a
// uint32 header length, the header's fields (each a uint32 length, then "name=value" with a
// binary value), a uint32 data length and the data; the header's `op` byte says what it is:
//   0x03 bag header   index_pos, conn_count, chunk_count; the data is padding
//   0x05 chunk        compression ("none", "lz4" or "bz2") and size (uncompressed); the data
//                     is records: connections and messages
//   0x07 connection   conn (uint32) and topic; the data holds fields of its own, among them
//                     `type` ("dvs_msgs/EventArray")
//   0x02 message      conn and time; the data is the message in ROS 1's serialization
//   0x04 index data, 0x06 chunk info: indexes, which a reader going front to back passes over
// One topic is read: the first whose type is an event type (event_messages.h), or the one named
// by `?topic=`. Its messages are taken in the order the file holds them. lz4 chunks are LZ4
// frames (rosbag's roslz4 writes the standard frame format), bz2 chunks bzip2 streams.
#include <bzlib.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "host/read/bytes.h"
#include "host/read/decompress.h"
#include "host/read/event_source.h"
#include "host/read/formats/event_messages.h"

namespace evms::read {
namespace {

constexpr std::string_view kMagic = "#ROSBAG V2.0\n";
// A record larger than this is corrupt: rosbag writes chunks of 768 KiB by default.
constexpr std::uint32_t kMaxRecordBytes = std::uint32_t{256} << 20;

enum Op : std::uint8_t { kMessageData = 0x02, kBagHeader = 0x03, kIndexData = 0x04, kChunk = 0x05, kChunkInfo = 0x06, kConnection = 0x07 };

// A record's header fields, by name.
class RecordFields {
 public:
  // Reads "uint32 length, name=value" fields from `bytes`, which start at byte `at` of the file;
  // for fields inside a chunk, `at` is the chunk's byte and `note` says where in it they are.
  RecordFields(std::span<const unsigned char> bytes, const std::string& path, std::uint64_t at, std::string note = "")
      : at_(at), note_(std::move(note)), path_(path) {
    size_t pos = 0;
    while (pos < bytes.size()) {
      if (bytes.size() - pos < 4) refuse(pos, "a header field's length is cut off");
      const std::uint32_t n = le32(&bytes[pos]);
      if (n > bytes.size() - pos - 4) refuse(pos, "a header field of " + std::to_string(n) + " bytes runs past its header");
      const std::string_view field(reinterpret_cast<const char*>(&bytes[pos + 4]), n);
      const size_t eq = field.find('=');
      if (eq == std::string_view::npos) refuse(pos, "a header field without '='");
      fields_.push_back({std::string(field.substr(0, eq)), field.substr(eq + 1)});
      pos += 4 + n;
    }
  }

  std::optional<std::string_view> find(std::string_view name) const {
    for (const Field& f : fields_) {
      if (f.name == name) return f.value;
    }
    return std::nullopt;
  }
  std::string_view text(std::string_view name) const {
    const auto v = find(name);
    if (!v) refuse(0, "the record has no '" + std::string(name) + "' field");
    return *v;
  }
  std::uint64_t number(std::string_view name, size_t bytes) const {
    const std::string_view v = text(name);
    if (v.size() != bytes) refuse(0, "field '" + std::string(name) + "' has " + std::to_string(v.size()) + " bytes, not " + std::to_string(bytes));
    std::uint64_t n = 0;
    for (size_t i = 0; i < bytes; ++i) n |= std::uint64_t{static_cast<unsigned char>(v[i])} << (8 * i);
    return n;
  }

 private:
  struct Field {
    std::string name;
    std::string_view value;
  };
  // In a chunk, the chunk's byte and the note (where in its records); else the field's byte.
  [[noreturn]] void refuse(size_t pos, const std::string& what) const {
    fail(path_, InputPosition::byte(note_.empty() ? at_ + pos : at_), "bad record: " + what + note_);
  }

  std::vector<Field> fields_;
  std::uint64_t at_;
  std::string note_;
  const std::string& path_;
};

// A record: its header's fields and its data. `at` is its byte in the file, or for a record in a
// chunk the chunk's, and `note` then says where in the chunk's records it is.
struct Record {
  std::uint8_t op = 0;
  std::optional<RecordFields> fields;
  std::span<const unsigned char> data;
  std::uint64_t at = 0;
  std::uint64_t data_at = 0;  // the data's byte, alike
  std::string note;
};

class Ros1BagSource final : public FileEventSource, EventMessageSink {
 public:
  Ros1BagSource(ByteReader in, const std::string& name, const std::string& topic, const SourceOptions& o)
      : FileEventSource(std::move(in), "ROS 1 bag", o), wanted_(topic) {
    info_.name = name;
    in_.skip(kMagic.size());
    // The topic and the sensor size come from the first message of the chosen topic.
    if (!next_message()) {
      if (!messages_) {
        fail(name, {}, printable(wanted_.empty() ? "no event topic" : "no topic '" + wanted_ + "'") + " in the bag (its topics: " +
                           printable(seen_.empty() ? "none" : seen_) + "; event types: " + EventMessages::types_known() + ")");
      }
      fail(name, {}, "topic '" + printable(topic_) + "' has no messages");
    }
    // --width/--height win over the messages, as for ROS 2 bags.
    const bool given = o.width > 0 && o.height > 0;
    set_sensor(given ? std::nullopt : messages_->sensor(message_, *this), std::nullopt, "");
    if (!given) info_.sensor_origin = "message header";  // as ROS 2 bags say it
    decode_current();
  }

 protected:
  bool decode_more() override {
    if (!next_message()) return false;
    decode_current();
    return true;
  }

 private:
  void decode_current() {
    messages_->decode(message_, *this);
    if (info_.format == "ROS 1 bag") info_.format = "ROS 1 bag, " + printable(topic_) + ": " + messages_->format();
  }

  void event(TimeUs t, std::uint64_t x, std::uint64_t y, int p, std::uint64_t at) override {
    emit(t, static_cast<long>(x), static_cast<long>(y), p, InputPosition::message(message_number_, at));
  }
  void skipped_records(const char* kind, std::int64_t n) override { count_skipped(kind, n); }
  [[noreturn]] void refuse(std::uint64_t at, const std::string& what) override {
    fail(in_.path(), InputPosition::message(message_number_, at), what);
  }

  // What a record may still hold: the bytes left in the file (a pipe's are not known), at most
  // kMaxRecordBytes. Nothing is allocated for a length that cannot be there.
  std::uint64_t most_bytes_left() const {
    const std::uint64_t left = in_.size() > in_.offset() ? in_.size() - in_.offset() : kMaxRecordBytes;
    return std::min<std::uint64_t>(left, kMaxRecordBytes);
  }

  // The next record of the file: its header and data are read into `buffer`.
  bool next_file_record(Record& r, std::vector<unsigned char>& buffer) {
    r.at = in_.offset();
    unsigned char length[4];
    const size_t got = in_.read(length, 4);
    if (got == 0) return false;
    if (got < 4) fail(in_.path(), InputPosition::byte(r.at), "a record cut off in its header length");
    const std::uint32_t header_bytes = le32(length);
    if (header_bytes > most_bytes_left()) fail(in_.path(), InputPosition::byte(r.at), "a record header of " + std::to_string(header_bytes) + " bytes runs past the end of the file");
    buffer.resize(header_bytes + 4);
    if (in_.read(buffer.data(), buffer.size()) < buffer.size()) fail(in_.path(), InputPosition::byte(r.at), "a record cut off in its header");
    const std::uint32_t data_bytes = le32(&buffer[header_bytes]);
    if (data_bytes > most_bytes_left()) fail(in_.path(), InputPosition::byte(r.at + 4 + header_bytes), "a record's data of " + std::to_string(data_bytes) + " bytes runs past the end of the file");
    buffer.resize(header_bytes + size_t{data_bytes});
    if (in_.read(buffer.data() + header_bytes, data_bytes) < data_bytes) fail(in_.path(), InputPosition::byte(r.at), "a record cut off in its data");
    const std::span<const unsigned char> bytes(buffer);
    r.note.clear();
    r.data_at = r.at + 8 + header_bytes;
    fill(r, bytes.first(header_bytes), r.at + 4, bytes.subspan(header_bytes));
    return true;
  }

  // The next record of the chunk being read; false at its end.
  bool next_chunk_record(Record& r) {
    if (chunk_pos_ == chunk_.size()) return false;
    const auto refuse_here = [&](const std::string& what) {
      fail(in_.path(), InputPosition::byte(chunk_at_), what + " (at byte " + std::to_string(chunk_pos_) + " of the chunk's records)");
    };
    if (chunk_.size() - chunk_pos_ < 4) refuse_here("a record cut off in its header length");
    const std::uint32_t header_bytes = le32(&chunk_[chunk_pos_]);
    if (header_bytes > chunk_.size() - chunk_pos_ - 4 || chunk_.size() - chunk_pos_ - 4 - header_bytes < 4) refuse_here("a record header runs past the chunk");
    const std::uint32_t data_bytes = le32(&chunk_[chunk_pos_ + 4 + header_bytes]);
    if (data_bytes > chunk_.size() - chunk_pos_ - 8 - header_bytes) refuse_here("a record's data runs past the chunk");
    r.at = r.data_at = chunk_at_;
    r.note = " (in the chunk at this byte, its record at byte " + std::to_string(chunk_pos_) + " of the chunk's records)";
    const std::span<const unsigned char> whole(chunk_.data() + chunk_pos_ + 4, header_bytes + 4 + size_t{data_bytes});
    chunk_pos_ += 8 + header_bytes + size_t{data_bytes};
    fill(r, whole.first(header_bytes), r.at, whole.subspan(header_bytes + 4));
    return true;
  }

  void fill(Record& r, std::span<const unsigned char> header, std::uint64_t header_at, std::span<const unsigned char> data) {
    r.fields.emplace(header, in_.path(), header_at, r.note);
    r.op = static_cast<std::uint8_t>(r.fields->number("op", 1));
    r.data = data;
  }

  // Opens a chunk record: its records, decompressed, become the ones read next.
  void open_chunk(const Record& r) {
    chunk_at_ = r.at;
    chunk_pos_ = 0;
    const std::string compression(r.fields->text("compression"));
    const std::uint64_t size = r.fields->number("size", 4);
    if (size > kMaxRecordBytes) fail(in_.path(), InputPosition::byte(r.at), "a chunk of " + std::to_string(size) + " bytes");
    if (compression == "none") {
      if (r.data.size() != size) fail(in_.path(), InputPosition::byte(r.at), "a chunk of " + std::to_string(r.data.size()) + " bytes that says " + std::to_string(size));
      chunk_.assign(r.data.begin(), r.data.end());
    } else if (compression == "lz4") {
      if (!lz4_frame_into(r.data, size, chunk_)) {
        fail(in_.path(), InputPosition::byte(r.at), "a corrupt lz4 chunk, or one that does not hold the " + std::to_string(size) + " bytes it says");
      }
    } else if (compression == "bz2") {
      decompress_bz2(r, size);
    } else {
      fail(in_.path(), InputPosition::byte(r.at), "a chunk compressed with '" + printable(compression) + "': evms reads 'none', 'lz4' and 'bz2'");
    }
  }

  // bzip2 has no useful bound on its ratio (a long run of one byte shrinks far more than lz4's 255 to 1), so
  // the chunk grows as its stream gives bytes, up to the size it says, instead of being
  // allocated at that size before a byte is known to be good.
  void decompress_bz2(const Record& r, std::uint64_t size) {
    bz_stream stream{};
    if (BZ2_bzDecompressInit(&stream, 0, 0) != BZ_OK) fail(in_.path(), {}, "cannot create a bzip2 decompressor");
    const std::unique_ptr<bz_stream, int (*)(bz_stream*)> owned(&stream, BZ2_bzDecompressEnd);
    const auto corrupt = [&] {
      fail(in_.path(), InputPosition::byte(r.at), "a corrupt bz2 chunk, or one that does not hold the " + std::to_string(size) + " bytes it says");
    };
    stream.next_in = const_cast<char*>(reinterpret_cast<const char*>(r.data.data()));
    stream.avail_in = static_cast<unsigned>(r.data.size());
    chunk_.resize(std::min<std::uint64_t>(size, std::max<std::uint64_t>(std::uint64_t{64} * r.data.size(), 1 << 16)));
    size_t out = 0;
    for (;;) {
      stream.next_out = reinterpret_cast<char*>(chunk_.data() + out);
      stream.avail_out = static_cast<unsigned>(chunk_.size() - out);
      const int status = BZ2_bzDecompress(&stream);
      out = chunk_.size() - stream.avail_out;
      if (status == BZ_STREAM_END) break;
      if (status != BZ_OK) corrupt();
      if (stream.avail_out == 0) {
        if (out == size) corrupt();  // more bytes than it says
        chunk_.resize(std::min<std::uint64_t>(size, 2 * std::uint64_t{chunk_.size()}));
      } else if (stream.avail_in == 0) {
        corrupt();  // the stream ends before its end mark
      }
    }
    if (out != size) corrupt();
    chunk_.resize(size);
  }

  // Moves to the next message of the chosen topic (choosing it at its first connection);
  // false at the end of the bag.
  bool next_message() {
    for (;;) {
      Record r;
      if (!next_chunk_record(r)) {
        if (!next_file_record(r, record_buffer_)) return false;
        if (r.op == kChunk) {
          open_chunk(r);
          continue;
        }
      }
      if (r.op == kConnection) {
        connection(r);
      } else if (r.op == kMessageData) {
        const std::uint64_t conn = r.fields->number("conn", 4);
        ++message_number_;
        if (chosen_.count(conn)) {
          message_ = r.data;
          return true;
        }
      } else if (r.op != kBagHeader && r.op != kIndexData && r.op != kChunkInfo) {
        fail(in_.path(), InputPosition::byte(r.at), "a record of unknown op " + std::to_string(r.op));
      }
    }
  }

  void connection(const Record& r) {
    const std::uint64_t conn = r.fields->number("conn", 4);
    const std::string topic(r.fields->text("topic"));
    const RecordFields details(r.data, in_.path(), r.data_at, r.note);
    const std::string type(details.text("type"));
    if (!seen_topics_.insert(topic).second) {
      if (topic == topic_) chosen_.insert(conn);  // another publisher on the chosen topic
      return;
    }
    seen_ += (seen_.empty() ? "" : ", ") + topic + " (" + type + ")";
    const bool wanted = wanted_.empty() ? !messages_ && EventMessages::is_event_type(type) : topic == wanted_;
    if (!wanted) return;
    if (!EventMessages::is_event_type(type)) {
      fail(info_.name, {}, "topic " + printable(topic) + " has type " + printable(type) + ", not an event type (" + EventMessages::types_known() + ")");
    }
    topic_ = topic;
    chosen_.insert(conn);
    messages_.emplace(type, EventMessages::Serialization::kRos1);
  }

  std::string wanted_, topic_, seen_;
  std::set<std::string> seen_topics_;
  std::set<std::uint64_t> chosen_;  // the chosen topic's connections
  std::optional<EventMessages> messages_;
  std::vector<unsigned char> record_buffer_, chunk_;
  std::uint64_t chunk_at_ = 0;
  size_t chunk_pos_ = 0;
  std::uint64_t message_number_ = 0;  // messages of every topic so far, counted from 1
  std::span<const unsigned char> message_;
};

}  // namespace

std::unique_ptr<EventSource> open_ros1_bag(ByteReader in, const std::string& name, const std::string& topic, const SourceOptions& o) {
  return std::make_unique<Ros1BagSource>(std::move(in), name, topic, o);
}

}  // namespace evms::read
