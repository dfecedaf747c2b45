// A Verilated board top (evms_board) with its UART driven and read bit by bit, and its AER
// pins reachable: the "virtual board" behind the board backend's tests and the pseudo-terminal
// bridge. Bytes queued with send() go out on the board's receive line at CLKS_PER_BIT clocks a
// bit; bytes the board transmits are sampled mid-bit into received.
#pragma once

#include <verilated.h>

#include <cstdint>
#include <deque>
#include <memory>
#include <span>

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
    for (int i = 0; i < 4; ++i) tick();
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

}  // namespace evms::sim
