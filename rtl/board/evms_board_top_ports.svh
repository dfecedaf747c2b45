// The pins every board top has (rtl/board/evms_arty_top.sv, evms_icebreaker_top.sv), after
// its LEDs, whose polarity is the board's; each board's constraint file maps them
// (constraints/arty_a7.xdc, constraints/icebreaker.pcf).
  input  logic        CLK,
  input  logic        BTN_N,
  input  logic        RX,
  output logic        TX,
  input  logic [15:0] AER_ADDR,
  input  logic        AER_REQ_N,
  output logic        AER_ACK_N
