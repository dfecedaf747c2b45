#include "tests/support/encoders.h"

#include <flatbuffers/flatbuffers.h>
#include <bzlib.h>
#include <lz4frame.h>
#include <sqlite3.h>
#include <unistd.h>
#include <zlib.h>
#include <zstd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "aedat4_events_generated.h"
#include "aedat4_io_header_generated.h"
#include "host/gen/random.h"
#include "host/read/formats/bag_storage.h"

namespace evms::test {
namespace {

void put_be32(Bytes& b, std::uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) b.push_back(static_cast<std::uint8_t>(v >> s));
}
void put_le32(Bytes& b, std::uint32_t v) {
  for (int s = 0; s < 32; s += 8) b.push_back(static_cast<std::uint8_t>(v >> s));
}
void put_le16(Bytes& b, std::uint16_t v) {
  b.push_back(static_cast<std::uint8_t>(v));
  b.push_back(static_cast<std::uint8_t>(v >> 8));
}
void put_text(Bytes& b, const std::string& s) { b.insert(b.end(), s.begin(), s.end()); }

}  // namespace

std::string rpg_text(const std::vector<Event>& events) {
  std::string s;
  char line[96];
  for (const Event& e : events) {
    std::snprintf(line, sizeof line, "%lld.%06lld000 %d %d %d\n", static_cast<long long>(e.t / 1000000),
                  static_cast<long long>(e.t % 1000000), e.x, e.y, e.p);
    s += line;
  }
  return s;
}

std::string csv(const std::vector<Event>& events) {
  std::string s = "t_us,x,y,p\n";
  for (const Event& e : events) {
    s += std::to_string(e.t) + "," + std::to_string(e.x) + "," + std::to_string(e.y) + "," + std::to_string(e.p) + "\n";
  }
  return s;
}

Bytes npy(const std::string& dict, const Bytes& data, int major) {
  const size_t prefix = major == 1 ? 10 : 12;
  std::string header = dict;
  while ((prefix + header.size() + 1) % 64 != 0) header += ' ';
  header += '\n';
  Bytes b = {0x93, 'N', 'U', 'M', 'P', 'Y', static_cast<std::uint8_t>(major), 0};
  put_int(b, header.size(), major == 1 ? 2 : 4);
  b.insert(b.end(), header.begin(), header.end());
  b.insert(b.end(), data.begin(), data.end());
  return b;
}

void put_int(Bytes& b, std::uint64_t v, int bytes, bool big_endian) {
  for (int i = 0; i < bytes; ++i) b.push_back(static_cast<std::uint8_t>(v >> (8 * (big_endian ? bytes - 1 - i : i))));
}

Bytes aedat2_dvs128(const std::vector<Event>& events) {
  Bytes b;
  put_text(b, "#!AER-DAT2.0\r\n# This is a raw AE data file\r\n# AEChip: ch.unizh.ini.jaer.chip.retina.DVS128\r\n");
  for (const Event& e : events) {
    put_be32(b, (std::uint32_t{e.y} << 8) | (std::uint32_t{e.x} << 1) | e.p);
    put_be32(b, static_cast<std::uint32_t>(e.t));
  }
  return b;
}

Bytes aedat2_davis240(const std::vector<Event>& events) {
  Bytes b;
  put_text(b, "#!AER-DAT2.0\r\n# AEChip: eu.seebetter.ini.chips.davis.DAVIS240C\r\n");
  for (const Event& e : events) {
    put_be32(b, (std::uint32_t{e.y} << 22) | (std::uint32_t{e.x} << 12) | (std::uint32_t{e.p} << 11));
    put_be32(b, static_cast<std::uint32_t>(e.t));
  }
  // An APS sample (type bit set) that the reader must skip.
  put_be32(b, 0x80000000u | (5u << 22) | (7u << 12) | 300u);
  put_be32(b, static_cast<std::uint32_t>(events.empty() ? 0 : events.back().t));
  return b;
}

Bytes aedat3_davis240(const std::vector<Event>& events) {
  Bytes b;
  put_text(b, "#!AER-DAT3.1\r\n#Format: RAW\r\n#Source 1: DAVIS240C\r\n#!END-HEADER\r\n");
  // A special-event packet first, which the reader must skip.
  put_le16(b, 0);
  put_le16(b, 1);
  put_le32(b, 8), put_le32(b, 4), put_le32(b, 0), put_le32(b, 1), put_le32(b, 1), put_le32(b, 1);
  put_le32(b, 0x1), put_le32(b, 0);
  for (size_t start = 0; start < events.size(); start += 50) {
    const size_t n = std::min<size_t>(50, events.size() - start);
    const std::int64_t overflow = events[start].t >> 31;
    put_le16(b, 1);
    put_le16(b, 1);
    put_le32(b, 8), put_le32(b, 4), put_le32(b, static_cast<std::uint32_t>(overflow));
    put_le32(b, static_cast<std::uint32_t>(n)), put_le32(b, static_cast<std::uint32_t>(n)), put_le32(b, static_cast<std::uint32_t>(n));
    for (size_t i = start; i < start + n; ++i) {
      const Event& e = events[i];
      if ((e.t >> 31) != overflow) throw std::logic_error("test encoder: packet spans a timestamp overflow");
      put_le32(b, (std::uint32_t{e.x} << 17) | (std::uint32_t{e.y} << 2) | (std::uint32_t{e.p} << 1) | 1u);
      put_le32(b, static_cast<std::uint32_t>(e.t & 0x7FFFFFFF));
    }
  }
  return b;
}

Bytes aedat4(const std::vector<Event>& events, SensorSize sensor, Aedat4Compression c, size_t per_packet) {
  const std::string xml =
      "<dv version=\"2.0\"><node name=\"outInfo\" path=\"/mainloop/Recorder/outInfo/\">"
      "<node name=\"0\" path=\"/mainloop/Recorder/outInfo/0/\">"
      "<attr key=\"typeIdentifier\" type=\"string\">EVTS</attr>"
      "<node name=\"info\" path=\"/mainloop/Recorder/outInfo/0/info/\">"
      "<attr key=\"sizeX\" type=\"int\">" + std::to_string(sensor.width) + "</attr>"
      "<attr key=\"sizeY\" type=\"int\">" + std::to_string(sensor.height) + "</attr></node></node>"
      "<node name=\"1\" path=\"/mainloop/Recorder/outInfo/1/\">"
      "<attr key=\"typeIdentifier\" type=\"string\">IMUS</attr></node></node></dv>";
  Bytes b;
  put_text(b, "#!AER-DAT4.0\r\n");
  flatbuffers::FlatBufferBuilder hb;
  auto info = hb.CreateString(xml);
  hb.FinishSizePrefixed(aedat4::CreateIOHeader(hb, static_cast<aedat4::Compression>(c), -1, info), aedat4::IOHeaderIdentifier());
  b.insert(b.end(), hb.GetBufferPointer(), hb.GetBufferPointer() + hb.GetSize());

  auto packet = [&](std::int32_t stream, const std::uint8_t* data, size_t size) {
    Bytes body;
    if (c == Aedat4Compression::kNone) {
      body.assign(data, data + size);
    } else if (c == Aedat4Compression::kLz4) {
      body.resize(LZ4F_compressFrameBound(size, nullptr));
      body.resize(LZ4F_compressFrame(body.data(), body.size(), data, size, nullptr));
    } else {
      body.resize(ZSTD_compressBound(size));
      body.resize(ZSTD_compress(body.data(), body.size(), data, size, 3));
    }
    put_le32(b, static_cast<std::uint32_t>(stream));
    put_le32(b, static_cast<std::uint32_t>(body.size()));
    b.insert(b.end(), body.begin(), body.end());
  };
  for (size_t start = 0; start < events.size(); start += per_packet) {
    std::vector<aedat4::PolarityEvent> v;
    for (size_t i = start; i < std::min(events.size(), start + per_packet); ++i) {
      const Event& e = events[i];
      v.emplace_back(e.t, static_cast<std::int16_t>(e.x), static_cast<std::int16_t>(e.y), e.p != 0);
    }
    flatbuffers::FlatBufferBuilder eb;
    eb.FinishSizePrefixed(aedat4::CreateEventPacket(eb, eb.CreateVectorOfStructs(v)), aedat4::EventPacketIdentifier());
    packet(0, eb.GetBufferPointer(), eb.GetSize());
    const std::uint8_t imu[16] = {1, 2, 3};
    packet(1, imu, sizeof imu);  // an IMU packet the reader must skip
  }
  return b;
}

Bytes evt2(const std::vector<Event>& events, SensorSize sensor) {
  Bytes b;
  put_text(b, "% evt 2.0\n% geometry " + std::to_string(sensor.width) + "x" + std::to_string(sensor.height) + "\n% end\n");
  std::int64_t high = -1;
  for (const Event& e : events) {
    if ((e.t >> 6) != high) {
      high = e.t >> 6;
      put_le32(b, (0x8u << 28) | static_cast<std::uint32_t>(high & 0x0FFFFFFF));
    }
    put_le32(b, (std::uint32_t{e.p} << 28) | (static_cast<std::uint32_t>(e.t & 0x3F) << 22) | (std::uint32_t{e.x} << 11) | e.y);
  }
  put_le32(b, 0xAu << 28);  // an external trigger, to be skipped
  return b;
}

Bytes evt21(const std::vector<Event>& events, SensorSize sensor, bool legacy) {
  Bytes b;
  put_text(b, "% evt 2.1\n% format EVT21;height=" + std::to_string(sensor.height) + ";width=" + std::to_string(sensor.width) +
                  (legacy ? ";endianness=legacy" : "") + "\n% end\n");
  const auto put_word = [&](std::uint32_t head, std::uint32_t mask) {
    put_le32(b, legacy ? head : mask);
    put_le32(b, legacy ? mask : head);
  };
  std::int64_t high = -1;
  for (size_t i = 0; i < events.size();) {
    const Event& e = events[i];
    if ((e.t >> 6) != high) {
      high = e.t >> 6;
      put_word((0x8u << 28) | static_cast<std::uint32_t>(high & 0x0FFFFFFF), 0);
    }
    // Following events of the same time, row and polarity at ascending x within 32 of this
    // one's share its word.
    std::uint32_t mask = 1;
    size_t next = i + 1;
    while (next < events.size() && events[next].t == e.t && events[next].y == e.y && events[next].p == e.p && events[next].x > events[next - 1].x &&
           events[next].x < e.x + 32) {
      mask |= std::uint32_t{1} << (events[next].x - e.x);
      ++next;
    }
    put_word((std::uint32_t{e.p} << 28) | (static_cast<std::uint32_t>(e.t & 0x3F) << 22) | (std::uint32_t{e.x} << 11) | e.y, mask);
    i = next;
  }
  put_word(0xAu << 28, 0);  // an external trigger, to be skipped
  return b;
}

Bytes evt3(const std::vector<Event>& events, SensorSize sensor) {
  Bytes b;
  put_text(b, "% evt 3.0\n% format EVT3;height=" + std::to_string(sensor.height) + ";width=" + std::to_string(sensor.width) + "\n% end\n");
  std::int64_t high = -1, low = -1;
  int y = -1;
  for (size_t i = 0; i < events.size(); ++i) {
    const Event& e = events[i];
    if ((e.t >> 12) != high) {
      high = e.t >> 12;
      put_le16(b, static_cast<std::uint16_t>((0x8u << 12) | (high & 0xFFF)));
      low = -1;
    }
    if ((e.t & 0xFFF) != low) {
      low = e.t & 0xFFF;
      put_le16(b, static_cast<std::uint16_t>((0x6u << 12) | low));
    }
    if (e.y != y) {
      y = e.y;
      put_le16(b, static_cast<std::uint16_t>(y));
    }
    // Runs of events on one row, time and polarity at consecutive x go out as a vector.
    size_t run = 1;
    while (i + run < events.size() && run < 12 && events[i + run].t == e.t && events[i + run].y == e.y &&
           events[i + run].p == e.p && events[i + run].x == e.x + run) {
      ++run;
    }
    if (run >= 3) {
      put_le16(b, static_cast<std::uint16_t>((0x3u << 12) | (std::uint32_t{e.p} << 11) | e.x));
      put_le16(b, static_cast<std::uint16_t>((0x4u << 12) | ((1u << run) - 1)));
      i += run - 1;
    } else {
      put_le16(b, static_cast<std::uint16_t>((0x2u << 12) | (std::uint32_t{e.p} << 11) | e.x));
    }
  }
  return b;
}

Bytes evt3_words(const std::vector<Event>& events) {
  Bytes b = evt3(events, {1, 1});
  const std::string end = "% end\n";
  const auto at = std::search(b.begin(), b.end(), end.begin(), end.end());
  b.erase(b.begin(), at + static_cast<long>(end.size()));
  return b;
}

namespace {

// CDR, little endian: primitives aligned to their size from the end of the 4-byte header.
// ROS messages in either serialization (host/read/formats/ros_message_reader.h says how they differ).
class MessageWriter {
 public:
  explicit MessageWriter(bool ros1 = false) : ros1_(ros1) {
    if (!ros1_) b_ = {0x00, 0x01, 0x00, 0x00};
  }
  template <class T>
  void put(T v) {
    while (!ros1_ && (b_.size() - 4) % sizeof(T)) b_.push_back(0);
    for (size_t i = 0; i < sizeof(T); ++i) b_.push_back(static_cast<std::uint8_t>(static_cast<std::uint64_t>(v) >> (8 * i)));
  }
  void string(const std::string& s) {
    put<std::uint32_t>(static_cast<std::uint32_t>(s.size() + (ros1_ ? 0 : 1)));
    b_.insert(b_.end(), s.begin(), s.end());
    if (!ros1_) b_.push_back(0);
  }
  void header() {
    if (ros1_) put<std::uint32_t>(41);  // seq
    put<std::int32_t>(1702309120);
    put<std::uint32_t>(5000);
    string("camera");
  }
  Bytes bytes() const { return b_; }
  Bytes b_;

 private:
  bool ros1_;
};

}  // namespace

Bytes event_packet_cdr(const std::string& encoding, std::uint64_t time_base_ns, SensorSize sensor, const Bytes& events, bool ros1) {
  MessageWriter w(ros1);
  w.header();
  w.put<std::uint32_t>(static_cast<std::uint32_t>(sensor.height));
  w.put<std::uint32_t>(static_cast<std::uint32_t>(sensor.width));
  w.put<std::uint64_t>(7);  // seq
  w.put<std::uint64_t>(time_base_ns);
  w.string(encoding);
  w.put<std::uint8_t>(0);  // is_bigendian
  w.put<std::uint32_t>(static_cast<std::uint32_t>(events.size()));
  w.b_.insert(w.b_.end(), events.begin(), events.end());
  return w.bytes();
}

Bytes libcaer_events(const std::vector<Event>& events) {
  Bytes b;
  for (const Event& e : events) {
    put_le32(b, 1u | (std::uint32_t{e.p} << 1) | (std::uint32_t{e.y} << 2) | (std::uint32_t{e.x} << 17));
    put_le32(b, static_cast<std::uint32_t>(e.t));
  }
  return b;
}

Bytes mono_events(const std::vector<Event>& events, std::uint64_t time_base_ns) {
  Bytes b;
  for (const Event& e : events) {
    const std::uint64_t dt = static_cast<std::uint64_t>(e.t) * 1000 - time_base_ns;
    const std::uint64_t word = (dt & 0xFFFFFFFFu) | (std::uint64_t{e.x} << 32) | (std::uint64_t{e.y} << 48) | (std::uint64_t{e.p} << 63);
    put_le32(b, static_cast<std::uint32_t>(word));
    put_le32(b, static_cast<std::uint32_t>(word >> 32));
  }
  return b;
}

Bytes dvs_event_array_cdr(const std::vector<Event>& events, SensorSize sensor, bool ros1) {
  MessageWriter w(ros1);
  w.header();
  w.put<std::uint32_t>(static_cast<std::uint32_t>(sensor.height));
  w.put<std::uint32_t>(static_cast<std::uint32_t>(sensor.width));
  w.put<std::uint32_t>(static_cast<std::uint32_t>(events.size()));
  for (const Event& e : events) {
    w.put<std::uint16_t>(e.x);
    w.put<std::uint16_t>(e.y);
    w.put<std::int32_t>(static_cast<std::int32_t>(e.t / 1000000));
    w.put<std::uint32_t>(static_cast<std::uint32_t>(e.t % 1000000 * 1000));
    w.put<std::uint8_t>(e.p);
  }
  return w.bytes();
}

void write_db3(const std::string& db3, const std::vector<BagTopic>& topics) {
  sqlite3* db = nullptr;
  if (sqlite3_open(db3.c_str(), &db) != SQLITE_OK) throw std::runtime_error("sqlite3_open " + db3);
  const char* schema =
      "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, serialization_format TEXT NOT NULL,"
      " offered_qos_profiles TEXT NOT NULL);"
      "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, timestamp INTEGER NOT NULL, data BLOB NOT NULL);";
  if (sqlite3_exec(db, schema, nullptr, nullptr, nullptr) != SQLITE_OK) throw std::runtime_error(sqlite3_errmsg(db));
  std::int64_t stamp = 1702309120000000000;
  for (size_t t = 0; t < topics.size(); ++t) {
    sqlite3_stmt* s = nullptr;
    sqlite3_prepare_v2(db, "INSERT INTO topics VALUES (?, ?, ?, 'cdr', '')", -1, &s, nullptr);
    sqlite3_bind_int64(s, 1, static_cast<std::int64_t>(t + 1));
    sqlite3_bind_text(s, 2, topics[t].name.c_str(), -1, SQLITE_TRANSIENT);
    sqlite3_bind_text(s, 3, topics[t].type.c_str(), -1, SQLITE_TRANSIENT);
    sqlite3_step(s);
    sqlite3_finalize(s);
    for (const Bytes& m : topics[t].messages) {
      sqlite3_prepare_v2(db, "INSERT INTO messages (topic_id, timestamp, data) VALUES (?, ?, ?)", -1, &s, nullptr);
      sqlite3_bind_int64(s, 1, static_cast<std::int64_t>(t + 1));
      sqlite3_bind_int64(s, 2, stamp += 1000000);
      sqlite3_bind_blob(s, 3, m.data(), static_cast<int>(m.size()), SQLITE_TRANSIENT);
      if (sqlite3_step(s) != SQLITE_DONE) throw std::runtime_error(sqlite3_errmsg(db));
      sqlite3_finalize(s);
    }
  }
  sqlite3_close(db);
}

std::string write_ros2_bag(const std::string& dir, const std::vector<BagTopic>& topics, const std::string& storage) {
  std::filesystem::create_directories(dir);
  const std::string name = std::filesystem::path(dir).filename().string();
  const std::string file = name + (storage == "mcap" ? "_0.mcap" : "_0.db3");
  if (storage == "mcap") {
    const Bytes b = mcap_file(topics);
    std::ofstream(dir + "/" + file, std::ios::binary).write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
  } else {
    write_db3(dir + "/" + file, topics);
  }
  std::ofstream(dir + "/metadata.yaml") << "rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: " << storage
                                        << "\n  compression_format: \"\"\n  compression_mode: \"\"\n  relative_file_paths:\n    - " << file << "\n";
  return dir;
}

Bytes mcap_file(const std::vector<BagTopic>& topics, const std::string& compression, size_t messages_per_chunk, const std::string& encoding,
                bool summary) {
  const auto string = [](Bytes& b, const std::string& s) {
    put_le32(b, static_cast<std::uint32_t>(s.size()));
    b.insert(b.end(), s.begin(), s.end());
  };
  const auto record = [](Bytes& b, std::uint8_t op, const Bytes& body) {
    b.push_back(op);
    put_int(b, body.size(), 8);
    b.insert(b.end(), body.begin(), body.end());
  };
  Bytes b(read::kMcapMagic.begin(), read::kMcapMagic.end());
  Bytes header;
  string(header, "ros2"), string(header, "evms test");
  record(b, 0x01, header);
  // Topic t's schema (ID t + 1) and channel (ID t).
  const auto definitions = [&](Bytes& out, size_t t) {
    Bytes schema, channel;
    put_int(schema, t + 1, 2), string(schema, topics[t].type), string(schema, encoding == "ros1" ? "ros1msg" : "ros2msg"), string(schema, "# test");
    record(out, 0x03, schema);
    put_int(channel, t, 2), put_int(channel, t + 1, 2), string(channel, topics[t].name), string(channel, encoding), put_le32(channel, 0);
    record(out, 0x04, channel);
  };
  std::vector<bool> announced(topics.size(), false);
  size_t most = 0;
  for (const BagTopic& t : topics) most = std::max(most, t.messages.size());
  const bool chunked = messages_per_chunk > 0;
  Bytes records;  // of the open chunk, or of the data section without chunks
  size_t in_chunk = 0;
  std::uint64_t log_ns = 1702309120000000000ull;
  const auto close_chunk = [&] {
    if (!chunked || records.empty()) return;
    Bytes data = records;
    if (compression == "lz4") {
      data.resize(LZ4F_compressFrameBound(records.size(), nullptr));
      data.resize(LZ4F_compressFrame(data.data(), data.size(), records.data(), records.size(), nullptr));
    } else if (compression == "zstd") {
      data.resize(ZSTD_compressBound(records.size()));
      data.resize(ZSTD_compress(data.data(), data.size(), records.data(), records.size(), 3));
    }
    Bytes chunk;
    put_int(chunk, 0, 8), put_int(chunk, 0, 8), put_int(chunk, records.size(), 8);
    put_le32(chunk, static_cast<std::uint32_t>(crc32(0, records.data(), static_cast<uInt>(records.size()))));
    string(chunk, compression);
    put_int(chunk, data.size(), 8);
    chunk.insert(chunk.end(), data.begin(), data.end());
    record(b, 0x06, chunk);
    records.clear();
    in_chunk = 0;
  };
  std::uint32_t sequence = 0;
  for (size_t m = 0; m < most; ++m) {
    for (size_t t = 0; t < topics.size(); ++t) {
      if (m >= topics[t].messages.size()) continue;
      Bytes& out = chunked ? records : b;
      if (!announced[t]) {
        definitions(out, t);
        announced[t] = true;
      }
      Bytes message;
      put_int(message, t, 2), put_le32(message, sequence++), put_int(message, log_ns, 8), put_int(message, log_ns, 8);
      log_ns += 1000000;
      message.insert(message.end(), topics[t].messages[m].begin(), topics[t].messages[m].end());
      record(out, 0x05, message);
      if (chunked && ++in_chunk == messages_per_chunk) close_chunk();
    }
  }
  close_chunk();
  Bytes data_end;
  put_le32(data_end, static_cast<std::uint32_t>(crc32(0, b.data(), static_cast<uInt>(b.size()))));
  record(b, 0x0F, data_end);
  const size_t summary_at = b.size();
  size_t channels = 0, messages = 0;
  Bytes counts;
  for (size_t t = 0; summary && t < topics.size(); ++t) {
    if (!announced[t]) continue;
    definitions(b, t);
    ++channels, messages += topics[t].messages.size();
    put_int(counts, t, 2), put_int(counts, topics[t].messages.size(), 8);
  }
  if (summary) {
    Bytes statistics;
    put_int(statistics, messages, 8), put_int(statistics, channels, 2), put_le32(statistics, static_cast<std::uint32_t>(channels));
    put_le32(statistics, 0), put_le32(statistics, 0), put_le32(statistics, 0), put_int(statistics, 0, 8), put_int(statistics, 0, 8);
    put_le32(statistics, static_cast<std::uint32_t>(counts.size()));
    statistics.insert(statistics.end(), counts.begin(), counts.end());
    record(b, 0x0B, statistics);
  }
  b.push_back(0x02);
  put_int(b, 20, 8), put_int(b, summary ? summary_at : 0, 8), put_int(b, 0, 8);
  put_le32(b, summary ? static_cast<std::uint32_t>(crc32(0, b.data() + summary_at, static_cast<uInt>(b.size() - summary_at))) : 0);
  b.insert(b.end(), read::kMcapMagic.begin(), read::kMcapMagic.end());
  return b;
}

namespace {

// A ROS 1 record: its header's fields ("name=value", each after its uint32 length) and its data.
void put_record(Bytes& b, const std::vector<std::pair<std::string, Bytes>>& fields, const Bytes& data) {
  Bytes header;
  for (const auto& [name, value] : fields) {
    put_le32(header, static_cast<std::uint32_t>(name.size() + 1 + value.size()));
    header.insert(header.end(), name.begin(), name.end());
    header.push_back('=');
    header.insert(header.end(), value.begin(), value.end());
  }
  put_le32(b, static_cast<std::uint32_t>(header.size()));
  b.insert(b.end(), header.begin(), header.end());
  put_le32(b, static_cast<std::uint32_t>(data.size()));
  b.insert(b.end(), data.begin(), data.end());
}

Bytes text_bytes(const std::string& s) { return Bytes(s.begin(), s.end()); }
Bytes int_bytes(std::uint64_t v, int n) {
  Bytes b;
  put_int(b, v, n);
  return b;
}

}  // namespace

Bytes ros1_bag(const std::vector<BagTopic>& topics, const std::string& compression, size_t messages_per_chunk) {
  Bytes b = text_bytes("#ROSBAG V2.0\n");
  Bytes padding(4000, ' ');
  put_record(b, {{"op", {0x03}}, {"index_pos", int_bytes(0, 8)}, {"conn_count", int_bytes(topics.size(), 4)}, {"chunk_count", int_bytes(1, 4)}},
             padding);
  const auto connection = [&](Bytes& out, size_t conn) {
    Bytes details;
    for (const auto& [name, value] : std::vector<std::pair<std::string, std::string>>{
             {"topic", topics[conn].name}, {"type", topics[conn].type}, {"md5sum", "*"}, {"message_definition", "# test"}}) {
      put_le32(details, static_cast<std::uint32_t>(name.size() + 1 + value.size()));
      details.insert(details.end(), name.begin(), name.end());
      details.push_back('=');
      details.insert(details.end(), value.begin(), value.end());
    }
    put_record(out, {{"op", {0x07}}, {"conn", int_bytes(conn, 4)}, {"topic", text_bytes(topics[conn].name)}}, details);
  };
  // Messages of every topic in turn, in chunks; each connection before its first message.
  std::vector<bool> announced(topics.size(), false);
  size_t most = 0;
  for (const BagTopic& t : topics) most = std::max(most, t.messages.size());
  std::uint64_t stamp = 1702309120ull;
  Bytes records;
  size_t in_chunk = 0;
  const auto close_chunk = [&] {
    if (records.empty()) return;
    Bytes data = records;
    if (compression == "lz4") {
      data.resize(LZ4F_compressFrameBound(records.size(), nullptr));
      data.resize(LZ4F_compressFrame(data.data(), data.size(), records.data(), records.size(), nullptr));
    } else if (compression == "bz2") {
      unsigned size = static_cast<unsigned>(records.size() + records.size() / 100 + 600);  // bzip2's bound
      data.resize(size);
      if (BZ2_bzBuffToBuffCompress(reinterpret_cast<char*>(data.data()), &size, reinterpret_cast<char*>(records.data()),
                                   static_cast<unsigned>(records.size()), 9, 0, 0) != BZ_OK) {
        throw std::runtime_error("bzip2 failed");
      }
      data.resize(size);
    }
    put_record(b, {{"op", {0x05}}, {"compression", text_bytes(compression)}, {"size", int_bytes(records.size(), 4)}}, data);
    put_record(b, {{"op", {0x04}}, {"ver", int_bytes(1, 4)}, {"conn", int_bytes(0, 4)}, {"count", int_bytes(0, 4)}}, {});
    records.clear();
    in_chunk = 0;
  };
  for (size_t m = 0; m < most; ++m) {
    for (size_t t = 0; t < topics.size(); ++t) {
      if (m >= topics[t].messages.size()) continue;
      if (!announced[t]) connection(records, t), announced[t] = true;
      put_record(records, {{"op", {0x02}}, {"conn", int_bytes(t, 4)}, {"time", int_bytes(stamp++ | (std::uint64_t{5000} << 32), 8)}},
                 topics[t].messages[m]);
      if (++in_chunk == messages_per_chunk) close_chunk();
    }
  }
  close_chunk();
  // The index at the end: every connection again, and a chunk info.
  for (size_t t = 0; t < topics.size(); ++t) connection(b, t);
  put_record(b, {{"op", {0x06}}, {"ver", int_bytes(1, 4)}, {"chunk_pos", int_bytes(4117, 8)}, {"start_time", int_bytes(0, 8)},
                 {"end_time", int_bytes(0, 8)}, {"count", int_bytes(0, 4)}},
             {});
  return b;
}

Bytes dat(const std::vector<Event>& events) {
  Bytes b;
  put_text(b, "% Data file containing Event2D events.\n% Version 2\n");
  b.push_back(0);
  b.push_back(8);
  for (const Event& e : events) {
    put_le32(b, static_cast<std::uint32_t>(e.t));
    put_le32(b, std::uint32_t{e.x} | (std::uint32_t{e.y} << 14) | (std::uint32_t{e.p} << 28));
  }
  return b;
}

TempDir::TempDir() {
  char tmpl[] = "/tmp/evms-test-XXXXXX";
  if (!mkdtemp(tmpl)) throw std::runtime_error("mkdtemp failed");
  dir_ = tmpl;
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(dir_, ec);
}

std::string TempDir::write(const std::string& name, const std::string& text) const {
  std::ofstream(path(name), std::ios::binary) << text;
  return path(name);
}

std::string TempDir::write(const std::string& name, const Bytes& bytes) const {
  std::ofstream(path(name), std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  return path(name);
}

void dvs128_event(Bytes& b, int x, int y, int p, int ts) {
  const int addr = ((127 - y) << 8) | ((127 - x) << 1) | (p ? 0 : 1);
  b.insert(b.end(), {static_cast<std::uint8_t>(addr), static_cast<std::uint8_t>(addr >> 8), static_cast<std::uint8_t>(ts),
                     static_cast<std::uint8_t>(ts >> 8)});
}
void dvs128_flag(Bytes& b, std::uint8_t byte3) { b.insert(b.end(), {0, 0, 0, byte3}); }
void davis_word(Bytes& b, unsigned w) { b.insert(b.end(), {static_cast<std::uint8_t>(w), static_cast<std::uint8_t>(w >> 8)}); }

Bytes dvs128_usb_words(const std::vector<Event>& events) {
  Bytes b;
  TimeUs base = 0;
  for (const Event& e : events) {
    for (; e.t - base >= 0x4000; base += 0x4000) dvs128_flag(b, 0x80);
    dvs128_event(b, e.x, e.y, e.p, static_cast<int>(e.t - base));
  }
  return b;
}

Bytes davis_usb_words(const std::vector<Event>& events) {
  Bytes b;
  const auto word = [&b](unsigned w) { davis_word(b, w); };
  TimeUs base = 0;
  for (const Event& e : events) {
    while (e.t - base >= 0x8000) {
      const TimeUs wraps = std::min<TimeUs>((e.t - base) / 0x8000, 0xFFF);
      word(0x7000u | static_cast<unsigned>(wraps));
      base += wraps * 0x8000;
    }
    word(0x8000u | static_cast<unsigned>(e.t - base));
    word(0x1000u | e.y);
    word((e.p ? 0x3000u : 0x2000u) | e.x);
  }
  return b;
}

std::vector<Event> sample_events(size_t n, SensorSize sensor, std::uint64_t seed) {
  gen::Random rng(seed);
  std::vector<Event> out;
  TimeUs t = 1000;
  for (size_t i = 0; i < n; ++i) {
    t += static_cast<TimeUs>(rng.below(40));
    out.push_back({t, static_cast<std::uint16_t>(rng.below(static_cast<std::uint64_t>(sensor.width))),
                   static_cast<std::uint16_t>(rng.below(static_cast<std::uint64_t>(sensor.height))),
                   static_cast<std::uint8_t>(rng.below(2))});
  }
  return out;
}

}  // namespace evms::test
