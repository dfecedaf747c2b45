// Each cluster's measurement, as hls/cluster/centroid.h: the centre of mass of its events
// (PosFrac fraction bits) at the mean of their timestamps, rounded half up, with their count
// and bounding box. One pass over the packet accumulates; then each cluster takes three
// divisions: through the reciprocal unit and
// the shared multiplier, or, with `exact` (the seeded path), through a restoring divider
// (math/evms_divide_rounded), NumBits + 2 clocks each.
//
// Timing: the quotients' shift amounts are registered when the reciprocal is done, and a
// cluster's time (t0 + its mean age) is added and written the clock after its last product,
// so that the product's rounding shift is the only logic behind the multiplier's register.
//
// With HasPolarityMidpoint and cfg_midpoint_min > 0, the exact path measures a cluster with at
// least cfg_midpoint_min ON and as many OFF events at the midpoint of the two polarities'
// centres of mass, (Sx_on n_off + Sx_off n_on) / (2 n_on n_off), through the same divider; the
// ON events' sums are a second memory beside the sums (cluster/evms_cluster_subset_sums.sv).
//
// With HasPixelCentre and cfg_pixel_centre, the exact path measures a cluster at the mean of its
// pixels, each pixel once: the sums and the count of its events that are the first of the packet
// on their pixel (ev_first, from cluster/evms_mode_links.sv), a fourth memory beside the sums
// (cluster/evms_cluster_subset_sums.sv); a
// cluster with none keeps its centre of mass. It takes the place of the midpoint.
//
// With HasSpreadNoise and cfg_meas_from_spread, each cluster also takes its measurement
// variance, as hls/track/measurement_variance.h: its spread squared, (n S2 - Sx^2 - Sy^2) / n^2
// with S2 the sum of x^2 + y^2 (a third memory beside the sums; the three products through the
// shared multiplier), then r (spread^2 + 1/6 px^2) / n, through a divider of its own and the
// multiplier. Otherwise, and for a cluster of no events, its variance is cfg_r.
//
// Area: the sums and the results are memories with one write port and a combinational read
// (distributed RAM on a Xilinx part) instead of registers with a write multiplexer each; a
// valid bit per cluster clears the sums at once at the start of a packet, so the schedule is
// the one of registers. The three divisions share one rounding shifter.
`include "evms_assert.svh"

module evms_centroid #(
  parameter int ClustersMax = 16,
  parameter int PosFrac     = 12,
  parameter int RecipFrac   = 20,
  parameter int PacketMax   = 256,
  parameter int SpreadFrac  = 8,      // fraction bits of a spread squared (hls/core/shape.h)
  parameter bit HasExact    = 1'b1,   // 0: no divider; `exact` must stay low
  parameter bit HasPolarityMidpoint = 1'b0,  // 0: cfg_midpoint_min is not read (the centre of mass)
  parameter bit HasSpreadNoise = 1'b0,  // 0: cfg_meas_from_spread is not read (every variance is cfg_r)
  parameter bit HasPixelCentre = 1'b0,  // 0: cfg_pixel_centre and ev_first are not read
  // The measurement variance's words (hls/core/shape.h).
  parameter int CovLog2      = 35,
  parameter int PerEventFrac = 16,
  parameter int PerEventLog2 = 28,
  parameter int PixelWidth2  = 43
) (
  input  logic        clk,
  input  logic        rst_n,
  input  logic        start,
  input  logic        exact,               // divide exactly (held from start to done)
  input  logic [15:0] n,
  input  logic [7:0]  clusters,
  input  logic [31:0] t0,                  // the packet's first event
  input  logic [15:0] cfg_midpoint_min,    // ON and OFF events a cluster needs for the midpoint; 0: off
  input  logic        cfg_meas_from_spread,  // a cluster's variance from its spread
  input  logic        cfg_pixel_centre,    // measure at the mean of the cluster's pixels
  input  logic signed [63:0] cfg_r,        // the measurement variance, px^2 (CovFrac fraction bits)
  // Packet and cluster_of reads (1-cycle latency), by rd_i.
  output logic [15:0] rd_i,
  input  logic [15:0] ev_x,
  input  logic [15:0] ev_y,
  input  logic [31:0] ev_t,
  input  logic        ev_p,
  input  logic        ev_first,            // the packet's first event with a mode on its pixel
  input  logic signed [7:0] ev_cluster,
  // Shared reciprocal and multiplier.
  output logic        recip_start,
  output logic [63:0] recip_x,
  input  logic        recip_done,
  input  logic [RecipFrac:0] recip_r,
  input  logic [6:0]  recip_m,
  output logic        mul_start,
  output logic signed [63:0] mul_a,
  output logic signed [63:0] mul_b,
  input  logic        mul_done,
  input  logic signed [63:0] mul_p,
  // Results, read by cluster index.
  input  logic [7:0]  z_c,
  output logic [31:0] z_t,
  output logic signed [31:0] z_x,
  output logic signed [31:0] z_y,
  output logic [15:0] z_events,            // the cluster's event count (at most PacketMax)
  output logic [15:0] z_x_min, z_y_min, z_x_max, z_y_max,  // the bounding box of its events
  output logic signed [63:0] z_r,          // its measurement variance, px^2 (CovFrac fraction bits)
  output logic        done
);
  localparam int ClusterIndexBits = ClustersMax > 1 ? $clog2(ClustersMax) : 1;
  typedef enum logic [4:0] {StIdle, StAccRead, StAccWait, StAccAdd, StDiv, StDivRecip, StDivX, StDivY, StDivT,
                            StDone, StExactX, StExactY, StExactT, StSpreadN, StSpreadX, StSpreadY, StSpreadDiv,
                            StSpreadPerEvent, StSpreadR} state_e;
  state_e state_q, state_d;
  // Per cluster: {x_min, y_min, x_max, y_max, sx, sy, st, count}, valid when the packet has
  // added to it.
  logic [223:0] sums [ClustersMax];
  logic [ClustersMax-1:0] sums_valid_q, sums_valid_d;
  // Per cluster: {t, x, y}, written when its last division ends.
  logic [95:0]  results [ClustersMax];
  logic signed [31:0] x_q, x_d, y_q, y_d;  // the cluster's x and y until its t is ready
  logic [15:0] i_q, i_d;                   // the event being added
  logic [7:0]  c_q, c_d;                   // the cluster being divided
  logic [6:0]  shift_xy_m1_q, shift_xy_m1_d, shift_t_m1_q, shift_t_m1_d;  // each quotient's right shift, minus one
  logic [RecipFrac:0] r_q, r_d;
  logic [31:0] mean_age_q, mean_age_d;     // added to t0 and stored the next clock
  logic        store_q, store_d;
  logic [ClusterIndexBits-1:0] store_c_q, store_c_d;
  logic        div_start_q, div_start_d;
  logic        done_d, recip_start_d, mul_start_d;
  logic signed [63:0] mul_a_d, mul_b_d;
  // The measurement variance (HasSpreadNoise): n^2 var accumulated from the three products, the
  // spread squared, and the variance, stored with the cluster's results.
  logic        spread_on;                    // this cluster's variance comes from its spread
  logic signed [63:0] n2var_q, n2var_d;
  logic [63:0] spread2_q, spread2_d;
  logic signed [63:0] meas_r_q, meas_r_d;
  logic        spread_div_start_q, spread_div_start_d, spread_div_done;
  logic [63:0] s2, spread_quotient;          // the cluster's sum of x^2 + y^2; the divider's result
  logic        last_quotient_done;          // a cluster's mean age lands this clock

  assign {z_t, z_x, z_y} = results[ClusterIndexBits'(z_c)];
  // The count and the bounding box stay in the sums until the next packet starts, after the
  // tracker's step.
  assign {z_x_min, z_y_min, z_x_max, z_y_max} = sums_valid_q[ClusterIndexBits'(z_c)] ? sums[ClusterIndexBits'(z_c)][223:160] : 64'd0;
  assign z_events = sums_valid_q[ClusterIndexBits'(z_c)] ? sums[ClusterIndexBits'(z_c)][15:0] : 16'd0;
  assign rd_i = i_q;

  // The sums of the cluster being added to (accumulating) or divided.
  logic [ClusterIndexBits-1:0] sum_c;
  logic [31:0]   sx, sy, count;
  logic [63:0]   st;
  logic [15:0]   x_min, y_min, x_max, y_max;
  logic          adding;  // this cycle adds the event to its cluster's sums
  assign adding = state_q == StAccAdd && ev_cluster >= 0;
  assign sum_c = state_q == StAccAdd ? ClusterIndexBits'(ev_cluster) : ClusterIndexBits'(c_q);
  // A cluster's first event opens its box; with no events yet the box is that event.
  assign {x_min, y_min, x_max, y_max, sx, sy, st, count} =
      sums_valid_q[sum_c] ? sums[sum_c] : {ev_x, ev_y, ev_x, ev_y, 160'd0};
  // Time since the packet's first event, modulo 2^32 like the C++ core's uint32 difference.
  logic [31:0] age;
  assign age = ev_t - t0;
  assign recip_x = 64'(count);

  `EVMS_ASSERT_INIT("the quotients shift right by at least one bit (RecipFrac > PosFrac)", RecipFrac > PosFrac)

  always_comb begin
    state_d = state_q;
    {i_d, c_d, shift_xy_m1_d, shift_t_m1_d, r_d, mean_age_d, store_c_d} = {i_q, c_q, shift_xy_m1_q, shift_t_m1_q, r_q, mean_age_q, store_c_q};
    {sums_valid_d, x_d, y_d, mul_a_d, mul_b_d} = {sums_valid_q, x_q, y_q, mul_a, mul_b};
    {n2var_d, spread2_d, meas_r_d} = {n2var_q, spread2_q, meas_r_q};
    {done_d, recip_start_d, mul_start_d, div_start_d, store_d, spread_div_start_d} = '0;
    case (state_q)
      StIdle: if (start) begin
        sums_valid_d = '0;
        i_d = '0;
        state_d = n == 0 ? StDiv : StAccRead;
        c_d = '0;
      end
      StAccRead: state_d = StAccWait;
      StAccWait: state_d = StAccAdd;
      StAccAdd: begin
        if (adding) sums_valid_d[sum_c] = 1'b1;
        if (32'(i_q) + 1 < 32'(n)) begin
          i_d = i_q + 1'b1;
          state_d = StAccRead;
        end else begin
          c_d = '0;
          state_d = StDiv;
        end
      end
      StDiv: begin
        if (c_q >= clusters) begin
          state_d = StDone;
        end else if (exact) begin
          div_start_d = 1'b1;
          state_d = StExactX;
        end else begin
          recip_start_d = 1'b1;
          state_d = StDivRecip;
        end
      end
      StExactX: if (div_done) begin
        x_d = 32'(div_quotient);
        div_start_d = 1'b1;
        state_d = StExactY;
      end
      StExactY: if (div_done) begin
        y_d = 32'(div_quotient);
        div_start_d = 1'b1;
        state_d = StExactT;
      end
      StExactT: if (div_done) begin
        mean_age_d = 32'(div_quotient);
      end
      StDivRecip: if (recip_done) begin
        r_d = recip_r;
        shift_xy_m1_d = 7'(RecipFrac - PosFrac - 1) + recip_m;
        shift_t_m1_d = 7'(RecipFrac - 1) + recip_m;
        mul_start_d = 1'b1;
        mul_a_d = $signed(64'(sx));
        mul_b_d = $signed(64'(recip_r));
        state_d = StDivX;
      end
      StDivX: if (mul_done) begin
        x_d = q_rounded;
        mul_start_d = 1'b1;
        mul_a_d = $signed(64'(sy));
        mul_b_d = $signed(64'(r_q));
        state_d = StDivY;
      end
      StDivY: if (mul_done) begin
        y_d = q_rounded;
        mul_start_d = 1'b1;
        mul_a_d = $signed(st);
        mul_b_d = $signed(64'(r_q));
        state_d = StDivT;
      end
      StDivT: if (mul_done) begin
        mean_age_d = q_rounded;
      end
      // n^2 var = n S2 - Sx^2 - Sy^2, exact.
      StSpreadN: if (mul_done) begin
        n2var_d = mul_p;
        mul_start_d = 1'b1;
        {mul_a_d, mul_b_d} = {$signed(64'(sx)), $signed(64'(sx))};
        state_d = StSpreadX;
      end
      StSpreadX: if (mul_done) begin
        n2var_d = n2var_q - mul_p;
        mul_start_d = 1'b1;
        {mul_a_d, mul_b_d} = {$signed(64'(sy)), $signed(64'(sy))};
        state_d = StSpreadY;
      end
      StSpreadY: if (mul_done) begin
        n2var_d = n2var_q - mul_p;
        spread_div_start_d = 1'b1;
        state_d = StSpreadDiv;
      end
      StSpreadDiv: if (spread_div_done) begin
        spread2_d = spread_quotient;
        spread_div_start_d = 1'b1;
        state_d = StSpreadPerEvent;
      end
      StSpreadPerEvent: if (spread_div_done) begin
        mul_start_d = 1'b1;
        {mul_a_d, mul_b_d} = {cfg_r, $signed(spread_quotient > PerEventMax ? PerEventMax : spread_quotient)};
        state_d = StSpreadR;
      end
      StSpreadR: if (mul_done) begin
        meas_r_d = spread_r < 64'sd1 ? 64'sd1 : (spread_r > CovMax ? CovMax : spread_r);
        store_d = 1'b1;
        store_c_d = ClusterIndexBits'(c_q);
        c_d = c_q + 1'b1;
        state_d = StDiv;
      end
      StDone: begin
        done_d = 1'b1;
        state_d = StIdle;
      end
      default: state_d = StIdle;
    endcase
    // A cluster's last quotient (its mean age) has landed: its variance next, or it is stored.
    if (last_quotient_done) begin
      if (spread_on) begin
        mul_start_d = 1'b1;
        {mul_a_d, mul_b_d} = {$signed(64'(count)), $signed(s2)};
        state_d = StSpreadN;
      end else begin
        meas_r_d = cfg_r;
        store_d = 1'b1;
        store_c_d = ClusterIndexBits'(c_q);
        c_d = c_q + 1'b1;
        state_d = StDiv;
      end
    end
  end

  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      state_q <= StIdle;
      {i_q, c_q, shift_xy_m1_q, shift_t_m1_q, r_q, mean_age_q, store_c_q} <= '0;
      {sums_valid_q, x_q, y_q, mul_a, mul_b} <= '0;
      {n2var_q, spread2_q, meas_r_q} <= '0;
      {done, recip_start, mul_start, div_start_q, store_q, spread_div_start_q} <= '0;
    end else begin
      state_q <= state_d;
      {i_q, c_q, shift_xy_m1_q, shift_t_m1_q, r_q, mean_age_q, store_c_q} <= {i_d, c_d, shift_xy_m1_d, shift_t_m1_d, r_d, mean_age_d, store_c_d};
      {sums_valid_q, x_q, y_q, mul_a, mul_b} <= {sums_valid_d, x_d, y_d, mul_a_d, mul_b_d};
      {n2var_q, spread2_q, meas_r_q} <= {n2var_d, spread2_d, meas_r_d};
      {done, recip_start, mul_start, div_start_q, store_q, spread_div_start_q} <=
          {done_d, recip_start_d, mul_start_d, div_start_d, store_d, spread_div_start_d};
    end
  end

  // The exact quotients: round(sx 2^PosFrac / count), round(sy 2^PosFrac / count) (or the
  // midpoint's numerators over 2 n_on n_off) and round(st / count), each started in the first
  // clock of its state. A midpoint numerator is below 2 n_on n_off 2^16 <= PacketMax^2 2^15.
  localparam int CountBits = $clog2(PacketMax + 1);
  localparam int CentreBits = 32 + CountBits > 16 + CountBits + PosFrac ? 32 + CountBits : 16 + CountBits + PosFrac;
  localparam int MidpointBits = 16 + 2 * CountBits + PosFrac;
  localparam int ExactBits = HasPolarityMidpoint && MidpointBits > CentreBits ? MidpointBits : CentreBits;
  localparam int DenBits = HasPolarityMidpoint && 2 * CountBits > 16 ? 2 * CountBits : 16;
  logic div_done;
  logic [ExactBits-1:0] div_num, div_quotient, num_x, num_y, mid_num_x, mid_num_y;
  logic [DenBits-1:0] den_xy, mid_den_xy;   // mid_*: the centre of mass or the midpoint
  logic [ExactBits-1:0] mass_num_x, mass_num_y;  // the centre of mass's numerators
  assign mass_num_x = ExactBits'(sx) << PosFrac;
  assign mass_num_y = ExactBits'(sy) << PosFrac;
  if (HasPolarityMidpoint) begin : g_midpoint
    logic [31:0] sx_on, sy_on;
    logic [15:0] count_on;
    evms_cluster_subset_sums #(.ClustersMax(ClustersMax)) u_on_sums (
      .clk, .valid(sums_valid_q), .c(sum_c), .adding, .in_subset(ev_p), .x(ev_x), .y(ev_y), .sx(sx_on), .sy(sy_on),
      .count(count_on));
    logic [15:0] count_off;
    logic use_midpoint;
    assign count_off = 16'(count) - count_on;
    assign use_midpoint = cfg_midpoint_min != 0 && count_on >= cfg_midpoint_min && count_off >= cfg_midpoint_min;
    logic [31:0] sx_off, sy_off;   // the OFF events' sums, 32-bit as the C++ core's
    assign sx_off = sx - sx_on;
    assign sy_off = sy - sy_on;
    assign mid_num_x = use_midpoint ? (ExactBits'(sx_on) * ExactBits'(count_off) + ExactBits'(sx_off) * ExactBits'(count_on)) << PosFrac
                                    : mass_num_x;
    assign mid_num_y = use_midpoint ? (ExactBits'(sy_on) * ExactBits'(count_off) + ExactBits'(sy_off) * ExactBits'(count_on)) << PosFrac
                                    : mass_num_y;
    assign mid_den_xy = use_midpoint ? (DenBits'(count_on) * DenBits'(count_off)) << 1 : DenBits'(count);
  end else begin : g_centre
    assign mid_num_x = mass_num_x;
    assign mid_num_y = mass_num_y;
    assign mid_den_xy = DenBits'(count);
    logic unused_midpoint;   // waived in cluster/evms_cluster.vlt
    assign unused_midpoint = ^{cfg_midpoint_min, ev_p};
  end
  if (HasPixelCentre) begin : g_pixel_centre
    logic [31:0] sx_px, sy_px;
    logic [15:0] count_px;
    evms_cluster_subset_sums #(.ClustersMax(ClustersMax)) u_pixel_sums (
      .clk, .valid(sums_valid_q), .c(sum_c), .adding, .in_subset(ev_first), .x(ev_x), .y(ev_y), .sx(sx_px), .sy(sy_px),
      .count(count_px));
    logic use_pixels;
    assign use_pixels = cfg_pixel_centre && count_px != 0;
    assign num_x = use_pixels ? ExactBits'(sx_px) << PosFrac : mid_num_x;
    assign num_y = use_pixels ? ExactBits'(sy_px) << PosFrac : mid_num_y;
    assign den_xy = use_pixels ? DenBits'(count_px) : mid_den_xy;
  end else begin : g_no_pixel_centre
    assign num_x = mid_num_x;
    assign num_y = mid_num_y;
    assign den_xy = mid_den_xy;
    logic unused_pixel_centre;   // waived in cluster/evms_cluster.vlt
    assign unused_pixel_centre = ^{cfg_pixel_centre, ev_first};
  end
  assign div_num = state_q == StExactX ? num_x : (state_q == StExactY ? num_y : ExactBits'(st));
  if (HasExact) begin : g_exact
    evms_divide_rounded #(.NumBits(ExactBits), .DenBits(DenBits)) u_divide (
      .clk, .rst_n, .start(div_start_q), .num(div_num), .den(state_q == StExactT ? DenBits'(count) : den_xy), .done(div_done),
      .quotient(div_quotient));
  end else begin : g_no_exact
    assign div_done = 1'b0;
    assign div_quotient = '0;
    logic unused_exact;   // waived in cluster/evms_cluster.vlt
    assign unused_exact = ^{div_start_q, div_num};
    `EVMS_ASSERT("a build without the divider cannot divide exactly", !(start && exact), clk, rst_n)
  end

  // The measurement variance's divisions, each rounded half up: round(n^2 var 2^SpreadFrac / n^2)
  // (the spread squared), then round((spread^2 + 1/6 px^2) 2^PerEventFrac / n), capped at
  // PerEventMax so that cfg_r (below 2^CovLog2) times it fits 63 bits; then r = that times cfg_r,
  // rounded to CovFrac bits and clamped to [1, CovMax] (hls/track/measurement_variance.h).
  localparam logic [63:0] PerEventMax = (64'd1 << PerEventLog2) - 1;
  localparam logic signed [63:0] CovMax = (64'sd1 <<< CovLog2) - 1;
  // n S2 < n^2 2^33 (x, y < 2^16); the second numerator is below 2^(34 + PerEventFrac).
  localparam int SpreadNumBits = 2 * CountBits + 33 + SpreadFrac > 34 + PerEventFrac ? 2 * CountBits + 33 + SpreadFrac
                                                                                       : 34 + PerEventFrac;
  assign last_quotient_done = (state_q == StExactT && div_done) || (state_q == StDivT && mul_done);

  localparam int SpreadDenBits = 2 * CountBits;
  logic signed [63:0] spread_r;
  assign spread_r = evms_round_pkg::shr_rnd(mul_p, PerEventFrac);
  if (HasSpreadNoise) begin : g_spread
    // Per cluster: the sum of x^2 + y^2 of its events, valid with the sums; the variance.
    logic [63:0] s2_sums [ClustersMax];
    logic signed [63:0] meas_r_mem [ClustersMax];
    logic [31:0] square_x, square_y;
    logic [SpreadNumBits-1:0] spread_num, spread_div_quotient;
    logic [SpreadDenBits-1:0] spread_den;
    assign square_x = ev_x * ev_x;
    assign square_y = ev_y * ev_y;
    assign s2 = sums_valid_q[sum_c] ? s2_sums[sum_c] : 64'd0;
    always_ff @(posedge clk) begin
      if (adding) s2_sums[sum_c] <= s2 + 64'(square_x) + 64'(square_y);
      if (store_q) meas_r_mem[store_c_q] <= meas_r_q;
    end
    assign spread_on = cfg_meas_from_spread && count != 0;
    assign z_r = meas_r_mem[ClusterIndexBits'(z_c)];   // every cluster stores one, cfg_r when not from its spread
    assign spread_num = state_q == StSpreadDiv ? SpreadNumBits'(n2var_q) << SpreadFrac
                                               : SpreadNumBits'(spread2_q + 64'(PixelWidth2)) << (PerEventFrac - SpreadFrac);
    // n^2, registered: the cluster (c_q) holds from its first division to its store, so the
    // product is ready when the spread's division starts, off the divider's start path.
    logic [SpreadDenBits-1:0] count_squared_q;
    always_ff @(posedge clk) count_squared_q <= SpreadDenBits'(count) * SpreadDenBits'(count);
    assign spread_den = state_q == StSpreadDiv ? count_squared_q : SpreadDenBits'(count);
    evms_divide_rounded #(.NumBits(SpreadNumBits), .DenBits(SpreadDenBits)) u_spread_divide (
      .clk, .rst_n, .start(spread_div_start_q), .num(spread_num), .den(spread_den), .done(spread_div_done),
      .quotient(spread_div_quotient));
    assign spread_quotient = 64'(spread_div_quotient);
  end else begin : g_no_spread
    assign s2 = '0;
    assign spread_on = 1'b0;
    assign z_r = cfg_r;
    assign spread_div_done = 1'b0;
    assign spread_quotient = '0;
    logic unused_spread;   // waived in cluster/evms_cluster.vlt
    assign unused_spread = ^{cfg_meas_from_spread, n2var_q, spread2_q, meas_r_q, spread_div_start_q, spread_r};
  end

  // One rounding shifter for the three quotients, round(p * 2^-(RecipFrac + m - extra)) as
  // Reciprocal::divide, with extra = PosFrac for x and y and 0 for t (the results are 32-bit
  // words, as the C++ core's).
  logic [31:0] q_rounded;
  assign q_rounded = 32'(evms_round_pkg::round_shift(64'(mul_p), state_q == StDivT ? shift_t_m1_q : shift_xy_m1_q));

  always_ff @(posedge clk) begin
    if (adding) sums[sum_c] <= {ev_x < x_min ? ev_x : x_min, ev_y < y_min ? ev_y : y_min, ev_x > x_max ? ev_x : x_max,
                                ev_y > y_max ? ev_y : y_max, sx + 32'(ev_x), sy + 32'(ev_y), st + 64'(age), count + 32'd1};
    if (store_q) results[store_c_q] <= {t0 + mean_age_q, x_q, y_q};
  end
endmodule
