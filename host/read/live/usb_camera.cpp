// usb://dvs128 and usb://davis: live iniVation cameras over libusb-1.0 (through usb_port.h).
//
// The reader opens the first camera of the kind, claims interface 0, starts streaming with the
// vendor requests libcaer uses (facts.md), and keeps kTransfers asynchronous bulk transfers in
// flight on its own thread. Each completed transfer is decoded (usb_decoders.h) and appended to
// the live buffer, then resubmitted. Biases are left as the camera holds them.
//
// Faults while streaming, each counted or named in one line:
//   - a stalled bulk endpoint is cleared (libusb_clear_halt) and streaming goes on; stalls
//     again and again with no data in between end the stream;
//   - a failed transfer is resubmitted (its bytes are lost); kTransfers failures in a row end it;
//   - an unplugged camera ends it;
//   - silence ends it: a streaming camera sends a timestamp wrap at least every 33 ms (DAVIS;
//     16 ms on the DVS128), so `silence-s` seconds (default 3) without a byte mean it has hung.
// Events decoded before the end are delivered, then the cause (live_source.h).
#include <algorithm>
#include <array>
#include <charconv>
#include <cstdio>
#include <string>

#include "host/read/live/live_source.h"
#include "host/read/live/usb_decoders.h"
#include "host/read/live/usb_port.h"
#include "host/read/uri.h"

namespace evms::read {
namespace {

constexpr std::uint16_t kInivationVid = 0x152A;
constexpr int kTransfers = 8;
constexpr int kTransferBytes = 16384;
constexpr unsigned kTimeoutMs = 1000;
constexpr int kStallsInARowMax = 3;
constexpr double kSilenceDefaultS = 3.0;
constexpr std::uint8_t kEndpointIn = 0x80, kRequestVendor = 0x40, kRecipientDevice = 0x00;
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

class UsbCamera final : public LiveSource, private DecodedSink {
 public:
  UsbCamera(const std::string& uri, const CameraKind& kind, double silence_s, const SourceOptions& o)
      : LiveSource(o.live_buffer_events), uri_(uri), kind_(kind), silence_ns_(static_cast<std::int64_t>(silence_s * 1e9)),
        dvs128_(*this), davis_(*this) {
    info_.name = uri;
    info_.format = std::string(kind.name) + " over USB";
    try {
      port_ = open_usb_port();
    } catch (const InputError& e) {
      throw InputError(uri_ + ": " + e.what());
    }
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
  std::string usb_error(int code) const { return port_->describe(code); }

  void open() {
    const std::vector<UsbDeviceId> devices = port_->devices();
    const auto found = std::find_if(devices.begin(), devices.end(), [this](const UsbDeviceId& d) {
      return d.vendor == kInivationVid && (d.product == kind_.pids[0] || d.product == kind_.pids[1]);
    });
    if (found == devices.end()) {
      char ids[64];
      std::snprintf(ids, sizeof ids, "VID 0x%04X, PID 0x%04X%s", kInivationVid, kind_.pids[0],
                    kind_.pids[0] != kind_.pids[1] ? " or 0x841A" : "");
      throw InputError(uri_ + ": no " + kind_.name + " camera found (" + ids + "); is it plugged in? 'lsusb' lists what is");
    }
    const int rc = port_->open(*found);
    device_open_ = rc == 0;
    if (rc == kUsbErrorAccess) {
      throw InputError(uri_ + ": no permission to open the " + kind_.name + " at USB bus " + std::to_string(found->bus) + " device " +
                       std::to_string(found->address) + ": " + kUdevHint);
    }
    if (rc < 0) throw InputError(uri_ + ": cannot open the " + kind_.name + " (" + usb_error(rc) + ")");
    if (int c = port_->claim_interface(0); c < 0) {
      throw InputError(uri_ + ": cannot claim the camera's interface 0 (" + usb_error(c) +
                       "); is another program (jAER, DV, caer) using it?");
    }
    if (is_davis()) {
      const std::uint32_t columns = read_config(1, 0), rows = read_config(1, 1);
      if (columns < 1 || rows < 1 || columns > static_cast<std::uint32_t>(kMaxSensorSide) || rows > static_cast<std::uint32_t>(kMaxSensorSide)) {
        throw InputError(uri_ + ": the camera reports a " + std::to_string(columns) + "x" + std::to_string(rows) +
                         " sensor, outside 1.." + std::to_string(kMaxSensorSide) + " a side");
      }
      info_.sensor = {static_cast<int>(columns), static_cast<int>(rows)};
      info_.sensor_origin = "camera";
    } else {
      info_.sensor = {128, 128};
      info_.sensor_origin = "DVS128";
    }
  }

  bool is_davis() const { return &kind_ == &kDavis; }

  void control(std::uint8_t request, std::uint16_t value, std::uint16_t index, std::span<unsigned char> data, bool in) {
    const auto type = static_cast<std::uint8_t>((in ? kEndpointIn : 0) | kRequestVendor | kRecipientDevice);
    const int rc = port_->control_transfer(type, request, value, index, data, kTimeoutMs);
    if (rc < 0 || (in && static_cast<size_t>(rc) < data.size())) {
      char what[64];
      std::snprintf(what, sizeof what, "vendor request 0x%02X (%u, %u)", request, value, index);
      throw InputError(uri_ + ": " + what + " failed (" +
                       (rc < 0 ? usb_error(rc) : "the camera answered " + std::to_string(rc) + " of " + std::to_string(data.size()) + " bytes") +
                       ")");
    }
  }
  void write_config(std::uint16_t module, std::uint16_t param, std::uint32_t v) {
    unsigned char be[4] = {static_cast<unsigned char>(v >> 24), static_cast<unsigned char>(v >> 16), static_cast<unsigned char>(v >> 8),
                           static_cast<unsigned char>(v)};
    control(0xBF, module, param, be, false);
  }
  std::uint32_t read_config(std::uint16_t module, std::uint16_t param) {
    unsigned char be[4] = {};
    control(0xBF, module, param, be, true);
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
      control(run ? 0xB3 : 0xB4, 0, 0, {}, false);
      if (run) control(0xBB, 0, 0, {}, false);
    }
  }

  void produce(std::stop_token stop) override {
    std::vector<unsigned char> memory(static_cast<size_t>(kTransfers) * kTransferBytes);
    std::array<UsbTransfer, kTransfers> transfers;
    for (int i = 0; i < kTransfers; ++i) {
      UsbTransfer& t = transfers[i];
      t.endpoint = kind_.endpoint;
      t.buffer = std::span(memory).subspan(static_cast<size_t>(i) * kTransferBytes, kTransferBytes);
      t.on_complete = [this](UsbTransfer& done) { completed(done); };
      if (int rc = port_->submit(t); rc < 0) {
        fail_ = uri_ + ": cannot start the bulk transfers (" + usb_error(rc) + ")";
        break;
      }
      ++in_flight_;
    }
    last_data_ns_ = steady_now_ns();
    while (in_flight_ > 0 || !halted_.empty()) {
      if ((stop.stop_requested() || !fail_.empty()) && !cancelled_) {
        for (auto& t : transfers) port_->cancel(t);
        cancelled_ = true;
      }
      if (cancelled_) halted_.clear();
      if (in_flight_ > 0) port_->handle_events(100);
      // libusb's synchronous calls do not belong in a completion, so a stall is cleared here.
      if (!halted_.empty() && !cancelled_ && fail_.empty()) recover_from_stall();
      if (!cancelled_ && fail_.empty() && silence_ns_ > 0 && steady_now_ns() - last_data_ns_ > silence_ns_) {
        char s[32];
        std::snprintf(s, sizeof s, "%g", static_cast<double>(silence_ns_) * 1e-9);
        fail_ = uri_ + ": the " + kind_.name + " sent nothing for " + s +
                " s, though a streaming camera sends a timestamp wrap every few ms; it has hung (replug it)";
      }
    }
    if (!fail_.empty()) throw InputError(fail_);
  }

  // Runs from handle_events(). A transfer that is not resubmitted leaves the flight.
  void completed(UsbTransfer& t) {
    --in_flight_;
    switch (t.status) {
      case UsbTransferStatus::kCompleted:
        if (t.received > 0) {
          last_data_ns_ = arrival_ = steady_now_ns();
          stalls_in_a_row_ = 0, failures_in_a_row_ = 0;
          const std::span<const std::uint8_t> bytes(t.buffer.data(), t.received);
          if (is_davis()) {
            davis_.feed(bytes);
          } else {
            dvs128_.feed(bytes);
          }
          flush();
        }
        resubmit(t);
        break;
      case UsbTransferStatus::kStall: halted_.push_back(&t); break;
      case UsbTransferStatus::kNoDevice: unplugged(); break;
      case UsbTransferStatus::kCancelled: break;
      default:
        count_skipped("failed bulk transfers, resubmitted (their bytes lost)");
        if (++failures_in_a_row_ >= kTransfers) {
          if (fail_.empty()) {
            fail_ = uri_ + ": " + std::to_string(failures_in_a_row_) + " bulk transfers failed in a row, the last with '" +
                    usb_transfer_status_name(t.status) + "'; replug the camera";
          }
        } else {
          resubmit(t);
        }
    }
  }

  void resubmit(UsbTransfer& t) {
    if (cancelled_ || !fail_.empty()) return;
    const int rc = port_->submit(t);
    if (rc == 0) {
      ++in_flight_;
    } else if (rc == kUsbErrorNoDevice) {
      unplugged();
    } else if (fail_.empty()) {
      fail_ = uri_ + ": cannot resubmit a bulk transfer (" + usb_error(rc) + ")";
    }
  }

  // Every transfer the stall ended is back once the endpoint is cleared; a stall that comes back
  // kStallsInARowMax times with no data between is a camera that needs replugging.
  void recover_from_stall() {
    count_skipped("bulk endpoint stalls, cleared");
    if (++stalls_in_a_row_ >= kStallsInARowMax) {
      fail_ = uri_ + ": the " + kind_.name + "'s bulk endpoint stalled " + std::to_string(stalls_in_a_row_) +
              " times in a row with no data between, though it was cleared each time; replug the camera";
      halted_.clear();
      return;
    }
    if (const int rc = port_->clear_halt(kind_.endpoint); rc < 0) {
      fail_ = rc == kUsbErrorNoDevice ? unplugged_message() : uri_ + ": the bulk endpoint stalled and could not be cleared (" + usb_error(rc) + ")";
      halted_.clear();
      return;
    }
    std::vector<UsbTransfer*> halted;
    halted.swap(halted_);
    for (UsbTransfer* t : halted) resubmit(*t);
  }

  std::string unplugged_message() const { return uri_ + ": the " + kind_.name + " was unplugged while streaming"; }
  void unplugged() {
    if (fail_.empty()) fail_ = unplugged_message();
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
    if (!device_open_) return;
    device_open_ = false;
    try {
      configure(false);
    } catch (const InputError&) {
      // The camera may be gone or was never opened; stopping it is then moot.
    }
    port_->close();
  }

  std::string uri_;
  const CameraKind& kind_;
  std::int64_t silence_ns_;
  std::unique_ptr<UsbPort> port_;
  Dvs128Decoder dvs128_;
  DavisDecoder davis_;
  std::vector<Event> pending_;
  std::vector<UsbTransfer*> halted_;  // ended by a stall, to resubmit once the endpoint is cleared
  std::int64_t arrival_ = 0, last_data_ns_ = 0;
  int in_flight_ = 0, stalls_in_a_row_ = 0, failures_in_a_row_ = 0;
  bool device_open_ = false, cancelled_ = false;
  std::string fail_;
};

}  // namespace

std::unique_ptr<EventSource> open_usb_camera(const std::string& uri, const SourceOptions& o) {
  const SourceUri parts = split_source_uri(uri);
  double silence_s = kSilenceDefaultS;
  for (const auto& [key, value] : parts.query) {
    if (key != "silence-s") throw InputError(uri + ": unknown option '" + printable(key) + "' (known: silence-s)");
    const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), silence_s);
    // At most a million seconds: the count of nanoseconds it becomes must fit its 64 bits.
    if (value.empty() || ec != std::errc() || end != value.data() + value.size() || !(silence_s >= 0 && silence_s <= 1e6)) {
      throw InputError(uri + ": 'silence-s' needs a number of seconds from 0 to 1000000 (0: wait for ever), got '" + printable(value) + "'");
    }
  }
  if (parts.target == "dvs128") return std::make_unique<UsbCamera>(uri, kDvs128, silence_s, o);
  if (parts.target == "davis") return std::make_unique<UsbCamera>(uri, kDavis, silence_s, o);
  throw InputError(uri + ": unknown camera '" + printable(parts.target) + "' (expected usb://dvs128 or usb://davis)");
}

}  // namespace evms::read
