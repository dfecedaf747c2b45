// The seeded path after the climbs and the links, as hls/cluster/warm_seeds.h: modes with at
// least cfg_min_cluster_size events become clusters, the first cfg_max_clusters of them in the
// order they opened (keep_clusters); every event gets its cluster or -1; each cluster's mode
// becomes a warm seed for the next packet with the ball radius^2 = cfg_warm_scale2 times the
// variance of its events' climb features about the mode, clamped to [h^2, max(h^2,
// cfg_warm_ball2_max)] (warm_balls). The climbs' features have no polarity or time, so the
// variance is that of x and y.
//
// Schedule: 1 to start; ModesMax to clear the sizes and sums; 2 an event to count them; 2 a mode
// to keep or drop it; 3 an event to label it and add it to its cluster's sums (2 without a
// mode); per cluster, 2 divisions of 66 clocks (both axes at once: the means, then the mean
// squares) and 4 more to read the sums, finish its ball and write the seed.
// The packet's events (mode after linking, climb features) and the modes are read through
// ev_j and md_c with the registered read of a block RAM: the data belong to the address of the
// clock before. The seeds go out on the warm port of evms_seeded_climbs.
`include "evms_assert.svh"

module evms_warm_seeds #(
  parameter int PacketMax   = 256,
  parameter int ModesMax    = 64,
  parameter int ClustersMax = 16,
  parameter int UnitShift   = 19,   // fraction bits of a climb feature: h^2 = 2^(2 UnitShift)
  parameter int SpreadFrac  = 8,    // fraction bits of cfg_warm_scale2
  parameter int CoordBits   = 32
) (
  input  logic                        clk,
  input  logic                        rst_n,
  input  logic                        start,
  input  logic [15:0]                 n,
  input  logic [15:0]                 mode_count,
  input  logic [15:0]                 cfg_min_cluster_size,
  input  logic [7:0]                  cfg_max_clusters,
  input  logic [31:0]                 cfg_warm_scale2,
  input  logic [63:0]                 cfg_warm_ball2_max,
  // The packet's events.
  output logic [15:0]                 ev_j,
  input  logic signed [15:0]          ev_mode,
  input  logic [CoordBits-1:0]        ev_x,
  input  logic [CoordBits-1:0]        ev_y,
  // The modes.
  output logic [7:0]                  md_c,
  input  logic [CoordBits-1:0]        md_x,
  input  logic [CoordBits-1:0]        md_y,
  // Each event's cluster.
  output logic                        co_we,
  output logic [15:0]                 co_j,
  output logic signed [7:0]           co_value,
  // The warm seeds for the next packet.
  output logic                        warm_we,
  output logic [7:0]                  warm_k,
  output logic [CoordBits-1:0]        warm_x,
  output logic [CoordBits-1:0]        warm_y,
  output logic [63:0]                 warm_ball2,
  output logic                        done,       // one clock
  output logic [7:0]                  clusters
);
  localparam int CntBits = $clog2(PacketMax + 1);
  localparam int ModeBits = ModesMax > 1 ? $clog2(ModesMax) : 1;
  localparam int ClusterBits = ClustersMax > 1 ? $clog2(ClustersMax) : 1;
  localparam int DevBits = CoordBits + 1;                 // a feature minus its mode, signed
  localparam int Sum1Bits = DevBits + CntBits;
  localparam logic [63:0] One = 64'(1) << (2 * UnitShift);
  `EVMS_ASSERT_INIT("h^2 must fit 64 bits", 2 * UnitShift < 64)
  `EVMS_ASSERT_INIT("a sum of deviations must fit the dividers", Sum1Bits <= 64)
  `EVMS_ASSERT_INIT("clusters must be counted in 8 bits", ClustersMax < 128)
  `EVMS_ASSERT_INIT("the sizes' clearing pass clears the sums too", ClustersMax <= ModesMax)

  typedef enum logic [4:0] {
    StIdle, StClear, StCountAddr, StCountMode, StCountAdd, StKeepRead, StKeepDecide, StLabelAddr, StLabelMode,
    StLabelCluster, StLabelAdd, StBallRead, StBallLoad, StBallMeans, StBallSquares, StBallWrite, StDone
  } state_e;
  state_e state_q, state_d;

  logic [15:0] j_q, j_d;     // event
  logic [15:0] c_q, c_d;     // mode, then cluster
  logic [7:0]  kept_q, kept_d;
  logic        keep_now;     // mode c_q becomes cluster kept_q

  // ---- memories --------------------------------------------------------------------------------
  // Events a mode has; then, for the labelling, its cluster (-1: dropped).
  logic                 size_we, renumber_we;
  logic [ModeBits-1:0]  size_wa, size_ra, renumber_ra;
  logic [CntBits-1:0]   size_wd, size_rd;
  logic signed [7:0]    renumber_rd;
  evms_ram_1w1r #(.Width(CntBits), .Depth(ModesMax)) u_size (
    .clk, .we(size_we), .wa(size_wa), .wd(size_wd), .ra(size_ra), .rd(size_rd));
  evms_ram_1w1r #(.Width(8), .Depth(ModesMax)) u_renumber (
    .clk, .we(renumber_we), .wa(ModeBits'(c_q)), .wd(keep_now ? 8'(kept_q) : 8'hFF), .ra(renumber_ra), .rd(renumber_rd));
  // Each cluster's mode, and the sums of its events' deviations from it.
  logic                   seed_we, sums_we;
  logic [ClusterBits-1:0] seed_ra, sums_wa, sums_ra;
  logic [2*CoordBits-1:0] seed_rd;
  localparam int SumsBits = CntBits + 2 * Sum1Bits + 2 * 64;
  logic [SumsBits-1:0]    sums_wd, sums_rd;
  evms_ram_1w1r #(.Width(2 * CoordBits), .Depth(ClustersMax)) u_seed (
    .clk, .we(seed_we), .wa(ClusterBits'(kept_q)), .wd({md_x, md_y}), .ra(seed_ra), .rd(seed_rd));
  evms_ram_1w1r #(.Width(SumsBits), .Depth(ClustersMax)) u_sums (
    .clk, .we(sums_we), .wa(sums_wa), .wd(sums_wd), .ra(sums_ra), .rd(sums_rd));

  // ---- registers ---------------------------------------------------------------------------------
  // An event's mode, features and cluster, and a cluster's seed and sums, are not held: each
  // stays on its memory's read port while its address does (ev_j and c_q change only when the
  // next one is due).
  logic [CoordBits-1:0]   mean_x_q, mean_x_d, mean_y_q, mean_y_d;   // |mean| < 2^CoordBits: only its square is used
  logic [63:0]            var_q, var_d;       // max(0, variance)

  // ---- the sums of one cluster ---------------------------------------------------------------
  logic [CntBits-1:0]         sum_count;
  logic signed [Sum1Bits-1:0] sum1_x, sum1_y;
  logic [63:0]                sum2_x, sum2_y;
  assign {sum_count, sum1_x, sum1_y, sum2_x, sum2_y} = sums_rd;
  // An event's deviation from its cluster's seed, registered before its squares: the seed is
  // the mode the event took (md at ev_mode, read in StLabelMode), so the deviation is taken
  // in StLabelCluster, while the cluster's sums are read, and the squares and sums in
  // StLabelAdd are a clock of their own.
  logic signed [DevBits-1:0]  dev_x, dev_y, dev_x_q, dev_y_q;
  logic [63:0]                dev2_x, dev2_y;
  // The C++ model rounds a negative mean to -round(|S1| / n), so |mean| = round(|S1| / n).
  logic [Sum1Bits-1:0]        abs_sum1_x, abs_sum1_y;
  assign abs_sum1_x = sum1_x < 0 ? $unsigned(-sum1_x) : $unsigned(sum1_x);
  assign abs_sum1_y = sum1_y < 0 ? $unsigned(-sum1_y) : $unsigned(sum1_y);
  assign dev_x = $signed({1'b0, ev_x}) - $signed({1'b0, md_x});
  assign dev_y = $signed({1'b0, ev_y}) - $signed({1'b0, md_y});
  assign dev2_x = 64'(dev_x_q * dev_x_q);
  assign dev2_y = 64'(dev_y_q * dev_y_q);
  always_ff @(posedge clk) begin
    dev_x_q <= dev_x;
    dev_y_q <= dev_y;
  end

  // ---- dividers: both axes at once ------------------------------------------------------------
  logic              div_start, div_done, div_y_done;
  logic [63:0]       div_num_x, div_num_y, quotient_x, quotient_y;
  evms_divide_rounded #(.NumBits(64), .DenBits(CntBits)) u_divide_x (
    .clk, .rst_n, .start(div_start), .num(div_num_x), .den(sum_count), .done(div_done), .quotient(quotient_x));
  evms_divide_rounded #(.NumBits(64), .DenBits(CntBits)) u_divide_y (
    .clk, .rst_n, .start(div_start), .num(div_num_y), .den(sum_count), .done(div_y_done), .quotient(quotient_y));

  assign keep_now = 32'(size_rd) >= 32'(cfg_min_cluster_size) && kept_q < cfg_max_clusters && 32'(kept_q) < ClustersMax;

  // ---- the ball -------------------------------------------------------------------------------------
  logic signed [63:0] variance;
  logic [63:0] ball2_scaled, ball2_top, ball2;
  // The means' squared length, registered a clock after the means: the second division, whose
  // quotients the variance waits for in StBallSquares, takes longer, so the squares cost no clock
  // and leave the variance two adds.
  logic [63:0] mean2_q;
  always_ff @(posedge clk) mean2_q <= 64'(mean_x_q) * 64'(mean_x_q) + 64'(mean_y_q) * 64'(mean_y_q);
  assign variance = $signed(quotient_x + quotient_y - mean2_q);
  `EVMS_ASSERT("the means' squares are registered before the variance takes them",
               !(state_q == StBallSquares && div_done) || mean2_q == 64'(mean_x_q) * 64'(mean_x_q) + 64'(mean_y_q) * 64'(mean_y_q),
               clk, rst_n)
  assign ball2_scaled = (64'(cfg_warm_scale2) * var_q + (64'(1) << (SpreadFrac - 1))) >> SpreadFrac;
  assign ball2_top = cfg_warm_ball2_max > One ? cfg_warm_ball2_max : One;
  assign ball2 = ball2_scaled < One ? One : (ball2_scaled > ball2_top ? ball2_top : ball2_scaled);


  always_comb begin
    state_d = state_q;
    j_d = j_q;
    c_d = c_q;
    kept_d = kept_q;
    mean_x_d = mean_x_q;
    mean_y_d = mean_y_q;
    var_d = var_q;
    size_we = 1'b0;
    size_wa = ModeBits'(c_q);
    size_wd = '0;
    size_ra = ModeBits'(c_q);
    renumber_we = 1'b0;
    renumber_ra = ModeBits'(ev_mode);
    seed_we = 1'b0;
    seed_ra = ClusterBits'(c_q);
    sums_we = 1'b0;
    sums_wa = ClusterBits'(c_q);
    sums_wd = '0;
    sums_ra = ClusterBits'(c_q);
    co_we = 1'b0;
    co_value = -8'sd1;
    div_start = 1'b0;
    div_num_x = '0;
    div_num_y = '0;
    warm_we = 1'b0;
    done = 1'b0;
    case (state_q)
      StIdle: if (start) begin
        c_d = '0;
        j_d = '0;
        kept_d = '0;
        state_d = StClear;
      end
      // Sizes of the modes, and the sums of the clusters (ClustersMax <= ModesMax), to zero.
      StClear: begin
        size_we = 1'b1;
        if (c_q < 16'(ClustersMax)) sums_we = 1'b1;
        c_d = c_q + 1'b1;
        if (32'(c_q) + 1 >= ModesMax) state_d = StCountAddr;
      end
      StCountAddr: state_d = StCountMode;
      // Event j's mode is here: read its size.
      StCountMode: begin
        if (j_q == n) begin
          c_d = '0;
          state_d = StKeepRead;
        end else begin
          size_ra = ModeBits'(ev_mode);
          j_d = j_q + 1'b1;
          state_d = ev_mode < 0 ? StCountAddr : StCountAdd;
        end
      end
      StCountAdd: begin
        size_we = 1'b1;
        size_wa = ModeBits'(ev_mode);
        size_wd = size_rd + 1'b1;
        state_d = StCountMode;
      end
      // Mode c's size and position are being read.
      StKeepRead: begin
        j_d = '0;
        state_d = c_q == mode_count ? StLabelAddr : StKeepDecide;
      end
      StKeepDecide: begin
        renumber_we = 1'b1;
        if (keep_now) begin
          seed_we = 1'b1;
          kept_d = kept_q + 1'b1;
        end
        c_d = c_q + 1'b1;
        state_d = StKeepRead;
      end
      StLabelAddr: state_d = StLabelMode;
      // Event j's mode and features are here: read its cluster.
      StLabelMode: begin
        if (j_q == n) begin
          c_d = '0;
          state_d = StBallRead;
        end else if (ev_mode < 0) begin
          co_we = 1'b1;
          j_d = j_q + 1'b1;
          state_d = StLabelAddr;
        end else begin
          state_d = StLabelCluster;
        end
      end
      // Its cluster is here: write it, and read the cluster's sums.
      StLabelCluster: begin
        co_we = 1'b1;
        co_value = renumber_rd;
        sums_ra = ClusterBits'(renumber_rd);
        j_d = j_q + 1'b1;
        state_d = renumber_rd < 0 ? StLabelAddr : StLabelAdd;
      end
      StLabelAdd: begin
        sums_we = 1'b1;
        sums_wa = ClusterBits'(renumber_rd);
        sums_wd = {sum_count + 1'b1, sum1_x + Sum1Bits'(dev_x_q), sum1_y + Sum1Bits'(dev_y_q), sum2_x + dev2_x, sum2_y + dev2_y};
        state_d = StLabelMode;      // event j + 1 was read this clock
      end
      // Cluster c's sums and seed are being read; they stay on the read ports while its two
      // divisions run (the dividers' denominator is the count read).
      StBallRead: state_d = c_q == 16'(kept_q) ? StDone : StBallLoad;
      StBallLoad: begin
        div_start = 1'b1;
        div_num_x = 64'(abs_sum1_x);
        div_num_y = 64'(abs_sum1_y);
        state_d = StBallMeans;
      end
      StBallMeans: if (div_done) begin
        mean_x_d = CoordBits'(quotient_x);
        mean_y_d = CoordBits'(quotient_y);
        div_start = 1'b1;
        div_num_x = sum2_x;
        div_num_y = sum2_y;
        state_d = StBallSquares;
      end
      StBallSquares: if (div_done) begin
        var_d = variance > 0 ? $unsigned(variance) : 64'd0;
        state_d = StBallWrite;
      end
      StBallWrite: begin
        warm_we = 1'b1;
        c_d = c_q + 1'b1;
        state_d = StBallRead;
      end
      StDone: begin
        done = 1'b1;
        state_d = StIdle;
      end
      default: state_d = StIdle;
    endcase
  end

  assign ev_j = j_q;
  // The modes are read by c (keeping them) and, while labelling, by the event's mode (its seed).
  assign md_c = state_q == StLabelMode ? 8'(ev_mode) : 8'(c_q);
  assign co_j = j_q;
  assign warm_k = 8'(c_q);
  assign warm_x = seed_rd[2*CoordBits-1:CoordBits];
  assign warm_y = seed_rd[CoordBits-1:0];
  assign warm_ball2 = ball2;
  assign clusters = kept_q;
  `EVMS_ASSERT("start only when idle", !start || state_q == StIdle, clk, rst_n)
  `EVMS_ASSERT("a mode must be below the mode count", !(state_q == StCountMode && j_q != n) || ev_mode < $signed(mode_count), clk, rst_n)

  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      state_q <= StIdle;
      j_q <= '0;
      c_q <= '0;
      kept_q <= '0;
      mean_x_q <= '0;
      mean_y_q <= '0;
      var_q <= '0;
    end else begin
      state_q <= state_d;
      j_q <= j_d;
      c_q <= c_d;
      kept_q <= kept_d;
      mean_x_q <= mean_x_d;
      mean_y_q <= mean_y_d;
      var_q <= var_d;
    end
  end
endmodule
