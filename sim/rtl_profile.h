// The core controller's states (hls/core/schedule.h, EVMS_CORE_CONTROLLER_STATES, from which
// rtl/generated/evms_core_states.svh is written) grouped into the stages of the cycle model, so
// that a run of the RTL can be set beside the model stage by stage.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "hls/core/core.h"
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

// The cycle model's side: the C++ core of shape S over the words, with the schedule counter as
// its observer and its outputs dropped.
template <class S>
hls::ScheduleCounter<S> modelled_schedule(const std::vector<hls::EventWord>& words, const hls::Config& cfg) {
  using Core = hls::Core<S, hls::ScheduleCounter<S>>;
  auto core = std::make_unique<Core>();  // too large for the stack
  auto labels = std::make_unique<typename Core::LabelStream>();
  typename Core::TrackStream tracks;
  typename Core::PacketStream packets;
  core->reset(cfg);
  core->observer().configure(cfg);
  for (const auto& w : words) {
    core->process(w, *labels, tracks, packets);
    labels->clear(), tracks.clear(), packets.clear();
  }
  return core->observer();
}

}  // namespace evms::sim
