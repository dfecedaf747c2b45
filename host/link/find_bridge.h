// The serial device of a board's UART when the command line names none. Both boards put their
// UART on the second interface (channel B) of an FT2232H, USB 0403:6010 (channel A is the
// iCEBreaker's flash and the Arty's JTAG), which Linux's ftdi_sio makes a /dev/ttyUSB* of its own.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace evms::link {

// The /dev paths of the FT2232H channel-B UARTs connected, in name order, found in sysfs under
// `sysfs_root` (/sys/class/tty/ttyUSB*, each one's device an interface numbered 01 of a USB
// device 0403:6010). Entries that cannot be read are passed over.
std::vector<std::string> ft2232h_uarts(const std::filesystem::path& sysfs_root = "/sys");

// The one FT2232H UART connected; std::invalid_argument saying what was found when there is none
// or more than one, for the user to name the device.
std::string the_board_uart(const std::filesystem::path& sysfs_root = "/sys");

}  // namespace evms::link
