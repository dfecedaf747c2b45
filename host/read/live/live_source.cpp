#include "host/read/live/live_source.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>

namespace evms::read {

std::int64_t steady_now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

namespace {
std::atomic<bool> g_end_requested{false};
static_assert(std::atomic<bool>::is_always_lock_free, "end_live_sources() must be async-signal-safe");
}  // namespace

void end_live_sources() noexcept { g_end_requested.store(true); }

LiveBuffer::LiveBuffer(size_t capacity) : events_(std::max<size_t>(capacity, 1)), arrival_(events_.size()) {}

void LiveBuffer::push(std::span<const Event> events, std::int64_t arrival_ns) {
  {
    std::lock_guard lock(mutex_);
    // Once the sources are ended, what arrives is past the input's end, not a drop: a source
    // that never falls quiet (a camera watching a busy scene, a replay) ends here.
    if (g_end_requested.load()) {
      closed_ = true;
    } else {
      const size_t room = events_.size() - size_;
      const size_t n = std::min(room, events.size());
      for (size_t i = 0; i < n; ++i) {
        const size_t at = (head_ + size_ + i) % events_.size();
        events_[at] = events[i];
        arrival_[at] = arrival_ns;
      }
      size_ += n;
      dropped_ += static_cast<std::int64_t>(events.size() - n);
    }
  }
  ready_.notify_one();
}

void LiveBuffer::close() {
  {
    std::lock_guard lock(mutex_);
    closed_ = true;
  }
  ready_.notify_all();
}

void LiveBuffer::fail(const std::string& message) {
  {
    std::lock_guard lock(mutex_);
    if (error_.empty()) error_ = message;
    closed_ = true;
  }
  ready_.notify_all();
}

bool LiveBuffer::wait_for_consumer(const std::stop_token& stop) {
  std::unique_lock lock(mutex_);
  // Polled, as a stop request and end_live_sources() notify no one.
  while (!ready_.wait_for(lock, std::chrono::milliseconds(10), [&] { return consumer_asked_; })) {
    if (stop.stop_requested() || g_end_requested.load()) return false;
  }
  return true;
}

size_t LiveBuffer::pop(std::span<Event> out, std::span<std::int64_t> arrival_ns) {
  std::unique_lock lock(mutex_);
  if (!consumer_asked_) consumer_asked_ = true, ready_.notify_all();
  // A signal handler cannot notify a condition variable, so waits poll for end_live_sources().
  while (!ready_.wait_for(lock, std::chrono::milliseconds(100), [&] { return size_ > 0 || closed_; })) {
    if (g_end_requested.load()) return 0;
  }
  // Events that came before a failure are still delivered; the error comes after them.
  if (size_ == 0 && !error_.empty()) throw InputError(error_);
  const size_t n = std::min({size_, out.size(), arrival_ns.size()});
  for (size_t i = 0; i < n; ++i) {
    out[i] = events_[head_];
    arrival_ns[i] = arrival_[head_];
    head_ = (head_ + 1) % events_.size();
  }
  size_ -= n;
  return n;
}

bool LiveBuffer::ready_within(int wait_ms) {
  std::unique_lock lock(mutex_);
  if (!consumer_asked_) consumer_asked_ = true, ready_.notify_all();
  return ready_.wait_for(lock, std::chrono::milliseconds(wait_ms), [&] { return size_ > 0 || closed_ || g_end_requested.load(); });
}

std::int64_t LiveBuffer::dropped() const {
  std::lock_guard lock(mutex_);
  return dropped_;
}

LiveSource::LiveSource(size_t capacity) : buffer_(capacity) {}

LiveSource::~LiveSource() { stop(); }

void LiveSource::start() {
  thread_ = std::jthread([this](std::stop_token stop) {
    try {
      produce(stop);
      buffer_.close();
    } catch (const std::exception& e) {
      buffer_.fail(e.what());
    }
  });
}

void LiveSource::stop() {
  if (thread_.joinable()) {
    thread_.request_stop();
    thread_.join();
  }
}

size_t LiveSource::read(std::span<Event> out) {
  arrivals_.resize(out.size());
  const size_t n = buffer_.pop(out, arrivals_);
  arrivals_.resize(n);
  return n;
}

std::vector<std::pair<std::string, std::int64_t>> LiveSource::skipped() const {
  std::lock_guard lock(skipped_mutex_);
  return skipped_;
}

void LiveSource::count_skipped(const std::string& kind, std::int64_t n) {
  std::lock_guard lock(skipped_mutex_);
  for (auto& [k, count] : skipped_) {
    if (k == kind) {
      count += n;
      return;
    }
  }
  skipped_.emplace_back(kind, n);
}

namespace {

class RealtimeReplay final : public LiveSource, public PlaybackControl {
 public:
  RealtimeReplay(std::unique_ptr<EventSource> inner, double speed, size_t capacity)
      : LiveSource(capacity), inner_(std::move(inner)), speed_(speed), requested_speed_(speed) {
    info_ = inner_->info();
    info_.format += ", replayed at " + format_speed(speed) + "x real time";
    start();
  }
  ~RealtimeReplay() override { stop(); }

  void set_speed(double speed) override {
    if (speed > 0 && std::isfinite(speed)) requested_speed_.store(speed);
  }
  double speed() const override { return requested_speed_.load(); }
  void set_paused(bool paused) override { paused_.store(paused); }

 private:
  static std::string format_speed(double s) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", s);
    return buf;
  }

  // Hands events over in slices of at most 100 us of sensor time, each when the wall clock
  // reaches its last timestamp (scaled by the speed). A pause or a change of speed restarts the
  // pacing from where the replay is. The pacing starts when the reader first asks for events, so
  // that what the reader does before (build a backend, open a window) does not count against it.
  void produce(std::stop_token stop) override {
    using clock = std::chrono::steady_clock;
    if (!buffer_.wait_for_consumer(stop)) return;
    std::vector<Event> batch(4096);
    bool started = false;
    TimeUs t0 = 0;
    clock::time_point wall0;
    while (!stop.stop_requested()) {
      const size_t n = inner_->read(batch);
      if (n == 0) return;
      size_t from = 0;
      while (from < n && !stop.stop_requested()) {
        if (paused_.load() || requested_speed_.load() != speed_) {
          while (paused_.load() && !stop.stop_requested()) std::this_thread::sleep_for(std::chrono::milliseconds(10));
          speed_ = requested_speed_.load();
          started = false;
        }
        if (!started) t0 = batch[from].t, wall0 = clock::now(), started = true;
        size_t to = from + 1;
        while (to < n && batch[to].t - batch[from].t < 100) ++to;
        const double due_s = static_cast<double>(batch[to - 1].t - t0) * 1e-6 / speed_;
        std::this_thread::sleep_until(wall0 + std::chrono::duration_cast<clock::duration>(std::chrono::duration<double>(due_s)));
        buffer_.push(std::span(batch).subspan(from, to - from), steady_now_ns());
        from = to;
      }
    }
  }

  std::unique_ptr<EventSource> inner_;
  double speed_;
  std::atomic<double> requested_speed_;
  std::atomic<bool> paused_{false};
};

}  // namespace

std::unique_ptr<EventSource> replay_in_real_time(std::unique_ptr<EventSource> inner, double speed, size_t capacity) {
  if (!(speed > 0) || !std::isfinite(speed)) throw std::invalid_argument("--speed must be a positive number");
  return std::make_unique<RealtimeReplay>(std::move(inner), speed, capacity);
}

}  // namespace evms::read
