// A serial device in raw mode (termios): the board's UART through a USB bridge, or the
// pseudo-terminal of `evms vboard`.
#pragma once

#include <cstdint>
#include <span>
#include <string>

namespace evms::link {

class SerialPort {
 public:
  // Opens `path` raw, 8N1, no flow control, at `baud` (any rate the driver takes: the FT2232H's
  // 12 MHz / n, the iCEBreaker's 6 Mbaud among them). Throws std::runtime_error naming the device
  // on failure.
  SerialPort(const std::string& path, int baud);
  ~SerialPort();
  SerialPort(const SerialPort&) = delete;
  SerialPort& operator=(const SerialPort&) = delete;

  void write_all(std::span<const std::uint8_t> bytes);
  // Waits up to timeout_ms for bytes; returns how many were read (0 on timeout).
  size_t read_some(std::span<std::uint8_t> out, int timeout_ms);
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int fd_ = -1;
};

}  // namespace evms::link
