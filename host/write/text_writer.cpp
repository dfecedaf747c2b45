#include "host/write/text_writer.h"

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace evms::write {

TextWriter::TextWriter(const std::string& path) : path_(path == "-" ? "standard output" : path) {
  file_ = path == "-" ? stdout : std::fopen(path.c_str(), "wb");
  if (!file_) throw std::runtime_error(path + ": cannot write: " + std::strerror(errno));
}

TextWriter::~TextWriter() {
  if (file_) {
    std::fwrite(buffer_.get(), 1, used_, file_);
    if (file_ != stdout) std::fclose(file_);
  }
}

void TextWriter::flush() {
  if (used_ > 0 && std::fwrite(buffer_.get(), 1, used_, file_) != used_) {
    throw std::runtime_error(path_ + ": write failed: " + std::strerror(errno));
  }
  used_ = 0;
}

TextWriter& TextWriter::write_through(std::string_view s) {
  if (std::fwrite(s.data(), 1, s.size(), file_) != s.size()) throw std::runtime_error(path_ + ": write failed: " + std::strerror(errno));
  return *this;
}

void TextWriter::close() {
  if (!file_) return;
  flush();
  const bool ok = file_ == stdout ? std::fflush(file_) == 0 : std::fclose(file_) == 0;
  file_ = nullptr;
  if (!ok) throw std::runtime_error(path_ + ": write failed: " + std::strerror(errno));
}

}  // namespace evms::write
