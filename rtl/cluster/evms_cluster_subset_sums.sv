// Per cluster, the sums of x and y and the count of the events of one subset (the ON events for
// the polarity midpoint, the events first on their pixel for the pixel centre), kept beside
// evms_centroid's sums and valid with them: a cluster whose sums are not valid yet reads zero,
// so a packet clears every cluster at once. A memory with one write port and a combinational
// read (distributed RAM on a Xilinx part), as the centroid's other sums.
module evms_cluster_subset_sums #(
  parameter int ClustersMax = 16,
  localparam int ClusterIndexBits = ClustersMax > 1 ? $clog2(ClustersMax) : 1
) (
  input  logic                        clk,
  input  logic [ClustersMax-1:0]      valid,    // the packet has added to the cluster
  input  logic [ClusterIndexBits-1:0] c,        // the cluster read, and added to when `adding`
  input  logic                        adding,
  input  logic                        in_subset,  // the event added is one of the subset
  input  logic [15:0]                 x,
  input  logic [15:0]                 y,
  output logic [31:0]                 sx,
  output logic [31:0]                 sy,
  output logic [15:0]                 count
);
  logic [79:0] sums [ClustersMax];
  assign {sx, sy, count} = valid[c] ? sums[c] : 80'd0;
  always_ff @(posedge clk) begin
    if (adding) sums[c] <= in_subset ? {sx + 32'(x), sy + 32'(y), count + 16'd1} : {sx, sy, count};
  end
endmodule
