// The events as the core's input words; the C++ core driven word by word with its output words
// collected in vectors, for the tests that compare its words (tests/hls, tests/sim, tests/cli);
// the core cut at its filter: the verdicts a cut board returns (hls::FilterCore) and the rest of
// the core run on them (hls::Core::process_decided), as the board backend runs it where it climbs
// a packet itself; and the core cut at its climbs: the frames a board that stops there returns with those
// verdicts (hls::Core::process_to_climbs) and the rest of the core run on both
// (hls::Core::process_climbed).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "hls/core/filter_core.h"
#include "types/event.h"
#include "host/backend/fixed_backend.h"

namespace evms::test {

// The events as the core's input words (each time one microsecond later, so that none is 0),
// then a flush.
inline std::vector<hls::EventWord> words_of(const std::vector<Event>& events) {
  std::vector<hls::EventWord> w;
  for (const Event& e : events) w.push_back({static_cast<std::uint32_t>(e.t + 1), e.x, e.y, e.p, false});
  hls::EventWord flush;
  flush.flush = true;
  w.push_back(flush);
  return w;
}

// `words` (ending in a flush) with another flush halfway.
inline std::vector<hls::EventWord> with_flush_midway(std::vector<hls::EventWord> words) {
  words.insert(words.begin() + static_cast<std::ptrdiff_t>(words.size() / 2), words.back());
  return words;
}

struct CoreWords {
  std::vector<hls::LabelWord> labels;
  std::vector<hls::TrackWord> tracks;
  std::vector<hls::PacketWord> packets;
};

// The host's C++ core (host/backend/fixed_backend.h) and every word it has released so far.
template <class S>
class CoreDriver {
 public:
  explicit CoreDriver(const hls::Config& cfg) : core_(cfg) {}
  void process(const hls::EventWord& w) {
    core_.process(w);
    take();
  }
  void process_decided(const hls::EventWord& w, bool kept) {
    core_.process_decided(w, kept);
    take();
  }
  // The word with its packets' climbs from `frames` (climbs_needed of them, from `next` on).
  void process_climbed(const hls::EventWord& w, bool kept, const std::vector<hls::ClimbsFrame<S>>& frames, size_t& next) {
    for (int k = core_.climbs_needed(w, kept); k > 0; --k) core_.give_climbs(frames.at(next++));
    core_.process_climbed(w, kept);
    take();
  }
  void flush() {
    core_.flush();
    take();
  }
  const CoreWords& out() const { return out_; }
  bool overflowed() const { return core_.overflowed(); }

 private:
  void take() {
    core_.drain([&](const hls::LabelWord& l) { out_.labels.push_back(l); }, [&](const hls::TrackWord& t) { out_.tracks.push_back(t); },
                [&](const hls::PacketWord& p) { out_.packets.push_back(p); });
  }

  backend::HostCore<S> core_;
  CoreWords out_;
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
  CoreDriver<S> core(cfg);
  for (const hls::LabelWord& v : verdicts) core.process_decided({v.t, v.x, v.y, v.p, false}, v.label == hls::kLabelPassedFilter);
  core.flush();
  return core.out();
}

// Each packet's climbs, in packet order: what a board whose core stops at the climbs returns
// besides its filter's verdicts (filter_core_verdicts).
template <class S>
std::vector<hls::ClimbsFrame<S>> climbs_core_frames(const std::vector<hls::EventWord>& words, const hls::Config& cfg) {
  backend::HostCore<S> core(cfg);
  std::vector<hls::ClimbsFrame<S>> frames;
  auto frame = std::make_unique<hls::ClimbsFrame<S>>();
  for (const hls::EventWord& w : words) {
    core.process_to_climbs(w);
    core.drain([](const hls::LabelWord&) {}, [](const hls::TrackWord&) {}, [](const hls::PacketWord&) {});
    while (core.next_climbs(*frame)) frames.push_back(*frame);
  }
  return frames;
}

// The rest of the core on every word (events and flush words) with the board's verdicts (one an
// event) and climbs frames: what the host makes of them.
template <class S>
CoreWords completed_from_climbs(const std::vector<hls::EventWord>& words, const std::vector<hls::LabelWord>& verdicts,
                                const std::vector<hls::ClimbsFrame<S>>& frames, const hls::Config& cfg) {
  CoreDriver<S> core(cfg);
  size_t verdict = 0, frame = 0;
  for (const hls::EventWord& w : words) {
    const bool kept = !w.flush && verdicts.at(verdict++).label == hls::kLabelPassedFilter;
    core.process_climbed(w, kept, frames, frame);
  }
  return core.out();
}

}  // namespace evms::test
