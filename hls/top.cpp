// The HLS top level: the default core behind AXI-Stream ports and an AXI-Lite register block.
// A C++ synthesis tool builds this function; evms builds it too (tests/hls/test_hls_rules)
// with -fno-exceptions -fno-rtti -Werror to keep the core within what such tools accept.
#include "hls/core/core.h"

namespace evms::hls {

using TopCore = Core<DefaultShape>;

void evms_core(Stream<EventWord, 64>& in, TopCore::LabelStream& labels, TopCore::TrackStream& tracks,
               TopCore::PacketStream& packets, const Config& cfg, bool reset) {
#pragma HLS INTERFACE axis port = in
#pragma HLS INTERFACE axis port = labels
#pragma HLS INTERFACE axis port = tracks
#pragma HLS INTERFACE axis port = packets
#pragma HLS INTERFACE s_axilite port = cfg
#pragma HLS INTERFACE s_axilite port = reset
#pragma HLS INTERFACE ap_ctrl_none port = return
  static TopCore core;
  if (reset) core.reset(cfg);
  EventWord e;
  while (in.read(e)) core.process(e, labels, tracks, packets);
}

}  // namespace evms::hls
