// The Python module `evms`: the readers, the golden model and the bit-accurate fixed-point core
// on NumPy arrays, for users who work in Python (tonic, NumPy) rather than through the evms
// program's files.
//
//   import evms
//   events, (width, height) = evms.read("recording.aedat4")     # or "gen://rotation", ...
//   labels, tracks = evms.run(events, (width, height), preset="evms", bandwidth=0.05)
//   labels, tracks = evms.run(events, (width, height), backend="fixed", core="ice40")
//   scores = evms.score(events, true_labels, labels, chunk_us=10000)   # as `evms metrics`
//   events, true_labels, truth, sensor = evms.generate("gen://family/crossing?seed=3")
//
//   stream = evms.stream("udp://0.0.0.0:8991?camera=dvs128")        # any source, in chunks, live ones too
//   tracker = evms.Tracker(stream.sensor)                            # the method on chunks as they come
//   for chunk in stream:
//       labelled, tracks = tracker.push(chunk)                       # the events whose packets closed
//
// `events` is a structured array with fields t (int64, us), x, y (uint16) and p (uint8, 1 = ON);
// run() takes any structured array with those four field names (tonic's included). `labels` has
// one int32 an event, as events.csv's label column; `tracks` has tracks.csv's columns. Keyword
// arguments are the evms program's parameters with '_' for '-' (`evms params` lists them).
// Bad input raises ValueError with the evms program's one-line message.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstring>
#include <limits>
#include <optional>
#include <tuple>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "host/backend/registry.h"
#include "host/gen/scene_generator.h"
#include "host/eval/chunks.h"
#include "host/eval/clustering_metrics.h"
#include "host/read/event_source.h"
#include "host/read/generated_source.h"
#include "host/read/input_error.h"
#include "host/read/source_window.h"
#include "types/params.h"

namespace py = pybind11;

namespace evms::python {
namespace {

struct TruthRow {
  std::int64_t t_us;
  std::int32_t object;
  double x, y;
};

// An event with its label, as events.csv's row.
struct LabelledRow {
  std::int64_t t;
  std::uint16_t x, y;
  std::uint8_t p;
  std::int32_t label;
};

struct TrackRow {
  std::int64_t t_us;
  std::int32_t track_id;
  std::uint8_t confirmed;
  double x, y, vx, vy;
  std::int32_t events, x_min, y_min, x_max, y_max;
  double var_x, cov_xy, var_y;
};

// What a backend gives: the labels alone (run()), or each event with its label (Tracker).
class Collector final : public OutputSink {
 public:
  explicit Collector(bool keep_events) : keep_events_(keep_events) {}
  void on_event(const LabelledEvent& e) override {
    if (keep_events_) {
      events.push_back({e.event.t, e.event.x, e.event.y, e.event.p, e.label});
    } else {
      labels.push_back(e.label);
    }
  }
  void on_track(const TrackUpdate& u) override {
    tracks.push_back({u.t, u.id, static_cast<std::uint8_t>(u.state == TrackState::kConfirmed), u.x, u.y, u.vx, u.vy, u.events,
                      u.x_min, u.y_min, u.x_max, u.y_max, u.var_x, u.cov_xy, u.var_y});
  }
  std::vector<std::int32_t> labels;
  std::vector<LabelledRow> events;
  std::vector<TrackRow> tracks;

 private:
  bool keep_events_;
};

// A parameter's name as the program spells it ('-') or as Python keywords do ('_').
std::string spelled(std::string name, char from, char to) {
  for (char& c : name) c = c == from ? to : c;
  return name;
}

// Records as a NumPy array of their dtype (PYBIND11_NUMPY_DTYPE below), copied.
template <typename T>
py::array_t<T> to_numpy(std::span<const T> v) {
  py::array_t<T> a(static_cast<py::ssize_t>(v.size()));
  if (!v.empty()) std::memcpy(a.mutable_data(), v.data(), v.size() * sizeof(T));
  return a;
}
template <typename T>
py::array_t<T> to_numpy(const std::vector<T>& v) {
  return to_numpy(std::span<const T>(v));
}

// Runs a step (a read, a backend's push) without the GIL; its errors as ValueError.
template <typename Step>
void unlocked(Step&& step) {
  std::string failure;
  {
    py::gil_scoped_release released;
    try {
      step();
    } catch (const std::exception& e) {
      failure = e.what();
    }
  }
  if (!failure.empty()) throw py::value_error(failure);
}

// A source read in chunks as they come: a file, a gen:// scene, a camera or a network stream.
class Stream {
 public:
  Stream(const std::string& source, const read::SourceOptions& options, std::int64_t chunk) : buffer_(checked_chunk(chunk)) {
    try {
      source_ = read::open_source(source, options);
    } catch (const std::exception& e) {
      throw py::value_error(e.what());
    }
    info_ = source_->info();
    if (info_.sensor_assumed()) {
      // A size the file does not give changes the labels, so it is said, as the program says it.
      const std::string said = source + ": sensor " + std::to_string(info_.sensor.width) + "x" + std::to_string(info_.sensor.height) + " " + info_.sensor_origin;
      if (PyErr_WarnEx(PyExc_UserWarning, said.c_str(), 1) != 0) throw py::error_already_set();
    }
  }

  // The next events, up to the chunk size; none at the end. A live source's events are those that
  // have arrived, after waiting for at least one.
  std::span<const Event> next() {
    if (!source_) return {};
    // A quiet live source is waited for in steps, so that Ctrl-C reaches Python between them.
    for (bool ready = false; !ready;) {
      {
        py::gil_scoped_release released;
        ready = source_->ready_within(100);
      }
      if (!ready && PyErr_CheckSignals() != 0) throw py::error_already_set();
    }
    size_t n = 0;
    try {
      unlocked([&] { n = source_->read(buffer_); });
    } catch (const py::value_error&) {
      close();
      throw;
    }
    if (n == 0) close();  // a live source's thread stops here
    return {buffer_.data(), n};
  }

  py::array_t<Event> next_array() {
    const std::span<const Event> events = next();
    if (events.empty()) throw py::stop_iteration();
    return to_numpy(events);
  }

  void close() {
    if (source_) dropped_ = source_->dropped(), reordered_ = source_->reordered();
    source_.reset();
  }
  py::tuple sensor() const { return py::make_tuple(info_.sensor.width, info_.sensor.height); }
  const std::string& format() const { return info_.format; }
  std::int64_t dropped() const { return source_ ? source_->dropped() : dropped_; }
  std::int64_t reordered() const { return source_ ? source_->reordered() : reordered_; }

 private:
  static size_t checked_chunk(std::int64_t chunk) {
    if (chunk < 1 || chunk > (1 << 24)) throw py::value_error("chunk: " + std::to_string(chunk) + " events (1 to 16,777,216)");
    return static_cast<size_t>(chunk);
  }

  std::unique_ptr<read::EventSource> source_;
  read::SourceInfo info_;
  std::vector<Event> buffer_;
  std::int64_t dropped_ = 0, reordered_ = 0;
};

// The options of read() and stream(): the size of a file that gives none, and what of the source
// to take, as the program's --width/--height, --start-us, --duration-us, --limit, --roi and
// --hot-pixels (host/read/source_window.h).
read::SourceOptions source_options(int width, int height, std::int64_t start_us, std::int64_t duration_us, std::int64_t limit,
                                   const std::optional<std::tuple<int, int, int, int>>& roi, const std::string& hot_pixels) {
  for (const auto& [name, value] : {std::pair{"start_us", start_us}, {"duration_us", duration_us}, {"limit", limit}}) {
    if (value < 0) throw py::value_error(std::string(name) + ": " + std::to_string(value) + " (0 or more)");
  }
  read::SourceOptions options;
  options.width = width, options.height = height;
  options.window.start_us = start_us, options.window.duration_us = duration_us, options.window.limit = limit;
  options.window.hot_pixels = hot_pixels;
  try {
    if (roi) {
      const auto& [x, y, w, h] = *roi;
      options.window.roi = read::parse_roi(std::to_string(x) + "," + std::to_string(y) + "," + std::to_string(w) + "," + std::to_string(h));
    }
  } catch (const std::exception& e) {
    throw py::value_error(e.what());
  }
  return options;
}

py::tuple read_source(const std::string& source, int width, int height, std::int64_t start_us, std::int64_t duration_us, std::int64_t limit,
                      const std::optional<std::tuple<int, int, int, int>>& roi, const std::string& hot_pixels) {
  // A camera or a network stream has no end to read to.
  if (read::is_live_source(source)) {
    throw py::value_error(source + ": evms.read takes files and gen:// scenes; a live source has no end (evms.stream reads it in chunks)");
  }
  Stream stream(source, source_options(width, height, start_us, duration_us, limit, roi, hot_pixels), 1 << 16);
  const py::tuple sensor = stream.sensor();
  std::vector<Event> events;
  for (std::span<const Event> chunk; !(chunk = stream.next()).empty();) events.insert(events.end(), chunk.begin(), chunk.end());
  return py::make_tuple(to_numpy(events), sensor);
}

std::unique_ptr<Stream> open_stream(const std::string& source, int width, int height, std::int64_t chunk, bool realtime, double speed,
                                    std::int64_t start_us, std::int64_t duration_us, std::int64_t limit,
                                    const std::optional<std::tuple<int, int, int, int>>& roi, const std::string& hot_pixels) {
  read::SourceOptions options = source_options(width, height, start_us, duration_us, limit, roi, hot_pixels);
  options.realtime = realtime, options.speed = speed;
  return std::make_unique<Stream>(source, options, chunk);
}

// A labelled scene with its truth, as `evms gen` writes it (events.txt, labels.csv, gt_tracks.csv).
py::tuple generate_scene(const std::string& uri) {
  std::vector<Event> events;
  std::vector<std::int32_t> labels;
  std::vector<TruthRow> truth;
  SensorSize sensor;
  try {
    gen::SceneGenerator generator(read::parse_scene_uri(uri));
    sensor = generator.sensor();
    std::vector<LabelledEvent> batch;
    std::vector<gen::TruthSample> samples;
    while (generator.next(batch, samples)) {
      for (const LabelledEvent& e : batch) events.push_back(e.event), labels.push_back(e.label);
      for (const gen::TruthSample& t : samples) truth.push_back({t.t, t.object, t.x, t.y});
      batch.clear(), samples.clear();
    }
  } catch (const std::exception& e) {
    throw py::value_error(e.what());
  }
  return py::make_tuple(to_numpy(events), to_numpy(labels), to_numpy(truth), py::make_tuple(sensor.width, sensor.height));
}

// One field of a structured array, as a contiguous array of T.
template <typename T>
py::array_t<T, py::array::c_style | py::array::forcecast> field(const py::array& events, const char* name) {
  if (!events.dtype().attr("names").is_none()) {
    const auto names = events.dtype().attr("names").cast<std::vector<std::string>>();
    for (const auto& n : names) {
      if (n == name) return py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(events[py::str(name)]);
    }
  }
  throw py::value_error(std::string("events: no field '") + name + "' (a structured array with fields t, x, y and p is needed)");
}

// The events of a structured array, each checked: inside the sensor, polarity 0 or 1, in time
// order, the first no earlier than `after_us` (the last event of a Tracker's earlier chunks).
std::vector<Event> events_of(const py::array& events, SensorSize sensor, TimeUs after_us = std::numeric_limits<TimeUs>::min()) {
  const auto t = field<std::int64_t>(events, "t");
  const auto x = field<std::int64_t>(events, "x");
  const auto y = field<std::int64_t>(events, "y");
  const auto p = field<std::int64_t>(events, "p");
  std::vector<Event> out(static_cast<size_t>(t.size()));
  for (py::ssize_t i = 0; i < t.size(); ++i) {
    std::string wrong;
    if (x.data()[i] < 0 || y.data()[i] < 0 || x.data()[i] >= sensor.width || y.data()[i] >= sensor.height) {
      wrong.append("(").append(std::to_string(x.data()[i])).append(",").append(std::to_string(y.data()[i])).append(") is outside the ");
      wrong.append(std::to_string(sensor.width)).append("x").append(std::to_string(sensor.height)).append(" sensor");
    } else if (p.data()[i] != 0 && p.data()[i] != 1) {
      wrong = "polarity " + std::to_string(p.data()[i]) + " is not 0 (OFF) or 1 (ON)";
    } else if (i > 0 && t.data()[i] < t.data()[i - 1]) {
      wrong = "t=" + std::to_string(t.data()[i]) + " us is earlier than the event before it (" + std::to_string(t.data()[i - 1]) + " us): sort by t";
    } else if (i == 0 && t.data()[0] < after_us) {
      wrong = "t=" + std::to_string(t.data()[0]) + " us is earlier than the last event pushed before it (" + std::to_string(after_us) + " us)";
    }
    if (!wrong.empty()) throw py::value_error("events[" + std::to_string(i) + "]: " + wrong);
    out[static_cast<size_t>(i)] = Event{t.data()[i], static_cast<std::uint16_t>(x.data()[i]), static_cast<std::uint16_t>(y.data()[i]),
                                        static_cast<std::uint8_t>(p.data()[i])};
  }
  return out;
}

SensorSize checked_sensor(std::pair<int, int> size) {
  const SensorSize sensor{size.first, size.second};
  if (sensor.width < 1 || sensor.height < 1 || sensor.width > read::kMaxSensorSide || sensor.height > read::kMaxSensorSide) {
    throw py::value_error("sensor: " + std::to_string(sensor.width) + "x" + std::to_string(sensor.height) + " is not a sensor size (1 to " +
                          std::to_string(read::kMaxSensorSide) + " px a side)");
  }
  return sensor;
}

// The method on a sensor: the golden model or a build of the fixed-point core, with the preset
// and keyword parameters as the program's options.
std::unique_ptr<backend::Backend> make_method(SensorSize sensor, const std::string& backend_name, const std::string& core,
                                              const std::string& preset, const py::kwargs& params) {
  Method method;
  method.preset = preset;
  for (const auto& [key, value] : params) {
    // Python's True/False, as the evms program's true/false.
    const std::string text = py::isinstance<py::bool_>(value) ? (value.cast<bool>() ? "true" : "false") : py::str(value).cast<std::string>();
    method.settings.emplace_back(spelled(key.cast<std::string>(), '_', '-'), text);
  }
  // The RTL and the board are the evms program's (--backend rtl|board): this module carries
  // neither the Verilated models nor the serial link.
  if (backend_name != "golden" && backend_name != "fixed") {
    throw py::value_error("backend '" + backend_name + "': the module runs golden and fixed (the evms program runs rtl and board)");
  }
  Params resolved, p;
  std::unique_ptr<backend::Backend> made;
  try {
    resolved = method.resolve(sensor);
    p = backend::fit_core_build(backend_name, core, resolved, method);
    backend::BackendOptions options = backend::options_for(p, sensor);
    options.core = core;
    made = backend_name == "golden" ? backend::make_golden_backend(options) : backend::make_fixed_backend(options);
  } catch (const std::exception& e) {
    throw py::value_error(e.what());
  }
  // As evms run's summary says it: what the core build changed of the method.
  if (const std::string changes = backend::fitted_settings(resolved, p); !changes.empty()) {
    const std::string said = "the " + core + " build runs " + changes;
    if (PyErr_WarnEx(PyExc_UserWarning, said.c_str(), 1) != 0) throw py::error_already_set();
  }
  return made;
}

py::tuple run_method(const py::array& events, std::pair<int, int> sensor_size, const std::string& backend_name, const std::string& core,
                     const std::string& preset, const py::kwargs& params) {
  const SensorSize sensor = checked_sensor(sensor_size);
  const std::unique_ptr<backend::Backend> method = make_method(sensor, backend_name, core, preset, params);
  const std::vector<Event> input = events_of(events, sensor);
  Collector out(false);
  out.labels.reserve(input.size());
  unlocked([&] {
    method->push(input, out);
    method->finish(out);
  });
  return py::make_tuple(to_numpy(out.labels), to_numpy(out.tracks));
}

// The method on a stream's chunks as they come: each push gives the events whose packets have
// closed, with their labels, and the track updates made since the last push; finish() the rest.
class Tracker {
 public:
  Tracker(std::pair<int, int> sensor, const std::string& backend_name, const std::string& core, const std::string& preset,
          const py::kwargs& params)
      : sensor_(checked_sensor(sensor)), method_(make_method(sensor_, backend_name, core, preset, params)) {}

  py::tuple push(const py::array& events) {
    if (finished_) throw py::value_error("the Tracker has finished; a new stream needs a new Tracker");
    const std::vector<Event> input = events_of(events, sensor_, last_t_);
    if (!input.empty()) last_t_ = input.back().t;
    Collector out(true);
    unlocked([&] { method_->push(input, out); });
    return py::make_tuple(to_numpy(out.events), to_numpy(out.tracks));
  }

  py::tuple finish() {
    Collector out(true);
    if (!finished_) unlocked([&] { method_->finish(out); });
    finished_ = true;
    return py::make_tuple(to_numpy(out.events), to_numpy(out.tracks));
  }

  py::dict stats() const {
    const backend::BackendStats s = method_->stats();
    py::dict d;
    d["events_in"] = s.events_in, d["events_kept"] = s.events_kept, d["packets"] = s.packets, d["clusters"] = s.clusters;
    d["tracks_started"] = s.tracks_started, d["unassigned_clusters"] = s.unassigned_clusters;
    return d;
  }
  py::tuple sensor() const { return py::make_tuple(sensor_.width, sensor_.height); }

 private:
  SensorSize sensor_;
  std::unique_ptr<backend::Backend> method_;
  TimeUs last_t_ = std::numeric_limits<TimeUs>::min();
  bool finished_ = false;
};

py::dict score_labels(const py::array& events, const py::array& truth, const py::array& pred, std::int64_t chunk_us, std::int64_t chunk_events) {
  if (chunk_us > 0 && chunk_events > 0) throw py::value_error("give chunk_us or chunk_events, not both");
  if (chunk_us < 0 || chunk_events < 0 || chunk_events == 1) throw py::value_error("chunk_us must be 1 us or more, chunk_events 2 or more");
  const auto t = py::array_t<std::int32_t, py::array::c_style | py::array::forcecast>::ensure(truth);
  const auto p = py::array_t<std::int32_t, py::array::c_style | py::array::forcecast>::ensure(pred);
  // Any sensor holds the events: score() looks at their times only.
  const std::vector<Event> ev = events_of(events, SensorSize{1 << 16, 1 << 16});
  if (!t || !p || t.ndim() != 1 || p.ndim() != 1 || t.size() != static_cast<py::ssize_t>(ev.size()) ||
      p.size() != static_cast<py::ssize_t>(ev.size())) {
    throw py::value_error("truth and pred must be one label an event (" + std::to_string(ev.size()) + " events)");
  }
  eval::Chunking chunking;
  if (chunk_us > 0) chunking = {eval::Chunking::Kind::kTime, chunk_us};
  if (chunk_events > 0) chunking = {eval::Chunking::Kind::kEvents, chunk_events};
  eval::ScoreAverage average;
  for (const auto& [first, last] : eval::chunk_ranges(ev, chunking)) {
    if (last - first < 2) continue;
    const auto n = static_cast<size_t>(last - first);
    average.add(eval::score({t.data() + first, n}, {p.data() + first, n}));
  }
  if (average.chunks() == 0) throw py::value_error("fewer than 2 events: nothing to score");
  const eval::ClusteringScores s = average.mean();
  py::dict d;
  d["ari"] = s.ari, d["nmi"] = s.nmi, d["precision"] = s.precision, d["recall"] = s.recall, d["f"] = s.f;
  d["chunks"] = average.chunks();
  return d;
}

py::dict parameters() {
  py::dict d;
  const Params defaults;
  for (const ParamInfo& info : param_table()) d[py::str(spelled(info.name, '-', '_'))] = param_text(defaults, info);
  return d;
}

}  // namespace
}  // namespace evms::python

PYBIND11_MODULE(evms, m) {
  using namespace evms::python;
  PYBIND11_NUMPY_DTYPE(evms::Event, t, x, y, p);
  PYBIND11_NUMPY_DTYPE(TruthRow, t_us, object, x, y);
  PYBIND11_NUMPY_DTYPE(LabelledRow, t, x, y, p, label);
  PYBIND11_NUMPY_DTYPE(TrackRow, t_us, track_id, confirmed, x, y, vx, vy, events, x_min, y_min, x_max, y_max, var_x, cov_xy, var_y);
  m.doc() = "evms: event-based mean-shift clustering and tracking (Barranco, Fermuller & Ros, IROS 2018); the readers, the golden model and the fixed-point core";
  m.def("read", &read_source, py::arg("source"), py::arg("width") = 0, py::arg("height") = 0, py::kw_only(), py::arg("start_us") = 0,
        py::arg("duration_us") = 0, py::arg("limit") = 0, py::arg("roi") = py::none(), py::arg("hot_pixels") = "",
        "Reads every event of a file or gen:// scene that `evms run` takes (no live source): returns (events, (width, height)),\n"
        "events a structured array with fields t (us), x, y and p. width and height are for formats without a sensor size;\n"
        "without them such a file's size is assumed, with a UserWarning that says so. start_us, duration_us, limit, roi=(x, y, w, h)\n"
        "(the sensor becomes w x h) and hot_pixels (a file of x,y lines, or \"auto\") take part of it, as evms run's options do.");
  m.def("generate", &generate_scene, py::arg("scene"),
        "Generates a labelled scene named as a gen:// source (gen://rotation?seed=2, gen://family/crossing?seed=1003&width=240&height=180):\n"
        "returns (events, labels, truth, (width, height)): the events as read() gives them, each one's object (-1 noise), and each\n"
        "object's centre every ms while it is wholly in view (t_us, object, x, y), as `evms gen` writes them.");
  m.def("run", &run_method, py::arg("events"), py::arg("sensor"), py::kw_only(), py::arg("backend") = "golden", py::arg("core") = "host",
        py::arg("preset") = "evms",
        "Clusters and tracks time-ordered events on a sensor (width, height) with the golden model, or with backend=\"fixed\" the\n"
        "bit-accurate core of build core (host, arty or ice40, in that build's sizes): returns (labels, tracks),\n"
        "one int32 label per event (-1 noise) and the track updates with tracks.csv's columns (confirmed: 1, tentative: 0).\n"
        "Keyword arguments set parameters, '_' for '-': evms.run(events, (240, 180), bandwidth=0.05, warm_start=False).");
  m.def("score", &score_labels, py::arg("events"), py::arg("truth"), py::arg("pred"), py::kw_only(), py::arg("chunk_us") = 0,
        py::arg("chunk_events") = 0,
        "Scores a labelling of the events against the true one as `evms metrics` does: the means over chunks (chunk_us-long windows,\n"
        "or chunk_events events, 256 by default) of the pair-counting ARI, NMI, precision, recall and F, each noise (-1) event a\n"
        "cluster of its own; returns a dict with those and the chunks scored.");
  py::class_<Stream>(m, "Stream",
                     "A source in chunks of at most `chunk` events, as evms.stream() opens it; iterate it for structured arrays\n"
                     "as read() gives. A live source's chunks hold the events that have arrived.")
      .def("__iter__", [](Stream& s) -> Stream& { return s; })
      .def("__next__", &Stream::next_array)
      .def("close", &Stream::close, "Stops reading (a live source's thread and its device are released).")
      .def_property_readonly("sensor", &Stream::sensor, "(width, height)")
      .def_property_readonly("format", &Stream::format, "the format read, as `evms info` names it")
      .def_property_readonly("dropped", &Stream::dropped, "events a live source dropped while its buffer was full (read faster to keep them)")
      .def_property_readonly("reordered", &Stream::reordered,
                             "events read so far that came late and were moved back into time order (within the reader's tolerance)");
  m.def("stream", &open_stream, py::arg("source"), py::kw_only(), py::arg("width") = 0, py::arg("height") = 0, py::arg("chunk") = 65536, py::arg("realtime") = false,
        py::arg("speed") = 1.0, py::arg("start_us") = 0, py::arg("duration_us") = 0, py::arg("limit") = 0, py::arg("roi") = py::none(),
        py::arg("hot_pixels") = "",
        "Opens any source `evms run` takes, live ones too (usb://dvs128, udp://0.0.0.0:8991?camera=dvs128), to read in chunks:\n"
        "for events in evms.stream(source): ... realtime=True replays a recording at `speed` times its own pace, as a camera\n"
        "would send it. Its sensor is stream.sensor; width and height are for formats without one, and the other keywords are\n"
        "read()'s.");
  py::class_<Tracker>(m, "Tracker",
                      "The method on a stream's chunks as they come: Tracker(sensor, *, backend, core, preset, **parameters) as run()\n"
                      "takes them. push(events) gives (labelled, tracks): the events whose packets have closed, as a structured array\n"
                      "with fields t, x, y, p and label, and the track updates made since the last push; finish() gives the rest.\n"
                      "Over a stream, the labels and tracks are run()'s on the whole of it.")
      .def(py::init<std::pair<int, int>, const std::string&, const std::string&, const std::string&, const py::kwargs&>(), py::arg("sensor"),
           py::kw_only(), py::arg("backend") = "golden", py::arg("core") = "host", py::arg("preset") = "evms")
      .def("push", &Tracker::push, py::arg("events"), "Takes the next time-ordered events; returns (labelled, tracks) of those done.")
      .def("finish", &Tracker::finish, "Closes the last packet; returns (labelled, tracks) of the rest. Later pushes are refused.")
      .def_property_readonly("stats", &Tracker::stats, "events in and kept by the filter, packets, clusters, tracks started, clusters without a track slot")
      .def_property_readonly("sensor", &Tracker::sensor, "(width, height)");
  m.def("parameters", &parameters, "The method's parameters (with '_' for '-', as run() takes them) and their defaults (--preset evms), as text.");
}
