// Buffered, forward-only reading of a file with the offset and line number of what was last
// consumed, so that every decoder can say where bad input is. Memory stays constant.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include "host/read/input_error.h"

namespace evms::read {

class ByteReader {
 public:
  explicit ByteReader(const std::string& path);
  ~ByteReader();
  ByteReader(ByteReader&&) noexcept;
  ByteReader& operator=(ByteReader&&) = delete;
  ByteReader(const ByteReader&) = delete;

  const std::string& path() const { return path_; }
  std::uint64_t size() const { return size_; }
  std::uint64_t offset() const { return offset_before_buffer_ + pos_; }
  std::uint64_t line() const { return line_; }
  InputPosition byte_position() const { return InputPosition::byte(offset()); }

  // Copies up to n bytes; fewer only at the end of the file.
  size_t read(void* dst, size_t n);
  // Makes at least n bytes available without consuming them (fewer only at the end).
  std::string_view peek(size_t n);
  void skip(std::uint64_t n);  // to the end of the file at most
  bool at_end();

  // The next line without its "\n" or "\r\n"; false at the end of the file. The view stays
  // valid until the next call.
  bool next_line(std::string_view& line);

  [[noreturn]] void fail_here(const std::string& what) const { fail(path_, byte_position(), what); }

 private:
  bool refill(size_t want);

  std::string path_;
  std::FILE* file_ = nullptr;
  std::uint64_t size_ = 0;
  bool regular_ = false;  // a regular file, which seeks; not a pipe
  std::vector<char> buffer_;
  size_t pos_ = 0;    // next unread byte in buffer_
  size_t end_ = 0;    // bytes valid in buffer_
  std::uint64_t offset_before_buffer_ = 0;
  std::uint64_t line_ = 0;
};

}  // namespace evms::read
