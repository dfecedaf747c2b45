// A UsbPort (host/read/live/usb_port.h) that plays a script instead of talking to a camera:
// the camera on the bus, how opening it goes, then what its bulk endpoint does, step by step:
// send bytes, stall, fail a transfer, go quiet, or be unplugged. It records what the reader
// asked of it (control requests, cleared halts), so that tests can check both sides.
//
// A script is also a text file, one step a line (# starts a comment):
//   camera davis|dvs128|none [COLUMNSxROWS]   the device on the bus (DAVIS default 240x180)
//   open-result CODE | claim-result CODE       a kUsbError code that opening or claiming returns
//   fail-control N CODE                        the Nth control request (from 0) returns CODE
//   events N                                   the next N events of sample_events, as wire words
//   stall | error | unplug                     the endpoint halts; one transfer fails; the camera goes
//   silence MS                                 nothing for MS milliseconds
// After the last step the camera is silent.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "types/event.h"
#include "host/read/live/usb_port.h"

namespace evms::test {

struct UsbScript {
  enum class Camera { kNone, kDavis, kDvs128 };
  struct Step {
    enum class Kind { kBytes, kStall, kError, kUnplug, kSilence } kind;
    std::vector<std::uint8_t> bytes;  // kBytes
    int ms = 0;                       // kSilence
  };
  Camera camera = Camera::kDavis;
  SensorSize sensor{240, 180};
  int open_result = 0, claim_result = 0;
  int failing_control = -1, failing_control_result = 0;
  std::vector<Step> steps;
  std::vector<Event> events;  // every event the kBytes steps carry, in order

  // Appends the wire words of `n` more events (sample_events continued in time).
  void add_events(size_t n);
  void add(Step::Kind kind, int ms = 0) { steps.push_back({kind, {}, ms}); }
  // Reads the text form above; throws std::runtime_error naming the file and line.
  static UsbScript from_file(const std::string& path);
};

// What the reader asked of the port.
struct UsbLog {
  struct Control {
    std::uint8_t request_type, request;
    std::uint16_t value, index;
  };
  std::vector<Control> controls;
  int cleared_halts = 0, opened = 0, closed = 0;
};

class ScriptedUsbPort final : public read::UsbPort {
 public:
  ScriptedUsbPort(UsbScript script, std::shared_ptr<UsbLog> log);

  std::vector<read::UsbDeviceId> devices() override;
  int open(const read::UsbDeviceId& device) override;
  int claim_interface(int interface_number) override;
  void close() override;
  int control_transfer(std::uint8_t request_type, std::uint8_t request, std::uint16_t value, std::uint16_t index,
                       std::span<unsigned char> data, unsigned timeout_ms) override;
  int clear_halt(unsigned char endpoint) override;
  int submit(read::UsbTransfer& transfer) override;
  int cancel(read::UsbTransfer& transfer) override;
  int handle_events(int timeout_ms) override;
  std::string describe(int result) const override;

 private:
  read::UsbTransfer* take_oldest();  // the transfer submitted first of those pending
  void complete(read::UsbTransfer& t, read::UsbTransferStatus status, size_t received = 0);

  UsbScript script_;
  std::shared_ptr<UsbLog> log_;
  size_t step_ = 0, step_offset_ = 0;
  std::deque<read::UsbTransfer*> pending_, cancelled_;
  bool halted_ = false, gone_ = false, open_ = false;
};

}  // namespace evms::test
