// Sources that run on their own clock: a camera over USB, a UDP stream, a file replayed in
// real time. A producer thread decodes events as they arrive and appends them to a bounded
// buffer; the consumer (the backend's loop) takes them out with read(). When the consumer
// falls behind and the buffer is full, new events are dropped and counted, never blocked on:
// the camera does not wait.
//
// Each event carries its arrival time on the host (steady clock), so that the latency from
// arrival to label can be measured downstream.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <span>
#include <stop_token>
#include <string>
#include <thread>
#include <vector>

#include "host/read/event_source.h"

namespace evms::read {

// Nanoseconds on the steady clock.
std::int64_t steady_now_ns();

// Ends every live source as if its input had ended: what is buffered is still delivered,
// then read() returns 0. Safe to call from a signal handler (Ctrl-C in evms run).
void end_live_sources() noexcept;

// A bounded FIFO of events between one producer and one consumer thread.
class LiveBuffer {
 public:
  explicit LiveBuffer(size_t capacity);

  // Producer side. Appends what fits, stamped `arrival_ns`; the rest is dropped and counted.
  void push(std::span<const Event> events, std::int64_t arrival_ns);
  void close();                          // no more events will come
  void fail(const std::string& message); // the producer failed; read() reports it
  // Waits until the consumer first asks for events (pop or ready_within), or `stop`, or the
  // sources' end; whether the consumer asked.
  bool wait_for_consumer(const std::stop_token& stop);

  // Consumer side. Waits for at least one event (or the end) and takes up to out.size();
  // returns 0 only at the end. Throws InputError with the producer's message when it failed.
  size_t pop(std::span<Event> out, std::span<std::int64_t> arrival_ns);
  // Waits up to `wait_ms` for at least one event or the end; whether either came.
  bool ready_within(int wait_ms);

  std::int64_t dropped() const;

 private:
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::vector<Event> events_;
  std::vector<std::int64_t> arrival_;
  size_t head_ = 0, size_ = 0;
  bool closed_ = false;
  bool consumer_asked_ = false;
  std::string error_;
  std::int64_t dropped_ = 0;
};

// Base of every live source: owns the buffer and the producer thread. A subclass starts the
// thread with start() at the end of its constructor and calls stop() first in its destructor,
// so that the thread never outlives the members it uses.
class LiveSource : public EventSource {
 public:
  const SourceInfo& info() const override { return info_; }
  size_t read(std::span<Event> out) override;
  std::span<const std::int64_t> arrivals() const override { return arrivals_; }
  std::int64_t dropped() const override { return buffer_.dropped(); }
  bool ready_within(int wait_ms) override { return buffer_.ready_within(wait_ms); }
  std::vector<std::pair<std::string, std::int64_t>> skipped() const override;

 protected:
  explicit LiveSource(size_t capacity);
  ~LiveSource() override;
  void start();
  void stop();
  // Runs on the producer thread until the input ends or `stop` is requested; feeds buffer_.
  virtual void produce(std::stop_token stop) = 0;
  void count_skipped(const std::string& kind, std::int64_t n = 1);

  SourceInfo info_;
  LiveBuffer buffer_;

 private:
  std::vector<std::int64_t> arrivals_;
  mutable std::mutex skipped_mutex_;
  std::vector<std::pair<std::string, std::int64_t>> skipped_;
  std::jthread thread_;
};

// The controls a viewer has over a replay: pause it and change its speed.
class PlaybackControl {
 public:
  virtual ~PlaybackControl() = default;
  virtual void set_speed(double speed) = 0;
  virtual double speed() const = 0;
  virtual void set_paused(bool paused) = 0;
};

// Replays `inner` at `speed` times the pace of its timestamps, from a thread of its own, into
// a buffer of `capacity` events: the paper's speed-factor runs. The pace starts at the
// consumer's first read. Events the consumer has no room for are dropped and counted.
std::unique_ptr<EventSource> replay_in_real_time(std::unique_ptr<EventSource> inner, double speed, size_t capacity);

}  // namespace evms::read
