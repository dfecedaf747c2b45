// The core cut at its filter, in C++: the verdicts a board that stops there returns
// (hls::FilterCore) and the rest of the core run on them (hls::Core::process_decided), as the
// board backend runs it. For the tests of that cut (tests/hls, tests/sim, tests/cli).
#pragma once

#include <memory>
#include <vector>

#include "hls/core/core.h"
#include "hls/core/filter_core.h"

namespace evms::test {

struct CoreWords {
  std::vector<hls::LabelWord> labels;
  std::vector<hls::TrackWord> tracks;
  std::vector<hls::PacketWord> packets;
};

// Each event's verdict (flush words have none), in input order.
template <class S>
std::vector<hls::LabelWord> filter_core_verdicts(const std::vector<hls::EventWord>& words, const hls::Config& cfg) {
  auto core = std::make_unique<hls::FilterCore<S>>();
  core->reset(cfg);
  typename hls::FilterCore<S>::LabelStream out;
  std::vector<hls::LabelWord> verdicts;
  for (const hls::EventWord& w : words) {
    core->process(w, out);
    hls::LabelWord l;
    while (out.read(l)) verdicts.push_back(l);
  }
  return verdicts;
}

// The rest of the core on the verdicts' events, then a flush: what the host makes of them.
template <class S>
CoreWords completed_on_the_host(const std::vector<hls::LabelWord>& verdicts, const hls::Config& cfg) {
  auto core = std::make_unique<hls::Core<S>>();
  auto labels = std::make_unique<typename hls::Core<S>::LabelStream>();
  typename hls::Core<S>::TrackStream tracks;
  typename hls::Core<S>::PacketStream packets;
  core->reset(cfg);
  CoreWords out;
  const auto take = [&] {
    hls::LabelWord l;
    while (labels->read(l)) out.labels.push_back(l);
    hls::TrackWord t;
    while (tracks.read(t)) out.tracks.push_back(t);
    hls::PacketWord p;
    while (packets.read(p)) out.packets.push_back(p);
  };
  for (const hls::LabelWord& v : verdicts) {
    core->process_decided({v.t, v.x, v.y, v.p, false}, v.label == hls::kLabelPassedFilter, *labels, tracks, packets);
    take();
  }
  hls::EventWord flush;
  flush.flush = true;
  core->process(flush, *labels, tracks, packets);
  take();
  return out;
}

}  // namespace evms::test
