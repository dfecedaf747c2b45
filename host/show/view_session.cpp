#include "host/show/view_session.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>

#include "host/read/live/live_source.h"

namespace evms::show {

class ViewSession::Sink final : public OutputSink {
 public:
  explicit Sink(FrameRenderer& r) : renderer_(r) {}
  void on_event(const LabelledEvent& e) override {
    renderer_.add(e);
    ++events_;
    latency_.labelled();
  }
  void on_track(const TrackUpdate& u) override {
    renderer_.add(u);
    latest_t_ = std::max(latest_t_, u.t);
  }
  void on_packet(const PacketSummary& p) override {
    clusters_ = p.clusters;
    latest_t_ = std::max(latest_t_, p.t_last);
  }

  eval::ArrivalLatency latency_;
  std::int64_t events_ = 0;
  int clusters_ = 0;
  TimeUs latest_t_ = 0;  // the latest time a track update or packet summary carried

 private:
  FrameRenderer& renderer_;
};

ViewSession::ViewSession(std::unique_ptr<read::EventSource> source, std::string backend, backend::BackendOptions options, double fps,
                         ViewStyle style)
    : ViewSession(Listening{}, source->info().sensor, std::move(backend), std::move(options), fps, style) {
  source_ = std::move(source);
}

ViewSession::ViewSession(Listening, SensorSize sensor, std::string backend, backend::BackendOptions options, double fps, ViewStyle style)
    : backend_name_(std::move(backend)),
      options_(std::move(options)),
      renderer_(sensor, style),
      period_us_(static_cast<TimeUs>(std::llround(1e6 / fps))) {
  options_.sensor = sensor;
  backend_ = backend::make_backend(backend_name_, options_);
  sink_ = std::make_unique<Sink>(renderer_);
}

ViewSession::~ViewSession() = default;

void ViewSession::switch_backend(const std::string& name) {
  auto next = backend::make_backend(name, options_);
  backend_->finish(*sink_);
  sink_->latency_.forget_waiting();
  backend_ = std::move(next);
  backend_name_ = name;
}

// Pushes every pending event with t <= t to the backend, reading more as needed; stops at the
// first later event (kept pending) or at the end of the source.
void ViewSession::push_until(TimeUs t) {
  for (;;) {
    if (pending_at_ == pending_.size()) {
      pending_.resize(4096);
      const size_t n = source_->read(pending_);
      pending_.resize(n);
      pending_at_ = 0;
      const auto arrivals = source_->arrivals();
      pending_arrival_.assign(arrivals.begin(), arrivals.end());
      if (n == 0) {
        ended_ = true;
        return;
      }
      if (!started_) t_first_ = pending_[0].t, started_ = true;
    }
    size_t end = pending_at_;
    while (end < pending_.size() && pending_[end].t <= t) ++end;
    if (end > pending_at_) {
      if (!pending_arrival_.empty()) sink_->latency_.arrived(std::span(pending_arrival_).subspan(pending_at_, end - pending_at_));
      const auto pushed = std::span(pending_).subspan(pending_at_, end - pending_at_);
      backend_->push(pushed, *sink_);
      last_pushed_t_ = std::max(last_pushed_t_, pushed.back().t);
      if (labels_on_board()) {
        for (const Event& e : pushed) renderer_.add(LabelledEvent{e, kNoiseLabel});
      }
      pending_at_ = end;
    }
    if (pending_at_ < pending_.size()) return;
  }
}

bool ViewSession::advance() {
  if (listening()) {
    // A frame's period of wall clock: the board's time runs as its sensor's does.
    backend_->listen(*sink_, static_cast<int>(std::lround(static_cast<double>(period_us_) * 1e-3)));
    ++frame_;
    if (!started_ && sink_->latest_t_ > 0) t_first_ = sink_->latest_t_, started_ = true;
    frame_t_ = std::max(frame_t_, sink_->latest_t_);
    return true;
  }
  if (ended_) return false;
  if (!started_) {
    push_until(-1);  // reads the first batch: the first frame is at the first event's time
    if (ended_) {
      backend_->finish(*sink_);
      ++frame_;
      return false;
    }
  }
  ++frame_;
  const TimeUs previous_frame_t = frame_t_;
  frame_t_ = t_first_ + frame_ * period_us_;
  push_until(frame_t_);
  if (ended_) {
    backend_->finish(*sink_);
    // The last frame is at the recording's last event, not up to a frame period past it: a
    // recording shorter than the events' window would otherwise end on a frame with none of them.
    frame_t_ = std::max(previous_frame_t, std::min(frame_t_, last_pushed_t_));
    return false;
  }
  return true;
}

const eval::LatencyHistogram& ViewSession::latency() const { return sink_->latency_.histogram(); }
std::int64_t ViewSession::events() const {
  if (!labels_on_board()) return sink_->events_;
  const backend::BackendStats s = backend_->stats();
  return s.board_labelled + s.board_noise;
}

void ViewSession::render(Canvas& canvas) {
  char line[96];
  std::vector<std::string> overlay;
  overlay.push_back("backend " + backend_name_);
  std::snprintf(line, sizeof line, "t %.2f s", static_cast<double>(frame_t_ - t_first_) * 1e-6);
  overlay.emplace_back(line);
  // Events per second over the last second of sensor time.
  const std::int64_t labelled = events();
  history_.emplace_back(frame_t_, labelled);
  while (history_.size() > 1 && history_.front().first < frame_t_ - 1000000) history_.pop_front();
  const double span_s = static_cast<double>(frame_t_ - history_.front().first) * 1e-6;
  const double rate = span_s > 0 ? static_cast<double>(labelled - history_.front().second) / span_s : 0.0;
  std::snprintf(line, sizeof line, "events/s %.0f", rate);
  overlay.emplace_back(line);
  std::snprintf(line, sizeof line, "clusters %d", sink_->clusters_);
  overlay.emplace_back(line);
  if (const auto& l = latency(); l.count() > 0) {
    std::snprintf(line, sizeof line, "latency p50 %.1f ms p99 %.1f ms", l.quantile_us(0.5) * 1e-3, l.quantile_us(0.99) * 1e-3);
    overlay.emplace_back(line);
  }
  if (source_) {
    std::snprintf(line, sizeof line, "dropped %lld", static_cast<long long>(source_->dropped()));
    overlay.emplace_back(line);
  } else {
    overlay.emplace_back("listening to the AER pins of the board");
  }
  if (auto* control = dynamic_cast<read::PlaybackControl*>(source_.get())) {
    std::snprintf(line, sizeof line, "speed %gx", control->speed());
    overlay.emplace_back(line);
  }
  renderer_.render(frame_t_, canvas, overlay);
}

}  // namespace evms::show
