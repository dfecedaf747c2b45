// The board's UART receiver (rtl/board/evms_uart_rx.sv) against a sender that is not on its
// clock: a host's UART whose first start bit begins at any phase of the board's clock and whose
// bits last a little more or a little less than ClksPerBit of its clocks (two crystals, a
// baud-rate divider). The virtual board (sim/virtual_board.h) sends on the board's clock edges
// and cannot show where within a bit the receiver samples; here the line is a waveform in
// continuous time, read at each clock edge. The model is built at the iCEBreaker's clocks a bit
// (sim/CMakeLists.txt), the fewest of the boards'. The seed is printed (EVMS_SEED=N repeats a run).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "Vuart_rx.h"
#include "sim/verilated_block.h"

namespace evms {
namespace {

constexpr int kClksPerBit = EVMS_UART_ClksPerBit;

// The line as levels from given times on (in board clocks, rising), high before the first.
struct Waveform {
  std::vector<std::pair<double, int>> levels;
  double end = 0;
  void hold(double from, int level) { levels.emplace_back(from, level), end = std::max(end, from); }
  // One 8N1 frame from `start`, each bit `bit_clocks` long: start bit, 8 data bits LSB first, stop bit.
  void frame(std::uint8_t byte, double start, double bit_clocks, bool stop_bit = true) {
    hold(start, 0);
    for (int k = 0; k < 8; ++k) hold(start + (1 + k) * bit_clocks, (byte >> k) & 1);
    hold(start + 9 * bit_clocks, stop_bit ? 1 : 0);
    hold(start + 10 * bit_clocks, 1);
  }
};

struct Received {
  std::vector<std::uint8_t> bytes;
  std::uint32_t framing_errors = 0;
};

// Plays the waveform into the receiver, reading the line at every clock edge; with `trace`, an
// FST trace of the run goes there.
Received play(const Waveform& line, const std::string& trace = "") {
  sim::VerilatedBlock<Vuart_rx> rx(trace);
  Received got;
  size_t next = 0;
  int level = 1;
  for (std::int64_t n = 0; n < static_cast<std::int64_t>(line.end) + 4 * kClksPerBit; ++n) {
    while (next < line.levels.size() && line.levels[next].first <= static_cast<double>(n)) level = line.levels[next++].second;
    rx->rx = static_cast<std::uint8_t>(level);
    rx.tick();
    if (rx->valid) got.bytes.push_back(rx->data);
  }
  got.framing_errors = rx->framing_errors;
  return got;
}

// What `got` lacks of `sent`: the framing errors, or the first byte that differs; empty when
// every byte arrived.
std::string difference(const Received& got, const std::vector<std::uint8_t>& sent) {
  if (got.framing_errors != 0) return std::to_string(got.framing_errors) + " framing errors";
  for (size_t i = 0; i < sent.size(); ++i) {
    if (i >= got.bytes.size()) return "byte " + std::to_string(i) + " of " + std::to_string(sent.size()) + " never arrived";
    if (got.bytes[i] != sent[i]) return "byte " + std::to_string(i) + ": sent " + std::to_string(sent[i]) + ", received " + std::to_string(got.bytes[i]);
  }
  return got.bytes.size() == sent.size() ? "" : std::to_string(got.bytes.size() - sent.size()) + " bytes more than were sent";
}

TEST(UartRx, EveryByteArrivesAtAnyPhaseAndWithinTwoPercentOfTheRate) {
  const std::uint64_t seed = sim::cosim_seed();
  std::mt19937_64 rng(seed);
  // Within a bit, the receiver's sample sits within a clock of the bit's middle; over the ten
  // bits of a frame a sender 2 % fast or slow moves the middle by a fifth of a bit.
  for (const double rate : {0.98, 0.99, 1.0, 1.01, 1.02}) {
    for (int sixteenth = 0; sixteenth < 16; ++sixteenth) {
      const double bit_clocks = kClksPerBit / rate;
      // Random bytes, mostly back to back, some after up to three idle bits.
      Waveform line;
      std::vector<std::uint8_t> sent;
      double start = 5 + sixteenth / 16.0;
      for (int i = 0; i < 48; ++i) {
        sent.push_back(static_cast<std::uint8_t>(rng()));
        line.frame(sent.back(), start, bit_clocks);
        start += 10 * bit_clocks + (rng() % 4 == 0 ? static_cast<double>(rng() % 4) * bit_clocks : 0.0);
      }
      const std::string what = "sender at " + std::to_string(rate) + " of the board's rate, phase " + std::to_string(sixteenth) + "/16 of a clock";
      EXPECT_EQ(sim::mismatch_traced("uart_rx", seed, what, difference(play(line), sent), [&](const std::string& trace) { play(line, trace); }), "");
    }
  }
}

TEST(UartRx, ALowStopBitIsAFramingErrorAndAGlitchNoStartBit) {
  const double bit = kClksPerBit;
  Waveform line;
  line.frame(0x5A, 5.5, bit, false);
  // The line low for less than a third of a bit is a glitch, not a start bit.
  line.hold(5.5 + 12 * bit, 0);
  line.hold(5.5 + 12.3 * bit, 1);
  line.frame(0xC3, 5.5 + 14 * bit, bit);
  const Received got = play(line);
  EXPECT_EQ(got.framing_errors, 1u);
  EXPECT_EQ(got.bytes, std::vector<std::uint8_t>({0xC3}));
}

}  // namespace
}  // namespace evms
