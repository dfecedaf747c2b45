// Multi-target tracking, as hls/track/tracker.h and hls/track/kalman_axis.h, one step at a
// time through the shared 64-bit multiplier and reciprocal unit:
//   expire -> every (live track, measurement) pair's distance, into the pair table -> rounds
//   of nearest pairs within the gate (with cfg_gate_boxes, then of those beyond it whose
//   track's last measurement lies in the measurement's box or the measurement in the last
//   one's box), each a scan of the table, a pair a clock, and its match
//   predicted and updated (x axis, then y) -> tentative tracks without a match end ->
//   unmatched measurements start tracks in the lowest free slots (with cfg_evict_stale and none
//   free, in the unmatched slot measured longest ago, found by a scan of the slots).
// A pair's distance is taken once: it changes only when its track is matched, and a matched
// track takes part in no later round. With cfg_associate_last it is the distance to the
// track's last measurement (two squares), otherwise to its prediction (two more products);
// with cfg_report_tentative tentative tracks report their updates too, marked by upd_confirmed.
// Every arithmetic step is the C++ one: the same products, the same rounding (half up) and
// the same clamps, so the results are equal bit for bit.
//
// Area: the Kalman steps all have the form  clamp(base +- round(product >> shift), bound), one
// step a state, so they share one adder-and-clamp (the "step unit") whose base, shift and
// bound the state selects, instead of an adder and two comparators per step. Each slot's
// filter state (pos, vel, p00, p01, p11) per axis is one word of a memory with one write port
// and a combinational read (distributed RAM on a Xilinx part), not registers with a write
// multiplexer each; so are each slot's ID and last time, and each measurement's track ID (with
// a valid bit a measurement, cleared in one clock). Covariances are stored in CovBits bits: every stored covariance is clamped
// to +-(2^CovLog2 - 1) or is P0, which host/backend/core_config.h keeps below 2^CovLog2.
`include "evms_assert.svh"

module evms_tracker #(
  parameter int ClustersMax = 16,
  parameter int TracksMax   = 16,
  parameter int PosFrac     = 12,
  parameter int TickLog2    = 14,
  parameter int CovFrac     = 16,
  parameter int GainFrac    = 20,
  parameter int NoiseFrac   = 32,
  parameter int RecipFrac   = 20,
  // Saturation bounds, each +-(2^n - 1), the gating differences' +-2^GateDistLog2, and the
  // longest time step (hls/core/shape.h).
  parameter int CovLog2      = 35,
  parameter int GainLog2     = 27,
  parameter int PosLog2      = 31,
  parameter int GateDistLog2 = 24,
  parameter int MaxDtLog2    = 18
) (
  input  logic        clk,
  input  logic        rst_n,
  input  logic [63:0] cfg_gate2,
  input  logic [7:0]  cfg_confirm_hits,
  input  logic [31:0] cfg_coast_us,
  input  logic [7:0]  cfg_max_tracks,
  input  logic        cfg_associate_last,
  input  logic        cfg_evict_stale,
  input  logic        cfg_gate_boxes,
  input  logic        cfg_report_tentative,
  input  logic [3:0]  cfg_size_ratio_log2,
  input  logic signed [63:0] cfg_q_third,
  input  logic signed [63:0] cfg_q_half,
  input  logic signed [63:0] cfg_q,
  input  logic signed [63:0] cfg_p0_pos,
  input  logic signed [63:0] cfg_p0_vel,
  input  logic        start,
  input  logic [31:0] packet_time,
  input  logic [7:0]  m,                 // measurements
  // Measurement reads (combinational), by index.
  output logic [7:0]  z_c,
  input  logic [31:0] z_t,
  input  logic signed [31:0] z_x,
  input  logic signed [31:0] z_y,
  input  logic [15:0] z_events,
  input  logic [15:0] z_x_min, z_y_min, z_x_max, z_y_max,
  input  logic signed [63:0] z_r,        // its variance, px^2 (CovFrac fraction bits): cfg_r, or from its spread
  // Track ID given to each measurement (-1: none), by index.
  input  logic [7:0]  id_c,
  output logic signed [31:0] id_of,
  // Track updates.
  output logic        upd_valid,
  input  logic        upd_ready,
  output logic [31:0] upd_t,
  output logic signed [31:0] upd_id, upd_x, upd_y, upd_vx, upd_vy, upd_zx, upd_zy,
  output logic        upd_confirmed,
  output logic [15:0] upd_events, upd_x_min, upd_y_min, upd_x_max, upd_y_max,  // the measurement's
  output logic signed [63:0] upd_var_x, upd_var_y,   // the position variances (p00 of each axis)
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
  output logic        done,
  output logic [31:0] tracks_started,
  output logic [31:0] unassigned
);
  localparam int TrackIndexBits = TracksMax > 1 ? $clog2(TracksMax) : 1;
  localparam int ClusterIndexBits = ClustersMax > 1 ? $clog2(ClustersMax) : 1;
  localparam logic signed [63:0] MaxDt = 64'sd1 <<< MaxDtLog2;   // longer time steps are clamped
  localparam int CovBits = CovLog2 + 1;
  localparam int GainBits = GainLog2 + 1, GainSumBits = GainLog2 + 2;
  `EVMS_ASSERT_INIT("the step unit rounds right shifts of at least one bit",
                   TickLog2 >= 1 && 2 * TickLog2 - CovFrac >= 1 && CovFrac >= 1 && NoiseFrac >= 1 && NoiseFrac + TickLog2 - CovFrac >= 1 && GainFrac >= 1)
  `EVMS_ASSERT_INIT("the gains' quotient shifts right (RecipFrac >= GainFrac) and its clamp fits 64 bits", RecipFrac >= GainFrac && GainLog2 <= 62)
  `EVMS_ASSERT_INIT("the gating distance assumes 2^(16 + PosFrac) + 2^GateDistLog2 < 2^PosLog2 - 1", (64'd1 << (16 + PosFrac)) + (64'd1 << GateDistLog2) < (64'd1 << PosLog2) - 64'd1)

  // clamp_sym(v, b) for the bounds the tracker uses, b = 2^n - 1 (ones) and b = 2^n (pow2),
  // decided from the sign and the high bits instead of two 64-bit comparisons, which are carry
  // chains (18 ns on an iCE40 UP5K each) on the step unit's path.
  function automatic logic outside_ones(input signed [63:0] v, input integer n);
    logic [63:0] hi;
    begin
      hi = 64'(v) >> n;   // bits [63:n]
      outside_ones = v[63] ? !(hi == ~(64'd0) >> n && 64'(v) << (64 - n) != 0) : hi != 0;
    end
  endfunction
  function automatic signed [63:0] clamp_ones(input signed [63:0] v, input integer n);
    begin
      if (!outside_ones(v, n)) clamp_ones = v;
      else clamp_ones = v[63] ? -((64'sd1 <<< n) - 1) : (64'sd1 <<< n) - 1;
    end
  endfunction
  function automatic signed [63:0] clamp_pow2(input signed [63:0] v, input integer n);
    logic [63:0] hi;
    begin
      hi = 64'(v) >> n;
      if (!v[63] && ((hi >> 1) != 0 || (hi[0] && 64'(v) << (64 - n) != 0))) clamp_pow2 = 64'sd1 <<< n;
      else if (v[63] && hi != ~(64'd0) >> n) clamp_pow2 = -(64'sd1 <<< n);
      else clamp_pow2 = v;
    end
  endfunction
  function automatic signed [63:0] capped_dt(input [31:0] raw_us);
    begin
      capped_dt = 64'(raw_us) > MaxDt ? MaxDt : 64'(raw_us);
    end
  endfunction

  // ---- slots ------------------------------------------------------------------------------
  logic                     s_valid_q [TracksMax], s_confirmed_q [TracksMax];
  logic [7:0]               s_hits_q [TracksMax];
  // Each slot's ID and last time: memories with one write port and combinational reads.
  logic signed [31:0]       s_id [TracksMax];
  logic [31:0]              s_t [TracksMax];
  // Filter state of each slot, one memory per axis: {pos, vel, p00, p01, p11}.
  localparam int AxisStateBits = 64 + 3 * CovBits;
  logic [AxisStateBits-1:0] kal_x [TracksMax], kal_y [TracksMax];
  logic [TracksMax-1:0]    slot_matched_q;
  logic [ClustersMax-1:0]  meas_matched_q;
  // Each measurement's track ID (memory), where ids_valid_q says it has one this packet.
  logic signed [31:0]       ids [ClustersMax];
  logic [ClustersMax-1:0]   ids_valid_q;
  // Each slot's last measurement {x, y} and its event count: memories with one write port and a
  // combinational read.
  logic [63:0]              s_z [TracksMax];
  logic [15:0]              s_events [TracksMax];
  logic [63:0]              s_box [TracksMax];   // and its bounding box {x_min, y_min, x_max, y_max}
  logic signed [31:0]       next_id_q;

  assign id_of = ids_valid_q[ClusterIndexBits'(id_c)] ? ids[ClusterIndexBits'(id_c)] : -32'sd1;
  assign tracks_started = 32'(next_id_q);

  typedef enum logic [5:0] {
    StIdle, StExpire, StRound, StScan, StPair, StPairPx, StPairPy, StPairDx2, StPairDy2, StPairEnd, StMatch,
    StDt2, StDt3, StAxBegin, StPredictPos, StPredictP00a, StPredictP00b, StPredictP00c, StPredictP01a, StPredictP01b, StPredictP11,
    StUpdateRecip, StUpdateK0, StUpdateK1, StUpdatePos, StUpdateVel, StUpdateP00, StUpdateP01, StUpdateP11, StAxEnd, StEmit, StDrop, StBirth, StBirthEmit,
    StEvict, StDone
  } state_e;
  state_e state_q;

  logic [7:0]  round_n_q;
  logic [TrackIndexBits:0] s_q;         // slot being scanned or updated
  logic [7:0]  k_q;         // measurement being scanned or born
  logic signed [8:0]  best_s_q;
  logic [7:0]  best_m_q;
  logic [63:0] best_d2_q, d2_q;
  logic signed [63:0] dt_q, dt2_q, dt3_q, dpred_q, dx_q;
  // The pair's distance per axis: to the slot's last measurement (associate_last; the pair's
  // slot and measurement stay addressed while its distances are squared), or the gated
  // prediction's, chosen after the register and not after the gating distance's carry chain,
  // which is the block's longest path.
  logic signed [63:0] pair_dx, pair_dy;
  assign pair_dx = cfg_associate_last ? 64'(z_x) - 64'($signed(s_z[si][63:32])) : dx_q;
  assign pair_dy = cfg_associate_last ? 64'(z_y) - 64'($signed(s_z[si][31:0])) : dpred_q;
  // Eviction: the scan for the stalest unmatched slot has run for this measurement
  // (evict_scanned_q), and what it found (evict_slot_q, -1: none; evict_t_q: its last time).
  logic               evict_scanned_q;
  logic signed [8:0]  evict_slot_q;
  logic [31:0]        evict_t_q;
  // The pair table: {rank, candidate, squared distance} of each (slot, measurement), written by
  // the distance pass and read by the rounds' scans (registered read: a pair issued in one clock
  // is compared in the next, scan_pending_q). The rank's high bit is a candidate beyond the
  // gate (by the boxes), its low bit sizes far apart: a pair ranks after every pair of a lower
  // rank (best_rank_q), then by distance.
  localparam int PairAddrBits = TrackIndexBits + ClusterIndexBits;
  logic                    pair_we;
  logic [PairAddrBits-1:0] pair_wa, pair_ra;
  logic [66:0]             pair_wd, pair_rd;
  logic [1:0]              best_rank_q;
  logic                    scan_pending_q;
  logic [TrackIndexBits-1:0] scan_slot_q;
  logic [7:0]              scan_meas_q;
  logic        axis_q;
  // Working copy of the axis being filtered.
  logic signed [63:0] w_pos_q, w_vel_q, w_p00_q, w_p01_q, w_p11_q, w_z_q, w_e_q;
  logic signed [63:0] acc_q, k0_q, k1_q, p00n_q;
  logic signed [CovBits-1:0] p01n_q;
  logic [RecipFrac:0] rr_q;
  // Reciprocal::divide for a non-negative numerator: q = p * 2^-shift rounded half up, with
  // shift = RecipFrac + m - GainFrac >= 0. As (p + 2^(s-1)) >> s == ((p >> (s-1)) + 1) >> 1,
  // q = (t + 1) >> 1 with t = {p, 0} >> shift: one shifter by a registered amount, then one add.
  logic [7:0]  q_shift_q;
  logic [64:0] q_t;
  assign q_t = {mul_p, 1'b0} >> q_shift_q;

  logic [TrackIndexBits-1:0] si;
  assign si = TrackIndexBits'(s_q);

  // The slot being scanned or updated, both axes.
  logic [AxisStateBits-1:0] kx, ky;
  logic [3*CovBits-1:0]      ka;  // the covariances of the axis being filtered
  logic signed [31:0]        pos_of [2], vel_of [2];
  logic signed [CovBits-1:0] p00_of, p01_of, p11_of;
  assign kx = kal_x[si];
  assign ky = kal_y[si];
  assign ka = axis_q ? ky[3*CovBits-1:0] : kx[3*CovBits-1:0];
  assign pos_of[0] = kx[AxisStateBits-1 -: 32];
  assign pos_of[1] = ky[AxisStateBits-1 -: 32];
  assign vel_of[0] = kx[AxisStateBits-33 -: 32];
  assign vel_of[1] = ky[AxisStateBits-33 -: 32];
  assign {p00_of, p01_of, p11_of} = ka;
  assign z_c = state_q == StMatch ? best_m_q : k_q;

  function automatic signed [63:0] cov_word(input signed [CovBits-1:0] v);
    begin
      cov_word = {{(64 - CovBits){v[CovBits-1]}}, v};
    end
  endfunction

  // An update's measurement (count, bounding box) and the slot's position variances, both axes
  // read from the filter-state memories: a match's once filtered, a birth's as born.
  logic [207:0] upd_extra;
  assign upd_extra = {z_events, z_x_min, z_y_min, z_x_max, z_y_max, cov_word(kx[3*CovBits-1 -: CovBits]), cov_word(ky[3*CovBits-1 -: CovBits])};

  // ---- the step unit: clamp(base +- round(mul_p >> shift), bound) ---------------------------
  typedef enum logic [2:0] {ShiftTick, ShiftDt2, ShiftCov, ShiftNoise, ShiftNoiseP11, ShiftGain} shift_e;
  typedef enum logic [1:0] {BoundNone, BoundPos, BoundCov} bound_e;
  // The state's operands are chosen a clock ahead and registered: a step's state waits at least
  // one clock for its product (the multiplier's latency), and its base was written when the
  // state was entered, so the registered choice is the state's own when the product arrives,
  // and the choice's multiplexers are off the path from the product to the step.
  shift_e             sel_shift, step_shift_q;
  bound_e             sel_bound, step_bound_q;
  logic               sel_negate, step_negate_q, step_carry, step_axis_q;
  logic signed [63:0] sel_base, step_base_q, step_half, step_hs, step_sum, step, gate_sum, gate_dist;
  logic signed [63:0] zp_q [2];   // z - pos of the pair being gated, per axis
  always_comb begin
    sel_shift = ShiftTick;
    sel_bound = BoundNone;
    sel_negate = 1'b0;
    sel_base = '0;
    case (state_q)
      StPairPx: begin sel_base = 64'(pos_of[0]); sel_bound = BoundPos; end
      StPairPy: begin sel_base = 64'(pos_of[1]); sel_bound = BoundPos; end
      StDt2:     sel_shift = ShiftDt2;
      StPredictPos:   begin sel_base = w_pos_q; sel_bound = BoundPos; end
      StPredictP00a:  sel_base = w_p00_q;
      StPredictP00b:  begin sel_base = acc_q; sel_shift = ShiftCov; end
      StPredictP00c,
      StPredictP01b:  begin sel_base = acc_q; sel_shift = ShiftNoise; sel_bound = BoundCov; end
      StPredictP01a:  sel_base = w_p01_q;
      StPredictP11:   begin sel_base = w_p11_q; sel_shift = ShiftNoiseP11; sel_bound = BoundCov; end
      StUpdatePos:   begin sel_base = w_pos_q; sel_shift = ShiftGain; sel_bound = BoundPos; end
      StUpdateVel:   begin sel_base = w_vel_q; sel_shift = ShiftGain; sel_bound = BoundPos; end
      StUpdateP00,
      StUpdateP01:   begin sel_shift = ShiftGain; sel_bound = BoundCov; end
      StUpdateP11:   begin sel_base = w_p11_q; sel_shift = ShiftGain; sel_bound = BoundCov; sel_negate = 1'b1; end
      default: ;
    endcase
  end
  always_ff @(posedge clk) begin
    step_shift_q <= sel_shift;
    step_bound_q <= sel_bound;
    step_negate_q <= sel_negate;
    step_base_q <= sel_base;
    step_axis_q <= state_q != StPairPx;
  end
  always_comb begin
    // (p + 2^(s-1)) >> s  ==  ((p >> (s-1)) + 1) >> 1, with one shifter for every s.
    case (step_shift_q)
      ShiftDt2:       step_half = mul_p >>> (2 * TickLog2 - CovFrac - 1);
      ShiftCov:       step_half = mul_p >>> (CovFrac - 1);
      ShiftNoise:     step_half = mul_p >>> (NoiseFrac - 1);
      ShiftNoiseP11: step_half = mul_p >>> (NoiseFrac + TickLog2 - CovFrac - 1);
      ShiftGain:      step_half = mul_p >>> (GainFrac - 1);
      default:      step_half = mul_p >>> (TickLog2 - 1);
    endcase
    // base +- ((h + 1) >> 1) as one adder with a carry in: (h + 1) >> 1 == (h >> 1) + h[0], and
    // base - q == base + ~q + 1, so the rounding add and the sum are one carry chain.
    // (a statement of its own: in an expression with the unsigned carry, >>> would be logical)
    step_hs = step_half >>> 1;
    step_carry = step_negate_q ^ step_half[0];
    step_sum = step_base_q + (step_negate_q ? ~step_hs : step_hs) + 64'(step_carry);
    step = step_bound_q == BoundPos ? clamp_ones(step_sum, PosLog2) : step_bound_q == BoundCov ? clamp_ones(step_sum, CovLog2) : step_sum;
    // The gating distance of the predicted position to the measurement, clamp(z - step): from
    // z - pos (registered when the pair was issued) minus the rounded term, a second carry chain
    // beside the step's rather than after it. When the prediction saturates at +-(2^PosLog2 - 1) the
    // distance saturates at -+2^GateDistLog2, as |z| < 2^(16 + PosFrac) (pixel coordinates).
    gate_sum = zp_q[step_axis_q] + ~step_hs + 64'(!step_carry);   // zp - (hs + carry)
    if (outside_ones(step_sum, PosLog2)) gate_dist = step_sum[63] ? 64'sd1 <<< GateDistLog2 : -(64'sd1 <<< GateDistLog2);
    else gate_dist = clamp_pow2(gate_sum, GateDistLog2);
  end

  // The lowest free slot a birth takes (-1: none); with none, the slot an eviction scan found.
  logic signed [8:0] free, birth_slot;
  always_comb begin
    free = -9'sd1;
    for (int q = TracksMax - 1; q >= 0; q--) begin
      if (!s_valid_q[q] && q < 32'(cfg_max_tracks)) free = 9'(q);
    end
    birth_slot = free >= 0 ? free : (evict_scanned_q ? evict_slot_q : -9'sd1);
  end
  // A birth with no free slot scans for one to evict first.
  logic evict_scan_needed;
  assign evict_scan_needed = free < 0 && cfg_evict_stale && !evict_scanned_q;

  // Issues a * b; the product comes back with mul_done.
`define EVMS_REQUEST(A, B) begin mul_start <= 1'b1; mul_a <= (A); mul_b <= (B); end

  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      state_q <= StIdle;
      done <= 1'b0;
      upd_valid <= 1'b0;
      {upd_t, upd_id, upd_x, upd_y, upd_vx, upd_vy, upd_zx, upd_zy} <= '0;
      {upd_events, upd_x_min, upd_y_min, upd_x_max, upd_y_max, upd_var_x, upd_var_y} <= '0;
      recip_start <= 1'b0;
      recip_x <= '0;
      mul_start <= 1'b0;
      mul_a <= '0;
      mul_b <= '0;
      next_id_q <= '0;
      unassigned <= '0;
      slot_matched_q <= '0;
      meas_matched_q <= '0;
      round_n_q <= '0;
      s_q <= '0;
      k_q <= '0;
      best_s_q <= '0;
      best_m_q <= '0;
      best_d2_q <= '0;
      best_rank_q <= '0;
      {d2_q, dt_q, dt2_q, dt3_q, dpred_q, dx_q} <= '0;
      zp_q[0] <= '0;
      zp_q[1] <= '0;
      evict_scanned_q <= 1'b0;
      evict_slot_q <= '0;
      evict_t_q <= '0;
      upd_confirmed <= 1'b0;
      axis_q <= 1'b0;
      {w_pos_q, w_vel_q, w_p00_q, w_p01_q, w_p11_q, w_z_q, w_e_q, acc_q, k0_q, k1_q, p00n_q, p01n_q} <= '0;
      rr_q <= '0;
      q_shift_q <= '0;
      for (int q = 0; q < TracksMax; q++) begin
        s_valid_q[q] <= 1'b0;
        s_confirmed_q[q] <= 1'b0;
        s_hits_q[q] <= '0;
      end
      ids_valid_q <= '0;
    end else begin
      done <= 1'b0;
      mul_start <= 1'b0;
      recip_start <= 1'b0;
      if (upd_valid && upd_ready) upd_valid <= 1'b0;
      if (scan_pending_q && pair_rd[64] &&
          (best_s_q < 0 || pair_rd[66:65] < best_rank_q || (pair_rd[66:65] == best_rank_q && pair_rd[63:0] < best_d2_q))) begin
        best_s_q <= $signed({1'b0, 8'(scan_slot_q)});
        best_m_q <= scan_meas_q;
        best_d2_q <= pair_rd[63:0];
        best_rank_q <= pair_rd[66:65];
      end
      case (state_q)
        StIdle: if (start) begin
          s_q <= '0;
          state_q <= StExpire;
        end
        // 1. Confirmed (and any) tracks not measured for more than coast_us end.
        StExpire: begin
          if (32'(s_q) >= TracksMax) begin
            slot_matched_q <= '0;
            meas_matched_q <= '0;
            ids_valid_q <= '0;
            s_q <= '0;
            k_q <= '0;
            state_q <= StPair;
          end else begin
            if (s_valid_q[si] && $signed(packet_time - s_t[si]) > $signed(cfg_coast_us)) s_valid_q[si] <= 1'b0;
            s_q <= s_q + 1'b1;
          end
        end
        // 2. The distance pass: every live slot's distance to every measurement, into the pair
        // table; to the last measurement (two squares) or to the prediction at the
        // measurement's time (two products first).
        StPair: begin
          if (32'(s_q) >= TracksMax) begin
            round_n_q <= '0;
            state_q <= StRound;
          end else if (!s_valid_q[si] || 32'(s_q) >= 32'(cfg_max_tracks) || k_q >= m) begin
            s_q <= s_q + 1'b1;
            k_q <= '0;
          end else if (cfg_associate_last) begin
            `EVMS_REQUEST(pair_dx, pair_dx)
            state_q <= StPairDx2;
          end else begin
            logic signed [31:0] raw;
            logic signed [63:0] dt_now;
            raw = $signed(z_t - s_t[si]);
            dt_now = raw > 0 ? capped_dt(32'(raw)) : 64'sd0;
            dt_q <= dt_now;
            zp_q[0] <= 64'(z_x) - 64'(pos_of[0]);
            zp_q[1] <= 64'(z_y) - 64'(pos_of[1]);
            `EVMS_REQUEST(64'(vel_of[0]), dt_now)
            state_q <= StPairPx;
          end
        end
        StPairPx: if (mul_done) begin
          dx_q <= gate_dist;
          `EVMS_REQUEST(64'(vel_of[1]), dt_q)
          state_q <= StPairPy;
        end
        StPairPy: if (mul_done) begin
          dpred_q <= gate_dist;
          `EVMS_REQUEST(pair_dx, pair_dx)
          state_q <= StPairDx2;
        end
        StPairDx2: if (mul_done) begin
          d2_q <= 64'(mul_p);
          `EVMS_REQUEST(pair_dy, pair_dy)
          state_q <= StPairDy2;
        end
        StPairDy2: if (mul_done) begin
          // (the pair table's write port takes d2 + mul_p)
          k_q <= k_q + 1'b1;
          state_q <= StPair;
        end
        // 3. Rounds: the nearest remaining pair within the gate, by a scan of the pair table in
        // slot-then-measurement order, so that ties go to the lower slot, then measurement.
        StRound: begin
          if (32'(round_n_q) >= ClustersMax) begin
            s_q <= '0;
            state_q <= StDrop;
          end else begin
            best_s_q <= -9'sd1;
            best_m_q <= '0;
            best_d2_q <= '0;
            best_rank_q <= '0;
            s_q <= '0;
            k_q <= '0;
            state_q <= StScan;
          end
        end
        // A pair is read the clock it is visited and compared the next (scan_pending_q, before
        // this case statement); a slot's last pair is compared in the clock that moves to the
        // next slot, so none is pending at the end.
        StScan: begin
          if (32'(s_q) >= TracksMax) begin
            if (best_s_q < 0) begin
              s_q <= '0;
              state_q <= StDrop;
            end else begin
              state_q <= StMatch;
            end
          end else if (!s_valid_q[si] || slot_matched_q[si] || 32'(s_q) >= 32'(cfg_max_tracks) || k_q >= m) begin
            s_q <= s_q + 1'b1;
            k_q <= '0;
          end else begin
            k_q <= k_q + 1'b1;
          end
        end
        // 4. The match: predict both axes to the measurement's time, then update them.
        StMatch: begin
          slot_matched_q[TrackIndexBits'(best_s_q)] <= 1'b1;
          meas_matched_q[ClusterIndexBits'(best_m_q)] <= 1'b1;
          s_q <= (TrackIndexBits+1)'(best_s_q);
          k_q <= best_m_q;
          begin
            logic [31:0] raw;
            raw = z_t - s_t[TrackIndexBits'(best_s_q)];
            dt_q <= capped_dt(raw);
            `EVMS_REQUEST(capped_dt(raw), capped_dt(raw))
          end
          state_q <= StDt2;
        end
        StDt2: if (mul_done) begin
          dt2_q <= step;
          `EVMS_REQUEST(step, dt_q)
          state_q <= StDt3;
        end
        StDt3: if (mul_done) begin
          dt3_q <= step;
          axis_q <= 1'b0;
          state_q <= StAxBegin;
        end
        StAxBegin: begin
          w_pos_q <= 64'(pos_of[axis_q]);
          w_vel_q <= 64'(vel_of[axis_q]);
          w_p00_q <= cov_word(p00_of);
          w_p01_q <= cov_word(p01_of);
          w_p11_q <= cov_word(p11_of);
          w_z_q <= axis_q == 0 ? 64'(z_x) : 64'(z_y);
          `EVMS_REQUEST(64'(vel_of[axis_q]), dt_q)
          state_q <= StPredictPos;
        end
        // predict: pos += vel dt
        StPredictPos: if (mul_done) begin
          w_pos_q <= step;
          `EVMS_REQUEST(2 * dt_q, w_p01_q)
          state_q <= StPredictP00a;
        end
        StPredictP00a: if (mul_done) begin
          acc_q <= step;
          `EVMS_REQUEST(dt2_q, w_p11_q)
          state_q <= StPredictP00b;
        end
        StPredictP00b: if (mul_done) begin
          acc_q <= step;
          `EVMS_REQUEST(cfg_q_third, dt3_q)
          state_q <= StPredictP00c;
        end
        StPredictP00c: if (mul_done) begin
          p00n_q <= step;
          `EVMS_REQUEST(dt_q, w_p11_q)
          state_q <= StPredictP01a;
        end
        StPredictP01a: if (mul_done) begin
          acc_q <= step;
          `EVMS_REQUEST(cfg_q_half, dt2_q)
          state_q <= StPredictP01b;
        end
        StPredictP01b: if (mul_done) begin
          w_p01_q <= step;
          `EVMS_REQUEST(cfg_q, dt_q)
          state_q <= StPredictP11;
        end
        StPredictP11: if (mul_done) begin
          w_p11_q <= step;
          w_p00_q <= p00n_q;
          // update: s = p00 + r, through the reciprocal
          recip_x <= 64'(p00n_q + z_r);
          recip_start <= 1'b1;
          state_q <= StUpdateRecip;
        end
        StUpdateRecip: if (recip_done) begin
          rr_q <= recip_r;
          q_shift_q <= 8'(RecipFrac - GainFrac) + 8'(recip_m);
          `EVMS_REQUEST(w_p00_q, 64'(recip_r))
          state_q <= StUpdateK0;
        end
        StUpdateK0: if (mul_done) begin
          k0_q <= 64'((q_t + 65'd1) >> 1);
          `EVMS_REQUEST(w_p01_q < 0 ? -w_p01_q : w_p01_q, 64'(rr_q))
          state_q <= StUpdateK1;
        end
        StUpdateK1: if (mul_done) begin
          logic [GainBits-1:0] mag;
          // clamp_sym(+-q, G) == +-min(q, G) for q >= 0; q >= 2^GainLog2 exactly when
          // t >= 2^GainBits - 1, so the add is GainBits bits and the negation one more.
          mag = q_t >> GainBits != 0 || &q_t[GainBits-1:0] ? GainBits'((65'd1 << GainLog2) - 65'd1)
                                                           : GainBits'(({1'b0, q_t[GainBits-1:0]} + GainSumBits'(1)) >> 1);
          k1_q <= 64'($signed(w_p01_q < 0 ? -{1'b0, mag} : {1'b0, mag}));
          w_e_q <= w_z_q - w_pos_q;
          `EVMS_REQUEST(k0_q, w_z_q - w_pos_q)
          state_q <= StUpdatePos;
        end
        StUpdatePos: if (mul_done) begin
          w_pos_q <= step;
          `EVMS_REQUEST(k1_q, clamp_ones(w_e_q, GainLog2))
          state_q <= StUpdateVel;
        end
        StUpdateVel: if (mul_done) begin
          w_vel_q <= step;
          `EVMS_REQUEST(z_r, k0_q)
          state_q <= StUpdateP00;
        end
        StUpdateP00: if (mul_done) begin
          p00n_q <= step;
          `EVMS_REQUEST(z_r, k1_q)
          state_q <= StUpdateP01;
        end
        StUpdateP01: if (mul_done) begin
          p01n_q <= CovBits'(step);
          `EVMS_REQUEST(k1_q, w_p01_q)
          state_q <= StUpdateP11;
        end
        StUpdateP11: if (mul_done) begin
          // (the filter state is written by the memory port below)
          state_q <= StAxEnd;
        end
        StAxEnd: begin
          if (axis_q == 0) begin
            axis_q <= 1'b1;
            state_q <= StAxBegin;
          end else begin
            axis_q <= 1'b0;
            ids_valid_q[ClusterIndexBits'(k_q)] <= 1'b1;
            if (!s_confirmed_q[si]) begin
              s_hits_q[si] <= s_hits_q[si] + 1'b1;
              s_confirmed_q[si] <= s_hits_q[si] + 1'b1 >= cfg_confirm_hits;
            end
            state_q <= StEmit;
          end
        end
        StEmit: begin
          if (!upd_valid || upd_ready) begin
            if (s_confirmed_q[si] || cfg_report_tentative) begin
              upd_valid <= 1'b1;
              upd_confirmed <= s_confirmed_q[si];
              upd_t <= z_t;
              upd_id <= s_id[si];
              upd_x <= pos_of[0];
              upd_y <= pos_of[1];
              upd_vx <= vel_of[0];
              upd_vy <= vel_of[1];
              upd_zx <= z_x;
              upd_zy <= z_y;
              {upd_events, upd_x_min, upd_y_min, upd_x_max, upd_y_max, upd_var_x, upd_var_y} <= upd_extra;
            end
            round_n_q <= round_n_q + 1'b1;
            state_q <= StRound;
          end
        end
        // 5. Tentative tracks without a match end.
        StDrop: begin
          if (32'(s_q) >= TracksMax) begin
            k_q <= '0;
            state_q <= StBirth;
          end else begin
            if (s_valid_q[si] && !slot_matched_q[si] && !s_confirmed_q[si]) s_valid_q[si] <= 1'b0;
            s_q <= s_q + 1'b1;
          end
        end
        // 6. Births in the lowest free slots.
        StBirth: begin
          if (k_q >= m) begin
            state_q <= StDone;
          end else if (meas_matched_q[ClusterIndexBits'(k_q)]) begin
            k_q <= k_q + 1'b1;
          end else if (evict_scan_needed) begin
            s_q <= '0;
            evict_slot_q <= -9'sd1;
            state_q <= StEvict;
          end else begin
            evict_scanned_q <= 1'b0;
            if (birth_slot < 0) begin
              unassigned <= unassigned + 1'b1;
              k_q <= k_q + 1'b1;
            end else begin
              // A slot born (or taken) this packet is matched: a later eviction passes it by.
              slot_matched_q[TrackIndexBits'(birth_slot)] <= 1'b1;
              s_valid_q[TrackIndexBits'(birth_slot)] <= 1'b1;
              next_id_q <= (next_id_q + 1) & 32'h7FFFFFFF;
              s_hits_q[TrackIndexBits'(birth_slot)] <= 8'd1;
              s_confirmed_q[TrackIndexBits'(birth_slot)] <= cfg_confirm_hits <= 8'd1;
              ids_valid_q[ClusterIndexBits'(k_q)] <= 1'b1;
              s_q <= (TrackIndexBits+1)'(birth_slot);
              state_q <= StBirthEmit;
            end
          end
        end
        // The unmatched slot measured longest ago (ties to the lower slot), one slot a clock.
        StEvict: begin
          if (32'(s_q) >= TracksMax) begin
            evict_scanned_q <= 1'b1;
            state_q <= StBirth;
          end else begin
            if (32'(s_q) < 32'(cfg_max_tracks) && !slot_matched_q[si] && (evict_slot_q < 0 || $signed(s_t[si] - evict_t_q) < 0)) begin
              evict_slot_q <= $signed({1'b0, 8'(s_q)});
              evict_t_q <= s_t[si];
            end
            s_q <= s_q + 1'b1;
          end
        end
        StBirthEmit: begin
          if (!upd_valid || upd_ready) begin
            if (cfg_confirm_hits <= 8'd1 || cfg_report_tentative) begin
              upd_valid <= 1'b1;
              upd_confirmed <= cfg_confirm_hits <= 8'd1;
              upd_t <= z_t;
              upd_id <= s_id[si];
              upd_x <= z_x;
              upd_y <= z_y;
              upd_vx <= '0;
              upd_vy <= '0;
              upd_zx <= z_x;
              upd_zy <= z_y;
              {upd_events, upd_x_min, upd_y_min, upd_x_max, upd_y_max, upd_var_x, upd_var_y} <= upd_extra;
            end
            k_q <= k_q + 1'b1;
            state_q <= StBirth;
          end
        end
        StDone: if (!upd_valid || upd_ready) begin
          done <= 1'b1;
          state_q <= StIdle;
        end
        default: state_q <= StIdle;
      endcase
    end
  end
`undef EVMS_REQUEST

  // ---- the pair table ------------------------------------------------------------------------
  logic [63:0] pair_d2_new;
  assign pair_d2_new = d2_q + 64'(mul_p);
  assign pair_we = state_q == StPairDy2 && mul_done;
  assign pair_wa = {si, ClusterIndexBits'(k_q)};
  // The pair's event counts differ by more than 2^cfg_size_ratio_log2 times (never when it is 0).
  logic [15:0] events_hi, events_lo;
  logic        pair_far;
  assign events_hi = s_events[si] > z_events ? s_events[si] : z_events;
  assign events_lo = s_events[si] > z_events ? z_events : s_events[si];
  assign pair_far = cfg_size_ratio_log2 != 4'd0 && 32'(events_hi) > (32'(events_lo) << cfg_size_ratio_log2);
  // cfg_gate_boxes: the slot's last measurement lies in the measurement's box, or the
  // measurement in the box of the slot's last one: the pixel a centre falls in (the whole part
  // of each coordinate) is one of the box's. A centre is a mean of 16-bit pixel coordinates, so
  // each compare is of its whole part's 16 bits, not of the fractions.
  function automatic logic box_holds(input [63:0] box, input [15:0] wx, input [15:0] wy);
    begin
      box_holds = wx >= box[63:48] && wx <= box[31:16] && wy >= box[47:32] && wy <= box[15:0];
    end
  endfunction
  // The box test is registered every clock: a pair's slot and measurement stay addressed from
  // its first distance state to its write (at least one clock, the multiplier's latency), so the
  // register holds the pair's own test when the table is written, off the path of the squares'
  // sum and the gate's compare.
  logic pair_within, pair_boxes_q;
  assign pair_within = pair_d2_new <= cfg_gate2;
  always_ff @(posedge clk) begin
    pair_boxes_q <= cfg_gate_boxes && (box_holds({z_x_min, z_y_min, z_x_max, z_y_max}, s_z[si][32 + PosFrac +: 16], s_z[si][PosFrac +: 16]) ||
                                       box_holds(s_box[si], z_x[PosFrac +: 16], z_y[PosFrac +: 16]));
  end
  assign pair_wd = {!pair_within, pair_far, pair_within || pair_boxes_q, pair_d2_new};
  assign pair_ra = {si, ClusterIndexBits'(k_q)};
  evms_ram_1w1r #(.Width(67), .Depth(1 << PairAddrBits)) u_pair_table (
    .clk, .we(pair_we), .wa(pair_wa), .wd(pair_wd), .ra(pair_ra), .rd(pair_rd)
  );
  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      scan_pending_q <= 1'b0;
      scan_slot_q <= '0;
      scan_meas_q <= '0;
    end else begin
      scan_pending_q <= state_q == StScan && 32'(s_q) < TracksMax && s_valid_q[si] && !slot_matched_q[si] && 32'(s_q) < 32'(cfg_max_tracks) &&
                        k_q < m && !meas_matched_q[ClusterIndexBits'(k_q)];
      scan_slot_q <= si;
      scan_meas_q <= k_q;
    end
  end
  `EVMS_ASSERT("a pending pair is compared while the scan runs", !scan_pending_q || state_q == StScan, clk, rst_n)

  // ---- the filter-state memories: a birth writes both axes, an update the axis it filtered --
  logic          birth_now, update_now;
  logic [TrackIndexBits-1:0] kal_addr;
  logic [AxisStateBits-1:0] kal_update;
  assign birth_now = state_q == StBirth && k_q < m && !meas_matched_q[ClusterIndexBits'(k_q)] && !evict_scan_needed && birth_slot >= 0;
  assign update_now = state_q == StUpdateP11 && mul_done;
  assign kal_addr = birth_now ? TrackIndexBits'(birth_slot) : si;
  assign kal_update = {32'(w_pos_q), 32'(w_vel_q), CovBits'(p00n_q), p01n_q, CovBits'(step)};
  // A new track's axis: at the measurement, at rest, with the initial covariance.
  function automatic [AxisStateBits-1:0] born_at(input signed [31:0] z);
    begin
      born_at = {z, 32'd0, CovBits'(cfg_p0_pos), CovBits'(0), CovBits'(cfg_p0_vel)};
    end
  endfunction
  always_ff @(posedge clk) begin
    if (birth_now || (update_now && !axis_q)) kal_x[kal_addr] <= birth_now ? born_at(z_x) : kal_update;
    if (birth_now || (update_now && axis_q)) kal_y[kal_addr] <= birth_now ? born_at(z_y) : kal_update;
    // The last measurement and its time: a birth's, or the match's once both axes are filtered;
    // the measurement's track ID: the new track's, or the matched slot's.
    if (birth_now || (state_q == StAxEnd && axis_q)) begin
      s_z[kal_addr] <= {z_x, z_y};
      s_events[kal_addr] <= z_events;
      s_box[kal_addr] <= {z_x_min, z_y_min, z_x_max, z_y_max};
      s_t[kal_addr] <= z_t;
      ids[ClusterIndexBits'(k_q)] <= birth_now ? next_id_q : s_id[si];
    end
    if (birth_now) s_id[kal_addr] <= next_id_q;
  end
endmodule
