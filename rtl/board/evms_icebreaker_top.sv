// iCEBreaker (iCE40 UP5K, 12 MHz) beside a DVS128: AER on PMOD1A/1B/2, the host link on the
// FT2232H's UART at 3 Mbaud (4 clocks a bit), LEDs for activity and link errors. The core stops
// at its filter (BoardCoreStopsAtFilter, rtl/generated/evms_cfg_ice40.svh): the board returns
// each event's verdict and the host clusters and tracks (host/backend/board_backend.cpp).
// Pins: constraints/icebreaker.pcf.
module evms_icebreaker_top #(
  // The synthesis flow's lane sweep (constraints/flow/synth.sh); 0 keeps the build's Lanes.
  parameter int LanesOverride = 0,
  // The flow's measure of the whole core on the UP5K (synth.sh's ice40core configurations): 0
  // puts it in; -1 keeps the build's BoardCoreStopsAtFilter.
  parameter int CoreStopsAtFilterOverride = -1
) (
  `include "evms_board_top_ports.svh"
);
  `include "evms_cfg_ice40.svh"
  `include "evms_board_top_body.svh"
endmodule
