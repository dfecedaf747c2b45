// MCAP files (https://mcap.dev/spec, major version 0): the magic "\x89MCAP0\r\n", then records,
// each an opcode byte, a uint64 length and that many bytes, up to the Data End record; the
// summary after it only repeats or indexes what came before, and is not read. The records read:
//   0x01 Header    first: profile, library
//   0x03 Schema    id (uint16), name (the message type, "event_camera_msgs/msg/EventPacket"),
//                  encoding, data
//   0x04 Channel   id, schema_id (uint16), topic, message_encoding ("cdr"; "ros1" in a file
//                  converted from a ROS 1 bag), metadata
//   0x05 Message   channel_id (uint16), sequence (uint32), log_time, publish_time (uint64),
//                  then the message's bytes
//   0x06 Chunk     message start and end times, uncompressed_size (uint64), uncompressed_crc
//                  (uint32), compression ("", "lz4" or "zstd"), then its records as a
//                  uint64-length byte string: schemas, channels and messages
//   0x0F Data End  the end of the data section: data_section_crc (uint32)
// and, from the summary section that the footer points to (rosbag2 writes one):
//   0x0B Statistics  counts of messages, schemas (uint16), channels, attachments, metadata and
//                    chunks (uint32), the first and last log times (uint64), then each
//                    channel's message count: a uint32 byte length of (uint16, uint64) pairs
//   0x02 Footer      summary_start, summary_offset_start (uint64), summary_crc (uint32): the
//                    CRC-32 of the summary section and the footer's fields before it
// A CRC-32 (zlib's) of 0 means none was written. A chunk's covers its decompressed records; the
// Data End's every byte of the file before that record, magic and header included. A file that
// fails either is refused where it fails: its messages before that place come out first, as
// from a file cut short.
// Strings are a uint32 length and UTF-8; every integer is little-endian. Other records
// (indexes, attachments, metadata) are passed over. A topic's messages are taken in the order
// the file holds them, as rosbag2 wrote them on receipt; each has its number, counted from 1
// over every message of the file, for errors. The topics and their counts come from the
// summary's schemas, channels and statistics when it has all three and they pass the CRC; a
// file without them is read twice: once for its topics and their counts (up to the first error,
// which the second pass reports after the messages before it), once for the messages.
#include <algorithm>
#include <map>
#include <optional>
#include <set>

#include <zlib.h>

#include "host/read/byte_reader.h"
#include "host/read/bytes.h"
#include "host/read/decompress.h"
#include "host/read/event_source.h"
#include "host/read/formats/bag_storage.h"

namespace evms::read {
namespace mcap {  // apart from ros1_bag.cpp's records, which a unity build puts beside these
namespace {

// A record or a chunk larger than this is corrupt: writers cut chunks at about 1 MiB.
constexpr std::uint64_t kMaxRecordBytes = std::uint64_t{256} << 20;

// v's last `digits` hexadecimal digits.
std::string hex(std::uint32_t v, int digits) {
  std::string s(static_cast<size_t>(digits), '0');
  for (int i = digits - 1; i >= 0; --i, v >>= 4) s[static_cast<size_t>(i)] = "0123456789abcdef"[v & 15];
  return s;
}

// zlib's CRC-32 of n more bytes; its length is a uInt, which a record or a summary of at most
// kMaxRecordBytes fits.
std::uint32_t crc32_of(std::uint32_t crc, const unsigned char* data, size_t n) {
  return static_cast<std::uint32_t>(crc32(crc, data, static_cast<uInt>(n)));
}

enum Op : std::uint8_t {
  kHeader = 0x01, kFooter = 0x02, kSchema = 0x03, kChannel = 0x04, kMessage = 0x05, kChunk = 0x06, kStatistics = 0x0B, kDataEnd = 0x0F
};

struct Record {
  std::uint8_t op = 0;
  std::span<const unsigned char> body;
  std::uint64_t at = 0;        // the record's byte in the file, or its chunk's
  std::uint64_t in_chunk = 0;  // inside a chunk: the record's byte in the decompressed records, plus 1
};

// The fields of one record, read in order; running past its end fails with where.
class Fields {
 public:
  Fields(const Record& r, const std::string& path) : r_(r), path_(path) {}
  std::uint16_t u16() { return le16(take(2).data()); }
  std::uint32_t u32() { return le32(take(4).data()); }
  std::uint64_t u64() { return le64(take(8).data()); }
  std::string string() {
    const std::uint32_t n = u32();
    return std::string(reinterpret_cast<const char*>(take(n).data()), n);
  }
  std::span<const unsigned char> bytes(std::uint64_t n) { return take(n); }
  std::span<const unsigned char> rest() { return take(r_.body.size() - pos_); }
  size_t consumed() const { return pos_; }

  [[noreturn]] void refuse(const std::string& what) const {
    fail(path_, InputPosition::byte(r_.at),
         (r_.in_chunk ? "the chunk's record at byte " + std::to_string(r_.in_chunk - 1) + " of its records: " : std::string()) + what);
  }

 private:
  std::span<const unsigned char> take(std::uint64_t n) {
    if (n > r_.body.size() - pos_) {
      refuse("a record of opcode 0x" + hex(r_.op, 2) + " and " + std::to_string(r_.body.size()) + " bytes is cut off inside its fields");
    }
    const auto s = r_.body.subspan(pos_, static_cast<size_t>(n));
    pos_ += static_cast<size_t>(n);
    return s;
  }
  const Record& r_;
  const std::string& path_;
  size_t pos_ = 0;
};

// The data section's records, front to back, with a chunk's records in its place.
class Records {
 public:
  explicit Records(const std::string& path) : in_(path) {
    if (in_.peek(kMcapMagic.size()) != kMcapMagic) {
      fail(path, InputPosition::byte(0), "not an MCAP file (its first bytes are not \\x89MCAP0\\r\\n)");
    }
    in_.skip(kMcapMagic.size());
    crc_of_data_ = crc32_of(0, reinterpret_cast<const unsigned char*>(kMcapMagic.data()), kMcapMagic.size());
    Record header;
    if (!next(header) || header.op != kHeader) fail(path, InputPosition::byte(kMcapMagic.size()), "the first record is not the MCAP header");
  }

  const std::string& path() const { return in_.path(); }

  bool next(Record& r) {
    for (;;) {
      if (chunk_pos_ < chunk_.size()) {
        r.at = chunk_at_;
        r.in_chunk = chunk_pos_ + 1;
        if (chunk_.size() - chunk_pos_ < 9) Fields(r, path()).refuse("a record's opcode and length are cut off at the chunk's end");
        r.op = chunk_[chunk_pos_];
        const std::uint64_t n = le64(&chunk_[chunk_pos_ + 1]);
        if (n > chunk_.size() - chunk_pos_ - 9) Fields(r, path()).refuse("a record of " + std::to_string(n) + " bytes runs past the chunk's end");
        r.body = std::span<const unsigned char>(chunk_).subspan(chunk_pos_ + 9, static_cast<size_t>(n));
        chunk_pos_ += 9 + static_cast<size_t>(n);
        return true;
      }
      if (ended_) return false;
      r.at = in_.offset();
      r.in_chunk = 0;
      unsigned char head[9];
      const size_t got = in_.read(head, sizeof head);
      if (got == 0) fail(path(), InputPosition::byte(r.at), "the file ends without its Data End and Footer records (a recording cut short)");
      if (got < sizeof head) fail(path(), InputPosition::byte(r.at), "a record's opcode and length are cut off at the end of the file");
      r.op = head[0];
      const std::uint64_t n = le64(head + 1);
      const std::uint64_t left = in_.size() > in_.offset() ? in_.size() - in_.offset() : 0;
      if (n > kMaxRecordBytes || (in_.size() > 0 && n > left)) {
        fail(path(), InputPosition::byte(r.at), "a record of " + std::to_string(n) + " bytes runs past the end of the file");
      }
      record_.resize(static_cast<size_t>(n));
      if (in_.read(record_.data(), record_.size()) < record_.size()) {
        fail(path(), InputPosition::byte(r.at), "a record of " + std::to_string(n) + " bytes runs past the end of the file");
      }
      r.body = record_;
      if (r.op == kDataEnd) check_data_section(r);
      if (r.op == kDataEnd || r.op == kFooter) {
        ended_ = true;
        return false;
      }
      crc_of_data_ = crc32_of(crc_of_data_, head, sizeof head);
      crc_of_data_ = crc32_of(crc_of_data_, record_.data(), record_.size());
      if (r.op != kChunk) return true;
      open_chunk(r);
    }
  }

 private:
  void open_chunk(const Record& r) {
    Fields f(r, path());
    f.u64(), f.u64();  // the messages' first and last log times
    const std::uint64_t size = f.u64();
    const std::uint32_t crc = f.u32();
    const std::string compression = f.string();
    const std::span<const unsigned char> records = f.bytes(f.u64());
    if (size > kMaxRecordBytes) f.refuse("a chunk of " + std::to_string(size) + " bytes uncompressed (more than 256 MiB)");
    bool ok = true;
    if (compression.empty()) {
      ok = records.size() == size;
      chunk_.assign(records.begin(), records.end());
    } else if (compression == "lz4") {
      ok = lz4_frame_into(records, size, chunk_);
    } else if (compression == "zstd") {
      ok = zstd_frame_into(records, size, chunk_);
    } else {
      f.refuse("a chunk compressed with '" + printable(compression) + "': evms reads uncompressed, 'lz4' and 'zstd' chunks");
    }
    if (!ok) f.refuse("a corrupt " + (compression.empty() ? std::string("uncompressed") : compression) + " chunk, or one that does not hold the " + std::to_string(size) + " bytes it says");
    refuse_unless_crc(f, crc, crc32_of(0, chunk_.data(), chunk_.size()), "the chunk's records fail their");
    chunk_at_ = r.at;
    chunk_pos_ = 0;
  }

  void check_data_section(const Record& r) {
    Fields f(r, path());
    refuse_unless_crc(f, f.u32(), crc_of_data_, "the data section fails its");
  }
  // `what` names the bytes and the verb: "the data section fails its".
  static void refuse_unless_crc(const Fields& f, std::uint32_t stored, std::uint32_t computed, const std::string& what) {
    if (stored != 0 && stored != computed) {
      f.refuse(what + " CRC-32 (stored 0x" + hex(stored, 8) + ", computed 0x" + hex(computed, 8) + "): the file is corrupt");
    }
  }

  ByteReader in_;
  std::uint32_t crc_of_data_ = 0;
  std::vector<unsigned char> record_, chunk_;
  size_t chunk_pos_ = 0;
  std::uint64_t chunk_at_ = 0;
  bool ended_ = false;
};

class McapStorage final : public BagStorage {
 public:
  explicit McapStorage(const std::string& path) : path_(path) {
    // Without a summary, the first pass: every schema and channel, and each channel's
    // messages. A file cut short or corrupt further on is counted up to there: the second pass
    // gives the messages before that place and then its error.
    Records records(path);
    if (read_summary()) return;
    std::int64_t number = 0;
    try {
      first_pass(records, number);
    } catch (const InputError&) {
      if (channels_.empty()) throw;
    }
  }

  // The topics and counts from the summary section; false, with nothing kept, when the file
  // has no summary, or one without statistics or a channel record for each channel counted,
  // or one that is malformed or fails its CRC: the first pass then finds them.
  bool read_summary() {
    constexpr std::uint64_t kFooterFields = 8 + 8 + 4, kFooterRecord = 9 + kFooterFields;
    ByteReader in(path_);
    if (in.size() < 2 * kMcapMagic.size() + kFooterRecord) return false;
    const std::uint64_t footer_at = in.size() - kMcapMagic.size() - kFooterRecord;
    in.skip(footer_at);
    unsigned char footer[kFooterRecord + kMcapMagic.size()];
    if (in.read(footer, sizeof footer) != sizeof footer || footer[0] != kFooter || le64(footer + 1) != kFooterFields ||
        std::string_view(reinterpret_cast<const char*>(footer + kFooterRecord), kMcapMagic.size()) != kMcapMagic) {
      return false;
    }
    const std::uint64_t summary_at = le64(footer + 9);
    const std::uint32_t summary_crc = le32(footer + 9 + 16);
    if (summary_at < kMcapMagic.size() || summary_at >= footer_at || footer_at - summary_at > kMaxRecordBytes) return false;
    std::vector<unsigned char> summary(static_cast<size_t>(footer_at - summary_at));
    ByteReader from(path_);
    from.skip(summary_at);
    if (from.read(summary.data(), summary.size()) != summary.size()) return false;
    const std::uint32_t crc = crc32_of(crc32_of(0, summary.data(), summary.size()), footer, 9 + 16);
    if (summary_crc != 0 && summary_crc != crc) return false;
    try {
      std::map<std::uint16_t, std::string> schemas;
      std::optional<std::uint32_t> channels_counted;
      for (size_t at = 0; at < summary.size();) {
        Record r;
        r.at = summary_at + at;
        if (summary.size() - at < 9 || le64(&summary[at + 1]) > summary.size() - at - 9) return false;
        r.op = summary[at];
        r.body = std::span<const unsigned char>(summary).subspan(at + 9, static_cast<size_t>(le64(&summary[at + 1])));
        at += 9 + r.body.size();
        if (r.op == kSchema || r.op == kChannel) {
          take_definition(r, schemas);
        } else if (r.op == kStatistics) {
          Fields f(r, path_);
          f.u64(), f.u16();  // messages, schemas
          channels_counted = f.u32();
          f.u32(), f.u32(), f.u32(), f.u64(), f.u64();  // attachments, metadata, chunks, first and last times
          Record pairs{r.op, f.bytes(f.u32()), r.at, 0};
          for (Fields p(pairs, path_); pairs.body.size() - p.consumed() >= 10;) {
            const std::uint16_t channel = p.u16();
            counts_[channel] = static_cast<std::int64_t>(std::min<std::uint64_t>(p.u64(), INT64_MAX));
          }
        }
      }
      if (channels_counted && *channels_counted == channels_.size() && !channels_.empty()) return true;
    } catch (const InputError&) {
    }
    channels_.clear();
    counts_.clear();
    return false;
  }

  void first_pass(Records& records, std::int64_t& number) {
    const std::string& path = records.path();
    std::map<std::uint16_t, std::string> schemas;
    for (Record r; records.next(r);) {
      Fields f(r, path);
      if (r.op == kSchema || r.op == kChannel) {
        take_definition(r, schemas);
      } else if (r.op == kMessage) {
        ++number;
        const std::uint16_t channel = f.u16();
        if (!channels_.count(channel)) refuse_unknown_channel(f, number, channel);
        ++counts_[channel];
      }
    }
  }

  // A schema (its message type, kept by its ID) or a channel (its topic, type and encoding); a
  // channel seen before is a repeat, identical by the specification. The channel's topic is
  // returned when it is new.
  const Topic* take_definition(const Record& r, std::map<std::uint16_t, std::string>& schemas) {
    Fields f(r, path_);
    if (r.op == kSchema) {
      const std::uint16_t id = f.u16();
      schemas[id] = f.string();
      return nullptr;
    }
    const std::uint16_t id = f.u16(), schema = f.u16();
    std::string topic = f.string(), encoding = f.string();
    if (channels_.count(id)) return nullptr;
    const auto type = schemas.find(schema);
    return &(channels_[id] = {id, std::move(topic), type == schemas.end() ? std::string() : type->second, std::move(encoding)});
  }

  [[noreturn]] static void refuse_unknown_channel(const Fields& f, std::int64_t number, std::uint16_t channel) {
    f.refuse("message " + std::to_string(number) + " is on channel " + std::to_string(channel) + ", which no channel record before it defines");
  }

  std::vector<Topic> topics() override {
    std::vector<Topic> out;
    for (const auto& [id, topic] : channels_) out.push_back(topic);
    return out;
  }
  // The messages of one channel: the bag reader adds up its topic's channels.
  std::int64_t count(std::int64_t id) override {
    const auto n = counts_.find(static_cast<std::uint16_t>(id));
    return n == counts_.end() ? 0 : n->second;
  }
  // Every channel of the topic: a topic has one channel for each publisher that recorded it.
  void select(std::int64_t id) override {
    records_.emplace(path_);
    selected_.clear();
    const auto chosen = channels_.find(static_cast<std::uint16_t>(id));
    selected_name_.reset();
    if (chosen != channels_.end()) selected_name_ = chosen->second.name;
    for (const auto& [channel, topic] : channels_) {
      if (selected_name_ && topic.name == *selected_name_) selected_.insert(channel);
    }
    data_schemas_.clear();
    number_ = 0;
  }
  bool next(std::int64_t& id, std::span<const unsigned char>& data) override {
    for (Record r; records_->next(r);) {
      if (r.op == kSchema || r.op == kChannel) {
        // Each channel's record repeats in the data section. One that a summary did not define
        // (a summary that does not match its data) is known from here on, and read when it is
        // the chosen topic's.
        const Topic* added = take_definition(r, data_schemas_);
        if (added && selected_name_ && added->name == *selected_name_) selected_.insert(static_cast<std::uint16_t>(added->id));
        continue;
      }
      if (r.op != kMessage) continue;
      ++number_;
      Fields f(r, path_);
      const std::uint16_t channel = f.u16();
      if (!channels_.count(channel)) refuse_unknown_channel(f, number_, channel);
      if (!selected_.count(channel)) continue;
      f.u32(), f.u64(), f.u64();  // sequence, log and publish times
      id = number_;
      data = f.rest();
      return true;
    }
    return false;
  }
  const std::string& path() const override { return path_; }
  const char* container() const override { return "MCAP"; }

 private:
  std::string path_;
  std::map<std::uint16_t, Topic> channels_;
  std::map<std::uint16_t, std::int64_t> counts_;
  std::optional<Records> records_;
  std::set<std::uint16_t> selected_;
  std::optional<std::string> selected_name_;
  std::map<std::uint16_t, std::string> data_schemas_;  // the second pass's schemas, by ID
  std::int64_t number_ = 0;
};

}  // namespace
}  // namespace mcap

std::unique_ptr<BagStorage> open_mcap_storage(const std::string& path) { return std::make_unique<mcap::McapStorage>(path); }

}  // namespace evms::read
