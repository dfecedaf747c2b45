// The pins every board top has (rtl/board/evms_arty_top.sv, evms_icebreaker_top.sv); each
// board's constraint file maps them (constraints/arty_a7.xdc, constraints/icebreaker.pcf).
  input  logic        CLK,
  input  logic        BTN_N,
  input  logic        RX,
  output logic        TX,
  output logic        LEDR_N,
  output logic        LEDG_N,
  input  logic [15:0] AER_ADDR,
  input  logic        AER_REQ_N,
  output logic        AER_ACK_N
