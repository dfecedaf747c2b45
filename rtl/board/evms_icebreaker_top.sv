// iCEBreaker (iCE40 UP5K, 12 MHz) beside a DVS128: AER on PMOD1A/1B/2, the host link on the
// FT2232H's UART at 3 Mbaud (4 clocks a bit), LEDs for activity and link errors.
// Pins: constraints/icebreaker.pcf.
module evms_icebreaker_top #(
  // The synthesis flow's lane sweep (constraints/flow/synth.sh); 0 keeps the build's LANES.
  parameter int LANES_OVERRIDE = 0
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
    .CLK_HZ(12000000), .CLKS_PER_BIT(4), .LINK_FIFO_DEPTH(512), .MUL_DIGIT_BITS(MUL_DIGIT_BITS),
    .MAX_WIDTH(MAX_WIDTH), .MAX_HEIGHT(MAX_HEIGHT), .TS_BITS(TS_BITS), .TS_SHIFT(TS_SHIFT), .PACKET_MAX(PACKET_MAX),
    .PENDING_DEPTH(PENDING_DEPTH), .LANES(LANES_OVERRIDE > 0 ? LANES_OVERRIDE : LANES), .ITERATIONS_MAX(ITERATIONS_MAX), .CLUSTERS_MAX(CLUSTERS_MAX),
    .TRACKS_MAX(TRACKS_MAX), .FEAT_INT(FEAT_INT), .FEAT_FRAC(FEAT_FRAC), .WEIGHT_FRAC(WEIGHT_FRAC), .EXP_LOG2(EXP_LOG2),
    .EXP_INTERP_BITS(EXP_INTERP_BITS), .SUM_FRAC(SUM_FRAC), .RECIP_LOG2(RECIP_LOG2), .RECIP_FRAC(RECIP_FRAC),
    .DECAY_FRAC(DECAY_FRAC), .COORD_SCALE_FRAC(COORD_SCALE_FRAC), .POS_FRAC(POS_FRAC), .TICK_LOG2(TICK_LOG2),
    .COV_FRAC(COV_FRAC), .GAIN_FRAC(GAIN_FRAC), .NOISE_FRAC(NOISE_FRAC), .EXP_MEM(EXP_MEM), .RECIP_MEM(RECIP_MEM),
    .DEF_SENSOR_WIDTH(DEF_SENSOR_WIDTH), .DEF_SENSOR_HEIGHT(DEF_SENSOR_HEIGHT), .DEF_FILTER_ENABLED(DEF_FILTER_ENABLED),
    .DEF_FILTER_WINDOW(DEF_FILTER_WINDOW), .DEF_PACKET_SIZE(DEF_PACKET_SIZE), .DEF_PACKET_MAX_SPAN_US(DEF_PACKET_MAX_SPAN_US),
    .DEF_SCALE_X(DEF_SCALE_X), .DEF_SCALE_Y(DEF_SCALE_Y), .DEF_PHI_ON(DEF_PHI_ON), .DEF_PHI_T_MAX(DEF_PHI_T_MAX),
    .DEF_INV_TAU(DEF_INV_TAU), .DEF_MAX_ITERATIONS(DEF_MAX_ITERATIONS), .DEF_TOLERANCE(DEF_TOLERANCE),
    .DEF_MERGE_RADIUS2(DEF_MERGE_RADIUS2), .DEF_MIN_CLUSTER_SIZE(DEF_MIN_CLUSTER_SIZE), .DEF_MAX_CLUSTERS(DEF_MAX_CLUSTERS),
    .DEF_GATE2(DEF_GATE2), .DEF_CONFIRM_HITS(DEF_CONFIRM_HITS), .DEF_COAST_US(DEF_COAST_US), .DEF_MAX_TRACKS(DEF_MAX_TRACKS),
    .DEF_Q_THIRD(DEF_Q_THIRD), .DEF_Q_HALF(DEF_Q_HALF), .DEF_Q(DEF_Q), .DEF_R(DEF_R), .DEF_P0_POS(DEF_P0_POS),
    .DEF_P0_VEL(DEF_P0_VEL)
  ) u_board (
    .clk(CLK), .rst_n(rst_n), .aer_req_n(AER_REQ_N), .aer_ack_n(AER_ACK_N), .aer_addr(AER_ADDR), .uart_rx(RX),
    .uart_tx(TX), .led_busy(busy), .led_error(error));
  assign LEDG_N = !busy;
  assign LEDR_N = !error;
endmodule
