// Arty A7-35T (100 MHz) with the 240x180 core: events from the host link (a DAVIS240 read by
// the host) or a DVS128 on the AER pins (PMOD JA/JB/JC). The host
// link runs on the USB UART at 2 Mbaud (50 clocks a bit); LEDs show activity and link errors.
// Pins: constraints/arty_a7.xdc.
module evms_arty_top #(
  // The synthesis flow's lane sweep (constraints/flow/synth.sh); 0 keeps the build's Lanes.
  parameter int LanesOverride = 0
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
  `include "evms_cfg_arty.svh"

  // Power-on reset: hold the design in reset for 16 clocks, and while the button is pressed.
  logic [4:0] por = '0;
  logic rst_n;
  always_ff @(posedge CLK) if (!por[4]) por <= por + 1'b1;
  assign rst_n = por[4] && BTN_N;

  logic busy, error;
  evms_board #(
    .ClkHz(BoardClockHz), .ClksPerBit(BoardClocksPerBit), .LinkFifoDepth(BoardLinkFifoDepth),
    .CoreStopsAtFilter(BoardCoreStopsAtFilter),
    `include "evms_board_build_params.svh"
  ) u_board (
    .clk(CLK), .rst_n(rst_n), .aer_req_n(AER_REQ_N), .aer_ack_n(AER_ACK_N), .aer_addr(AER_ADDR), .uart_rx(RX),
    .uart_tx(TX), .led_busy(busy), .led_error(error));
  assign LEDG_N = !busy;
  assign LEDR_N = !error;
endmodule
