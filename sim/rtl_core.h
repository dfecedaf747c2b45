// Drives a Verilated evms_core (one per core build, prefix Vcore_<build>) through its
// valid/ready streams: words in, labelled events, track updates and packet summaries out.
// Output readies follow a seeded random pattern (backpressure); with ready_probability 1
// they are always ready. A trace (FST) is written when a path is given.
#pragma once

#include <verilated.h>
#include <verilated_fst_c.h>

#include <array>
#include <cstdint>
#include <deque>
#include <memory>
#include <stdexcept>
#include <string>

#include "hls/core/config.h"
#include "hls/core/words.h"
#include "sim/cfg_ports.h"
#include "sim/rtl_profile.h"

namespace evms::sim {

template <class V>
class RtlCore {
 public:
  RtlCore(const hls::Config& cfg, std::uint64_t seed = 1, double ready_probability = 1.0, const std::string& trace_path = "")
      : ctx_(std::make_unique<VerilatedContext>()), rng_(seed | 1), ready_p_(ready_probability) {
    ctx_->traceEverOn(!trace_path.empty());
    top_ = std::make_unique<V>(ctx_.get());
    if (!trace_path.empty()) {
      trace_ = std::make_unique<VerilatedFstC>();
      top_->trace(trace_.get(), 99);
      trace_->open(trace_path.c_str());
    }
    configure(cfg);
    top_->rst_n = 0;
    top_->clk = 0;
    for (int i = 0; i < 4; ++i) tick();
    top_->rst_n = 1;
    // The filter clears its memory after reset.
    while (!top_->in_ready) tick();
    state_cycles_ = {};
  }
  ~RtlCore() {
    if (trace_) trace_->close();
    top_->final();
  }
  RtlCore(const RtlCore&) = delete;
  RtlCore& operator=(const RtlCore&) = delete;

  // Offers a word and ticks until the core takes it, collecting outputs meanwhile.
  void push(const hls::EventWord& w) {
    top_->in_valid = 1;
#define EVMS_DRIVE_FIELD(name, type, bits, reset) top_->in_##name = w.name;
    EVMS_EVENT_WORD_FIELDS(EVMS_DRIVE_FIELD)
#undef EVMS_DRIVE_FIELD
    accepted_ = false;
    std::uint64_t guard = 0;
    while (!accepted_) {
      tick();
      if (++guard > kStallLimit) throw std::runtime_error("evms_core did not take an input word for " + std::to_string(kStallLimit) + " cycles");
    }
    top_->in_valid = 0;
  }

  // Ticks until the core is idle with nothing left to send.
  void settle() {
    std::uint64_t quiet = 0, guard = 0;
    while (quiet < 64) {
      tick();
      const bool busy = !top_->idle || top_->lab_valid || top_->trk_valid || top_->pkt_valid;
      quiet = busy ? 0 : quiet + 1;
      if (++guard > kStallLimit) throw std::runtime_error("evms_core did not settle");
    }
  }

  std::deque<hls::LabelWord> labels;
  std::deque<hls::TrackWord> tracks;
  std::deque<hls::PacketWord> packets;
  std::uint64_t cycles() const { return cycles_; }
  // Cycles spent in each state of the core's controller (hls/core/schedule.h,
  // EVMS_CORE_CONTROLLER_STATES, then the idle state's waits for the intake); idle cycles with
  // no word offered or in the intake are not counted.
  const StateCycles& state_cycles() const { return state_cycles_; }
  std::int32_t tracks_started() const { return static_cast<std::int32_t>(top_->stat_tracks_started); }
  std::int64_t unassigned() const { return top_->stat_unassigned; }

 private:
  static constexpr std::uint64_t kStallLimit = 200000000;

  // Every register of the RTL core (hls/core/registers.h) to its cfg_ port.
  void configure(const hls::Config& c) { set_cfg_ports(*top_, c); }

  bool ready_draw() {
    if (ready_p_ >= 1.0) return true;
    rng_ ^= rng_ << 13;
    rng_ ^= rng_ >> 7;
    rng_ ^= rng_ << 17;
    return static_cast<double>(rng_ >> 11) * 0x1.0p-53 < ready_p_;
  }

  // One clock. Handshakes complete at the rising edge: sample them just before it.
  void tick() {
    top_->lab_ready = ready_draw();
    top_->trk_ready = ready_draw();
    top_->pkt_ready = ready_draw();
    top_->clk = 0;
    top_->eval();
    if (trace_) trace_->dump(ctx_->time());
    const unsigned state = top_->rootp->evms_core__DOT__state_q;
    if (state >= hls::kControllerStates) throw std::runtime_error("evms_core entered state " + std::to_string(state) + ", which hls/core/schedule.h does not list");
    if (state != 0) {
      ++state_cycles_[state];
    } else if (top_->rootp->evms_core__DOT__q_valid) {
      ++state_cycles_[0];
    } else if (top_->in_valid || !top_->rootp->evms_core__DOT__intake_empty) {
      ++state_cycles_[kWaitingForIntake];
    }
    ctx_->timeInc(1);
    if (top_->in_valid && top_->in_ready) accepted_ = true;
    if (top_->lab_valid && top_->lab_ready) {
      hls::LabelWord l;
#define EVMS_TAKE_FIELD(name, type, bits, reset) l.name = static_cast<type>(top_->lab_##name);
      EVMS_LABEL_WORD_FIELDS(EVMS_TAKE_FIELD)
#undef EVMS_TAKE_FIELD
      labels.push_back(l);
    }
    if (top_->trk_valid && top_->trk_ready) {
      hls::TrackWord w;
#define EVMS_TAKE_FIELD(name, type, bits, reset) w.name = static_cast<type>(top_->trk_##name);
      EVMS_TRACK_WORD_FIELDS(EVMS_TAKE_FIELD)
#undef EVMS_TAKE_FIELD
      tracks.push_back(w);
    }
    if (top_->pkt_valid && top_->pkt_ready) {
      hls::PacketWord w;
#define EVMS_TAKE_FIELD(name, type, bits, reset) w.name = static_cast<type>(top_->pkt_##name);
      EVMS_PACKET_WORD_FIELDS(EVMS_TAKE_FIELD)
#undef EVMS_TAKE_FIELD
      packets.push_back(w);
    }
    top_->clk = 1;
    top_->eval();
    if (trace_) trace_->dump(ctx_->time());
    ctx_->timeInc(1);
    ++cycles_;
  }

  std::unique_ptr<VerilatedContext> ctx_;
  std::unique_ptr<V> top_;
  std::unique_ptr<VerilatedFstC> trace_;
  std::uint64_t rng_;
  double ready_p_;
  bool accepted_ = false;
  std::uint64_t cycles_ = 0;
  StateCycles state_cycles_{};
};

}  // namespace evms::sim
