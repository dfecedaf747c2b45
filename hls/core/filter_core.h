// The core cut after its filter: every event labelled kLabelNoise or kLabelPassedFilter, in
// input order, with no packets and no tracks: the verdicts a cut board returns first
// (EVMS_BOARD_BUILDS in hls/core/configs.h; rtl/core/evms_climbs_core.sv). Core::process_decided
// completes it: fed these verdicts, Core<S> gives the words of the whole core.
#pragma once

#include "hls/core/config.h"
#include "hls/core/words.h"
#include "hls/filter/ba_filter.h"
#include "hls/fixed/stream.h"

namespace evms::hls {

template <class S>
class FilterCore {
 public:
  using LabelStream = Stream<LabelWord, 2>;

  void reset(const Config& cfg) {
    cfg_ = cfg;
    filter_.reset();
  }

  // A flush word has nothing to release: every event left at once.
  void process(const EventWord& in, LabelStream& labels) {
    if (in.flush) return;
    const bool kept = filter_.accept(in, cfg_);
    labels.write({in.t, in.x, in.y, in.p, kept ? kLabelPassedFilter : kLabelNoise});
  }

 private:
  Config cfg_;
  BackgroundActivityFilter<S> filter_;
};

}  // namespace evms::hls
