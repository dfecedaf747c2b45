// A serial device's line rate in bits a second, any rate the driver takes (Linux's termios2 with
// BOTHER): the iCEBreaker's 6 Mbaud has no Bnnn constant in <termios.h>.
#pragma once

namespace evms::link {

// Sets the open terminal `fd` to `baud` both ways; false (errno set) when the driver refuses.
bool set_line_rate(int fd, int baud);
// The rate `fd` sends at; -1 (errno set) when it cannot be read.
int line_rate(int fd);

}  // namespace evms::link
