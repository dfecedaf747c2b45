// Signed 64 x 64 multiplier, low 64 bits, for the core's sequential stages (features, merging,
// centroids, tracking), which the core keeps below 2^63 so that the low bits are the product.
//   DigitBits = 64: pipelined over three clocks (FPGAs with DSP blocks, and simulation);
//   DigitBits < 64: DigitBits bits of |b| a cycle (iCE40: a few hundred LUTs, no DSP).
// start is taken in any cycle in which busy is low; done pulses with p valid, and p holds until
// the next product is done.
module evms_mul #(
  parameter int DigitBits = 64
) (
  input  logic               clk,
  input  logic               rst_n,
  input  logic               start,
  input  logic signed [63:0] a,
  input  logic signed [63:0] b,
  output logic               busy,
  output logic               done,
  output logic signed [63:0] p
);
  if (DigitBits >= 64) begin : g_pipelined
    // The low 64 bits of a two's-complement product are those of the unsigned product, so the
    // operands split into four 16-bit digits, and only the ten digit products with i + j <= 3
    // reach the low half. Each is one DSP multiply with a register behind it (no cascade, so
    // no chain of DSP adders in one clock); the next clock sums each diagonal i + j, the last
    // the four diagonals.
    logic [31:0] pp_q [4][4];   // the digit products, each behind its DSP's register
    logic [31:0] diag0_q, diag2_q;
    logic [32:0] diag1_q;
    logic [15:0] diag3_q;
    logic [1:0]  valid_q;
    always_ff @(posedge clk or negedge rst_n) begin
      if (!rst_n) begin
        valid_q <= '0;
        done  <= 1'b0;
        p     <= '0;
        diag0_q <= '0;
        diag1_q <= '0;
        diag2_q <= '0;
        diag3_q <= '0;
        for (int i = 0; i < 4; i++) for (int j = 0; j < 4; j++) pp_q[i][j] <= '0;
      end else begin
        valid_q <= {valid_q[0], start};
        done  <= valid_q[1];
        if (start) begin
          for (int i = 0; i < 4; i++)
            for (int j = 0; j < 4 - i; j++) pp_q[i][j] <= 32'(a[16*i +: 16]) * 32'(b[16*j +: 16]);
        end
        if (valid_q[0]) begin
          diag0_q <= pp_q[0][0];
          diag1_q <= 33'(pp_q[0][1]) + 33'(pp_q[1][0]);
          diag2_q <= pp_q[0][2] + pp_q[1][1] + pp_q[2][0];
          diag3_q <= 16'(pp_q[0][3]) + 16'(pp_q[1][2]) + 16'(pp_q[2][1]) + 16'(pp_q[3][0]);
        end
        if (valid_q[1]) p <= $signed(64'(diag0_q) + {15'd0, diag1_q, 16'd0} + {diag2_q, 32'd0} + {diag3_q, 48'd0});
      end
    end
    assign busy = 1'b0;
  end else begin : g_serial
    localparam int Steps = (64 + DigitBits - 1) / DigitBits;
    logic [63:0] mag_a_q, mag_a_d, mag_b_q, mag_b_d;   // the operands' magnitudes
    logic [63:0] acc_q, acc_d;                         // the digits of |b| taken so far, times |a|
    logic [63:0] acc_next;
    logic        negate_q, negate_d;
    logic [$clog2(Steps+1)-1:0] step_q, step_d;
    logic        busy_q, busy_d, done_d;
    logic signed [63:0] p_q, p_d;
    assign busy = busy_q;
    assign p = p_q;
    // acc shifted a digit up, plus |a| times |b|'s digit `step`, from the top digit down
    assign acc_next = (acc_q << DigitBits) + mag_a_q * 64'(mag_b_q[63 - (32'(step_q) * DigitBits) -: DigitBits]);
    always_comb begin
      {mag_a_d, mag_b_d, negate_d, acc_d, step_d, busy_d, p_d} = {mag_a_q, mag_b_q, negate_q, acc_q, step_q, busy_q, p_q};
      done_d = 1'b0;
      if (start && !busy_q) begin
        mag_a_d  = a[63] ? -a : a;
        mag_b_d  = b[63] ? -b : b;
        negate_d = a[63] ^ b[63];
        acc_d    = '0;
        step_d   = '0;
        busy_d   = 1'b1;
      end else if (busy_q) begin
        acc_d  = acc_next;
        step_d = step_q + 1'b1;
        if (32'(step_q) == Steps - 1) begin
          busy_d = 1'b0;
          done_d = 1'b1;
          p_d    = negate_q ? -acc_next : acc_next;
        end
      end
    end
    always_ff @(posedge clk or negedge rst_n) begin
      if (!rst_n) begin
        {mag_a_q, mag_b_q, negate_q, acc_q, step_q, busy_q, p_q} <= '0;
        done <= 1'b0;
      end else begin
        {mag_a_q, mag_b_q, negate_q, acc_q, step_q, busy_q, p_q} <= {mag_a_d, mag_b_d, negate_d, acc_d, step_d, busy_d, p_d};
        done <= done_d;
      end
    end
  end
endmodule
