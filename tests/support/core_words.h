// The C++ core driven word by word with its output streams drained into vectors, for the tests
// that compare its words (tests/hls, tests/sim, tests/cli); and the core cut at its filter: the
// verdicts a board that stops there returns (hls::FilterCore) and the rest of the core run on
// them (hls::Core::process_decided), as the board backend runs it.
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

// One core (on the heap: its memories are large) and everything it has released so far.
template <class S>
class CoreDriver {
 public:
  explicit CoreDriver(const hls::Config& cfg)
      : core_(std::make_unique<hls::Core<S>>()), labels_(std::make_unique<typename hls::Core<S>::LabelStream>()) {
    core_->reset(cfg);
  }
  void process(const hls::EventWord& w) {
    core_->process(w, *labels_, tracks_, packets_);
    take();
  }
  void process_decided(const hls::EventWord& w, bool kept) {
    core_->process_decided(w, kept, *labels_, tracks_, packets_);
    take();
  }
  void flush() {
    hls::EventWord w;
    w.flush = true;
    process(w);
  }
  const CoreWords& out() const { return out_; }
  bool overflowed() const { return labels_->overflowed() || tracks_.overflowed() || packets_.overflowed(); }

 private:
  void take() {
    hls::LabelWord l;
    while (labels_->read(l)) out_.labels.push_back(l);
    hls::TrackWord t;
    while (tracks_.read(t)) out_.tracks.push_back(t);
    hls::PacketWord p;
    while (packets_.read(p)) out_.packets.push_back(p);
  }

  std::unique_ptr<hls::Core<S>> core_;
  std::unique_ptr<typename hls::Core<S>::LabelStream> labels_;
  typename hls::Core<S>::TrackStream tracks_;
  typename hls::Core<S>::PacketStream packets_;
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

}  // namespace evms::test
