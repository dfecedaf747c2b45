// iCEBreaker (iCE40 UP5K) beside a DVS128: AER on PMOD1A/1B/2, the host link on the FT2232H's
// UART at 6 Mbaud, LEDs for activity and link errors. The PLL makes the build's clock
// (BoardClockHz, 18 MHz) of the board's 12 MHz oscillator, so that 3 clocks a bit give 6 Mbaud,
// a rate the FT2232H makes exactly (120 MHz / 20); the design is held in reset until it locks.
// Simulation and lint (no SYNTHESIS) take the oscillator's pin as the clock. The core stops
// after its climbs (BoardCoreCut, rtl/generated/evms_cfg_ice40.svh): the board returns each
// event's verdict and each packet's climbs, and the host completes the clusters and tracks them
// (host/backend/board_backend.cpp).
// Pins: constraints/icebreaker.pcf.
`include "evms_assert.svh"
module evms_icebreaker_top #(
  // The synthesis flow's lane sweep (constraints/flow/synth.sh); 0 keeps the build's Lanes.
  parameter int LanesOverride = 0,
  // 0 puts the whole core in (evms_board's CoreCut), as the flow measures it on the UP5K
  // (synth.sh's ice40core configurations); -1 keeps the build's BoardCoreCut.
  parameter int CoreCutOverride = -1
) (
  // The red and the green LED beside the button, lit by a low level.
  output logic LEDR_N,
  output logic LEDG_N,
  `include "evms_board_top_ports.svh"
);
  `include "evms_cfg_ice40.svh"
  // 12 MHz x (PllDivF + 1) / (PllDivR + 1) / 2^PllDivQ, the VCO at 12 MHz x 48 = 576 MHz (within
  // its 533-1066 MHz), the filter range of a 12 MHz reference (icestorm's icepll gives the same).
  localparam int OscillatorHz = 12000000;
  localparam int PllDivR = 0, PllDivF = 47, PllDivQ = 5;
  `EVMS_ASSERT_INIT("the PLL makes the build's clock of the oscillator",
                    BoardClockHz == OscillatorHz / (PllDivR + 1) * (PllDivF + 1) / (1 << PllDivQ))
  logic board_clk, board_clk_locked;
`ifdef SYNTHESIS
  localparam int PllFilterRange = 1;
  SB_PLL40_PAD #(
    .FEEDBACK_PATH("SIMPLE"), .DIVR(4'(PllDivR)), .DIVF(7'(PllDivF)), .DIVQ(3'(PllDivQ)), .FILTER_RANGE(3'(PllFilterRange))
  ) u_pll (
    .PACKAGEPIN(CLK), .PLLOUTGLOBAL(board_clk), .LOCK(board_clk_locked), .RESETB(1'b1), .BYPASS(1'b0)
  );
`else
  assign board_clk = CLK;
  assign board_clk_locked = 1'b1;
`endif
  `include "evms_board_top_body.svh"
  assign LEDG_N = !busy;
  assign LEDR_N = !error;
endmodule
