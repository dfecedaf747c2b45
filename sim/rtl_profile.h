// The core controller's states (rtl/core/evms_core.sv, state_e, in declaration order) grouped
// into the stages of the cycle model (hls/core/schedule.h), so that a run of the RTL can be
// set beside the model stage by stage.
#pragma once

#include <array>
#include <cstdint>

#include "hls/core/schedule.h"

namespace evms::sim {

inline hls::Stage stage_of_core_state(unsigned state) {
  using hls::Stage;
  switch (state) {
    case 0: return Stage::kAccept;                 // C_IDLE, with a word offered
    case 1: return Stage::kFilter;                 // C_FILTER
    case 2: case 3: return Stage::kPacketControl;  // C_APPEND, C_CLOSE
    case 13: return Stage::kMeanShift;             // C_MEANSHIFT
    case 14: return Stage::kMerge;                 // C_MERGE
    case 15: return Stage::kCentroid;              // C_CENTROID
    case 16: return Stage::kTrack;                 // C_TRACK
    case 17: return Stage::kPacketControl;         // C_PACKET
    default: return state >= 4 && state <= 12 ? Stage::kFeatures : Stage::kRelease;  // C_FEAT_*, C_RELEASE_*
  }
}

inline hls::StageCycles stage_cycles(const std::array<std::uint64_t, 32>& state_cycles) {
  hls::StageCycles s{};
  for (unsigned i = 0; i < 22; ++i) s[static_cast<int>(stage_of_core_state(i))] += static_cast<double>(state_cycles[i]);
  return s;
}

}  // namespace evms::sim
