// A serial device's line rate in bits a second, any rate the driver takes (Linux's termios2 with
// BOTHER): the iCEBreaker's 6 Mbaud has no Bnnn constant in <termios.h>. And its driver's
// low-latency mode.
#pragma once

namespace evms::link {

// Sets the open terminal `fd` to `baud` both ways; false (errno set) when the driver refuses.
bool set_line_rate(int fd, int baud);
// The rate `fd` sends at; -1 (errno set) when it cannot be read.
int line_rate(int fd);
// Asks the driver of `fd` to pass received bytes on at once (ASYNC_LOW_LATENCY): an FTDI bridge,
// the FT2232H of both boards, holds a part-filled USB packet until its latency timer runs out,
// 16 ms by default, and Linux's ftdi_sio sets that timer to 1 ms in this mode. False (errno set)
// when the driver has no such mode, as a pseudo-terminal (`evms vboard`'s) has not.
bool set_low_latency(int fd);

}  // namespace evms::link
