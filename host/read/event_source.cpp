#include "host/read/event_source.h"

#include <utility>
#include "host/read/csv_columns.h"
#include "host/read/formats/bag_storage.h"
#include "host/read/live/live_source.h"
#include "host/read/source_window.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstring>
#include <filesystem>

namespace evms::read {

FileEventSource::FileEventSource(ByteReader in, std::string format, const SourceOptions& options)
    : in_(std::move(in)), options_(options) {
  info_.name = in_.path();
  info_.format = std::move(format);
}

void FileEventSource::set_sensor(std::optional<SensorSize> from_header,
                                 std::optional<SensorSize> fallback, const char* fallback_origin) {
  if (from_header) {
    info_.sensor = *from_header;
    info_.sensor_origin = "header";
  } else if (options_.width > 0 && options_.height > 0) {
    info_.sensor = {options_.width, options_.height};
    info_.sensor_origin = "--width/--height";
  } else if (fallback) {
    info_.sensor = *fallback;
    info_.sensor_origin = fallback_origin;
  } else {
    fail(in_.path(), {}, "the file does not say the sensor size: pass --width and --height");
  }
  // Coordinates are 16-bit and the filter keeps a timestamp per pixel: a larger size is a
  // corrupt header, not a sensor.
  if (info_.sensor.width < 1 || info_.sensor.height < 1 || info_.sensor.width > kMaxSensorSide || info_.sensor.height > kMaxSensorSide) {
    fail(in_.path(), info_.sensor_origin == std::string("header") ? InputPosition::byte(0) : InputPosition{},
         "a sensor of " + std::to_string(info_.sensor.width) + "x" + std::to_string(info_.sensor.height) + " (from the " +
             info_.sensor_origin + ") is outside 1x1 to " + std::to_string(kMaxSensorSide) + "x" + std::to_string(kMaxSensorSide));
  }
  start_ordering(in_.path(), options_.reorder_us);
}

size_t DecodedEventSource::read(std::span<Event> out) {
  size_t n = 0;
  for (;;) {
    n += ordering_->pop(out.subspan(n));
    if (n == out.size() || exhausted_) {
      // The events decoded before a bad record come out first; the error after them.
      if (n == 0 && failure_) std::rethrow_exception(std::exchange(failure_, nullptr));
      return n;
    }
    try {
      if (!decode_more()) {
        exhausted_ = true;
        ordering_->finish();
      }
    } catch (const InputError&) {
      failure_ = std::current_exception();
      exhausted_ = true;
      ordering_->finish();
    }
  }
}

double FileEventSource::progress() const {
  return in_.size() ? static_cast<double>(in_.offset()) / static_cast<double>(in_.size()) : -1.0;
}

void DecodedEventSource::count_skipped(const std::string& kind, std::int64_t n) {
  for (auto& [k, count] : skipped_) {
    if (k == kind) {
      count += n;
      return;
    }
  }
  skipped_.emplace_back(kind, n);
}

SensorSize smallest_usual_sensor_holding(long width, long height) {
  static constexpr SensorSize kUsualSensors[] = {{128, 128}, {240, 180}, {304, 240}, {320, 240},
                                                 {346, 260}, {640, 480}, {1280, 720}, {1280, 960}};
  for (const SensorSize& usual : kUsualSensors) {
    if (usual.width >= width && usual.height >= height) return usual;
  }
  return {static_cast<int>(width), static_cast<int>(height)};
}

std::optional<SensorSize> sensor_of_model(const std::string& model) {
  std::string m;
  for (char c : model) m += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  // Longest names first, so that DAVIS346 does not match a shorter prefix.
  static const std::array<std::pair<const char*, SensorSize>, 9> kModels = {{
      {"DVXPLORER_LITE", {320, 240}},
      {"DVXPLORER", {640, 480}},
      {"DAVIS346", {346, 260}},
      {"DAVIS240", {240, 180}},
      {"DAVIS640", {640, 480}},
      {"DAVIS128", {128, 128}},
      {"DVS128", {128, 128}},
      {"DVS132S", {132, 104}},
      {"DVS640", {640, 480}},
  }};
  for (const auto& [name, size] : kModels) {
    if (m.find(name) != std::string::npos) return size;
  }
  return std::nullopt;
}

std::unique_ptr<EventSource> open_generated_scene(const std::string& uri, const SourceOptions& o);

std::unique_ptr<EventSource> open_usb_camera(const std::string& uri, const SourceOptions& o);
std::unique_ptr<EventSource> open_udp_stream(const std::string& uri, const SourceOptions& o);

namespace {

std::unique_ptr<EventSource> open_recorded(const std::string& name, const SourceOptions& options);

}  // namespace

std::unique_ptr<EventSource> open_source(const std::string& name, const SourceOptions& options) {
  if (is_live_source(name)) {
    return window_source(name.rfind("usb://", 0) == 0 ? open_usb_camera(name, options) : open_udp_stream(name, options), options.window, nullptr);
  }
  auto source = window_source(open_recorded(name, options), options.window, [&] { return open_recorded(name, options); });
  if (!options.realtime) return source;
  return replay_in_real_time(std::move(source), options.speed, options.live_buffer_events);
}

namespace {

std::unique_ptr<EventSource> open_recorded(const std::string& name, const SourceOptions& options) {
  if (name.rfind("gen://", 0) == 0) return open_generated_scene(name, options);
  if (name.find("://") != std::string::npos) {
    throw InputError(name + ": unknown source scheme (expected a file path, gen://SCENE, usb://dvs128, usb://davis or udp://HOST:PORT)");
  }
  // A ROS 2 bag is a folder or an sqlite3 file, and may name its topic after a '?'.
  const size_t query = name.find("?topic=");
  const std::string path = query == std::string::npos ? name : name.substr(0, query);
  const std::string topic = query == std::string::npos ? "" : name.substr(query + 7);
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return open_ros2_bag(name, path, topic, options);
  ByteReader in(path);
  const std::string_view head = in.peek(64);
  if (head.empty()) fail(path, InputPosition::byte(0), "empty file");
  if (head.substr(0, 16) == std::string_view("SQLite format 3\0", 16) || head.rfind(kMcapMagic, 0) == 0) {
    return open_ros2_bag(name, path, topic, options);
  }
  if (head.rfind("#ROSBAG V2.0\n", 0) == 0) return open_ros1_bag(std::move(in), name, topic, options);
  if (head.rfind("#ROSBAG", 0) == 0) {
    fail(name, InputPosition::byte(0), "bad header: ROS bag version '" + printable(head.substr(0, head.find('\n'))) + "' (2.0 is read)");
  }
  if (query != std::string::npos) fail(name, {}, "?topic= applies to ROS bags only");
  if (head.rfind("#!AER-DAT2", 0) == 0) return open_aedat2(std::move(in), options);
  if (head.rfind("#!AER-DAT3", 0) == 0) return open_aedat3(std::move(in), options);
  if (head.rfind("#!AER-DAT4", 0) == 0) return open_aedat4(std::move(in), options);
  if (head.rfind("#!AER-DAT", 0) == 0) {
    fail(name, InputPosition::byte(0), "bad header: unsupported AEDAT version '" +
                                           std::string(head.substr(0, head.find('\r'))) + "'");
  }
  if (head.rfind("\x93NUMPY", 0) == 0) return open_npy(std::move(in), options);
  // Metavision's CSV begins with "%geometry:W,H"; its RAW and DAT files with other '%' lines.
  if (head.rfind("%geometry:", 0) == 0) return open_csv(std::move(in), options);
  if (head[0] == '%') return open_prophesee(std::move(in), options);
  // Text formats: the first line that is neither blank nor a comment ('#', such as the
  // "# sensor WxH" evms writes) decides. CSV has commas, the RPG format has spaces. A UTF-8
  // byte-order mark, which spreadsheets write, is not part of the text.
  std::string_view lines = in.peek(512);
  if (lines.rfind(kUtf8ByteOrderMark, 0) == 0) lines.remove_prefix(kUtf8ByteOrderMark.size());
  const auto passed_over = [](std::string_view line) {
    const size_t first = line.find_first_not_of(" \t\r");
    return first == std::string_view::npos || line[first] == '#';
  };
  while (lines.find('\n') != std::string_view::npos && passed_over(lines.substr(0, lines.find('\n')))) {
    lines.remove_prefix(lines.find('\n') + 1);
  }
  const std::string_view first = lines.substr(0, lines.find('\n'));
  bool text = std::all_of(first.begin(), first.end(), [](char c) {
    return c == '\t' || c == '\r' || (c >= 32 && c < 127);
  });
  // A header with ';' or tabs between its names is a CSV too (csv_columns.h), and so are rows
  // separated by ';', which no events.txt holds.
  const bool separated_header = is_csv_header(first) && first.find_first_of(";\t") != std::string_view::npos;
  if (text && (first.find_first_of(",;") != std::string_view::npos || separated_header)) return open_csv(std::move(in), options);
  if (text) return open_rpg_text(std::move(in), options);
  fail(name, InputPosition::byte(0),
       "bad header: not a known event format (events.txt, CSV, AEDAT 2/3/4, EVT 2/3 RAW, DAT, NPY, ROS 1 or 2 bag)");
}

}  // namespace

}  // namespace evms::read
