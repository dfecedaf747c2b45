// exp(-u) from a table with linear interpolation, as hls/math/exp_table.h: u has UF fraction
// bits; u >= 16 gives 0; else i = u >> (UF + 4 - L), f = the IB bits below the index, and
// w = v[i] - ((v[i] - v[i+1]) * f >> IB). The ROM holds v[0..2^L], one word per entry, and is
// read at i and i+1 through two ports. Latency 2; a new u every cycle: the first clock reads
// the table, the second the slope's product into a register, so that the product is not in
// series with the consumer's own multiply (the mean-shift lanes weight by w in the next clock).
// The samples never increase (ExpTable.SamplesNeverIncrease), so v[i] - v[i+1] is WF + 1 bits.
// The slope's product by the IB-bit fraction is a sum of shifted copies in fabric, not a
// multiplier: Yosys would give every product a DSP, and the lanes' DSPs are what limits their
// count on the XC7A35T (a DSP48E1 a lane; docs/rtl.md, "Area").
module evms_exp_lut #(
  parameter int    L        = 9,
  parameter int    WF       = 16,
  parameter int    IB       = 8,
  parameter int    UF       = 22,
  parameter int    UW       = 64,
  parameter        MEM_FILE = "exp_9_16.mem"
) (
  input  logic          clk,
  input  logic [UW-1:0] u,
  output logic [WF:0]   w
);
  localparam int Below = UF + 4 - L;
  logic [WF:0] rom [0:(1<<L)];
  initial $readmemh(MEM_FILE, rom);

  logic [L-1:0]   i;
  logic           zero_q, zero_qq;
  logic [IB-1:0]  f_q;
  logic [WF:0]    v0_q, v1_q, v0_qq;
  logic [WF+IB:0] slope_q;
  logic [WF:0]    step;
  logic [WF+IB:0] slope;
  assign i = L'(u >> Below);
  assign step = v0_q - v1_q;
  always_comb begin
    slope = '0;
    for (int b = 0; b < IB; b++) slope = slope + (f_q[b] ? (WF+IB+1)'(step) << b : '0);
  end

  always_ff @(posedge clk) begin
    zero_q  <= (u >> (UF + 4)) != 0;
    f_q     <= IB'(u >> (Below - IB));
    v0_q    <= rom[{1'b0, i}];
    v1_q    <= rom[(L+1)'(i) + 1'b1];
    slope_q <= slope;
    v0_qq   <= v0_q;
    zero_qq <= zero_q;
  end
  assign w = zero_qq ? '0 : v0_qq - (WF+1)'(slope_q >> IB);
endmodule
