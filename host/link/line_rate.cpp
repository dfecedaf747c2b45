// Kept apart from serial_port.cpp: <asm/termbits.h> and glibc's <termios.h> define the same names.
#include "host/link/line_rate.h"

#include <asm/termbits.h>
#include <linux/serial.h>
#include <sys/ioctl.h>

namespace evms::link {

bool set_line_rate(int fd, int baud) {
  termios2 t{};
  if (ioctl(fd, TCGETS2, &t) != 0) return false;
  t.c_cflag &= ~static_cast<tcflag_t>(CBAUD | (CBAUD << IBSHIFT));
  t.c_cflag |= BOTHER | (BOTHER << IBSHIFT);
  t.c_ispeed = t.c_ospeed = static_cast<speed_t>(baud);
  return ioctl(fd, TCSETS2, &t) == 0;
}

bool set_low_latency(int fd) {
  serial_struct s{};
  if (ioctl(fd, TIOCGSERIAL, &s) != 0) return false;
  s.flags |= ASYNC_LOW_LATENCY;
  return ioctl(fd, TIOCSSERIAL, &s) == 0;
}

int line_rate(int fd) {
  termios2 t{};
  if (ioctl(fd, TCGETS2, &t) != 0) return -1;
  return static_cast<int>(t.c_ospeed);
}

}  // namespace evms::link
