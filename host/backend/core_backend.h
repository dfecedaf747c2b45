// What every backend built on the core shares: mapping evms events to core words (times
// relative to the first event, modulo 2^32) and core output words back to labelled events and
// track updates. The fixed backend runs the C++ core; the rtl and board backends run the same
// words through the Verilated RTL or a serial link.
#pragma once

#include <cmath>
#include <deque>
#include <span>
#include <vector>

#include "host/backend/backend.h"
#include "host/backend/core_config.h"
#include "hls/core/words.h"

namespace evms::backend {

template <class S>
class CoreWordMapper {
 public:
  hls::EventWord to_word(const Event& e) {
    // Core time starts at 1 or later: the filter's memory reserves 0 for "never fired". The
    // offset is a whole number of 2^16 us, so that core time keeps the host's phase within the
    // filter's 16-bit stamps and its 2^15 us noise intervals: a board's own stamps (its AER
    // pins) and the same events read back from a file then give the same words' results.
    if (!started_) base_ = ((e.t - 1) >> 16) << 16, started_ = true;
    latest_ = e.t;
    pending_.push_back(e);
    return {static_cast<std::uint32_t>(e.t - base_), e.x, e.y, e.p, false};
  }
  // An event that entered at the board's AER pins, as the board stamped it: kept for its label
  // like to_word's, at the board's microsecond (its 32-bit counter widened past its wrap).
  void stamped(const hls::EventWord& w) {
    const TimeUs t = started_ ? latest_ + static_cast<std::int32_t>(w.t - static_cast<std::uint32_t>(latest_)) : TimeUs{w.t};
    started_ = true;
    latest_ = t;
    pending_.push_back({t, w.x, w.y, w.p});
  }
  // The oldest event not yet labelled, with its label; the word must be its echo.
  LabelledEvent label(const hls::LabelWord& w) {
    const Event e = pending_.front();
    pending_.pop_front();
    if (w.x != e.x || w.y != e.y || w.t != static_cast<std::uint32_t>(e.t - base_)) {
      throw std::logic_error("core returned labels out of order");
    }
    return {e, w.label};
  }
  // The oldest event not yet labelled, whose label was lost on the way (the board backend).
  LabelledEvent lost() {
    const Event e = pending_.front();
    pending_.pop_front();
    return {e, kLabelLostOnLink};
  }
  // The oldest event not yet labelled, whose label stays where it was made (a board in tracks mode).
  void forget_oldest() { pending_.pop_front(); }
  TimeUs to_time(std::uint32_t core_t) const {
    const std::uint32_t latest = static_cast<std::uint32_t>(latest_ - base_);
    return latest_ - static_cast<std::int32_t>(latest - core_t);
  }
  TrackUpdate track(const hls::TrackWord& w) const {
    const double cov = std::ldexp(1.0, -S::kCovFrac);
    return {to_time(w.t), w.id, core_px<S>(w.x), core_px<S>(w.y), core_px_per_s<S>(w.vx), core_px_per_s<S>(w.vy),
            core_px<S>(w.zx), core_px<S>(w.zy), w.confirmed ? TrackState::kConfirmed : TrackState::kTentative,
            static_cast<std::int32_t>(w.events), w.x_min, w.y_min, w.x_max, w.y_max, static_cast<double>(w.var_x) * cov, 0.0,
            static_cast<double>(w.var_y) * cov};
  }
  PacketSummary packet(const hls::PacketWord& w) const {
    return {to_time(w.t_first), to_time(w.t_last), w.events, w.clusters, w.iterations};
  }
  size_t waiting() const { return pending_.size(); }

 private:
  bool started_ = false;
  TimeUs base_ = 0, latest_ = 0;
  std::deque<Event> pending_;
};

// A run's words for the core: each event's, as CoreWordMapper makes them, then the flush that
// closes the last packet (the cycle model, the RTL's cycles and the vector testbench take these).
template <class S>
std::vector<hls::EventWord> core_words_of(std::span<const Event> events) {
  CoreWordMapper<S> mapper;
  std::vector<hls::EventWord> words;
  words.reserve(events.size() + 1);
  for (const Event& e : events) words.push_back(mapper.to_word(e));
  hls::EventWord flush;
  flush.flush = true;
  words.push_back(flush);
  return words;
}

// Statistics every core backend counts from its output words.
struct CoreStats {
  BackendStats s;
  void on_packet(const hls::PacketWord& w) {
    ++s.packets;
    s.events_kept += w.events;
    s.clusters += w.clusters;
    s.iterations += w.iterations;
  }
};

}  // namespace evms::backend
