// What every board top holds once its build's constants are included (evms_cfg_<build>.svh)
// and its clock is made (board_clk, and board_clk_locked once it is steady): a power-on reset
// and the board (rtl/board/evms_board.sv) at the build's shape, whose busy and error the top
// drives its LEDs with, at its board's polarity. The top's
// LanesOverride and CoreCutOverride let the synthesis flow (constraints/flow/synth.sh)
// sweep the lanes and measure the core cut elsewhere than the build cuts it.

  // The design is in reset from power-up until the clock is steady and 18 clocks after, and while
  // the button is pressed; it leaves the reset on a clock edge (rtl/board/evms_reset_gen.sv).
  logic rst_n;
  evms_reset_gen #(.HoldClocksLog2(4)) u_reset (.clk(board_clk), .clk_locked(board_clk_locked), .button_n(BTN_N), .rst_n(rst_n));

  logic busy, error;
  evms_board #(
    .ClkHz(BoardClockHz), .ClksPerBit(BoardClocksPerBit), .LinkFifoDepth(BoardLinkFifoDepth),
    .CoreCut(CoreCutOverride >= 0 ? CoreCutOverride : BoardCoreCut),
    `include "evms_board_build_params.svh"
  ) u_board (
    .clk(board_clk), .rst_n(rst_n), .aer_req_n(AER_REQ_N), .aer_ack_n(AER_ACK_N), .aer_addr(AER_ADDR), .uart_rx(RX),
    .uart_tx(TX), .led_busy(busy), .led_error(error));
