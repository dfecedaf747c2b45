// The seam between the USB cameras' reader (usb_camera.cpp) and libusb-1.0: the calls the
// reader makes, shaped as libusb's (device list, open, claim, control transfers, asynchronous
// bulk transfers completed from an event loop, clear halt). usb_libusb.cpp passes them to
// libusb; tests put a scripted port behind it (tests/support/scripted_usb_port.h) that stalls,
// fails a transfer or unplugs mid-stream, so that what the reader does then is tested without a
// camera.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace evms::read {

// libusb's error codes (enum libusb_error), which usb_libusb.cpp checks it passes unchanged.
inline constexpr int kUsbOk = 0;
inline constexpr int kUsbErrorIo = -1;
inline constexpr int kUsbErrorAccess = -3;
inline constexpr int kUsbErrorNoDevice = -4;
inline constexpr int kUsbErrorBusy = -6;
inline constexpr int kUsbErrorTimeout = -7;
inline constexpr int kUsbErrorPipe = -9;

// How a bulk transfer ended (enum libusb_transfer_status).
enum class UsbTransferStatus { kCompleted, kError, kTimedOut, kCancelled, kStall, kNoDevice, kOverflow };
const char* usb_transfer_status_name(UsbTransferStatus s);

// An asynchronous bulk IN transfer (struct libusb_transfer): the port fills `buffer`, sets
// `status` and `received`, and calls `on_complete` from handle_events().
struct UsbTransfer {
  unsigned char endpoint = 0;
  std::span<unsigned char> buffer;
  UsbTransferStatus status = UsbTransferStatus::kCompleted;
  size_t received = 0;
  std::function<void(UsbTransfer&)> on_complete;
  void* port_state = nullptr;  // the port's own handle for this transfer
};

// A device on the bus (libusb_device with its descriptor).
struct UsbDeviceId {
  std::uint16_t vendor = 0, product = 0;
  int bus = 0, address = 0;
};

class UsbPort {
 public:
  virtual ~UsbPort() = default;
  // libusb_get_device_list with each device's descriptor.
  virtual std::vector<UsbDeviceId> devices() = 0;
  // libusb_open, with the kernel driver detached on claim; then libusb_claim_interface.
  virtual int open(const UsbDeviceId& device) = 0;
  virtual int claim_interface(int interface_number) = 0;
  // libusb_release_interface and libusb_close; safe to call when nothing is open.
  virtual void close() = 0;
  // libusb_control_transfer: the bytes moved, or one of the kUsbError codes.
  virtual int control_transfer(std::uint8_t request_type, std::uint8_t request, std::uint16_t value, std::uint16_t index,
                               std::span<unsigned char> data, unsigned timeout_ms) = 0;
  // libusb_clear_halt on a stalled endpoint.
  virtual int clear_halt(unsigned char endpoint) = 0;
  // libusb_submit_transfer / libusb_cancel_transfer. A cancelled transfer still completes,
  // with kCancelled, from a later handle_events().
  virtual int submit(UsbTransfer& transfer) = 0;
  virtual int cancel(UsbTransfer& transfer) = 0;
  // libusb_handle_events_timeout_completed: waits up to `timeout_ms` and runs the completions.
  virtual int handle_events(int timeout_ms) = 0;
  // libusb_error_name and libusb_strerror of a kUsbError code.
  virtual std::string describe(int result) const = 0;
};

// The port every usb:// source opens: libusb's, unless a harness set another.
std::unique_ptr<UsbPort> open_usb_port();
std::unique_ptr<UsbPort> open_libusb_port();
void set_usb_port_factory(std::function<std::unique_ptr<UsbPort>()> factory);

}  // namespace evms::read
