// A Verilated board top (evms_board) with its UART driven and read bit by bit, and its AER
// pins reachable: the "virtual board" behind the board backend's tests and the pseudo-terminal
// bridge. Bytes queued with send() go out on the board's receive line at CLKS_PER_BIT clocks a
// bit; bytes the board transmits are sampled mid-bit into received. An AerSender plays a
// sensor's side of the AER handshake.
#pragma once

#include <verilated.h>

#include <algorithm>
#include <cstdint>
#include <deque>
#include <memory>
#include <span>
#include <vector>

namespace evms::sim {

template <class V>
class VirtualBoard {
 public:
  explicit VirtualBoard(int clks_per_bit) : ctx_(std::make_unique<VerilatedContext>()), cpb_(clks_per_bit) {
    top_ = std::make_unique<V>(ctx_.get());
    top_->uart_rx = 1;
    top_->aer_req_n = 1;
    top_->aer_addr = 0;
    top_->rst_n = 0;
    for (std::uint64_t i = 0; i < kResetCycles; ++i) tick();
    top_->rst_n = 1;
  }
  ~VirtualBoard() { top_->final(); }
  VirtualBoard(const VirtualBoard&) = delete;
  VirtualBoard& operator=(const VirtualBoard&) = delete;

  void send(std::span<const std::uint8_t> bytes) { to_board_.insert(to_board_.end(), bytes.begin(), bytes.end()); }
  bool sending() const { return !to_board_.empty() || tx_bit_ >= 0; }
  void run(std::uint64_t cycles) {
    for (std::uint64_t i = 0; i < cycles; ++i) tick();
  }
  V& pins() { return *top_; }
  std::uint64_t cycles() const { return cycles_; }

  std::deque<std::uint8_t> received;
  static constexpr std::uint64_t kResetCycles = 4;  // the constructor's, before the board's clocks count

  void tick() {
    drive_rx();
    top_->clk = 0;
    top_->eval();
    top_->clk = 1;
    top_->eval();
    sample_tx();
    ++cycles_;
  }

 private:
  // Host -> board: start bit, 8 data bits LSB first, stop bit.
  void drive_rx() {
    if (tx_bit_ < 0) {
      if (to_board_.empty()) {
        top_->uart_rx = 1;
        return;
      }
      tx_byte_ = to_board_.front();
      to_board_.pop_front();
      tx_bit_ = 0;
      tx_count_ = 0;
    }
    top_->uart_rx = tx_bit_ == 0 ? 0 : (tx_bit_ <= 8 ? (tx_byte_ >> (tx_bit_ - 1)) & 1 : 1);
    if (++tx_count_ == cpb_) {
      tx_count_ = 0;
      if (++tx_bit_ == 10) tx_bit_ = -1;
    }
  }
  // Board -> host: wait for a start bit, then sample every bit in its middle.
  void sample_tx() {
    const int line = top_->uart_tx;
    if (rx_bit_ < 0) {
      if (line == 0) {
        rx_bit_ = 0;
        rx_count_ = cpb_ / 2;
        rx_byte_ = 0;
      }
      return;
    }
    if (--rx_count_ > 0) return;
    rx_count_ = cpb_;
    if (rx_bit_ >= 1 && rx_bit_ <= 8) rx_byte_ |= static_cast<std::uint8_t>(line << (rx_bit_ - 1));
    if (rx_bit_ == 9) {
      if (line == 1) received.push_back(rx_byte_);
      rx_bit_ = -1;
      return;
    }
    ++rx_bit_;
  }

  std::unique_ptr<VerilatedContext> ctx_;
  std::unique_ptr<V> top_;
  int cpb_;
  std::deque<std::uint8_t> to_board_;
  int tx_bit_ = -1, tx_count_ = 0;
  std::uint8_t tx_byte_ = 0;
  int rx_bit_ = -1, rx_count_ = 0;
  std::uint8_t rx_byte_ = 0;
  std::uint64_t cycles_ = 0;
};

// A DVS128's side of the AER handshake (rtl/board/evms_aer_rx.sv): every event is requested
// in the microsecond it is due, or, when the board is still acknowledging the one before, in
// the first microsecond after. One request a microsecond at most (a sensor's 1 M events/s),
// a quarter into it, so that the board's microsecond stamp is the microsecond of the request:
// stamp() gives it. drive() goes before each clock, with the board's cycle count.
class AerSender {
 public:
  struct Event {
    std::uint32_t t_us;  // due, in the board's microseconds since its reset
    std::uint16_t x, y;  // 7 bits each (the DVS128's address)
    std::uint8_t p;
  };
  AerSender(std::vector<Event> events, int ticks_per_us) : events_(std::move(events)), ticks_per_us_(ticks_per_us), stamps_(events_.size()) {}

  template <class V>
  void drive(V& pins, std::uint64_t cycle) {
    const std::uint64_t since_reset = cycle - VirtualBoard<V>::kResetCycles;
    switch (phase_) {
      case Phase::kIdle: {
        const std::uint64_t us = since_reset / static_cast<std::uint64_t>(ticks_per_us_);
        if (next_ >= events_.size() || since_reset % ticks_per_us_ != static_cast<std::uint64_t>(ticks_per_us_ / 4) ||
            us < events_[next_].t_us || us == last_us_) {
          return;
        }
        const Event& e = events_[next_];
        pins.aer_addr = static_cast<std::uint16_t>(((e.y & 0x7F) << 8) | ((e.x & 0x7F) << 1) | (e.p & 1));
        pins.aer_req_n = 0;
        stamps_[next_] = static_cast<std::uint32_t>(us);
        max_lag_us_ = std::max<std::uint64_t>(max_lag_us_, us - e.t_us);
        last_us_ = us;
        phase_ = Phase::kRequested;
        return;
      }
      case Phase::kRequested:
        if (!pins.aer_ack_n) pins.aer_req_n = 1, phase_ = Phase::kReleased;
        return;
      case Phase::kReleased:
        if (pins.aer_ack_n) ++next_, phase_ = Phase::kIdle;
        return;
    }
  }
  bool done() const { return next_ == events_.size(); }
  size_t sent() const { return next_; }
  // The board's stamp of event i: the microsecond of its request.
  std::uint32_t stamp(size_t i) const { return stamps_[i]; }
  // How long the most delayed event waited past its due microsecond.
  std::uint64_t max_lag_us() const { return max_lag_us_; }

 private:
  enum class Phase { kIdle, kRequested, kReleased };
  std::vector<Event> events_;
  int ticks_per_us_;
  std::vector<std::uint32_t> stamps_;
  size_t next_ = 0;
  std::uint64_t last_us_ = UINT64_MAX, max_lag_us_ = 0;
  Phase phase_ = Phase::kIdle;
};

}  // namespace evms::sim
