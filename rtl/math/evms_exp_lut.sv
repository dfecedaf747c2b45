// exp(-u) from a table with linear interpolation, as hls/math/exp_table.h: u has ArgFrac fraction
// bits; u >= 16 gives 0; else i = u >> (ArgFrac + 4 - TableLog2), f = the InterpBits bits below the index, and
// w = v[i] - ((v[i] - v[i+1]) * f >> InterpBits). The ROM holds v[0..2^TableLog2], one word per entry, and is
// read at i and i+1 through two ports. Latency 2; a new u every cycle: the first clock reads
// the table, the second the slope's product into a register, so that the product is not in
// series with the consumer's own multiply (the mean-shift lanes weight by w in the next clock).
// The samples never increase (ExpTable.SamplesNeverIncrease), so v[i] - v[i+1] is WeightFrac + 1 bits.
// The slope's product by the InterpBits-bit fraction is a sum of shifted copies in fabric, not a
// multiplier: Yosys would give every product a DSP, and the lanes' DSPs are what limits their
// count on the XC7A35T (a DSP48E1 a lane; docs/rtl.md, "Area").
module evms_exp_lut #(
  parameter int    TableLog2        = 9,
  parameter int    WeightFrac       = 16,
  parameter int    InterpBits       = 8,
  parameter int    ArgFrac       = 22,
  parameter int    ArgBits       = 64,
  parameter        TableFile = "../generated/exp_9_16.mem"
) (
  input  logic          clk,
  input  logic [ArgBits-1:0] u,
  output logic [WeightFrac:0]   w
);
  localparam int Below = ArgFrac + 4 - TableLog2;
  logic [WeightFrac:0] rom [0:(1<<TableLog2)];
  initial $readmemh(TableFile, rom);

  logic [TableLog2-1:0]   i;
  logic           zero_q, zero_qq;
  logic [InterpBits-1:0]  f_q;
  logic [WeightFrac:0]    v0_q, v1_q, v0_qq;
  logic [WeightFrac+InterpBits:0] slope_q;
  logic [WeightFrac:0]    step;
  logic [WeightFrac+InterpBits:0] slope;
  assign i = TableLog2'(u >> Below);
  assign step = v0_q - v1_q;
  always_comb begin
    slope = '0;
    for (int b = 0; b < InterpBits; b++) slope = slope + (f_q[b] ? (WeightFrac+InterpBits+1)'(step) << b : '0);
  end

  always_ff @(posedge clk) begin
    zero_q  <= (u >> (ArgFrac + 4)) != 0;
    f_q     <= InterpBits'(u >> (Below - InterpBits));
    v0_q    <= rom[{1'b0, i}];
    v1_q    <= rom[(TableLog2+1)'(i) + 1'b1];
    slope_q <= slope;
    v0_qq   <= v0_q;
    zero_qq <= zero_q;
  end
  assign w = zero_qq ? '0 : v0_qq - (WeightFrac+1)'(slope_q >> InterpBits);
endmodule
