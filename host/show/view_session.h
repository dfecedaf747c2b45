// What the viewer shows, frame by frame, independent of where the frames go (an SDL window or
// PNG files): source -> backend -> renderer, with frames at fixed steps of sensor time.
//
// Frame k shows the state after every event with t <= t_first + k / fps has been pushed to the
// backend, and nothing later, however the source delivered its events. So a window and a
// headless run of the same source show the same frames.
#pragma once

#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "host/backend/backend.h"
#include "host/eval/latency_histogram.h"
#include "host/read/event_source.h"
#include "host/show/frame_renderer.h"

namespace evms::show {

class ViewSession {
 public:
  ViewSession(std::unique_ptr<read::EventSource> source, std::string backend, backend::BackendOptions options, double fps,
              ViewStyle style);
  // Listening to a board whose events enter at its AER pins (Backend::listen): no source, and
  // each frame shows the board's tracks as they came in the frame's period of wall clock, at
  // the latest time they carry.
  struct Listening {};
  ViewSession(Listening, SensorSize sensor, std::string backend, backend::BackendOptions options, double fps, ViewStyle style);
  ~ViewSession();

  // Processes input up to the next frame's time. Returns false once the source has ended and
  // the last frame (after the backend's flush) is ready.
  bool advance();
  void render(Canvas& canvas);
  Canvas make_canvas() const { return renderer_.make_canvas(); }
  std::int64_t frame() const { return frame_; }

  // Replaces the backend; events from now on go to the new one. Names as in --backend.
  void switch_backend(const std::string& name);
  const std::string& backend_name() const { return backend_name_; }
  // The source; none when listening.
  read::EventSource* source() { return source_.get(); }
  bool listening() const { return !source_; }
  // Arrival-to-label latency of the events of a live source, and the events labelled so far
  // (by a board in tracks mode, as its progress frames count them).
  const eval::LatencyHistogram& latency() const;
  std::int64_t events() const;
  // A board in tracks mode: its labels stay on it, and the events are drawn unlabelled.
  bool labels_on_board() const { return backend_name_ == "board" && options_.board_keeps_labels; }

 private:
  class Sink;
  void push_until(TimeUs t);

  std::unique_ptr<read::EventSource> source_;
  std::string backend_name_;
  backend::BackendOptions options_;
  std::unique_ptr<backend::Backend> backend_;
  std::unique_ptr<Sink> sink_;
  FrameRenderer renderer_;
  TimeUs period_us_;
  std::vector<Event> pending_;  // read, not yet pushed: later than the frame being built
  std::vector<std::int64_t> pending_arrival_;
  size_t pending_at_ = 0;
  bool started_ = false, ended_ = false;
  TimeUs t_first_ = 0, frame_t_ = 0;
  TimeUs last_pushed_t_ = 0;  // the latest event pushed: where the last frame of a recording is
  std::int64_t frame_ = -1;
  std::deque<std::pair<TimeUs, std::int64_t>> history_;  // (frame time, events labelled by then)
};

}  // namespace evms::show
