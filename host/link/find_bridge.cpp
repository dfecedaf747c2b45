#include "host/link/find_bridge.h"

#include <algorithm>
#include <fstream>
#include <stdexcept>
#include <system_error>

namespace evms::link {
namespace {

std::string first_line(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  return line;
}

}  // namespace

std::vector<std::string> ft2232h_uarts(const std::filesystem::path& sysfs_root) {
  namespace fs = std::filesystem;
  std::vector<std::string> found;
  std::error_code ec;
  for (const fs::directory_entry& tty : fs::directory_iterator(sysfs_root / "class" / "tty", ec)) {
    const std::string name = tty.path().filename().string();
    if (name.rfind("ttyUSB", 0) != 0) continue;
    // device: the usb-serial port, below the USB interface, below the USB device.
    const fs::path port = fs::canonical(tty.path() / "device", ec);
    if (ec) continue;
    const fs::path interface = port.parent_path(), usb_device = interface.parent_path();
    if (first_line(usb_device / "idVendor") == "0403" && first_line(usb_device / "idProduct") == "6010" &&
        first_line(interface / "bInterfaceNumber") == "01") {
      found.push_back("/dev/" + name);
    }
  }
  std::sort(found.begin(), found.end());
  return found;
}

std::string the_board_uart(const std::filesystem::path& sysfs_root) {
  const std::vector<std::string> found = ft2232h_uarts(sysfs_root);
  if (found.size() == 1) return found.front();
  if (found.empty()) {
    throw std::invalid_argument("the board backend needs --device: no board's UART is connected (an FT2232H's channel B, USB 0403:6010, in " +
                                (sysfs_root / "class" / "tty").string() + "); a virtual board's is the path evms vboard prints");
  }
  std::string list;
  for (const std::string& d : found) list += (list.empty() ? "" : ", ") + d;
  throw std::invalid_argument("several boards' UARTs are connected (" + list + "): name the one to use with --device");
}

}  // namespace evms::link
