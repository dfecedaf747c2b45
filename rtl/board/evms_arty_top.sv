// Arty A7-35T (100 MHz) with the 240x180 core: events from the host link (a DAVIS240 read by
// the host) or a DVS128 on the AER pins (PMOD JA/JB/JC). The host
// link runs on the USB UART at 2 Mbaud (50 clocks a bit); LEDs show activity and link errors.
// Pins: constraints/arty_a7.xdc.
module evms_arty_top #(
  // The synthesis flow's lane sweep (constraints/flow/synth.sh); 0 keeps the build's Lanes.
  parameter int LanesOverride = 0,
  // 0 or 1 overrides the build's BoardCoreCut (evms_board's CoreCut); -1 keeps it.
  parameter int CoreCutOverride = -1
) (
  // LD4 and LD5, lit by a high level (the board's LEDs are anode-connected to the pins).
  output logic LED_BUSY,
  output logic LED_ERROR,
  `include "evms_board_top_ports.svh"
);
  `include "evms_cfg_arty.svh"
  // The board's 100 MHz oscillator is the build's clock.
  logic board_clk, board_clk_locked;
  assign board_clk = CLK;
  assign board_clk_locked = 1'b1;
  `include "evms_board_top_body.svh"
  assign LED_BUSY = busy;
  assign LED_ERROR = error;
endmodule
