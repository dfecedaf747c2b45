// Modes to clusters, as hls/cluster/merge.h: each mode in input order joins the nearest seed
// (a cluster's first mode, kept here in registers) within the merge radius, ties to the older
// cluster; or opens a new cluster while fewer than max_clusters are open; or is noise. Then
// clusters smaller than min_cluster_size become noise and the rest are renumbered in seed
// order. One cycle per (mode, seed) pair, through a three-stage pipeline (the differences to the
// seed, their squared sum, the comparison), so that no clock holds a multiply and a 64-bit
// comparison in series: a mode's seeds take seeds + 2 clocks.
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
  typedef enum logic [3:0] {S_IDLE, S_READ, S_WAIT, S_SEEDS, S_DECIDE, S_RENUMBER, S_RELABEL_READ, S_RELABEL_WAIT,
                            S_RELABEL_WRITE, S_DONE} state_e;
  state_e state;
  logic [ModeBits-1:0] seed_x [ClustersMax], seed_y [ClustersMax], seed_p [ClustersMax], seed_t [ClustersMax];
  logic [15:0]   size [ClustersMax];
  logic signed [7:0] renumber [ClustersMax];
  logic [ModeBits-1:0] mx, my, mp, mt;
  logic [15:0]   i;
  logic [7:0]    c, seeds, count;
  logic signed [8:0] best;
  logic [63:0]   best_d2;

  // Distance from the mode to seed c: the differences (stage A), then their squared sum (B),
  // each with the seed's index and a valid bit; stage C compares.
  logic signed [ModeBits:0] ex, ey, ep, et;
  logic [63:0] d2;
  logic        a_valid, b_valid;
  logic [7:0]  a_c, b_c;
  always_ff @(posedge clk) begin
    if (state == S_SEEDS) begin
      ex <= $signed({1'b0, mx}) - $signed({1'b0, seed_x[ClusterIndexBits'(c)]});
      ey <= $signed({1'b0, my}) - $signed({1'b0, seed_y[ClusterIndexBits'(c)]});
      ep <= $signed({1'b0, mp}) - $signed({1'b0, seed_p[ClusterIndexBits'(c)]});
      et <= $signed({1'b0, mt}) - $signed({1'b0, seed_t[ClusterIndexBits'(c)]});
      a_c <= c;
      d2 <= 64'($signed(64'(ex)) * $signed(64'(ex))) + 64'($signed(64'(ey)) * $signed(64'(ey))) +
            64'($signed(64'(ep)) * $signed(64'(ep))) + 64'($signed(64'(et)) * $signed(64'(et)));
      b_c <= a_c;
    end
  end

  assign rd_i = i;

  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      state <= S_IDLE;
      done <= 1'b0;
      clusters <= '0;
      co_we <= 1'b0;
      co_i <= '0;
      co_value <= '0;
      i <= '0;
      c <= '0;
      seeds <= '0;
      count <= '0;
      best <= '0;
      best_d2 <= '0;
      a_valid <= 1'b0;
      b_valid <= 1'b0;
      {mx, my, mp, mt} <= '0;
      for (int q = 0; q < ClustersMax; q++) begin
        size[q] <= '0;
        renumber[q] <= '0;
        {seed_x[q], seed_y[q], seed_p[q], seed_t[q]} <= '0;
      end
    end else begin
      done <= 1'b0;
      co_we <= 1'b0;
      case (state)
        S_IDLE: if (start) begin
          i <= '0;
          seeds <= '0;
          state <= n == 0 ? S_RENUMBER : S_READ;
        end
        S_READ: state <= S_WAIT;  // rd_i = i is being read
        S_WAIT: begin
          {mx, my, mp, mt} <= {rd_x, rd_y, rd_p, rd_t};
          best <= -9'sd1;
          best_d2 <= '1;
          c <= '0;
          state <= S_SEEDS;
        end
        S_SEEDS: begin
          a_valid <= c < seeds;
          b_valid <= a_valid;
          if (b_valid && d2 <= cfg_merge_radius2 && d2 < best_d2) begin
            best <= $signed({1'b0, b_c});
            best_d2 <= d2;
          end
          c <= c + 1'b1;
          if (9'(c) >= 9'(seeds) + 9'd1) state <= S_DECIDE;  // the last seed is compared in this clock
        end
        S_DECIDE: begin
          logic signed [8:0] b;
          b = best;
          if (b < 0 && seeds < cfg_max_clusters && 32'(seeds) < ClustersMax) begin
            b = $signed({1'b0, seeds});
            seed_x[ClusterIndexBits'(seeds)] <= mx;
            seed_y[ClusterIndexBits'(seeds)] <= my;
            seed_p[ClusterIndexBits'(seeds)] <= mp;
            seed_t[ClusterIndexBits'(seeds)] <= mt;
            size[ClusterIndexBits'(seeds)] <= 16'd1;
            seeds <= seeds + 1'b1;
          end else if (b >= 0) begin
            size[ClusterIndexBits'(b)] <= size[ClusterIndexBits'(b)] + 1'b1;
          end
          co_we <= 1'b1;
          co_i <= i;
          co_value <= 8'(b);
          if (32'(i) + 1 < 32'(n)) begin
            i <= i + 1'b1;
            state <= S_READ;
          end else begin
            c <= '0;
            count <= '0;
            state <= S_RENUMBER;
          end
        end
        S_RENUMBER: begin
          if (c >= seeds) begin
            i <= '0;
            state <= n == 0 ? S_DONE : S_RELABEL_READ;
          end else begin
            if (size[ClusterIndexBits'(c)] >= cfg_min_cluster_size) begin
              renumber[ClusterIndexBits'(c)] <= $signed(count);
              count <= count + 1'b1;
            end else begin
              renumber[ClusterIndexBits'(c)] <= -8'sd1;
            end
            c <= c + 1'b1;
          end
        end
        S_RELABEL_READ: begin
          co_i <= i;
          state <= S_RELABEL_WAIT;
        end
        S_RELABEL_WAIT: state <= S_RELABEL_WRITE;
        S_RELABEL_WRITE: begin
          co_we <= 1'b1;
          co_value <= co_rdata >= 0 ? renumber[ClusterIndexBits'(co_rdata)] : -8'sd1;
          if (32'(i) + 1 < 32'(n)) begin
            i <= i + 1'b1;
            state <= S_RELABEL_READ;
          end else begin
            state <= S_DONE;
          end
        end
        S_DONE: begin
          clusters <= count;
          done <= 1'b1;
          state <= S_IDLE;
        end
        default: state <= S_IDLE;
      endcase
    end
  end
endmodule
