// The hybrid mean-shift engine, as hls/cluster/mean_shift.h, with Lanes kernel evaluations a
// cycle. Per sweep and point i, every point j contributes
//   u = (x_i - x0_j)^2 + (y_i - y0_j)^2 + (p_i - p_j)^2 + (t_i - t_j)^2,  w = exp(-u),
//   sums += w, (w x0_j) >> ProductShift, (w y0_j) >> ProductShift, (w p_j) >> ProductShift, (w t_j) >> ProductShift
// and the point moves to sums / sum(w) (rounded, through the reciprocal), or stays when
// sum(w) = 0. Sums are exact, so the lane count cannot change a result.
//
// Memories: the original positions x0, y0 and two buffers of (x, y, p, t) that take turns as
// the current points and the next ones, each split into Lanes banks (point j in bank j % Lanes
// at address j / Lanes) so that every lane reads its point in the same cycle.
//
// Schedule per point: one clock reading the point, then ceil(n / Lanes) clocks issuing point
// pairs; the next point is read in the clock after the last issue, so the points' kernel loops
// follow each other while each one's terms still drain through the lanes (seven clocks). A
// point's sums go to the divider when its last terms are in; the divider takes R + 10 clocks a
// point, so points start at least that far apart. A sweep ends when the divider has finished
// the last point.
`include "evms_assert.svh"

module evms_mean_shift #(
  parameter int PacketMax     = 256,
  parameter int Lanes          = 8,
  parameter int IterationsMax = 8,
  parameter int FeatBits      = 16,   // kFeatInt + kFeatFrac
  parameter int FeatFrac      = 11,
  parameter int WeightFrac    = 16,
  parameter int SumFrac       = 16,
  parameter int ExpTableLog2       = 9,
  parameter int ExpInterpBits     = 8,
  parameter int RecipFrac     = 20,
  parameter     ExpTableFile        = "../generated/exp_9_16.mem"
) (
  input  logic        clk,
  input  logic        rst_n,
  // Loading the packet's features (point i = load_i).
  input  logic                    load_we,
  input  logic [15:0]             load_i,
  input  logic [FeatBits-1:0]    load_x,
  input  logic [FeatBits-1:0]    load_y,
  input  logic [FeatBits-1:0]    load_p,
  input  logic [FeatBits-1:0]    load_t,
  // Running.
  input  logic                    start,
  input  logic [15:0]             n,
  input  logic [7:0]              cfg_max_iterations,
  input  logic [31:0]             cfg_tolerance,
  output logic                    done,
  output logic [7:0]              sweeps,
  // Reading the modes after done (1-cycle latency).
  input  logic [15:0]             rd_i,
  output logic [FeatBits:0]      rd_x,
  output logic [FeatBits:0]      rd_y,
  output logic [FeatBits:0]      rd_p,
  output logic [FeatBits:0]      rd_t,
  // The core's reciprocal unit (math/evms_recip), which no other stage uses while mean shift runs.
  output logic                    recip_start,
  output logic [63:0]             recip_x,
  input  logic                    recip_done,
  input  logic [RecipFrac:0]     recip_r,
  input  logic [6:0]              recip_m
);
  localparam int ModeBits = FeatBits + 1;                          // a mode may round one LSB past the features
  localparam int Depth = (PacketMax + Lanes - 1) / Lanes;
  localparam int AddrBits = Depth > 1 ? $clog2(Depth) : 1;
  localparam int LaneIndexBits = Lanes > 1 ? $clog2(Lanes) : 1;
  localparam int DistFrac = 2 * FeatFrac;
  localparam int ProductShift = WeightFrac + FeatFrac - SumFrac;     // product shift
  localparam int QuotientFrac = FeatFrac + WeightFrac - SumFrac;     // quotient fraction bits
  `EVMS_ASSERT_INIT("the quotient shift must be positive (QuotientFrac <= RecipFrac)", QuotientFrac < RecipFrac + 1)

  // Point j lives in bank j % Lanes at address j / Lanes.
  function automatic [LaneIndexBits-1:0] bank_of(input [15:0] idx);
    begin
      bank_of = LaneIndexBits'(32'(idx) % Lanes);
    end
  endfunction
  function automatic [AddrBits-1:0] addr_of(input [15:0] idx);
    begin
      addr_of = AddrBits'(32'(idx) / Lanes);
    end
  endfunction

  // ---- memories --------------------------------------------------------------------------
  // Per bank: the original positions (x0, y0), and both buffers of points as {x, y} and {p, t},
  // the buffer index as the top address bit. Each memory has one write port and one registered
  // read port, so that it maps to block RAM.
  logic cur_q;  // buffer holding the current points

  // Writes: loading (into buffer 0 and x0, y0) or the divider's next values.
  logic          wr_en_q;
  logic [15:0]   wr_i_q;
  logic [ModeBits-1:0] wr_x_q, wr_y_q, wr_p_q, wr_t_q;

  // Read addresses: lanes read chunk a; a new point reads point i; merging reads rd_i.
  logic [AddrBits:0]   pt_addr, xy_addr;
  logic [ModeBits-1:0] bank_x [Lanes], bank_y [Lanes], bank_p [Lanes], bank_t [Lanes];
  logic [FeatBits-1:0] m_x0_q [Lanes], m_y0_q [Lanes];
  logic [ModeBits-1:0] m_p [Lanes], m_t [Lanes];

  for (genvar b = 0; b < Lanes; b++) begin : g_bank
    logic [FeatBits-1:0] x0 [Depth];
    logic [FeatBits-1:0] y0 [Depth];
    logic [2*ModeBits-1:0] xy [2*Depth];
    logic [2*ModeBits-1:0] pt [2*Depth];
    logic [2*ModeBits-1:0] xy_q, pt_q;
    wire load_here = load_we && bank_of(load_i) == LaneIndexBits'(b);
    wire next_here = wr_en_q && bank_of(wr_i_q) == LaneIndexBits'(b);
    always_ff @(posedge clk) begin
      if (load_here) begin
        x0[addr_of(load_i)] <= load_x;
        y0[addr_of(load_i)] <= load_y;
      end
      m_x0_q[b] <= x0[AddrBits'(a_q)];
      m_y0_q[b] <= y0[AddrBits'(a_q)];
    end
    always_ff @(posedge clk) begin
      if (load_here) begin
        xy[{1'b0, addr_of(load_i)}] <= {ModeBits'(load_x), ModeBits'(load_y)};
      end else if (next_here) begin
        xy[{~cur_q, addr_of(wr_i_q)}] <= {wr_x_q, wr_y_q};
      end
      xy_q <= xy[xy_addr];
    end
    always_ff @(posedge clk) begin
      if (load_here) begin
        pt[{1'b0, addr_of(load_i)}] <= {ModeBits'(load_p), ModeBits'(load_t)};
      end else if (next_here) begin
        pt[{~cur_q, addr_of(wr_i_q)}] <= {wr_p_q, wr_t_q};
      end
      pt_q <= pt[pt_addr];
    end
    assign {bank_x[b], bank_y[b]} = xy_q;
    assign {bank_p[b], bank_t[b]} = pt_q;
    assign m_p[b] = pt_q[2*ModeBits-1:ModeBits];
    assign m_t[b] = pt_q[ModeBits-1:0];
  end

  // Merging reads the modes after done; the bank is chosen by the index it presents.
  assign rd_x = bank_x[bank_of(rd_i)];
  assign rd_y = bank_y[bank_of(rd_i)];
  assign rd_p = bank_p[bank_of(rd_i)];
  assign rd_t = bank_t[bank_of(rd_i)];

  // ---- control ----------------------------------------------------------------------------
  typedef enum logic [2:0] {StIdle, StPoint, StIssue, StSweepEnd, StDone} state_e;
  state_e state_q;
  logic [7:0]  k_q;          // sweep
  logic [15:0] i_q;          // point
  logic [AddrBits:0] a_q;          // chunk address
  logic [7:0]  limit_q;
  logic [31:0] max_move_q;
  logic        sweep_begin_q;  // pulses when a sweep starts: the divider restarts its largest move

  // The point i's current coordinates, read at StPoint and taken in its first issue clock.
  logic signed [ModeBits+1:0] xi_q, yi_q, pi_q, ti_q;
  // The point whose terms drain through the lanes, until its sums go to the divider.
  logic [15:0]   drain_i_q;
  logic [ModeBits-1:0] drain_cur_q [4];
  logic          draining;
  // Clocks until the next point may start: points start R + 10 clocks apart at least, so that
  // the divider has finished the previous point when the next one's sums are in.
  localparam int PointSpacing = 6 + 10;   // evms_recip's latency + the divider's own clocks
  logic [4:0]    spacing_q;

  assign xy_addr = state_q == StPoint ? {cur_q, addr_of(i_q)} : {cur_q, addr_of(rd_i)};
  assign pt_addr = state_q == StPoint ? {cur_q, addr_of(i_q)} : (state_q == StIdle ? {cur_q, addr_of(rd_i)} : {cur_q, AddrBits'(a_q)});

  // Lane issue: address a, chunk valid per lane.
  logic issue, last_chunk;
  assign issue = state_q == StIssue;
  assign last_chunk = (32'(a_q) + 1) * Lanes >= 32'(n);
  logic [Lanes-1:0] lane_valid_issue;
  always_comb begin
    for (int l = 0; l < Lanes; l++) lane_valid_issue[l] = issue && (32'(a_q) * Lanes + l < 32'(n));
  end

  // ---- lanes ------------------------------------------------------------------------------
  // s1: memory data; s2: differences; s3: u; s4..s5: exp; s6: products.
  logic [Lanes-1:0] v1_q, v2_q, v3_q, v4_q, v5_q, v6_q;
  logic [ModeBits-1:0] d_x0_q [5][Lanes], d_y0_q [5][Lanes], d_p_q [5][Lanes], d_t_q [5][Lanes];
  // Differences of two values in [0, 2^ModeBits) fit ModeBits + 1 signed bits: 18 on the Arty build, the
  // widest operand one DSP48E1 squares (19 bits take two).
  logic signed [ModeBits:0] dx_q [Lanes], dy_q [Lanes], dp_q [Lanes], dtt_q [Lanes];
  logic [63:0] u_q [Lanes];
  logic [WeightFrac:0] w [Lanes];
  logic [WeightFrac:0] w6_q [Lanes];
  logic [63:0] px6_q [Lanes], py6_q [Lanes], pp6_q [Lanes], pt6_q [Lanes];
  logic last1_q, last2_q, last3_q, last4_q, last5_q, last6_q;

  for (genvar l = 0; l < Lanes; l++) begin : g_lane
    always_ff @(posedge clk) begin
      dx_q[l]  <= (ModeBits+1)'(xi_q - $signed({2'b0, m_x0_q[l]}));
      dy_q[l]  <= (ModeBits+1)'(yi_q - $signed({2'b0, m_y0_q[l]}));
      dp_q[l]  <= (ModeBits+1)'(pi_q - $signed({1'b0, m_p[l]}));
      dtt_q[l] <= (ModeBits+1)'(ti_q - $signed({1'b0, m_t[l]}));
      // Operands widen before they multiply: a cast of a product would keep its narrow width.
      u_q[l] <= 64'($signed(64'(dx_q[l])) * $signed(64'(dx_q[l]))) + 64'($signed(64'(dy_q[l])) * $signed(64'(dy_q[l]))) +
              64'($signed(64'(dp_q[l])) * $signed(64'(dp_q[l]))) + 64'($signed(64'(dtt_q[l])) * $signed(64'(dtt_q[l])));
      w6_q[l] <= v5_q[l] ? w[l] : '0;
      px6_q[l] <= (64'(w[l]) * 64'(d_x0_q[3][l])) >> ProductShift;
      py6_q[l] <= (64'(w[l]) * 64'(d_y0_q[3][l])) >> ProductShift;
      pp6_q[l] <= (64'(w[l]) * 64'(d_p_q[3][l])) >> ProductShift;
      pt6_q[l] <= (64'(w[l]) * 64'(d_t_q[3][l])) >> ProductShift;
    end
    // The lane's point, carried along to the product stage.
    always_ff @(posedge clk) begin
      d_x0_q[0][l] <= ModeBits'(m_x0_q[l]);
      d_y0_q[0][l] <= ModeBits'(m_y0_q[l]);
      d_p_q[0][l] <= m_p[l];
      d_t_q[0][l] <= m_t[l];
      for (int s = 1; s < 5; s++) begin
        d_x0_q[s][l] <= d_x0_q[s-1][l];
        d_y0_q[s][l] <= d_y0_q[s-1][l];
        d_p_q[s][l] <= d_p_q[s-1][l];
        d_t_q[s][l] <= d_t_q[s-1][l];
      end
    end
    evms_exp_lut #(.TableLog2(ExpTableLog2), .WeightFrac(WeightFrac), .InterpBits(ExpInterpBits), .ArgFrac(DistFrac), .ArgBits(64), .TableFile(ExpTableFile))
      u_exp (.clk(clk), .u(u_q[l]), .w(w[l]));
  end

  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      {v1_q, v2_q, v3_q, v4_q, v5_q, v6_q} <= '0;
      {last1_q, last2_q, last3_q, last4_q, last5_q, last6_q} <= '0;
    end else begin
      v1_q <= lane_valid_issue;
      v2_q <= v1_q;
      v3_q <= v2_q;
      v4_q <= v3_q;
      v5_q <= v4_q;
      v6_q <= v5_q;
      last1_q <= issue && last_chunk;
      last2_q <= last1_q;
      last3_q <= last2_q;
      last4_q <= last3_q;
      last5_q <= last4_q;
      last6_q <= last5_q;
    end
  end

  // s7: sums of the point, across lanes: a balanced tree of adders (log2 P deep, not P) over
  // the lanes' valid terms, then the running sums. Node k of the tree sums nodes 2k and 2k + 1;
  // the lanes are the leaves P .. 2P - 1, and node 1 is the total, one per quantity (w, x, y,
  // p, t).
  logic [63:0] sw_q, sx_q, sy_q, sp_q, st_q;
  logic        sums_ready_q;
  // A point's terms are in the lanes from its last issue until its sums are handed off.
  assign draining = last1_q | last2_q | last3_q | last4_q | last5_q | last6_q | sums_ready_q;
  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      {sw_q, sx_q, sy_q, sp_q, st_q} <= '0;
      sums_ready_q <= 1'b0;
    end else begin
      // node k's five sums are bits [320 k +: 320] (a flat vector: Yosys takes no multi-dimensional
      // variable declared in a block)
      logic [2*Lanes*320-1:0] lane_tree;
      logic [63:0] aw, ax, ay, ap, at;
      lane_tree = '0;
      for (int l = 0; l < Lanes; l++)
        if (v6_q[l]) lane_tree[320*(Lanes + l) +: 320] = {64'(w6_q[l]), px6_q[l], py6_q[l], pp6_q[l], pt6_q[l]};
      for (int node = Lanes - 1; node >= 1; node--)
        for (int q = 0; q < 5; q++)
          lane_tree[320*node + 64*q +: 64] = lane_tree[640*node + 64*q +: 64] + lane_tree[640*node + 320 + 64*q +: 64];
      {aw, ax, ay, ap, at} = lane_tree[320 +: 320];
      // A point's sums are complete the clock after its last terms (last6_q); they go to the
      // divider in that clock and the next point's sums start from zero (its first terms
      // arrive a clock later at the earliest).
      sw_q <= (sums_ready_q ? 64'd0 : sw_q) + aw;
      sx_q <= (sums_ready_q ? 64'd0 : sx_q) + ax;
      sy_q <= (sums_ready_q ? 64'd0 : sy_q) + ay;
      sp_q <= (sums_ready_q ? 64'd0 : sp_q) + ap;
      st_q <= (sums_ready_q ? 64'd0 : st_q) + at;
      sums_ready_q <= last6_q;
    end
  end

  // ---- divider: next = sums / sw, rounded; moves ------------------------------------------
  logic        job_valid_q, job_busy_q;
  logic [15:0] job_i_q;
  logic [63:0] job_sw_q, job_s_q [4];
  logic [ModeBits-1:0] job_cur_q [4];
  logic [2:0]  job_dim_q;
  logic [ModeBits-1:0] job_next_q [4];
  typedef enum logic [2:0] {DrainIdle, DrainRecip, DrainQuot, DrainWrite} dstate_e;
  dstate_e dstate_q;

  assign recip_x = job_sw_q;

  // The quotients are a three-clock pipeline, one dimension a clock, so that no clock holds
  // more than one multiply or one wide add: the sum's four 16-bit digits times r (one DSP
  // each), their sum (the low 64 bits of sum * r) into quot_p_q, then the rounding shift (by at
  // least one bit: QuotientFrac <= RecipFrac).
  logic [RecipFrac+16:0] quot_pp_q [4];
  logic [63:0] quot_p_q;
  logic [6:0]  quot_shift;
  assign quot_shift = 7'(RecipFrac) + recip_m - 7'(QuotientFrac);

  // The sweep's largest move so far, with one more coordinate's move. The quotient pipeline
  // takes the dimensions' moves one a clock as their quotients land, instead of all four in
  // series when the point is written.
  function automatic [31:0] larger_move(input [31:0] so_far, input [ModeBits-1:0] next, input [ModeBits-1:0] now);
    logic [31:0] diff;
    begin
      diff = next > now ? 32'(next) - 32'(now) : 32'(now) - 32'(next);
      larger_move = diff > so_far ? diff : so_far;
    end
  endfunction

  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      dstate_q <= DrainIdle;
      job_busy_q <= 1'b0;
      recip_start <= 1'b0;
      job_dim_q <= '0;
      quot_p_q <= '0;
      for (int g = 0; g < 4; g++) quot_pp_q[g] <= '0;
      wr_en_q <= 1'b0;
      wr_i_q <= '0;
      {wr_x_q, wr_y_q, wr_p_q, wr_t_q} <= '0;
      max_move_q <= '0;
      for (int d = 0; d < 4; d++) job_next_q[d] <= '0;
    end else begin
      recip_start <= 1'b0;
      wr_en_q <= 1'b0;
      if (sweep_begin_q) max_move_q <= '0;
      case (dstate_q)
        DrainIdle: if (job_valid_q) begin
          job_busy_q <= 1'b1;
          if (job_sw_q == 0) begin
            for (int d = 0; d < 4; d++) job_next_q[d] <= job_cur_q[d];
            dstate_q <= DrainWrite;
          end else begin
            recip_start <= 1'b1;
            dstate_q <= DrainRecip;
          end
        end
        DrainRecip: if (recip_done) begin
          job_dim_q <= '0;
          dstate_q <= DrainQuot;
        end
        DrainQuot: begin
          if (job_dim_q < 4)
            for (int g = 0; g < 4; g++) quot_pp_q[g] <= (RecipFrac+17)'(job_s_q[job_dim_q[1:0]][16*g +: 16]) * (RecipFrac+17)'(recip_r);
          if (job_dim_q >= 1 && job_dim_q <= 4)
            quot_p_q <= 64'(quot_pp_q[0]) + (64'(quot_pp_q[1]) << 16) + (64'(quot_pp_q[2]) << 32) + (64'(quot_pp_q[3]) << 48);
          if (job_dim_q >= 2) job_next_q[2'(job_dim_q - 3'd2)] <= ModeBits'(evms_round_pkg::round_shift(quot_p_q, quot_shift - 7'd1));
          if (job_dim_q >= 3) max_move_q <= larger_move(max_move_q, job_next_q[2'(job_dim_q - 3'd3)], job_cur_q[2'(job_dim_q - 3'd3)]);
          job_dim_q <= job_dim_q + 1'b1;
          if (job_dim_q == 5) dstate_q <= DrainWrite;
        end
        DrainWrite: begin
          max_move_q <= larger_move(max_move_q, job_next_q[3], job_cur_q[3]);
          wr_en_q <= 1'b1;
          wr_i_q <= job_i_q;
          {wr_x_q, wr_y_q, wr_p_q, wr_t_q} <= {job_next_q[0], job_next_q[1], job_next_q[2], job_next_q[3]};
          job_busy_q <= 1'b0;
          dstate_q <= DrainIdle;
        end
        default: dstate_q <= DrainIdle;
      endcase
    end
  end

  // ---- sequencing -------------------------------------------------------------------------
  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      state_q <= StIdle;
      done <= 1'b0;
      sweeps <= '0;
      cur_q <= 1'b0;
      k_q <= '0;
      i_q <= '0;
      a_q <= '0;
      limit_q <= '0;
      spacing_q <= '0;
      job_valid_q <= 1'b0;
      job_i_q <= '0;
      job_sw_q <= '0;
      drain_i_q <= '0;
      for (int d = 0; d < 4; d++) begin
        job_s_q[d] <= '0;
        job_cur_q[d] <= '0;
        drain_cur_q[d] <= '0;
      end
      {xi_q, yi_q, pi_q, ti_q} <= '0;
      sweep_begin_q <= 1'b0;
    end else begin
      done <= 1'b0;
      sweep_begin_q <= 1'b0;
      if (spacing_q != 0) spacing_q <= spacing_q - 1'b1;
      if (job_valid_q && dstate_q == DrainIdle) job_valid_q <= 1'b0;
      if (sums_ready_q) begin
        // (the point spacing keeps the divider free here: it took the previous point at least
        // R + 10 clocks ago)
        job_valid_q <= 1'b1;
        job_i_q <= drain_i_q;
        job_sw_q <= sw_q;
        job_s_q[0] <= sx_q;
        job_s_q[1] <= sy_q;
        job_s_q[2] <= sp_q;
        job_s_q[3] <= st_q;
        for (int d = 0; d < 4; d++) job_cur_q[d] <= drain_cur_q[d];
      end
      // The draining point: named at its last issue, its coordinates the clock after (when a
      // one-chunk point has taken them too), handed to the divider when its sums are in.
      if (issue && last_chunk) drain_i_q <= i_q;
      if (last1_q) begin
        drain_cur_q[0] <= ModeBits'(xi_q);
        drain_cur_q[1] <= ModeBits'(yi_q);
        drain_cur_q[2] <= ModeBits'(pi_q);
        drain_cur_q[3] <= ModeBits'(ti_q);
      end
      case (state_q)
        StIdle: if (start) begin
          cur_q <= 1'b0;
          k_q <= '0;
          sweeps <= '0;
          limit_q <= cfg_max_iterations < 8'(IterationsMax) ? cfg_max_iterations : 8'(IterationsMax);
          if (cfg_max_iterations == 0 || n == 0) begin
            done <= 1'b1;
          end else begin
            i_q <= '0;
            sweep_begin_q <= 1'b1;
            state_q <= StPoint;
          end
        end
        // Point i is being read; its kernel loop starts once the previous point started
        // PointSpacing clocks ago.
        StPoint: if (spacing_q == 0) begin
          spacing_q <= 5'(PointSpacing - 1);
          a_q <= '0;
          state_q <= StIssue;
        end
        StIssue: begin
          if (a_q == 0) begin
            xi_q  <= $signed({2'b0, bank_x[bank_of(i_q)]});
            yi_q  <= $signed({2'b0, bank_y[bank_of(i_q)]});
            pi_q <= $signed({2'b0, bank_p[bank_of(i_q)]});
            ti_q  <= $signed({2'b0, bank_t[bank_of(i_q)]});
          end
          if (last_chunk) begin
            if (32'(i_q) + 1 < 32'(n)) begin
              i_q <= i_q + 1'b1;
              state_q <= StPoint;
            end else begin
              state_q <= StSweepEnd;
            end
          end else begin
            a_q <= a_q + 1'b1;
          end
        end
        StSweepEnd: if (!draining && !job_valid_q && !job_busy_q && dstate_q == DrainIdle && !wr_en_q) begin
          // The divider has written every next point: they become the current ones.
          cur_q <= ~cur_q;
          sweeps <= k_q + 1'b1;
          if (max_move_q <= cfg_tolerance || k_q + 1'b1 >= limit_q) begin
            state_q <= StDone;
          end else begin
            k_q <= k_q + 1'b1;
            i_q <= '0;
            sweep_begin_q <= 1'b1;
            state_q <= StPoint;
          end
        end
        StDone: begin
          done <= 1'b1;
          state_q <= StIdle;
        end
        default: state_q <= StIdle;
      endcase
    end
  end

  // The divider must be free when a point's sums are in (the point spacing guarantees it).
  `EVMS_ASSERT("a_q point's sums are in while the divider is busy", !(sums_ready_q && (job_valid_q || job_busy_q || dstate_q != DrainIdle)), clk, rst_n)
endmodule
