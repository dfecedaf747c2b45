// The C++ core driven word by word with its output words collected in vectors, for the tests
// that compare its words (tests/hls, tests/sim, tests/cli); and the core cut at its filter: the
// verdicts a board that stops there returns (hls::FilterCore) and the rest of the core run on
// them (hls::Core::process_decided), as the board backend runs it.
#pragma once

#include <memory>
#include <vector>

#include "hls/core/filter_core.h"
#include "host/backend/fixed_backend.h"

namespace evms::test {

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

}  // namespace evms::test
