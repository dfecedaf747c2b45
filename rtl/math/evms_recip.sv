// Reciprocal by table and one Newton-Raphson step, as hls/math/reciprocal.h:
//   m = msb(x); mant = x normalized to [1, 2) with RecipFrac fraction bits (truncated);
//   r0 = TableLog2[top TableLog2 bits after the leading one]; r1 = (r0 * (2 - (mant * r0 >> RecipFrac))) >> RecipFrac
// so that 1/x = r1 * 2^-(RecipFrac + m). Start (x > 0) ... done 6 clocks later, one step a clock:
// x registered, its leading one, the normalizing shift, the table read, and each of the two
// products with its register, so that no clock holds more than one multiply or one wide search.
module evms_recip #(
  parameter int TableLog2        = 8,
  parameter int RecipFrac       = 20,
  parameter     TableFile = "../generated/recip_8_20.mem"
) (
  input  logic        clk,
  input  logic        rst_n,
  input  logic        start,
  input  logic [63:0] x,
  output logic        done,
  output logic [RecipFrac:0] r,
  output logic [6:0]  m
);
  logic [RecipFrac:0] table_rom [0:(1<<TableLog2)-1];
  initial $readmemh(TableFile, table_rom);

  // The most significant set bit, as a tree: each byte's own leading one and whether it has
  // one side by side, then the top nonzero byte picks its own (a loop over the 64 bits would
  // map to a 64-deep priority chain).
  function automatic [5:0] msb(input [63:0] v);
    logic [2:0] in_byte [8];
    logic [7:0] nonzero;
    logic [2:0] top;
    begin
      for (int b = 0; b < 8; b++) begin
        nonzero[b] = |v[8*b +: 8];
        in_byte[b] = 3'd0;
        for (int k = 0; k < 8; k++) if (v[8*b + k]) in_byte[b] = 3'(k);
      end
      top = 3'd0;
      for (int b = 0; b < 8; b++) if (nonzero[b]) top = 3'(b);
      msb = {top, in_byte[top]};
    end
  endfunction

  logic [63:0]     x_q;
  logic [5:0]      lead_q;
  logic [RecipFrac:0]     mant_q, r0_q;
  logic [RecipFrac+1:0]   two_minus_mr0_q;
  logic [2*RecipFrac+1:0] mr0_full;
  logic [2*RecipFrac+2:0] r1_full;
  logic [5:0]      step_q;  // one-hot position in the pipeline: each stage's register below loads in its step
  logic            take;  // a start the pipeline accepts
  assign take = start && step_q == 0;
  assign mr0_full = (2*RecipFrac+2)'(mant_q) * (2*RecipFrac+2)'(r0_q);
  assign r1_full = (2*RecipFrac+3)'(r0_q) * (2*RecipFrac+3)'(two_minus_mr0_q);
  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      step_q <= '0;
      done <= 1'b0;
      r <= '0;
      x_q <= '0;
      lead_q <= '0;
      mant_q <= '0;
      r0_q <= '0;
      two_minus_mr0_q <= '0;
    end else begin
      step_q <= {step_q[4:0], take};
      done <= step_q[4];
      if (take) x_q <= x;
      if (step_q[0]) lead_q <= msb(x_q);
      if (step_q[1]) mant_q <= (RecipFrac+1)'((x_q << (6'd63 - lead_q)) >> (63 - RecipFrac));  // the leading one to bit RecipFrac
      if (step_q[2]) r0_q <= table_rom[TableLog2'(mant_q >> (RecipFrac - TableLog2))];
      if (step_q[3]) two_minus_mr0_q <= (RecipFrac+2)'(1 << (RecipFrac + 1)) - (RecipFrac+2)'(mr0_full >> RecipFrac);
      if (step_q[4]) r <= (RecipFrac+1)'(r1_full >> RecipFrac);
    end
  end
  assign m = {1'b0, lead_q};
endmodule
