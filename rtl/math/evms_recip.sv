// Reciprocal by table and one Newton-Raphson step, as hls/math/reciprocal.h:
//   m = msb(x); mant = x normalized to [1, 2) with RF fraction bits (truncated);
//   r0 = T[top T bits after the leading one]; r1 = (r0 * (2 - (mant * r0 >> RF))) >> RF
// so that 1/x = r1 * 2^-(RF + m). Sequential: start (x > 0) ... done after 4 cycles.
module evms_recip #(
  parameter int T        = 8,
  parameter int RF       = 20,
  parameter     MEM_FILE = "recip_8_20.mem"
) (
  input  logic        clk,
  input  logic        rst_n,
  input  logic        start,
  input  logic [63:0] x,
  output logic        done,
  output logic [RF:0] r,
  output logic [6:0]  m
);
  logic [RF:0] table_rom [0:(1<<T)-1];
  initial $readmemh(MEM_FILE, table_rom);

  // The most significant set bit.
  function automatic [6:0] msb(input [63:0] v);
    integer k;
    begin
      msb = 7'd0;
      for (k = 0; k < 64; k = k + 1) if (v[k]) msb = k[6:0];
    end
  endfunction

  logic [6:0]  m_x;
  logic [RF+1:0] two_minus_mr0;
  assign m_x = msb(x);
  logic [2:0]  stage;
  logic [RF:0] mant, r0;
  logic [2*RF+2:0] mr0_full, r1_full;
  logic [RF+1:0] mr0;
  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      stage <= '0;
      done <= 1'b0;
      r <= '0;
      m <= '0;
      mant <= '0;
      r0 <= '0;
    end else begin
      done <= 1'b0;
      case (stage)
        3'd0: if (start) begin
          m     <= m_x;
          mant  <= 32'(m_x) >= RF ? (RF+1)'(x >> (32'(m_x) - RF)) : (RF+1)'(x << (RF - 32'(m_x)));
          stage <= 3'd1;
        end
        3'd1: begin
          r0    <= table_rom[T'(mant >> (RF - T))];
          stage <= 3'd2;
        end
        3'd2: stage <= 3'd3;
        3'd3: begin
          r     <= (RF+1)'(r1_full >> RF);
          done  <= 1'b1;
          stage <= 3'd0;
        end
        default: stage <= 3'd0;
      endcase
    end
  end
  assign mr0_full = (2*RF+3)'(mant) * (2*RF+3)'(r0);
  assign mr0 = (RF+2)'(mr0_full >> RF);
  assign two_minus_mr0 = (RF+2)'(1 << (RF + 1)) - mr0;
  assign r1_full = (2*RF+3)'(r0) * (2*RF+3)'(two_minus_mr0);
endmodule
