// Per cluster, the sums of x and y and the count of the events of one subset (the ON events for
// the polarity midpoint, the events first on their pixel for the pixel centre), and with HasAge
// the sum of their ages (time since the packet's first event, which times the pixel centre),
// kept beside evms_centroid's sums and valid with them: a cluster whose sums are not valid yet
// reads zero, so a packet clears every cluster at once. A memory with one write port and a
// combinational read (distributed RAM on a Xilinx part), as the centroid's other sums.
module evms_cluster_subset_sums #(
  parameter int ClustersMax = 16,
  parameter bit HasAge      = 1'b0,   // 0: `age` is not read and `st` is zero
  localparam int ClusterIndexBits = ClustersMax > 1 ? $clog2(ClustersMax) : 1,
  localparam int SumBits = HasAge ? 144 : 80
) (
  input  logic                        clk,
  input  logic [ClustersMax-1:0]      valid,    // the packet has added to the cluster
  input  logic [ClusterIndexBits-1:0] c,        // the cluster read, and added to when `adding`
  input  logic                        adding,
  input  logic                        in_subset,  // the event added is one of the subset
  input  logic [15:0]                 x,
  input  logic [15:0]                 y,
  input  logic [31:0]                 age,
  output logic [31:0]                 sx,
  output logic [31:0]                 sy,
  output logic [15:0]                 count,
  output logic [63:0]                 st
);
  logic [SumBits-1:0] sums [ClustersMax];
  logic [SumBits-1:0] sums_c;
  assign sums_c = valid[c] ? sums[c] : '0;
  assign {sx, sy, count} = sums_c[79:0];
  if (HasAge) begin : g_age
    assign st = sums_c[143:80];
    always_ff @(posedge clk) begin
      if (adding) sums[c] <= in_subset ? {st + 64'(age), sx + 32'(x), sy + 32'(y), count + 16'd1} : sums_c;
    end
  end else begin : g_no_age
    assign st = '0;
    logic unused_age;   // waived in cluster/evms_cluster.vlt
    assign unused_age = ^age;
    always_ff @(posedge clk) begin
      if (adding) sums[c] <= in_subset ? {sx + 32'(x), sy + 32'(y), count + 16'd1} : sums_c;
    end
  end
endmodule
