// The board's reset, of its clock's lock and its reset button, both asynchronous to the clock.
//
// Every flip-flop of the design resets asynchronously (rst_n low). Entering the reset may be
// asynchronous; leaving it may not: a release between clock edges reaches some flip-flops a
// clock before others, or within their recovery time, and a state machine can then leave reset
// half-way. So the lock and the button enter the reset at once, through the synchronizer's
// asynchronous reset, and leave it through its two flops; a counter then holds the reset for
// 2^HoldClocksLog2 clocks more, and its top bit, a register, is rst_n: the reset ends on a clock
// edge, the same for every flip-flop. A bouncing button restarts the count at each bounce.
module evms_reset_gen #(
  parameter int HoldClocksLog2 = 4   // clocks rst_n stays low after the synchronizer's release, log2
) (
  input  logic clk,
  input  logic clk_locked,   // the clock is steady (a PLL's lock; 1 when the clock is the oscillator's)
  input  logic button_n,     // the reset button, low while pressed
  output logic rst_n         // low at once while either is low; high 2 + 2^HoldClocksLog2 clocks after both are high
);
  logic hold_n;   // clock steady and button released, two clocks ago and since
  evms_sync #(.Width(1), .ResetValue(1'b0)) u_hold_sync (.clk(clk), .rst_n(clk_locked && button_n), .d(1'b1), .q(hold_n));
  logic [HoldClocksLog2:0] count_q = '0;   // power-up: in reset
  always_ff @(posedge clk or negedge hold_n) begin
    if (!hold_n) count_q <= '0;
    else if (!count_q[HoldClocksLog2]) count_q <= count_q + 1'b1;
  end
  assign rst_n = count_q[HoldClocksLog2];
endmodule
