#include "host/read/byte_reader.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <sys/stat.h>
#include <utility>

namespace evms::read {
namespace {
constexpr size_t kChunk = 1 << 20;
constexpr size_t kMaxLine = 1 << 20;
}  // namespace

std::string describe(const std::string& path, InputPosition pos) {
  switch (pos.kind) {
    case InputPosition::Kind::kByte: return path + ": byte " + std::to_string(pos.value);
    case InputPosition::Kind::kLine: return path + ": line " + std::to_string(pos.value);
    case InputPosition::Kind::kNone: break;
  }
  return path;
}

void fail(const std::string& path, InputPosition pos, const std::string& what) {
  throw InputError(describe(path, pos) + ": " + what);
}

ByteReader::ByteReader(const std::string& path) : path_(path) {
  struct stat st {};
  if (stat(path.c_str(), &st) != 0) fail(path, {}, std::string("cannot open: ") + std::strerror(errno));
  if (S_ISDIR(st.st_mode)) fail(path, {}, "is a directory, not an event file");
  file_ = std::fopen(path.c_str(), "rb");
  if (!file_) fail(path, {}, std::string("cannot open: ") + std::strerror(errno));
  size_ = static_cast<std::uint64_t>(st.st_size);
  buffer_.resize(kChunk);
}

ByteReader::~ByteReader() {
  if (file_) std::fclose(file_);
}

ByteReader::ByteReader(ByteReader&& o) noexcept
    : path_(std::move(o.path_)),
      file_(std::exchange(o.file_, nullptr)),
      size_(o.size_),
      buffer_(std::move(o.buffer_)),
      pos_(o.pos_),
      end_(o.end_),
      offset_before_buffer_(o.offset_before_buffer_),
      line_(o.line_) {}

bool ByteReader::refill(size_t want) {
  if (end_ - pos_ >= want) return true;
  if (pos_ > 0) {
    std::memmove(buffer_.data(), buffer_.data() + pos_, end_ - pos_);
    offset_before_buffer_ += pos_;
    end_ -= pos_;
    pos_ = 0;
  }
  if (buffer_.size() < want) buffer_.resize(want);
  while (end_ < want) {
    size_t got = std::fread(buffer_.data() + end_, 1, buffer_.size() - end_, file_);
    if (got == 0) {
      if (std::ferror(file_)) fail(path_, byte_position(), std::string("read error: ") + std::strerror(errno));
      return false;
    }
    end_ += got;
  }
  return true;
}

size_t ByteReader::read(void* dst, size_t n) {
  auto* out = static_cast<char*>(dst);
  size_t done = 0;
  while (done < n) {
    if (pos_ == end_ && !refill(1)) break;
    size_t take = std::min(n - done, end_ - pos_);
    std::memcpy(out + done, buffer_.data() + pos_, take);
    pos_ += take;
    done += take;
  }
  return done;
}

std::string_view ByteReader::peek(size_t n) {
  refill(n);
  return {buffer_.data() + pos_, std::min(n, end_ - pos_)};
}

void ByteReader::skip(std::uint64_t n) {
  while (n > 0) {
    if (pos_ == end_ && !refill(1)) return;
    size_t take = static_cast<size_t>(std::min<std::uint64_t>(n, end_ - pos_));
    pos_ += take;
    n -= take;
  }
}

bool ByteReader::at_end() { return pos_ == end_ && !refill(1); }

bool ByteReader::next_line(std::string_view& line) {
  size_t scanned = 0;
  for (;;) {
    const char* begin = buffer_.data() + pos_;
    const void* nl = std::memchr(begin + scanned, '\n', end_ - pos_ - scanned);
    if (nl) {
      size_t len = static_cast<size_t>(static_cast<const char*>(nl) - begin);
      pos_ += len + 1;
      ++line_;
      if (len > 0 && begin[len - 1] == '\r') --len;
      line = {begin, len};
      return true;
    }
    scanned = end_ - pos_;
    if (scanned > kMaxLine) fail(path_, InputPosition::line(line_ + 1), "line longer than 1 MiB");
    if (!refill(scanned + 1)) {
      if (scanned == 0) return false;
      // The last line has no newline.
      begin = buffer_.data() + pos_;
      size_t len = end_ - pos_;
      pos_ = end_;
      ++line_;
      if (len > 0 && begin[len - 1] == '\r') --len;
      line = {begin, len};
      return true;
    }
  }
}

}  // namespace evms::read
