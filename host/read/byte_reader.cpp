#include "host/read/byte_reader.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <sys/stat.h>
#include <utility>

namespace evms::read {
namespace {
constexpr size_t kChunk = 1 << 20;
constexpr size_t kMinChunk = 1 << 16;
constexpr size_t kMaxLine = 1 << 20;
}  // namespace

std::string describe(const std::string& path, InputPosition pos) {
  switch (pos.kind) {
    case InputPosition::Kind::kByte: return path + ": byte " + std::to_string(pos.value);
    case InputPosition::Kind::kLine: return path + ": line " + std::to_string(pos.value);
    case InputPosition::Kind::kMessage:
      return path + ": message " + std::to_string(pos.value) + ", byte " + std::to_string(pos.byte_in_message);
    case InputPosition::Kind::kNone: break;
  }
  return path;
}

void fail(const std::string& path, InputPosition pos, const std::string& what) {
  throw InputError(describe(path, pos) + ": " + what);
}

namespace {
// The length of the well-formed UTF-8 sequence that starts text[i] (RFC 3629: no overlong
// forms, no surrogates, nothing above U+10FFFF), or 0.
size_t utf8_sequence(std::string_view text, size_t i) {
  const auto byte = [&](size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  size_t n = 0;
  unsigned char lo = 0x80, hi = 0xBF;  // range of the second byte
  if (lead >= 0xC2 && lead <= 0xDF) n = 2;
  else if (lead >= 0xE0 && lead <= 0xEF) n = 3, lo = lead == 0xE0 ? 0xA0 : 0x80, hi = lead == 0xED ? 0x9F : 0xBF;
  else if (lead >= 0xF0 && lead <= 0xF4) n = 4, lo = lead == 0xF0 ? 0x90 : 0x80, hi = lead == 0xF4 ? 0x8F : 0xBF;
  else return 0;
  if (i + n > text.size() || byte(i + 1) < lo || byte(i + 1) > hi) return 0;
  for (size_t k = 2; k < n; ++k) {
    if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return 0;
  }
  return n;
}
}  // namespace

std::string printable(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7F) {
      out += static_cast<char>(c), ++i;
    } else if (const size_t n = c >= 0x80 ? utf8_sequence(text, i) : 0; n > 0) {
      out.append(text.substr(i, n)), i += n;
    } else {
      static constexpr char kHex[] = "0123456789abcdef";
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
      ++i;
    }
  }
  return out;
}

ByteReader::ByteReader(const std::string& path) : path_(path) {
  struct stat st {};
  if (stat(path.c_str(), &st) != 0) fail(path, {}, std::string("cannot open: ") + std::strerror(errno));
  if (S_ISDIR(st.st_mode)) fail(path, {}, "is a directory, not an event file");
  file_ = std::fopen(path.c_str(), "rb");
  if (!file_) fail(path, {}, std::string("cannot open: ") + std::strerror(errno));
  size_ = static_cast<std::uint64_t>(st.st_size);
  regular_ = S_ISREG(st.st_mode);
  // A small file gets a small buffer (it grows when a reader asks for more): opening many
  // small files, as the fuzz targets do, then costs no megabyte each.
  buffer_.resize(static_cast<size_t>(std::clamp<std::uint64_t>(size_ + 1, kMinChunk, kChunk)));
}

ByteReader::~ByteReader() {
  if (file_) std::fclose(file_);
}

ByteReader::ByteReader(ByteReader&& o) noexcept
    : path_(std::move(o.path_)),
      file_(std::exchange(o.file_, nullptr)),
      size_(o.size_),
      regular_(o.regular_),
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
  if (buffer_.size() < want) buffer_.resize(std::max(want, 2 * buffer_.size()));
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
  // Past what is buffered, a regular file seeks (to its end at most) instead of reading.
  if (regular_ && n > end_ - pos_) {
    const std::uint64_t at = std::min(offset(), size_);
    const std::uint64_t to = n >= size_ - at ? size_ : at + n;
    if (fseeko(file_, static_cast<off_t>(to), SEEK_SET) == 0) {
      offset_before_buffer_ = to;
      pos_ = end_ = 0;
      return;
    }
  }
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
