// The core controller's states (hls/core/schedule.h, EVMS_CORE_CONTROLLER_STATES, from which
// rtl/generated/evms_core_states.svh is written) grouped into the stages of the cycle model, so
// that a run of the RTL can be set beside the model stage by stage.
#pragma once

#include <array>
#include <cstdint>

#include "hls/core/schedule.h"

namespace evms::sim {

// Cycles spent in each controller state, indexed by the state's encoding, and last the idle
// state's cycles with the intake's queue empty: the controller waiting for the filter.
constexpr int kWaitingForIntake = hls::kControllerStates;
using StateCycles = std::array<std::uint64_t, hls::kControllerStates + 1>;

inline hls::StageCycles stage_cycles(const StateCycles& state_cycles) {
  hls::StageCycles s{};
  for (int i = 0; i < hls::kControllerStates; ++i) s[hls::kControllerStateStage[i]] += static_cast<double>(state_cycles[i]);
  s[hls::Stage::kFilter] += static_cast<double>(state_cycles[kWaitingForIntake]);
  return s;
}

}  // namespace evms::sim
