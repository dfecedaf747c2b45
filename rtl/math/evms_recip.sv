// Reciprocal by table and one Newton-Raphson step, as hls/math/reciprocal.h:
//   m = msb(x); mant = x normalized to [1, 2) with RF fraction bits (truncated);
//   r0 = T[top T bits after the leading one]; r1 = (r0 * (2 - (mant * r0 >> RF))) >> RF
// so that 1/x = r1 * 2^-(RF + m). Start (x > 0) ... done 6 clocks later, one step a clock:
// x registered, its leading one, the normalizing shift, the table read, and each of the two
// products with its register, so that no clock holds more than one multiply or one wide search.
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
  logic [5:0]      lead;
  logic [RF:0]     mant, r0;
  logic [RF+1:0]   two_minus_mr0;
  logic [2*RF+1:0] mr0_full;
  logic [2*RF+2:0] r1_full;
  logic [5:0]      step;  // one-hot position in the pipeline
  logic            take;  // a start the pipeline accepts
  assign take = start && step == 0;
  assign mr0_full = (2*RF+2)'(mant) * (2*RF+2)'(r0);
  assign r1_full = (2*RF+3)'(r0) * (2*RF+3)'(two_minus_mr0);
  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      step <= '0;
      done <= 1'b0;
      r <= '0;
      x_q <= '0;
      lead <= '0;
      mant <= '0;
      r0 <= '0;
      two_minus_mr0 <= '0;
    end else begin
      step <= {step[4:0], take};
      done <= step[4];
      if (take) x_q <= x;
      if (step[0]) lead <= msb(x_q);
      if (step[1]) mant <= (RF+1)'((x_q << (6'd63 - lead)) >> (63 - RF));  // the leading one to bit RF
      if (step[2]) r0 <= table_rom[T'(mant >> (RF - T))];
      if (step[3]) two_minus_mr0 <= (RF+2)'(1 << (RF + 1)) - (RF+2)'(mr0_full >> RF);
      if (step[4]) r <= (RF+1)'(r1_full >> RF);
    end
  end
  assign m = {1'b0, lead};
endmodule
