#include "tests/support/scripted_usb_port.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "tests/support/encoders.h"

namespace evms::test {

using read::UsbTransfer;
using read::UsbTransferStatus;

void UsbScript::add_events(size_t n) {
  const auto words = [this](const std::vector<Event>& e) { return camera == Camera::kDvs128 ? dvs128_usb_words(e) : davis_usb_words(e); };
  // sample_events is deterministic, and the wire words of a prefix of events are a prefix of
  // the words: this step sends what the longer run adds, with the wraps the decoder expects.
  const Bytes earlier = words(events);
  events = sample_events(events.size() + n, sensor);
  const Bytes all = words(events);
  steps.push_back({Step::Kind::kBytes, Bytes(all.begin() + static_cast<std::ptrdiff_t>(earlier.size()), all.end()), 0});
}

UsbScript UsbScript::from_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open the USB script");
  UsbScript s;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    line = line.substr(0, line.find('#'));
    std::istringstream words(line);
    std::string word;
    if (!(words >> word)) continue;
    const auto bad = [&](const std::string& why) { throw std::runtime_error(path + ": line " + std::to_string(number) + ": " + why); };
    const auto number_after = [&]() {
      long long v = 0;
      if (!(words >> v)) bad("'" + word + "' needs a number");
      return v;
    };
    if (word == "camera") {
      std::string kind, size;
      words >> kind >> size;
      s.camera = kind == "davis" ? Camera::kDavis : kind == "dvs128" ? Camera::kDvs128 : kind == "none" ? Camera::kNone : (bad("unknown camera '" + kind + "'"), Camera::kNone);
      s.sensor = s.camera == Camera::kDvs128 ? SensorSize{128, 128} : SensorSize{240, 180};
      if (!size.empty() && std::sscanf(size.c_str(), "%dx%d", &s.sensor.width, &s.sensor.height) != 2) bad("bad size '" + size + "'");
    } else if (word == "open-result") {
      s.open_result = static_cast<int>(number_after());
    } else if (word == "claim-result") {
      s.claim_result = static_cast<int>(number_after());
    } else if (word == "fail-control") {
      s.failing_control = static_cast<int>(number_after());
      s.failing_control_result = static_cast<int>(number_after());
    } else if (word == "events") {
      s.add_events(static_cast<size_t>(number_after()));
    } else if (word == "stall") {
      s.add(Step::Kind::kStall);
    } else if (word == "error") {
      s.add(Step::Kind::kError);
    } else if (word == "unplug") {
      s.add(Step::Kind::kUnplug);
    } else if (word == "silence") {
      s.add(Step::Kind::kSilence, static_cast<int>(number_after()));
    } else {
      bad("unknown step '" + word + "'");
    }
  }
  return s;
}

ScriptedUsbPort::ScriptedUsbPort(UsbScript script, std::shared_ptr<UsbLog> log) : script_(std::move(script)), log_(std::move(log)) {}

std::vector<read::UsbDeviceId> ScriptedUsbPort::devices() {
  std::vector<read::UsbDeviceId> d{{0x046D, 0xC52B, 1, 2}};  // a keyboard receiver, to be passed over
  if (script_.camera == UsbScript::Camera::kDavis) d.push_back({0x152A, 0x841B, 3, 7});
  if (script_.camera == UsbScript::Camera::kDvs128) d.push_back({0x152A, 0x8400, 3, 7});
  return d;
}

int ScriptedUsbPort::open(const read::UsbDeviceId& device) {
  if (device.bus != 3 || device.address != 7) return read::kUsbErrorNoDevice;
  if (script_.open_result != 0) return script_.open_result;
  ++log_->opened;
  open_ = true;
  return 0;
}

int ScriptedUsbPort::claim_interface(int) { return script_.claim_result; }

void ScriptedUsbPort::close() {
  if (open_) ++log_->closed;
  open_ = false;
}

int ScriptedUsbPort::control_transfer(std::uint8_t request_type, std::uint8_t request, std::uint16_t value, std::uint16_t index,
                                      std::span<unsigned char> data, unsigned) {
  const int n = static_cast<int>(log_->controls.size());
  log_->controls.push_back({request_type, request, value, index});
  if (gone_) return read::kUsbErrorNoDevice;
  if (n == script_.failing_control) return script_.failing_control_result;
  // DAVIS configuration reads: DVS module (1), parameters 0 and 1 are the columns and rows.
  if ((request_type & 0x80) && request == 0xBF && value == 1 && index <= 1 && data.size() == 4) {
    const auto v = static_cast<std::uint32_t>(index == 0 ? script_.sensor.width : script_.sensor.height);
    data[0] = static_cast<unsigned char>(v >> 24), data[1] = static_cast<unsigned char>(v >> 16);
    data[2] = static_cast<unsigned char>(v >> 8), data[3] = static_cast<unsigned char>(v);
  }
  return static_cast<int>(data.size());
}

int ScriptedUsbPort::clear_halt(unsigned char) {
  if (gone_) return read::kUsbErrorNoDevice;
  ++log_->cleared_halts;
  halted_ = false;
  return 0;
}

int ScriptedUsbPort::submit(UsbTransfer& t) {
  if (gone_) return read::kUsbErrorNoDevice;
  pending_.push_back(&t);
  return 0;
}

int ScriptedUsbPort::cancel(UsbTransfer& t) {
  const auto it = std::find(pending_.begin(), pending_.end(), &t);
  if (it == pending_.end()) return -5;  // LIBUSB_ERROR_NOT_FOUND
  pending_.erase(it);
  cancelled_.push_back(&t);
  return 0;
}

UsbTransfer* ScriptedUsbPort::take_oldest() {
  UsbTransfer* t = pending_.front();
  pending_.pop_front();
  return t;
}

void ScriptedUsbPort::complete(UsbTransfer& t, UsbTransferStatus status, size_t received) {
  t.status = status;
  t.received = received;
  t.on_complete(t);
}

int ScriptedUsbPort::handle_events(int timeout_ms) {
  const auto all_pending = [this](UsbTransferStatus status) {
    std::deque<UsbTransfer*> ended;
    ended.swap(pending_);
    for (UsbTransfer* t : ended) complete(*t, status);
  };
  if (!cancelled_.empty()) {
    std::deque<UsbTransfer*> ended;
    ended.swap(cancelled_);
    for (UsbTransfer* t : ended) complete(*t, UsbTransferStatus::kCancelled);
    return 0;
  }
  if (gone_) return all_pending(UsbTransferStatus::kNoDevice), 0;
  if (halted_) return all_pending(UsbTransferStatus::kStall), 0;
  if (pending_.empty() || step_ >= script_.steps.size()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(timeout_ms));
    return 0;
  }
  UsbScript::Step& step = script_.steps[step_];
  switch (step.kind) {
    case UsbScript::Step::Kind::kBytes: {
      UsbTransfer* t = take_oldest();
      const size_t n = std::min(t->buffer.size(), step.bytes.size() - step_offset_);
      std::copy_n(step.bytes.begin() + static_cast<std::ptrdiff_t>(step_offset_), n, t->buffer.begin());
      step_offset_ += n;
      if (step_offset_ == step.bytes.size()) ++step_, step_offset_ = 0;
      complete(*t, UsbTransferStatus::kCompleted, n);
      break;
    }
    case UsbScript::Step::Kind::kStall:
      ++step_;
      halted_ = true;
      all_pending(UsbTransferStatus::kStall);
      break;
    case UsbScript::Step::Kind::kError:
      ++step_;
      complete(*take_oldest(), UsbTransferStatus::kError);
      break;
    case UsbScript::Step::Kind::kUnplug:
      ++step_;
      gone_ = true;
      all_pending(UsbTransferStatus::kNoDevice);
      break;
    case UsbScript::Step::Kind::kSilence:
      ++step_;
      std::this_thread::sleep_for(std::chrono::milliseconds(step.ms));
      break;
  }
  return 0;
}

std::string ScriptedUsbPort::describe(int result) const {
  switch (result) {
    case read::kUsbErrorIo: return "LIBUSB_ERROR_IO: Input/Output Error";
    case read::kUsbErrorAccess: return "LIBUSB_ERROR_ACCESS: Access denied (insufficient permissions)";
    case read::kUsbErrorNoDevice: return "LIBUSB_ERROR_NO_DEVICE: No such device (it may have been disconnected)";
    case read::kUsbErrorBusy: return "LIBUSB_ERROR_BUSY: Resource busy";
    case read::kUsbErrorTimeout: return "LIBUSB_ERROR_TIMEOUT: Operation timed out";
    case read::kUsbErrorPipe: return "LIBUSB_ERROR_PIPE: Pipe error";
  }
  return "LIBUSB_ERROR " + std::to_string(result);
}

}  // namespace evms::test
