// What the climbs' block tests (test_seeded_climbs.cpp, test_serial_climbs.cpp) load into both
// climbs' RTL (the packet's features and the registers they share), what they read back from the
// C++ climbs and from the RTL, and the first difference between the two: every event's mode,
// every mode's position, and the climb, step and lost-mode counts. Each test loads and compares
// what its block adds (warm seeds and the least density; the supports) on its own.
#pragma once

#include <algorithm>
#include <cstdint>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "hls/cluster/seeded_climbs.h"
#include "sim/verilated_block.h"

namespace evms::sim {

// Writes the packet's n features into the block, one a clock, and sets the registers both
// climbs take.
template <class Model, class Phi>
void load_packet(VerilatedBlock<Model>& rtl, const Phi& phi, int n, const hls::Config& cfg) {
  for (int i = 0; i < n; ++i) {
    rtl->load_we = 1, rtl->load_i = static_cast<std::uint16_t>(i), rtl->load_x = phi.x[i], rtl->load_y = phi.y[i];
    rtl.tick();
  }
  rtl->load_we = 0;
  rtl->n = static_cast<std::uint16_t>(n);
  rtl->cfg_max_iterations = cfg.max_iterations;
  rtl->cfg_tolerance = cfg.tolerance;
  rtl->cfg_merge_radius2 = cfg.merge_radius2;
}

struct ClimbsReadout {
  std::vector<int> first_mode;
  std::vector<std::pair<std::int64_t, std::int64_t>> modes;
  int climbs = 0, steps = 0, modes_lost = 0;
  std::uint64_t cycles = 0;
};

template <class S>
ClimbsReadout model_readout(const std::int16_t* first_mode, int n, const hls::Modes<S>& modes, const hls::ClimbTrace& trace) {
  ClimbsReadout r;
  r.first_mode.assign(first_mode, first_mode + n);
  for (int k = 0; k < modes.count; ++k) r.modes.push_back({modes.x[k], modes.y[k]});
  r.climbs = trace.climbs, r.steps = trace.steps, r.modes_lost = trace.modes_lost;
  return r;
}

// Runs the loaded block to done and reads every event's mode (rd_j, rd_mode) and every mode
// (rd_c, rd_mode_x, rd_mode_y); per_mode(k) reads what else the block gives of mode k.
template <class Model, class PerMode>
ClimbsReadout rtl_readout(VerilatedBlock<Model>& rtl, int n, std::uint64_t clock_limit, PerMode per_mode) {
  ClimbsReadout r;
  r.cycles = rtl.run_until_done([&] { rtl.tick(); }, clock_limit);
  for (int j = 0; j < n; ++j) {
    rtl->rd_j = static_cast<std::uint16_t>(j);
    rtl.tick();
    r.first_mode.push_back(static_cast<std::int16_t>(rtl->rd_mode));
  }
  for (int k = 0; k < rtl->mode_count; ++k) {
    rtl->rd_c = static_cast<std::uint8_t>(k);
    rtl.tick();
    r.modes.push_back({rtl->rd_mode_x, rtl->rd_mode_y});
    per_mode(k);
  }
  r.climbs = rtl->climbs, r.steps = rtl->steps, r.modes_lost = rtl->modes_lost;
  return r;
}

// The first difference, in the order above; empty when there is none.
inline std::string readout_difference(const ClimbsReadout& want, const ClimbsReadout& got) {
  std::ostringstream o;
  for (size_t j = 0; j < want.first_mode.size(); ++j) {
    if (want.first_mode[j] != got.first_mode[j]) {
      o << "event " << j << ": mode " << got.first_mode[j] << ", want " << want.first_mode[j];
      return o.str();
    }
  }
  if (want.modes != got.modes) {
    o << got.modes.size() << " modes, want " << want.modes.size();
    for (size_t k = 0; k < std::min(want.modes.size(), got.modes.size()); ++k) {
      if (want.modes[k] != got.modes[k]) o << "; mode " << k << " at " << got.modes[k].first << "," << got.modes[k].second << ", want "
                                           << want.modes[k].first << "," << want.modes[k].second;
    }
    return o.str();
  }
  if (want.climbs != got.climbs || want.steps != got.steps || want.modes_lost != got.modes_lost) {
    o << "climbs/steps/lost " << got.climbs << "/" << got.steps << "/" << got.modes_lost << ", want " << want.climbs << "/" << want.steps
      << "/" << want.modes_lost;
  }
  return o.str();
}

}  // namespace evms::sim
