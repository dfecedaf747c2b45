// Signed 64 x 64 multiplier, low 64 bits, for the core's sequential stages (features, merging,
// centroids, tracking), which the core keeps below 2^63 so that the low bits are the product.
//   DIGIT_BITS = 64: one cycle (FPGAs with DSP cascades, and simulation);
//   DIGIT_BITS < 64: DIGIT_BITS bits of |b| a cycle (iCE40: a few hundred LUTs, no DSP).
// start is taken in any cycle in which busy is low; done pulses with p valid, and p holds until
// the next start.
module evms_mul #(
  parameter int DIGIT_BITS = 64
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
  if (DIGIT_BITS >= 64) begin : g_single
    always_ff @(posedge clk or negedge rst_n) begin
      if (!rst_n) begin
        done <= 1'b0;
        p    <= '0;
      end else begin
        done <= start;
        if (start) p <= a * b;
      end
    end
    assign busy = 1'b0;
  end else begin : g_serial
    localparam int Steps = (64 + DIGIT_BITS - 1) / DIGIT_BITS;
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
          // acc += |a| * digit(|b|, step) << (step * DIGIT_BITS), from the top digit down
          acc  <= (acc << DIGIT_BITS) + mag_a * 64'(mag_b[63 - (32'(step) * DIGIT_BITS) -: DIGIT_BITS]);
          step <= step + 1'b1;
          if (32'(step) == Steps - 1) begin
            busy <= 1'b0;
            done <= 1'b1;
            p    <= negate ? -((acc << DIGIT_BITS) + mag_a * 64'(mag_b[DIGIT_BITS-1:0]))
                           : ((acc << DIGIT_BITS) + mag_a * 64'(mag_b[DIGIT_BITS-1:0]));
          end
        end
      end
    end
  end
endmodule
