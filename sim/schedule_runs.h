// The two sides of the cycle model's comparison over one stream of words: the C++ core counting
// its schedule (hls/core/schedule.h) and the RTL counting the clocks its controller spends in each
// state (sim/rtl_profile.h). `evms cycles` prints them; tests/sim/test_cosim.cpp holds them equal.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "hls/core/core.h"
#include "hls/core/schedule.h"
#include "sim/rtl_core.h"
#include "sim/rtl_profile.h"

namespace evms::sim {

// The C++ core of shape S over the words, with the schedule counter as its observer and its
// outputs dropped.
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

// The Verilated core V over the words, every output always ready, and its cycles by stage;
// `after_word(i)` is called after word i is taken.
template <class V, class AfterWord>
hls::StageCycles measured_schedule(const std::vector<hls::EventWord>& words, const hls::Config& cfg, AfterWord&& after_word) {
  RtlCore<V> core(cfg);
  for (std::size_t i = 0; i < words.size(); ++i) {
    core.push(words[i]);
    core.labels.clear(), core.tracks.clear(), core.packets.clear();
    after_word(i);
  }
  core.settle();
  return stage_cycles(core.state_cycles());
}

}  // namespace evms::sim
