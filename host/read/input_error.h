// Bad input is reported as one line that names the file, the position and what is wrong:
//   recording.raw: byte 4096: unknown EVT 3.0 word type 0x9
//   events.txt: line 17: x=300 is outside the 240x180 sensor (set --width/--height)
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

namespace evms::read {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct InputPosition {
  // kMessage: a record of a container (a ROS 2 bag's message), and a byte offset inside it.
  enum class Kind { kByte, kLine, kMessage, kNone };
  Kind kind = Kind::kNone;
  std::uint64_t value = 0;
  std::uint64_t byte_in_message = 0;

  static InputPosition byte(std::uint64_t offset) { return {Kind::kByte, offset, 0}; }
  static InputPosition line(std::uint64_t number) { return {Kind::kLine, number, 0}; }
  static InputPosition message(std::uint64_t number, std::uint64_t offset) { return {Kind::kMessage, number, offset}; }
};

std::string describe(const std::string& path, InputPosition pos);

[[noreturn]] void fail(const std::string& path, InputPosition pos, const std::string& what);

// `text` safe to print on a terminal: control bytes, DEL and bytes that are not part of a
// well-formed UTF-8 sequence become \xNN, so that a file cannot put escape sequences on the
// screen through an error message that quotes it.
std::string printable(std::string_view text);

}  // namespace evms::read
