// The UsbPort of usb_port.h over libusb-1.0.
#include <libusb.h>

#include <mutex>

#include "host/read/input_error.h"
#include "host/read/live/usb_port.h"

namespace evms::read {

static_assert(kUsbErrorIo == LIBUSB_ERROR_IO && kUsbErrorAccess == LIBUSB_ERROR_ACCESS && kUsbErrorNoDevice == LIBUSB_ERROR_NO_DEVICE &&
              kUsbErrorBusy == LIBUSB_ERROR_BUSY && kUsbErrorTimeout == LIBUSB_ERROR_TIMEOUT && kUsbErrorPipe == LIBUSB_ERROR_PIPE);

const char* usb_transfer_status_name(UsbTransferStatus s) {
  switch (s) {
    case UsbTransferStatus::kCompleted: return "completed";
    case UsbTransferStatus::kError: return "transfer error";
    case UsbTransferStatus::kTimedOut: return "timed out";
    case UsbTransferStatus::kCancelled: return "cancelled";
    case UsbTransferStatus::kStall: return "endpoint stalled";
    case UsbTransferStatus::kNoDevice: return "device gone";
    case UsbTransferStatus::kOverflow: return "overflow: the device sent more than was asked";
  }
  return "unknown";
}

namespace {

UsbTransferStatus status_of(libusb_transfer_status s) {
  switch (s) {
    case LIBUSB_TRANSFER_COMPLETED: return UsbTransferStatus::kCompleted;
    case LIBUSB_TRANSFER_TIMED_OUT: return UsbTransferStatus::kTimedOut;
    case LIBUSB_TRANSFER_CANCELLED: return UsbTransferStatus::kCancelled;
    case LIBUSB_TRANSFER_STALL: return UsbTransferStatus::kStall;
    case LIBUSB_TRANSFER_NO_DEVICE: return UsbTransferStatus::kNoDevice;
    case LIBUSB_TRANSFER_OVERFLOW: return UsbTransferStatus::kOverflow;
    case LIBUSB_TRANSFER_ERROR: break;
  }
  return UsbTransferStatus::kError;
}

class LibusbPort final : public UsbPort {
 public:
  LibusbPort() {
    if (int rc = libusb_init(&ctx_); rc < 0) throw InputError("libusb could not start (" + LibusbPort::describe(rc) + ")");
  }
  ~LibusbPort() override {
    close();
    for (libusb_transfer* t : transfers_) libusb_free_transfer(t);
    libusb_exit(ctx_);
  }

  std::vector<UsbDeviceId> devices() override {
    std::vector<UsbDeviceId> found;
    libusb_device** list = nullptr;
    const ssize_t n = libusb_get_device_list(ctx_, &list);
    for (ssize_t i = 0; i < n; ++i) {
      libusb_device_descriptor d{};
      if (libusb_get_device_descriptor(list[i], &d) == 0) {
        found.push_back({d.idVendor, d.idProduct, libusb_get_bus_number(list[i]), libusb_get_device_address(list[i])});
      }
    }
    if (n >= 0) libusb_free_device_list(list, 1);
    return found;
  }

  int open(const UsbDeviceId& device) override {
    libusb_device** list = nullptr;
    const ssize_t n = libusb_get_device_list(ctx_, &list);
    int rc = kUsbErrorNoDevice;
    for (ssize_t i = 0; i < n; ++i) {
      if (libusb_get_bus_number(list[i]) == device.bus && libusb_get_device_address(list[i]) == device.address) {
        rc = libusb_open(list[i], &handle_);
        break;
      }
    }
    if (n >= 0) libusb_free_device_list(list, 1);
    if (rc == 0) libusb_set_auto_detach_kernel_driver(handle_, 1);
    return rc;
  }

  int claim_interface(int interface_number) override {
    const int rc = libusb_claim_interface(handle_, interface_number);
    if (rc == 0) claimed_ = interface_number;
    return rc;
  }

  void close() override {
    if (!handle_) return;
    if (claimed_ >= 0) libusb_release_interface(handle_, claimed_);
    libusb_close(handle_);
    handle_ = nullptr;
    claimed_ = -1;
  }

  int control_transfer(std::uint8_t request_type, std::uint8_t request, std::uint16_t value, std::uint16_t index,
                       std::span<unsigned char> data, unsigned timeout_ms) override {
    if (!handle_) return LIBUSB_ERROR_NO_DEVICE;
    return libusb_control_transfer(handle_, request_type, request, value, index, data.data(), static_cast<std::uint16_t>(data.size()),
                                   timeout_ms);
  }

  int clear_halt(unsigned char endpoint) override { return handle_ ? libusb_clear_halt(handle_, endpoint) : LIBUSB_ERROR_NO_DEVICE; }

  int submit(UsbTransfer& t) override {
    if (!handle_) return LIBUSB_ERROR_NO_DEVICE;
    auto* lt = static_cast<libusb_transfer*>(t.port_state);
    if (!lt) {
      lt = libusb_alloc_transfer(0);
      if (!lt) return LIBUSB_ERROR_NO_MEM;
      transfers_.push_back(lt);
      t.port_state = lt;
    }
    libusb_fill_bulk_transfer(lt, handle_, t.endpoint, t.buffer.data(), static_cast<int>(t.buffer.size()), &LibusbPort::completed, &t, 0);
    return libusb_submit_transfer(lt);
  }

  int cancel(UsbTransfer& t) override {
    return t.port_state ? libusb_cancel_transfer(static_cast<libusb_transfer*>(t.port_state)) : LIBUSB_ERROR_NOT_FOUND;
  }

  int handle_events(int timeout_ms) override {
    timeval tick{timeout_ms / 1000, (timeout_ms % 1000) * 1000};
    return libusb_handle_events_timeout_completed(ctx_, &tick, nullptr);
  }

  std::string describe(int result) const override {
    return std::string(libusb_error_name(result)) + ": " + libusb_strerror(static_cast<libusb_error>(result));
  }

 private:
  static void LIBUSB_CALL completed(libusb_transfer* lt) {
    auto& t = *static_cast<UsbTransfer*>(lt->user_data);
    t.status = status_of(lt->status);
    t.received = lt->actual_length > 0 ? static_cast<size_t>(lt->actual_length) : 0;
    t.on_complete(t);
  }

  libusb_context* ctx_ = nullptr;
  libusb_device_handle* handle_ = nullptr;
  int claimed_ = -1;
  std::vector<libusb_transfer*> transfers_;
};

std::mutex g_factory_mutex;
std::function<std::unique_ptr<UsbPort>()> g_factory;

}  // namespace

std::unique_ptr<UsbPort> open_libusb_port() { return std::make_unique<LibusbPort>(); }

std::unique_ptr<UsbPort> open_usb_port() {
  std::lock_guard lock(g_factory_mutex);
  return g_factory ? g_factory() : open_libusb_port();
}

void set_usb_port_factory(std::function<std::unique_ptr<UsbPort>()> factory) {
  std::lock_guard lock(g_factory_mutex);
  g_factory = std::move(factory);
}

}  // namespace evms::read
