// One storage file of a ROS 2 bag, as rosbag2 writes it: sqlite3 (`.db3`, ros2_bag.cpp) or
// MCAP (`.mcap`, mcap_storage.cpp, the default storage since ROS 2 Iron). The bag reader
// (ros2_bag.cpp) lists its topics and takes one topic's messages through this.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace evms::read {

class BagStorage {
 public:
  struct Topic {
    std::int64_t id;
    std::string name, type, serialization;
  };
  virtual ~BagStorage() = default;
  virtual std::vector<Topic> topics() = 0;
  // Messages of the topic `id`.
  virtual std::int64_t count(std::int64_t id) = 0;
  // The messages next() gives: those of the topic `id`, from the first.
  virtual void select(std::int64_t id) = 0;
  // The next message's number (for messages: the sqlite row id, or its count from 1 over every
  // message of an MCAP file) and bytes, valid until the next call; false at the end.
  virtual bool next(std::int64_t& id, std::span<const unsigned char>& data) = 0;
  virtual const std::string& path() const = 0;
  // For the format line: "ROS 2 bag" (sqlite3) or "MCAP".
  virtual const char* container() const = 0;
};

// The first (and last) bytes of an MCAP file.
inline constexpr std::string_view kMcapMagic{"\x89MCAP0\r\n", 8};

// An MCAP file; fails with one line when it is not one.
std::unique_ptr<BagStorage> open_mcap_storage(const std::string& path);

}  // namespace evms::read
