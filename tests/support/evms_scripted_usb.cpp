// The evms program with a scripted USB camera (scripted_usb_port.h) behind usb://: every
// usb:// source plays the script named by EVMS_USB_SCRIPT. Tests run it as they run evms, to
// see what `evms run usb://davis` does when the camera stalls, fails or is unplugged.
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "host/cli/commands.h"
#include "tests/support/scripted_usb_port.h"

int main(int argc, char** argv) {
  const char* path = std::getenv("EVMS_USB_SCRIPT");
  if (!path) {
    std::fprintf(stderr, "evms_scripted_usb: EVMS_USB_SCRIPT must name a script (tests/support/scripted_usb_port.h)\n");
    return 2;
  }
  try {
    const evms::test::UsbScript script = evms::test::UsbScript::from_file(path);
    evms::read::set_usb_port_factory(
        [script] { return std::make_unique<evms::test::ScriptedUsbPort>(script, std::make_shared<evms::test::UsbLog>()); });
  } catch (const std::exception& e) {
    std::fprintf(stderr, "evms_scripted_usb: %s\n", e.what());
    return 2;
  }
  return evms::cli::run_evms(argc, argv);
}
