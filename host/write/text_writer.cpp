#include "host/write/text_writer.h"

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace evms::write {

TextWriter::TextWriter(const std::string& path) : path_(path == "-" ? "standard output" : path) {
  file_ = path == "-" ? stdout : std::fopen(path.c_str(), "wb");
  if (!file_) throw std::runtime_error(path + ": cannot write: " + std::strerror(errno));
  buffer_.reserve(kFlushAt + 4096);
}

TextWriter::~TextWriter() {
  if (file_) {
    std::fwrite(buffer_.data(), 1, buffer_.size(), file_);
    if (file_ != stdout) std::fclose(file_);
  }
}

void TextWriter::flush() {
  if (!buffer_.empty() && std::fwrite(buffer_.data(), 1, buffer_.size(), file_) != buffer_.size()) {
    throw std::runtime_error(path_ + ": write failed: " + std::strerror(errno));
  }
  buffer_.clear();
}

void TextWriter::close() {
  if (!file_) return;
  flush();
  const bool ok = file_ == stdout ? std::fflush(file_) == 0 : std::fclose(file_) == 0;
  file_ = nullptr;
  if (!ok) throw std::runtime_error(path_ + ": write failed: " + std::strerror(errno));
}

}  // namespace evms::write
