// usb://dvs128 and usb://davis: live iniVation cameras over libusb-1.0.
//
// The reader opens the first camera of the kind, claims interface 0, starts streaming with the
// vendor requests libcaer uses (facts.md), and keeps kTransfers asynchronous bulk transfers in
// flight on its own thread. Each completed transfer is decoded (usb_decoders.h) and appended to
// the live buffer, then resubmitted. Biases are left as the camera holds them.
#include <libusb.h>

#include <array>
#include <cstdio>
#include <string>

#include "host/read/live/live_source.h"
#include "host/read/live/usb_decoders.h"

namespace evms::read {
namespace {

constexpr std::uint16_t kInivationVid = 0x152A;
constexpr int kTransfers = 8;
constexpr int kTransferBytes = 16384;
constexpr unsigned kTimeoutMs = 1000;
constexpr const char* kUdevHint =
    "add a udev rule such as /etc/udev/rules.d/65-inivation.rules containing "
    "SUBSYSTEM==\"usb\", ATTR{idVendor}==\"152a\", MODE=\"0666\", then run 'sudo udevadm control --reload' and replug the camera";

struct CameraKind {
  const char* name;
  std::array<std::uint16_t, 2> pids;
  unsigned char endpoint;
};
constexpr CameraKind kDvs128{"DVS128", {0x8400, 0x8400}, 0x86};
constexpr CameraKind kDavis{"DAVIS", {0x841B, 0x841A}, 0x82};

std::string usb_error(int code) { return std::string(libusb_error_name(code)) + ": " + libusb_strerror(static_cast<libusb_error>(code)); }

class UsbCamera final : public LiveSource, private DecodedSink {
 public:
  UsbCamera(const std::string& uri, const CameraKind& kind, const SourceOptions& o)
      : LiveSource(o.live_buffer_events), uri_(uri), kind_(kind), dvs128_(*this), davis_(*this) {
    info_.name = uri;
    info_.format = std::string(kind.name) + " over USB";
    if (int rc = libusb_init(&ctx_); rc < 0) throw InputError(uri + ": libusb could not start (" + usb_error(rc) + ")");
    try {
      open();
      configure(true);
    } catch (...) {
      close_device();
      throw;
    }
    start();
  }

  ~UsbCamera() override {
    stop();
    close_device();
  }

 private:
  void open() {
    libusb_device** list = nullptr;
    const ssize_t n = libusb_get_device_list(ctx_, &list);
    libusb_device* found = nullptr;
    for (ssize_t i = 0; i < n && !found; ++i) {
      libusb_device_descriptor d{};
      if (libusb_get_device_descriptor(list[i], &d) == 0 && d.idVendor == kInivationVid &&
          (d.idProduct == kind_.pids[0] || d.idProduct == kind_.pids[1])) {
        found = list[i];
      }
    }
    if (!found) {
      libusb_free_device_list(list, 1);
      char ids[64];
      std::snprintf(ids, sizeof ids, "VID 0x%04X, PID 0x%04X%s", kInivationVid, kind_.pids[0],
                    kind_.pids[0] != kind_.pids[1] ? " or 0x841A" : "");
      throw InputError(uri_ + ": no " + kind_.name + " camera found (" + ids + "); is it plugged in? 'lsusb' lists what is");
    }
    const int bus = libusb_get_bus_number(found), address = libusb_get_device_address(found);
    const int rc = libusb_open(found, &handle_);
    libusb_free_device_list(list, 1);
    if (rc == LIBUSB_ERROR_ACCESS) {
      throw InputError(uri_ + ": no permission to open the " + kind_.name + " at USB bus " + std::to_string(bus) + " device " +
                       std::to_string(address) + ": " + kUdevHint);
    }
    if (rc < 0) throw InputError(uri_ + ": cannot open the " + kind_.name + " (" + usb_error(rc) + ")");
    libusb_set_auto_detach_kernel_driver(handle_, 1);
    if (int c = libusb_claim_interface(handle_, 0); c < 0) {
      throw InputError(uri_ + ": cannot claim the camera's interface 0 (" + usb_error(c) +
                       "); is another program (jAER, DV, caer) using it?");
    }
    if (is_davis()) {
      const std::uint32_t columns = read_config(1, 0), rows = read_config(1, 1);
      info_.sensor = {static_cast<int>(columns), static_cast<int>(rows)};
      info_.sensor_origin = "camera";
    } else {
      info_.sensor = {128, 128};
      info_.sensor_origin = "DVS128";
    }
  }

  bool is_davis() const { return &kind_ == &kDavis; }

  void control(std::uint8_t request, std::uint16_t value, std::uint16_t index, unsigned char* data, std::uint16_t length, bool in) {
    const unsigned direction = in ? LIBUSB_ENDPOINT_IN : LIBUSB_ENDPOINT_OUT;
    const auto type = static_cast<std::uint8_t>(direction | unsigned{LIBUSB_REQUEST_TYPE_VENDOR} | unsigned{LIBUSB_RECIPIENT_DEVICE});
    const int rc = libusb_control_transfer(handle_, type, request, value, index, data, length, kTimeoutMs);
    if (rc < 0) {
      char what[64];
      std::snprintf(what, sizeof what, "vendor request 0x%02X (%u, %u)", request, value, index);
      throw InputError(uri_ + ": " + what + " failed (" + usb_error(rc) + ")");
    }
  }
  void write_config(std::uint16_t module, std::uint16_t param, std::uint32_t v) {
    unsigned char be[4] = {static_cast<unsigned char>(v >> 24), static_cast<unsigned char>(v >> 16), static_cast<unsigned char>(v >> 8),
                           static_cast<unsigned char>(v)};
    control(0xBF, module, param, be, 4, false);
  }
  std::uint32_t read_config(std::uint16_t module, std::uint16_t param) {
    unsigned char be[4] = {};
    control(0xBF, module, param, be, 4, true);
    return (std::uint32_t{be[0]} << 24) | (std::uint32_t{be[1]} << 16) | (std::uint32_t{be[2]} << 8) | be[3];
  }

  // Starts or stops streaming: the DVS128's start/stop requests and a timestamp reset; the
  // DAVIS's USB output, multiplexer, timestamp generator, chip and DVS state machine.
  void configure(bool run) {
    if (is_davis()) {
      const std::uint32_t on = run ? 1 : 0;
      write_config(9, 0, on);  // USB: run
      write_config(0, 3, on);  // MUX: run chip
      write_config(0, 1, on);  // MUX: timestamp run
      write_config(0, 0, on);  // MUX: run
      write_config(1, 3, on);  // DVS: run
      if (run) write_config(0, 2, 1);  // MUX: timestamp reset
    } else {
      control(run ? 0xB3 : 0xB4, 0, 0, nullptr, 0, false);
      if (run) control(0xBB, 0, 0, nullptr, 0, false);
    }
  }

  void produce(std::stop_token stop) override {
    std::array<libusb_transfer*, kTransfers> transfers{};
    std::vector<unsigned char> memory(static_cast<size_t>(kTransfers) * kTransferBytes);
    for (int i = 0; i < kTransfers; ++i) {
      transfers[i] = libusb_alloc_transfer(0);
      libusb_fill_bulk_transfer(transfers[i], handle_, kind_.endpoint, memory.data() + static_cast<size_t>(i) * kTransferBytes,
                                kTransferBytes, &UsbCamera::on_transfer, this, 0);
      if (int rc = libusb_submit_transfer(transfers[i]); rc < 0) {
        fail_ = uri_ + ": cannot start the bulk transfers (" + usb_error(rc) + ")";
        break;
      }
      ++in_flight_;
    }
    timeval tick{0, 100000};
    while (in_flight_ > 0) {
      if ((stop.stop_requested() || !fail_.empty()) && !cancelled_) {
        for (auto* t : transfers) libusb_cancel_transfer(t);
        cancelled_ = true;
      }
      libusb_handle_events_timeout_completed(ctx_, &tick, nullptr);
    }
    for (auto* t : transfers) libusb_free_transfer(t);
    if (!fail_.empty()) throw InputError(fail_);
  }

  static void LIBUSB_CALL on_transfer(libusb_transfer* t) {
    auto* self = static_cast<UsbCamera*>(t->user_data);
    switch (t->status) {
      case LIBUSB_TRANSFER_COMPLETED: {
        self->arrival_ = steady_now_ns();
        const std::span<const std::uint8_t> bytes(t->buffer, static_cast<size_t>(t->actual_length));
        if (self->is_davis()) {
          self->davis_.feed(bytes);
        } else {
          self->dvs128_.feed(bytes);
        }
        self->flush();
        if (!self->cancelled_ && libusb_submit_transfer(t) == 0) return;
        break;
      }
      case LIBUSB_TRANSFER_NO_DEVICE:
        if (self->fail_.empty()) self->fail_ = self->uri_ + ": the " + self->kind_.name + " was unplugged while streaming";
        break;
      case LIBUSB_TRANSFER_CANCELLED: break;
      default:
        if (self->fail_.empty()) {
          self->fail_ = self->uri_ + ": a bulk transfer failed (" + libusb_error_name(t->status) + ")";
        }
    }
    --self->in_flight_;
  }

  void event(TimeUs t, std::uint16_t x, std::uint16_t y, std::uint8_t p) override {
    if (x >= info_.sensor.width || y >= info_.sensor.height) {
      count_skipped("addresses outside the sensor");
      return;
    }
    pending_.push_back(Event{t, x, y, p});
  }
  void skip(const char* kind) override { count_skipped(kind); }
  void flush() {
    buffer_.push(pending_, arrival_);
    pending_.clear();
  }

  void close_device() {
    if (handle_) {
      try {
        configure(false);
      } catch (const InputError&) {
        // The camera may be gone; stopping it is then moot.
      }
      libusb_release_interface(handle_, 0);
      libusb_close(handle_);
      handle_ = nullptr;
    }
    if (ctx_) libusb_exit(ctx_), ctx_ = nullptr;
  }

  std::string uri_;
  const CameraKind& kind_;
  libusb_context* ctx_ = nullptr;
  libusb_device_handle* handle_ = nullptr;
  Dvs128Decoder dvs128_;
  DavisDecoder davis_;
  std::vector<Event> pending_;
  std::int64_t arrival_ = 0;
  int in_flight_ = 0;
  bool cancelled_ = false;
  std::string fail_;
};

}  // namespace

std::unique_ptr<EventSource> open_usb_camera(const std::string& uri, const SourceOptions& o) {
  const std::string kind = uri.substr(6);
  if (kind == "dvs128") return std::make_unique<UsbCamera>(uri, kDvs128, o);
  if (kind == "davis") return std::make_unique<UsbCamera>(uri, kDavis, o);
  throw InputError(uri + ": unknown camera '" + kind + "' (expected usb://dvs128 or usb://davis)");
}

}  // namespace evms::read
