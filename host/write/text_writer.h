// Buffered output with exact integer and fixed-decimal formatting (std::to_chars), for the CSV,
// events.txt, npy and EVT 3.0 writers. A failed write throws with the file's name.
#pragma once

#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>

namespace evms::write {

class TextWriter {
 public:
  // "-" is standard output.
  explicit TextWriter(const std::string& path);
  ~TextWriter();
  TextWriter(const TextWriter&) = delete;
  TextWriter& operator=(const TextWriter&) = delete;

  TextWriter& text(std::string_view s) {
    if (used_ + s.size() > kFlushAt) {
      flush();
      if (s.size() > kFlushAt) return write_through(s);
    }
    std::memcpy(buffer_.get() + used_, s.data(), s.size());
    used_ += s.size();
    return *this;
  }
  TextWriter& ch(char c) {
    if (used_ + 1 > kFlushAt) flush();
    buffer_[used_++] = c;
    return *this;
  }
  TextWriter& integer(std::int64_t v) {
    char b[24];
    auto r = std::to_chars(b, b + sizeof b, v);
    return text({b, static_cast<size_t>(r.ptr - b)});
  }
  TextWriter& fixed(double v, int decimals) {
    char b[64];
    auto r = std::to_chars(b, b + sizeof b, v, std::chars_format::fixed, decimals);
    return text({b, static_cast<size_t>(r.ptr - b)});
  }
  TextWriter& bytes(const void* data, size_t n) { return text({static_cast<const char*>(data), n}); }
  // Room for `n` more bytes at the end of the buffer, to format into in place; commit() says how
  // many were used. For the writers' hot loops: one bounds check a row, not one a field.
  char* reserve(size_t n) {
    if (used_ + n > kFlushAt) flush();
    return buffer_.get() + used_;
  }
  void commit(char* end) { used_ = static_cast<size_t>(end - buffer_.get()); }
  // Closes the file; throws if anything failed.
  void close();

 private:
  static constexpr size_t kFlushAt = 1 << 16;
  void flush();
  TextWriter& write_through(std::string_view s);  // a text longer than the buffer
  std::string path_;
  std::FILE* file_ = nullptr;
  std::unique_ptr<char[]> buffer_ = std::make_unique_for_overwrite<char[]>(kFlushAt);
  size_t used_ = 0;
};

}  // namespace evms::write
