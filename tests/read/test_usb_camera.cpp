// The USB camera reader (host/read/live/usb_camera.cpp) against a scripted port
// (tests/support/scripted_usb_port.h): what it asks of the camera, what it delivers, and how it
// ends when the camera stalls, fails a transfer, goes quiet or is unplugged mid-stream.
#include <gtest/gtest.h>

#include <chrono>

#include "host/read/event_source.h"
#include "host/read/live/usb_port.h"
#include "tests/support/command.h"
#include "tests/support/encoders.h"
#include "tests/support/read_all.h"
#include "tests/support/scripted_usb_port.h"

namespace evms::test {
namespace {

using Step = UsbScript::Step::Kind;

// Puts `script` behind usb:// for the length of a test.
class ScriptedCamera {
 public:
  explicit ScriptedCamera(const UsbScript& script) {
    read::set_usb_port_factory([script, log = log_] { return std::make_unique<ScriptedUsbPort>(script, log); });
  }
  ~ScriptedCamera() { read::set_usb_port_factory(nullptr); }
  const UsbLog& log() const { return *log_; }

 private:
  std::shared_ptr<UsbLog> log_ = std::make_shared<UsbLog>();
};

struct Drained {
  std::vector<Event> events;
  std::string error;  // the InputError that ended the stream, if one did
  std::vector<std::pair<std::string, std::int64_t>> skipped;
  SensorSize sensor;
};

Drained drain(const std::string& uri) {
  Drained d;
  auto source = read::open_source(uri, {});
  d.sensor = source->info().sensor;
  try {
    read_into(*source, d.events);
  } catch (const read::InputError& e) {
    d.error = e.what();
  }
  d.skipped = source->skipped();
  return d;
}

std::int64_t skipped_count(const Drained& d, const std::string& kind) {
  for (const auto& [k, n] : d.skipped) {
    if (k == kind) return n;
  }
  return 0;
}

UsbScript script_of(UsbScript::Camera camera) {
  UsbScript s;
  s.camera = camera;
  s.sensor = camera == UsbScript::Camera::kDvs128 ? SensorSize{128, 128} : SensorSize{240, 180};
  return s;
}

TEST(UsbCamera, DeliversEveryEventTheCameraSendsThenNamesTheUnplug) {
  for (const auto camera : {UsbScript::Camera::kDavis, UsbScript::Camera::kDvs128}) {
    const bool davis = camera == UsbScript::Camera::kDavis;
    UsbScript s = script_of(camera);
    if (davis) s.sensor = {346, 260};  // the size comes from the camera, not a default
    s.add_events(3000);
    s.add_events(40000);  // more than a 16 kB transfer holds: words are split across transfers
    s.add(Step::kUnplug);
    ScriptedCamera cam(s);
    const std::string uri = davis ? "usb://davis" : "usb://dvs128";
    const Drained d = drain(uri);
    EXPECT_EQ(d.sensor, s.sensor);
    ASSERT_EQ(d.events.size(), s.events.size()) << uri;
    EXPECT_EQ(d.events, s.events) << uri;
    EXPECT_GT(d.events.back().t, 0x8000 * 10) << "the stream spans many timestamp wraps";
    EXPECT_EQ(d.error, uri + ": the " + (davis ? "DAVIS" : "DVS128") + " was unplugged while streaming");
    EXPECT_EQ(cam.log().opened, 1);
    EXPECT_EQ(cam.log().closed, 1);
    // Streaming was started with the vendor requests of facts.md.
    ASSERT_FALSE(cam.log().controls.empty());
    const UsbLog::Control first_write = cam.log().controls[davis ? 2 : 0];
    EXPECT_EQ(first_write.request_type, 0x40);  // vendor, host to device
    EXPECT_EQ(first_write.request, davis ? 0xBF : 0xB3);
    if (davis) {
      EXPECT_EQ(first_write.value, 9);  // the USB module's run bit first
    }
  }
}

TEST(UsbCamera, AStalledEndpointIsClearedAndStreamingGoesOn) {
  UsbScript s = script_of(UsbScript::Camera::kDavis);
  s.add_events(1000);
  s.add(Step::kStall);
  s.add_events(1000);
  s.add(Step::kStall);
  s.add_events(1000);
  s.add(Step::kUnplug);
  ScriptedCamera cam(s);
  const Drained d = drain("usb://davis");
  EXPECT_EQ(d.events, s.events);
  EXPECT_EQ(cam.log().cleared_halts, 2);
  EXPECT_EQ(skipped_count(d, "bulk endpoint stalls, cleared"), 2);
  EXPECT_NE(d.error.find("unplugged"), std::string::npos) << d.error;
}

TEST(UsbCamera, AStallThatComesBackEndsTheStreamNamingIt) {
  UsbScript s = script_of(UsbScript::Camera::kDavis);
  s.add_events(500);
  for (int i = 0; i < 5; ++i) s.add(Step::kStall);
  ScriptedCamera cam(s);
  const Drained d = drain("usb://davis");
  EXPECT_EQ(d.events, s.events);
  EXPECT_EQ(d.error, "usb://davis: the DAVIS's bulk endpoint stalled 3 times in a row with no data between, though it was cleared "
                     "each time; replug the camera");
  EXPECT_EQ(cam.log().cleared_halts, 2);
  EXPECT_EQ(cam.log().closed, 1);
}

TEST(UsbCamera, AFailedTransferIsResubmittedAndCountedAndOnlyARunOfThemEndsTheStream) {
  {
    UsbScript s = script_of(UsbScript::Camera::kDvs128);
    s.add_events(1000);
    s.add(Step::kError);
    s.add_events(1000);
    s.add(Step::kUnplug);
    ScriptedCamera cam(s);
    const Drained d = drain("usb://dvs128");
    EXPECT_EQ(d.events, s.events);
    EXPECT_EQ(skipped_count(d, "failed bulk transfers, resubmitted (their bytes lost)"), 1);
    EXPECT_NE(d.error.find("unplugged"), std::string::npos) << d.error;
  }
  {
    UsbScript s = script_of(UsbScript::Camera::kDvs128);
    s.add_events(1000);
    for (int i = 0; i < 8; ++i) s.add(Step::kError);
    s.add_events(1000);  // never reached
    ScriptedCamera cam(s);
    const Drained d = drain("usb://dvs128");
    EXPECT_EQ(d.events.size(), 1000u);
    EXPECT_EQ(d.error, "usb://dvs128: 8 bulk transfers failed in a row, the last with 'transfer error'; replug the camera");
  }
}

TEST(UsbCamera, ACameraThatGoesQuietEndsTheStreamNamingIt) {
  UsbScript s = script_of(UsbScript::Camera::kDavis);
  s.add_events(500);
  ScriptedCamera cam(s);
  const auto start = std::chrono::steady_clock::now();
  const Drained d = drain("usb://davis?silence-s=0.3");
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(d.events, s.events);
  EXPECT_EQ(d.error.rfind("usb://davis?silence-s=0.3: the DAVIS sent nothing for 0.3 s, though a streaming camera", 0), 0u) << d.error;
  EXPECT_LT(took, 5.0) << "ended by the silence, not by a test timeout";
}

TEST(UsbCamera, ClosingMidStreamCancelsTheTransfersAndStopsTheCamera) {
  UsbScript s = script_of(UsbScript::Camera::kDavis);
  s.add_events(2000);
  ScriptedCamera cam(s);
  {
    auto source = read::open_source("usb://davis?silence-s=0", {});
    std::vector<Event> batch(100);
    ASSERT_GT(source->read(batch), 0u);
  }  // the camera is still streaming (silently) here
  EXPECT_EQ(cam.log().closed, 1);
  // The last requests clear the run bits: DVS state machine last of all.
  const UsbLog::Control last = cam.log().controls.back();
  EXPECT_EQ(last.request, 0xBF);
  EXPECT_EQ(last.value, 1);
  EXPECT_EQ(last.index, 3);
}

TEST(UsbCamera, OpeningFaultsAreOneLineErrorsThatSayWhatToDo) {
  const auto open_error = [](const UsbScript& s, const std::string& uri) {
    ScriptedCamera cam(s);
    try {
      auto source = read::open_source(uri, {});
    } catch (const read::InputError& e) {
      return std::string(e.what());
    }
    return std::string("(opened)");
  };
  UsbScript none = script_of(UsbScript::Camera::kNone);
  EXPECT_EQ(open_error(none, "usb://davis"), "usb://davis: no DAVIS camera found (VID 0x152A, PID 0x841B or 0x841A); is it plugged "
                                             "in? 'lsusb' lists what is");
  UsbScript denied = script_of(UsbScript::Camera::kDavis);
  denied.open_result = read::kUsbErrorAccess;
  EXPECT_NE(open_error(denied, "usb://davis").find("no permission to open the DAVIS at USB bus 3 device 7: add a udev rule"),
            std::string::npos);
  UsbScript busy = script_of(UsbScript::Camera::kDvs128);
  busy.claim_result = read::kUsbErrorBusy;
  EXPECT_EQ(open_error(busy, "usb://dvs128"),
            "usb://dvs128: cannot claim the camera's interface 0 (LIBUSB_ERROR_BUSY: Resource busy); is another program (jAER, DV, caer) "
            "using it?");
  UsbScript refused = script_of(UsbScript::Camera::kDavis);
  refused.failing_control = 1, refused.failing_control_result = read::kUsbErrorPipe;
  EXPECT_EQ(open_error(refused, "usb://davis"), "usb://davis: vendor request 0xBF (1, 1) failed (LIBUSB_ERROR_PIPE: Pipe error)");
  UsbScript huge = script_of(UsbScript::Camera::kDavis);
  huge.sensor = {70000, 180};
  EXPECT_EQ(open_error(huge, "usb://davis"), "usb://davis: the camera reports a 70000x180 sensor, outside 1..4096 a side");
  EXPECT_EQ(open_error(script_of(UsbScript::Camera::kDavis), "usb://davis?silence=3"),
            "usb://davis?silence=3: unknown option 'silence' (known: silence-s)");
  EXPECT_EQ(open_error(script_of(UsbScript::Camera::kDavis), "usb://davis?silence-s=soon"),
            "usb://davis?silence-s=soon: 'silence-s' needs a number of seconds from 0 to 1000000 (0: wait for ever), got 'soon'");
  // An infinite or huge wait would overflow its count of nanoseconds.
  EXPECT_EQ(open_error(script_of(UsbScript::Camera::kDavis), "usb://davis?silence-s=inf"),
            "usb://davis?silence-s=inf: 'silence-s' needs a number of seconds from 0 to 1000000 (0: wait for ever), got 'inf'");
  EXPECT_EQ(open_error(script_of(UsbScript::Camera::kDavis), "usb://davis?silence-s=1e20"),
            "usb://davis?silence-s=1e20: 'silence-s' needs a number of seconds from 0 to 1000000 (0: wait for ever), got '1e20'");
}

// End to end: `evms run usb://davis` with the camera failing under it writes complete outputs
// of every event that arrived, prints its summary with the faults counted, then names the cause.
TEST(UsbCamera, EvmsRunKeepsItsOutputsWhenTheCameraFailsUnderIt) {
  TempDir dir;
  UsbScript s = script_of(UsbScript::Camera::kDavis);
  s.add_events(6000);
  const std::string script = dir.write("camera.txt", std::string("# a DAVIS240 that stalls, fails a transfer, then is unplugged\n"
                                                                  "camera davis 240x180\nevents 6000\nstall\nevents 6000\nerror\n"
                                                                  "events 6000\nunplug\n"));
  const CommandResult r = run_command("EVMS_USB_SCRIPT=" + script + " " + scripted_usb_binary() + " run usb://davis --out " + dir.path("out"));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.err, "evms: usb://davis: the DAVIS was unplugged while streaming\n");
  const std::string csv_text = read_file(dir.path("out/events.csv"));
  EXPECT_EQ(std::count(csv_text.begin(), csv_text.end(), '\n'), 2 + 18000) << "the sensor line, the header and every event";
  const Event& first = s.events.front();
  EXPECT_NE(csv_text.find("t_us,x,y,p,label\n" + std::to_string(first.t) + "," + std::to_string(first.x) + "," + std::to_string(first.y) + ","),
            std::string::npos);
  EXPECT_FALSE(read_file(dir.path("out/tracks.csv")).empty());
  EXPECT_NE(r.out.find("events in   18,000"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("live        0 events dropped while the backend was behind; 1 bulk endpoint stalls, cleared; 1 failed bulk "
                       "transfers, resubmitted (their bytes lost)"),
            std::string::npos)
      << r.out;
}

}  // namespace
}  // namespace evms::test
