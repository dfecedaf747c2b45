// One run of the Verilated core cut after its climbs (rtl/core/evms_climbs_core.sv): its words
// in, every verdict and climbs frame word out (hls/cluster/climbs_words.h), each output ready
// with a probability, and the clocks until the core is idle after the last word.
// tests/sim/test_climbs_core.cpp holds it against the C++ core cut at the same place, and
// `evms cycles --build ice40` counts its clocks an event (host/cli/cmd_cycles.cpp).
#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "hls/cluster/climbs_words.h"
#include "hls/core/config.h"
#include "hls/core/words.h"
#include "sim/cfg_ports.h"
#include "sim/verilated_block.h"

namespace evms::sim {

struct ClimbsCoreOutputs {
  std::vector<hls::LabelWord> verdicts;
  std::vector<hls::ClimbsWord> frame_words;
  std::uint64_t clocks = 0;
  bool finished = false;  // idle after the last word, within the clock limit
};

// The RTL (V, a Verilated evms_climbs_core) on `words`, each output ready with probability
// `ready_p` (drawn from `seed`); an FST trace to `trace` unless it is empty.
template <class V>
ClimbsCoreOutputs run_climbs_core(const std::vector<hls::EventWord>& words, const hls::Config& cfg, std::uint64_t seed, double ready_p,
                                  const std::string& trace) {
  VerilatedBlock<V> rtl(trace);
  set_cfg_ports(*rtl.operator->(), cfg);
  std::mt19937_64 rng(seed);
  std::bernoulli_distribution ready(ready_p);
  ClimbsCoreOutputs out;
  size_t next = 0;
  const std::uint64_t limit = 400 * words.size() + 2'000'000;
  while (out.clocks < limit) {
    if (next < words.size()) {
      const hls::EventWord& w = words[next];
      rtl->in_valid = 1, rtl->in_t = w.t, rtl->in_x = w.x, rtl->in_y = w.y, rtl->in_p = w.p, rtl->in_flush = w.flush;
    } else {
      rtl->in_valid = 0;
    }
    rtl->lab_ready = ready(rng), rtl->clm_ready = ready(rng);
    rtl->eval();
    if (next == words.size() && rtl->idle) {
      out.finished = true;
      break;
    }
    if (rtl->in_valid && rtl->in_ready) ++next;
    if (rtl->lab_valid && rtl->lab_ready) {
      out.verdicts.push_back({rtl->lab_t, static_cast<std::uint16_t>(rtl->lab_x), static_cast<std::uint16_t>(rtl->lab_y),
                              static_cast<std::uint8_t>(rtl->lab_p), static_cast<std::int32_t>(rtl->lab_label)});
    }
    if (rtl->clm_valid && rtl->clm_ready) {
      const auto& d = rtl->clm_data;  // 80 bits: d[2] holds bits 79-64
      out.frame_words.push_back({static_cast<hls::ClimbsWordKind>(rtl->clm_kind), static_cast<std::uint16_t>(d[2] & 0xFFFF),
                                 (static_cast<std::uint64_t>(d[1]) << 32) | d[0]});
    }
    rtl.tick();
    ++out.clocks;
  }
  return out;
}

}  // namespace evms::sim
