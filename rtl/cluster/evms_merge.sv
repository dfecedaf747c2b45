// Modes to clusters, as hls/cluster/merge.h: each mode in input order joins the nearest seed
// (a cluster's first mode, kept here in registers) within the merge radius, ties to the older
// cluster; or opens a new cluster while fewer than max_clusters are open; or is noise. Then
// clusters smaller than min_cluster_size become noise and the rest are renumbered in seed
// order. One cycle per (mode, seed) pair, through a three-stage pipeline (the differences to the
// seed, their squared sum, the comparison), so that no clock holds a multiply and a 64-bit
// comparison in series: a mode's seeds take seeds + 2 clocks.
`include "evms_assert.svh"

module evms_merge #(
  parameter int ClustersMax = 16,
  parameter int ModeBits           = 17      // mode width (features + 1)
) (
  input  logic          clk,
  input  logic          rst_n,
  input  logic          start,
  input  logic [15:0]   n,
  input  logic [63:0]   cfg_merge_radius2,
  input  logic [15:0]   cfg_min_cluster_size,
  input  logic [7:0]    cfg_max_clusters,
  // Mode reads (1-cycle latency).
  output logic [15:0]   rd_i,
  input  logic [ModeBits-1:0] rd_x,
  input  logic [ModeBits-1:0] rd_y,
  input  logic [ModeBits-1:0] rd_p,
  input  logic [ModeBits-1:0] rd_t,
  // Cluster of each point: written here, read by the core afterwards.
  output logic          co_we,
  output logic [15:0]   co_i,
  output logic signed [7:0] co_value,
  input  logic signed [7:0] co_rdata,   // cluster_of[co_i], 1-cycle latency
  output logic          done,
  output logic [7:0]    clusters
);
  localparam int ClusterIndexBits = ClustersMax > 1 ? $clog2(ClustersMax) : 1;
  `EVMS_ASSERT_INIT("a cluster's index fits the 8-bit signed label (ClustersMax <= 127)", ClustersMax <= 127)
  typedef enum logic [3:0] {StIdle, StRead, StWait, StSeeds, StDecide, StRenumber, StRelabelRead, StRelabelWait,
                            StRelabelWrite, StDone} state_e;
  state_e state_q, state_d;
  // Each cluster's seed (its first mode), size and new number: register files written below.
  logic [ModeBits-1:0] seed_x_q [ClustersMax], seed_y_q [ClustersMax], seed_p_q [ClustersMax], seed_t_q [ClustersMax];
  logic [15:0]   size_q [ClustersMax];
  logic signed [7:0] renumber_q [ClustersMax];
  logic [ModeBits-1:0] mx_q, mx_d, my_q, my_d, mp_q, mp_d, mt_q, mt_d;   // the mode being merged
  logic [15:0]   i_q, i_d;
  logic [7:0]    c_q, c_d, seeds_q, seeds_d, count_q, count_d;
  logic signed [8:0] best_q, best_d;
  logic [63:0]   best_d2_q, best_d2_d;
  logic          done_d, co_we_d;
  logic [15:0]   co_i_d;
  logic signed [7:0] co_value_d;
  logic [7:0]    clusters_d;

  // Distance from the mode to seed c: the differences (stage A), then their squared sum (B),
  // each with the seed's index and a valid bit; stage C compares.
  logic signed [ModeBits:0] ex_q, ey_q, ep_q, et_q;
  logic [63:0] d2_q;
  logic        a_valid_q, a_valid_d, b_valid_q, b_valid_d;
  logic [7:0]  a_c_q, b_c_q;
  always_ff @(posedge clk) begin
    if (state_q == StSeeds) begin
      ex_q <= $signed({1'b0, mx_q}) - $signed({1'b0, seed_x_q[ClusterIndexBits'(c_q)]});
      ey_q <= $signed({1'b0, my_q}) - $signed({1'b0, seed_y_q[ClusterIndexBits'(c_q)]});
      ep_q <= $signed({1'b0, mp_q}) - $signed({1'b0, seed_p_q[ClusterIndexBits'(c_q)]});
      et_q <= $signed({1'b0, mt_q}) - $signed({1'b0, seed_t_q[ClusterIndexBits'(c_q)]});
      a_c_q <= c_q;
      d2_q <= 64'($signed(64'(ex_q)) * $signed(64'(ex_q))) + 64'($signed(64'(ey_q)) * $signed(64'(ey_q))) +
              64'($signed(64'(ep_q)) * $signed(64'(ep_q))) + 64'($signed(64'(et_q)) * $signed(64'(et_q)));
      b_c_q <= a_c_q;
    end
  end

  assign rd_i = i_q;

  // The cluster the mode joins in StDecide (-1: noise), opening one when it may.
  logic signed [8:0] joined;
  logic opens;
  assign opens = best_q < 0 && seeds_q < cfg_max_clusters && 32'(seeds_q) < ClustersMax;
  assign joined = opens ? $signed({1'b0, seeds_q}) : best_q;

  always_comb begin
    state_d = state_q;
    {mx_d, my_d, mp_d, mt_d} = {mx_q, my_q, mp_q, mt_q};
    {i_d, c_d, seeds_d, count_d, best_d, best_d2_d} = {i_q, c_q, seeds_q, count_q, best_q, best_d2_q};
    {a_valid_d, b_valid_d} = {a_valid_q, b_valid_q};
    {co_i_d, co_value_d, clusters_d} = {co_i, co_value, clusters};
    {done_d, co_we_d} = '0;
    case (state_q)
      StIdle: if (start) begin
        i_d = '0;
        seeds_d = '0;
        state_d = n == 0 ? StRenumber : StRead;
      end
      StRead: state_d = StWait;  // rd_i = i is being read
      StWait: begin
        {mx_d, my_d, mp_d, mt_d} = {rd_x, rd_y, rd_p, rd_t};
        best_d = -9'sd1;
        best_d2_d = '1;
        c_d = '0;
        state_d = StSeeds;
      end
      StSeeds: begin
        a_valid_d = c_q < seeds_q;
        b_valid_d = a_valid_q;
        if (b_valid_q && d2_q <= cfg_merge_radius2 && d2_q < best_d2_q) begin
          best_d = $signed({1'b0, b_c_q});
          best_d2_d = d2_q;
        end
        c_d = c_q + 1'b1;
        if (9'(c_q) >= 9'(seeds_q) + 9'd1) state_d = StDecide;  // the last seed is compared in this clock
      end
      StDecide: begin
        if (opens) seeds_d = seeds_q + 1'b1;
        co_we_d = 1'b1;
        co_i_d = i_q;
        co_value_d = 8'(joined);
        if (32'(i_q) + 1 < 32'(n)) begin
          i_d = i_q + 1'b1;
          state_d = StRead;
        end else begin
          c_d = '0;
          count_d = '0;
          state_d = StRenumber;
        end
      end
      StRenumber: begin
        if (c_q >= seeds_q) begin
          i_d = '0;
          state_d = n == 0 ? StDone : StRelabelRead;
        end else begin
          if (size_q[ClusterIndexBits'(c_q)] >= cfg_min_cluster_size) count_d = count_q + 1'b1;
          c_d = c_q + 1'b1;
        end
      end
      StRelabelRead: begin
        co_i_d = i_q;
        state_d = StRelabelWait;
      end
      StRelabelWait: state_d = StRelabelWrite;
      StRelabelWrite: begin
        co_we_d = 1'b1;
        co_value_d = co_rdata >= 0 ? renumber_q[ClusterIndexBits'(co_rdata)] : -8'sd1;
        if (32'(i_q) + 1 < 32'(n)) begin
          i_d = i_q + 1'b1;
          state_d = StRelabelRead;
        end else begin
          state_d = StDone;
        end
      end
      StDone: begin
        clusters_d = count_q;
        done_d = 1'b1;
        state_d = StIdle;
      end
      default: state_d = StIdle;
    endcase
  end

  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      state_q <= StIdle;
      {mx_q, my_q, mp_q, mt_q} <= '0;
      {i_q, c_q, seeds_q, count_q, best_q, best_d2_q} <= '0;
      {a_valid_q, b_valid_q} <= '0;
      {co_i, co_value, clusters, done, co_we} <= '0;
    end else begin
      state_q <= state_d;
      {mx_q, my_q, mp_q, mt_q} <= {mx_d, my_d, mp_d, mt_d};
      {i_q, c_q, seeds_q, count_q, best_q, best_d2_q} <= {i_d, c_d, seeds_d, count_d, best_d, best_d2_d};
      {a_valid_q, b_valid_q} <= {a_valid_d, b_valid_d};
      {co_i, co_value, clusters, done, co_we} <= {co_i_d, co_value_d, clusters_d, done_d, co_we_d};
    end
  end

  // The register files: a new cluster's seed and size, a joined cluster's size, and each
  // cluster's new number as StRenumber passes it.
  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      for (int q = 0; q < ClustersMax; q++) begin
        size_q[q] <= '0;
        renumber_q[q] <= '0;
        {seed_x_q[q], seed_y_q[q], seed_p_q[q], seed_t_q[q]} <= '0;
      end
    end else if (state_q == StDecide && opens) begin
      seed_x_q[ClusterIndexBits'(seeds_q)] <= mx_q;
      seed_y_q[ClusterIndexBits'(seeds_q)] <= my_q;
      seed_p_q[ClusterIndexBits'(seeds_q)] <= mp_q;
      seed_t_q[ClusterIndexBits'(seeds_q)] <= mt_q;
      size_q[ClusterIndexBits'(seeds_q)] <= 16'd1;
    end else if (state_q == StDecide && best_q >= 0) begin
      size_q[ClusterIndexBits'(best_q)] <= size_q[ClusterIndexBits'(best_q)] + 1'b1;
    end else if (state_q == StRenumber && c_q < seeds_q) begin
      renumber_q[ClusterIndexBits'(c_q)] <= size_q[ClusterIndexBits'(c_q)] >= cfg_min_cluster_size ? $signed(count_q) : -8'sd1;
    end
  end
endmodule
