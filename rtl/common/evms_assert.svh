// The RTL's assertion macros, in one place (as lowRISC's prim_assert.sv): every check in rtl/
// is one of these, so that a tool that lacks a construct is handled here once.
//   `EVMS_ASSERT_INIT(message, condition)        a property of the parameters, checked at
//                                                elaboration (Verilator and Yosys both stop)
//   `EVMS_ASSERT(message, condition, clk, rst_n) checked at every rising edge out of reset (rst_n
//                                                active low, asynchronous as every reset in rtl/),
//                                                in simulation only (synthesis defines SYNTHESIS)
`ifndef EVMS_ASSERT_SVH
`define EVMS_ASSERT_SVH

`define EVMS_ASSERT_INIT(message, condition) \
  initial if (!(condition)) $error("%m: %s", message);

`ifdef SYNTHESIS
`define EVMS_ASSERT(message, condition, clk, rst_n)
`else
`define EVMS_ASSERT(message, condition, clk, rst_n) \
  always_ff @(posedge clk or negedge rst_n) if (!(rst_n)) begin end else if (!(condition)) $error("%m: %s (at %0t)", message, $time);
`endif

`endif  // EVMS_ASSERT_SVH
