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
  input  logic        CLK,
  input  logic        BTN_N,
  input  logic        RX,
  output logic        TX,
  output logic        LEDR_N,
  output logic        LEDG_N,
  input  logic [15:0] AER_ADDR,
  input  logic        AER_REQ_N,
  output logic        AER_ACK_N
);
  `include "evms_cfg_ice40.svh"

  // Power-on reset: hold the design in reset for 16 clocks, and while the button is pressed.
  logic [4:0] por = '0;
  logic rst_n;
  always_ff @(posedge CLK) if (!por[4]) por <= por + 1'b1;
  assign rst_n = por[4] && BTN_N;

  logic busy, error;
  evms_board #(
    .ClkHz(BoardClockHz), .ClksPerBit(BoardClocksPerBit), .LinkFifoDepth(BoardLinkFifoDepth),
    .CoreStopsAtFilter(CoreStopsAtFilterOverride >= 0 ? CoreStopsAtFilterOverride : BoardCoreStopsAtFilter),
    `include "evms_board_build_params.svh"
  ) u_board (
    .clk(CLK), .rst_n(rst_n), .aer_req_n(AER_REQ_N), .aer_ack_n(AER_ACK_N), .aer_addr(AER_ADDR), .uart_rx(RX),
    .uart_tx(TX), .led_busy(busy), .led_error(error));
  assign LEDG_N = !busy;
  assign LEDR_N = !error;
endmodule
