// Buffered output with exact integer and fixed-decimal formatting (std::to_chars), for the CSV,
// events.txt, npy and EVT 3.0 writers. A failed write throws with the file's name.
#pragma once

#include <charconv>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

namespace evms::write {

class TextWriter {
 public:
  // "-" is standard output.
  explicit TextWriter(const std::string& path);
  ~TextWriter();
  TextWriter(const TextWriter&) = delete;
  TextWriter& operator=(const TextWriter&) = delete;

  TextWriter& text(std::string_view s) {
    if (buffer_.size() + s.size() > kFlushAt) flush();
    buffer_.insert(buffer_.end(), s.begin(), s.end());
    return *this;
  }
  TextWriter& ch(char c) {
    buffer_.push_back(c);
    if (buffer_.size() > kFlushAt) flush();
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
    if (buffer_.size() + n > kFlushAt) flush();
    const size_t used = buffer_.size();
    buffer_.resize(used + n);
    return buffer_.data() + used;
  }
  void commit(char* end) { buffer_.resize(static_cast<size_t>(end - buffer_.data())); }
  // Closes the file; throws if anything failed.
  void close();

 private:
  static constexpr size_t kFlushAt = 1 << 16;
  void flush();
  std::string path_;
  std::FILE* file_ = nullptr;
  std::vector<char> buffer_;
};

}  // namespace evms::write
