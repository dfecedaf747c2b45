#include "host/link/serial_port.h"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "host/link/line_rate.h"

namespace evms::link {

SerialPort::SerialPort(const std::string& path, int baud) : path_(path) {
  if (baud < 50 || baud > 12000000) throw std::invalid_argument("unsupported baud rate " + std::to_string(baud));
  fd_ = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (fd_ < 0) {
    const std::string why = std::strerror(errno);
    const std::string hint = errno == EACCES ? " (add yourself to the 'dialout' group)" : "";
    throw std::runtime_error(path + ": cannot open the serial device: " + why + hint);
  }
  termios t{};
  if (tcgetattr(fd_, &t) != 0) {
    ::close(fd_);
    throw std::runtime_error(path + ": not a serial device (" + std::strerror(errno) + ")");
  }
  cfmakeraw(&t);
  t.c_cflag |= CLOCAL | CREAD;
  t.c_cflag &= ~static_cast<tcflag_t>(CSTOPB | CRTSCTS | PARENB);
  t.c_cc[VMIN] = 0;
  t.c_cc[VTIME] = 0;
  if (tcsetattr(fd_, TCSANOW, &t) != 0) {
    ::close(fd_);
    throw std::runtime_error(path + ": cannot configure the serial device (" + std::strerror(errno) + ")");
  }
  if (!set_line_rate(fd_, baud)) {
    const std::string why = std::strerror(errno);
    ::close(fd_);
    throw std::runtime_error(path + ": the device does not take " + std::to_string(baud) + " baud (" + why + ")");
  }
  // A board's labels and tracks come in small frames: without the mode, an FTDI bridge would hold
  // each quiet stretch's last frames up to 16 ms. A driver without it refuses, and nothing changes.
  set_low_latency(fd_);
  tcflush(fd_, TCIOFLUSH);
}

SerialPort::~SerialPort() {
  if (fd_ >= 0) ::close(fd_);
}

void SerialPort::write_all(std::span<const std::uint8_t> bytes) {
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd_, bytes.data() + done, bytes.size() - done);
    if (n < 0) {
      if (errno == EINTR || errno == EAGAIN) {
        pollfd p{fd_, POLLOUT, 0};
        ::poll(&p, 1, 100);
        continue;
      }
      throw std::runtime_error(path_ + ": write failed (" + std::strerror(errno) + ")");
    }
    done += static_cast<size_t>(n);
  }
}

size_t SerialPort::read_some(std::span<std::uint8_t> out, int timeout_ms) {
  pollfd p{fd_, POLLIN, 0};
  const int ready = ::poll(&p, 1, timeout_ms);
  if (ready < 0 && errno != EINTR) throw std::runtime_error(path_ + ": poll failed (" + std::strerror(errno) + ")");
  if (ready <= 0) return 0;
  if (p.revents & (POLLHUP | POLLERR) && !(p.revents & POLLIN)) throw std::runtime_error(path_ + ": the device hung up");
  const ssize_t n = ::read(fd_, out.data(), out.size());
  if (n < 0) {
    if (errno == EINTR || errno == EAGAIN) return 0;
    throw std::runtime_error(path_ + ": read failed (" + std::strerror(errno) + ")");
  }
  return static_cast<size_t>(n);
}

}  // namespace evms::link
