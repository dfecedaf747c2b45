// A source of events: a recorded file, a generated scene, a live camera or a network
// stream. Every evms subcommand that reads events takes any source by its name:
//   path/to/file.{txt,csv,aedat,aedat4,raw,dat,npy}   format detected from the header
//   path/to/bag[/file.db3][?topic=/events]       a ROS 2 bag (formats/ros2_bag.cpp)
//   path/to/file.bag[?topic=/dvs/events]         a ROS 1 bag (formats/ros1_bag.cpp)
//   gen://rotation?seed=1&duration-s=2           a generated labelled scene
//   usb://dvs128, usb://davis                    a live camera over libusb (usb_camera.cpp)
//   udp://HOST:PORT?camera=dvs128|davis          a jAER AEUnicast stream (udp_source.cpp)
// With SourceOptions::realtime any of them is replayed at its own pace (live_source.h).
#pragma once

#include <cstdint>
#include <exception>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "types/event.h"
#include "host/read/byte_reader.h"
#include "host/read/event_ordering.h"

namespace evms::read {

// The largest sensor side evms accepts, from a header or --width/--height (the largest event
// sensors are 1280x720 and 1280x960).
inline constexpr int kMaxSensorSide = 4096;

// The UTF-8 byte-order mark that spreadsheet programs put before a CSV's first line.
inline constexpr std::string_view kUtf8ByteOrderMark = "\xEF\xBB\xBF";

struct Roi {
  int x = 0, y = 0, width = 0, height = 0;
};

// What of a source a run takes (source_window.h).
struct SourceWindow {
  TimeUs start_us = 0;
  TimeUs duration_us = 0;
  std::int64_t limit = 0;
  std::optional<Roi> roi;
  std::string hot_pixels;    // a file, "auto" or empty
  double hot_factor = 20.0;  // auto: times the median active pixel's event count
  bool active() const { return start_us > 0 || duration_us > 0 || limit > 0 || roi || !hot_pixels.empty(); }
};

struct SourceOptions {
  int width = 0;              // sensor size for formats without one in their header
  int height = 0;
  TimeUs reorder_us = 1000;   // out-of-order tolerance, see event_ordering.h
  bool realtime = false;      // replay at the pace of the timestamps (live sources always are)
  double speed = 1.0;         // ... times this factor
  size_t live_buffer_events = 1 << 20;  // a live source's buffer; beyond it events are dropped
  SourceWindow window;
};

struct SourceInfo {
  std::string name;           // path or URI as given
  std::string format;         // e.g. "EVT 3.0", "AEDAT 4.0"
  SensorSize sensor;
  std::string sensor_origin;  // where the size came from: "header", "--width/--height", ...
  // The size is a guess ("assumed: the file does not say ..."), which the user should be told.
  bool sensor_assumed() const { return sensor_origin.rfind("assumed", 0) == 0; }
};

class EventSource {
 public:
  virtual ~EventSource() = default;
  virtual const SourceInfo& info() const = 0;
  // Fills up to out.size() events in time order; returns how many. 0 means the end.
  virtual size_t read(std::span<Event> out) = 0;
  // Fraction of the input consumed, or a negative number when unknown.
  virtual double progress() const { return -1.0; }
  // Records that are not polarity events (APS frames, IMU, triggers, ...), by kind.
  virtual std::vector<std::pair<std::string, std::int64_t>> skipped() const { return {}; }
  // Events moved back into time order (see event_ordering.h).
  virtual std::int64_t reordered() const { return 0; }
  // Live sources: the host arrival time (steady clock, ns) of each event the last read()
  // returned; empty for sources that are not live.
  virtual std::span<const std::int64_t> arrivals() const { return {}; }
  // Live sources: events that arrived while the buffer was full.
  virtual std::int64_t dropped() const { return 0; }
  // Whether read() would return at once (events are waiting, or the input ended), waiting up to
  // `wait_ms` for it. A recorded source always would; a live one lets a caller that must stay
  // responsive (Ctrl-C in the Python module) wait in steps instead of inside read().
  virtual bool ready_within(int /*wait_ms*/) { return true; }
};

// Base of every decoder of recorded input (files, bags): decodes on demand into the ordering
// stage and pulls events through it, and counts what is not a polarity event.
class DecodedEventSource : public EventSource {
 public:
  const SourceInfo& info() const override { return info_; }
  size_t read(std::span<Event> out) override;
  std::vector<std::pair<std::string, std::int64_t>> skipped() const override { return skipped_; }
  std::int64_t reordered() const override { return ordering_ ? ordering_->reordered() : 0; }

 protected:
  // Decodes some more input into the ordering stage; returns false once the input is exhausted.
  virtual bool decode_more() = 0;
  // Starts the ordering stage once info_.sensor is known; `path` names the input in errors.
  void start_ordering(const std::string& path, TimeUs reorder_us) { ordering_.emplace(path, info_.sensor, reorder_us); }
  void emit(TimeUs t, long x, long y, int p, InputPosition where) { ordering_->push(t, x, y, p, where); }
  void count_skipped(const std::string& kind, std::int64_t n = 1);

  SourceInfo info_;

 private:
  std::optional<EventOrdering> ordering_;
  std::vector<std::pair<std::string, std::int64_t>> skipped_;
  bool exhausted_ = false;
  std::exception_ptr failure_;  // a decoding error, reported once the events before it are read
};

// Base of every file decoder: owns the byte reader.
class FileEventSource : public DecodedEventSource {
 public:
  double progress() const override;

 protected:
  FileEventSource(ByteReader in, std::string format, const SourceOptions& options);
  // Fixes the sensor size (from the header, else options, else `fallback`) and starts the
  // ordering stage.
  void set_sensor(std::optional<SensorSize> from_header, std::optional<SensorSize> fallback,
                  const char* fallback_origin);

  ByteReader in_;
  SourceOptions options_;
};

std::unique_ptr<EventSource> open_source(const std::string& name, const SourceOptions& options);
// Whether open_source(name) is a live source (a camera, a network stream), which has no end to
// read to and cannot be read twice.
inline bool is_live_source(const std::string& name) { return name.rfind("usb://", 0) == 0 || name.rfind("udp://", 0) == 0; }

// The format decoders (one file each under formats/).
std::unique_ptr<EventSource> open_rpg_text(ByteReader in, const SourceOptions& o);
std::unique_ptr<EventSource> open_csv(ByteReader in, const SourceOptions& o);
std::unique_ptr<EventSource> open_aedat2(ByteReader in, const SourceOptions& o);
std::unique_ptr<EventSource> open_aedat3(ByteReader in, const SourceOptions& o);
std::unique_ptr<EventSource> open_aedat4(ByteReader in, const SourceOptions& o);
std::unique_ptr<EventSource> open_prophesee(ByteReader in, const SourceOptions& o);
std::unique_ptr<EventSource> open_npy(ByteReader in, const SourceOptions& o);
// A ROS 1 bag (format 2.0); `topic` empty picks the first event topic.
std::unique_ptr<EventSource> open_ros1_bag(ByteReader in, const std::string& name, const std::string& topic, const SourceOptions& o);
// A ROS 2 bag folder or one of its .db3 files; `topic` empty picks the first event topic.
std::unique_ptr<EventSource> open_ros2_bag(const std::string& name, const std::string& path, const std::string& topic,
                                          const SourceOptions& o);

// Sensor size of a camera model named in a header ("DAVIS240C", "DVS128", ...).
std::optional<SensorSize> sensor_of_model(const std::string& model);

// For a file that does not say its size: the smallest usual sensor (128x128 up to 1280x960)
// whose width and height hold every event's x and y, where `width` and `height` are one past
// the largest x and y; the extent itself when no usual sensor holds it. Background activity
// fires over the whole array, so a recording's extent is its sensor's.
SensorSize smallest_usual_sensor_holding(long width, long height);
inline constexpr const char* kSensorAssumedFromExtent =
    "assumed: the file does not say; the smallest usual sensor that holds every event; pass --width and --height";

}  // namespace evms::read
