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
    logic [31:0] pp [4][4];
    logic [31:0] diag0, diag2;
    logic [32:0] diag1;
    logic [15:0] diag3;
    logic [1:0]  valid;
    always_ff @(posedge clk or negedge rst_n) begin
      if (!rst_n) begin
        valid <= '0;
        done  <= 1'b0;
        p     <= '0;
        diag0 <= '0;
        diag1 <= '0;
        diag2 <= '0;
        diag3 <= '0;
        for (int i = 0; i < 4; i++) for (int j = 0; j < 4; j++) pp[i][j] <= '0;
      end else begin
        valid <= {valid[0], start};
        done  <= valid[1];
        if (start) begin
          for (int i = 0; i < 4; i++)
            for (int j = 0; j < 4 - i; j++) pp[i][j] <= 32'(a[16*i +: 16]) * 32'(b[16*j +: 16]);
        end
        if (valid[0]) begin
          diag0 <= pp[0][0];
          diag1 <= 33'(pp[0][1]) + 33'(pp[1][0]);
          diag2 <= pp[0][2] + pp[1][1] + pp[2][0];
          diag3 <= 16'(pp[0][3]) + 16'(pp[1][2]) + 16'(pp[2][1]) + 16'(pp[3][0]);
        end
        if (valid[1]) p <= $signed(64'(diag0) + {15'd0, diag1, 16'd0} + {diag2, 32'd0} + {diag3, 48'd0});
      end
    end
    assign busy = 1'b0;
  end else begin : g_serial
    localparam int Steps = (64 + DigitBits - 1) / DigitBits;
    logic [63:0] mag_a, mag_b, acc;
    logic        negate;
    logic [$clog2(Steps+1)-1:0] step;
    always_ff @(posedge clk or negedge rst_n) begin
      if (!rst_n) begin
        busy <= 1'b0;
        done <= 1'b0;
        p    <= '0;
        step <= '0;
        mag_a <= '0;
        mag_b <= '0;
        acc <= '0;
        negate <= 1'b0;
      end else begin
        done <= 1'b0;
        if (start && !busy) begin
          mag_a  <= a[63] ? -a : a;
          mag_b  <= b[63] ? -b : b;
          negate <= a[63] ^ b[63];
          acc    <= '0;
          step   <= '0;
          busy   <= 1'b1;
        end else if (busy) begin
          // acc += |a| * digit(|b|, step) << (step * DigitBits), from the top digit down
          acc  <= (acc << DigitBits) + mag_a * 64'(mag_b[63 - (32'(step) * DigitBits) -: DigitBits]);
          step <= step + 1'b1;
          if (32'(step) == Steps - 1) begin
            busy <= 1'b0;
            done <= 1'b1;
            p    <= negate ? -((acc << DigitBits) + mag_a * 64'(mag_b[DigitBits-1:0]))
                           : ((acc << DigitBits) + mag_a * 64'(mag_b[DigitBits-1:0]));
          end
        end
      end
    end
  end
endmodule
