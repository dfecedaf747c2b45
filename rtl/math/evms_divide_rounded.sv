// round(num / den) for num >= 0, den > 0, half up, as detail::divide_rounded in
// hls/cluster/seeded_climbs.h: (2 num + den) / (2 den), by restoring division, one quotient bit
// a clock (NumBits + 2 clocks from start to done). Exact: the seeded climbs' mode positions
// depend on every bit.
`include "evms_assert.svh"

module evms_divide_rounded #(
  parameter int NumBits = 48,
  parameter int DenBits = 16
) (
  input  logic               clk,
  input  logic               rst_n,
  input  logic               start,
  input  logic [NumBits-1:0] num,
  input  logic [DenBits-1:0] den,
  output logic               done,     // one clock, with quotient valid until the next start
  output logic [NumBits-1:0] quotient
);
  localparam int DividendBits = NumBits + 2;   // 2 num + den < 2^(NumBits + 2)
  localparam int DivisorBits = DenBits + 1;
  localparam int StepBits = $clog2(DividendBits + 1);
  `EVMS_ASSERT_INIT("the denominator must be narrower than the numerator", DenBits < NumBits)

  logic [DividendBits-1:0] dividend_q, dividend_d;   // shifts left; quotient bits enter at the bottom
  logic [DivisorBits:0]    remainder_q, remainder_d;
  logic [DivisorBits-1:0]  divisor_q, divisor_d;
  logic [StepBits-1:0]     steps_left_q, steps_left_d;
  logic                    busy_q, busy_d, done_d;

  always_comb begin
    dividend_d = dividend_q;
    remainder_d = remainder_q;
    divisor_d = divisor_q;
    steps_left_d = steps_left_q;
    busy_d = busy_q;
    done_d = 1'b0;
    if (start) begin
      dividend_d = {1'b0, num, 1'b0} + DividendBits'(den);
      divisor_d = {den, 1'b0};
      remainder_d = '0;
      steps_left_d = StepBits'(DividendBits);
      busy_d = 1'b1;
    end else if (busy_q) begin
      // Bring down the dividend's top bit; subtract the divisor when it fits.
      remainder_d = {remainder_q[DivisorBits-1:0], dividend_q[DividendBits-1]};
      dividend_d = {dividend_q[DividendBits-2:0], 1'b0};
      if (remainder_d >= {1'b0, divisor_q}) begin
        remainder_d = remainder_d - {1'b0, divisor_q};
        dividend_d[0] = 1'b1;
      end
      steps_left_d = steps_left_q - 1'b1;
      if (steps_left_q == StepBits'(1)) begin
        busy_d = 1'b0;
        done_d = 1'b1;
      end
    end
  end

  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      dividend_q <= '0;
      remainder_q <= '0;
      divisor_q <= '0;
      steps_left_q <= '0;
      busy_q <= 1'b0;
      done <= 1'b0;
    end else begin
      dividend_q <= dividend_d;
      remainder_q <= remainder_d;
      divisor_q <= divisor_d;
      steps_left_q <= steps_left_d;
      busy_q <= busy_d;
      done <= done_d;
    end
  end

  // (2 num + den) / (2 den) = num / den + 1/2, so the quotient is at most num (den >= 1).
  assign quotient = dividend_q[NumBits-1:0];
endmodule
