// The evms core, as hls/core/core.h: filter -> packets -> features -> mean shift -> merging
// -> centroids -> tracking -> labels, with valid/ready streams and full backpressure: no event
// is ever dropped; the input simply waits while a packet is being clustered and released.
//
// Word by word: an event passes the filter (or is noise) and joins the pending queue, and,
// when kept, the packet. A packet closes when it holds cfg_packet_size events, when the next
// kept event is more than cfg_packet_max_span_us newer than its first, when the pending queue
// is full, or on a flush word. Closing clusters and tracks the packet, sends its summary, and
// releases every pending event with its label. A noise event that arrives while no packet is
// open is released at once. The parameters are one Shape (hls/core/shape.h), generated into
// rtl/generated/evms_cfg_*.svh.
module evms_core #(
  parameter int MAX_WIDTH        = 240,
  parameter int MAX_HEIGHT       = 180,
  parameter int TS_BITS          = 16,
  parameter int TS_SHIFT         = 7,
  parameter int PACKET_MAX       = 256,
  parameter int PENDING_DEPTH    = 1024,
  parameter int LANES            = 8,
  parameter int ITERATIONS_MAX   = 8,
  parameter int CLUSTERS_MAX     = 16,
  parameter int TRACKS_MAX       = 16,
  parameter int FEAT_INT         = 5,
  parameter int FEAT_FRAC        = 11,
  parameter int WEIGHT_FRAC      = 16,
  parameter int EXP_LOG2         = 9,
  parameter int EXP_INTERP_BITS  = 8,
  parameter int SUM_FRAC         = 16,
  parameter int RECIP_LOG2       = 8,
  parameter int RECIP_FRAC       = 20,
  parameter int DECAY_FRAC       = 32,
  parameter int COORD_SCALE_FRAC = 20,
  parameter int POS_FRAC         = 12,
  parameter int TICK_LOG2        = 14,
  parameter int COV_FRAC         = 16,
  parameter int GAIN_FRAC        = 20,
  parameter int NOISE_FRAC       = 32,
  parameter int MUL_DIGIT_BITS   = 64,
  parameter     EXP_MEM          = "exp_9_16.mem",
  parameter     RECIP_MEM        = "recip_8_20.mem"
) (
  input  logic        clk,
  input  logic        rst_n,
  // Registers (hls/core/config.h).
  input  logic [15:0] cfg_sensor_width,
  input  logic [15:0] cfg_sensor_height,
  input  logic        cfg_filter_enabled,
  input  logic [31:0] cfg_filter_window,
  input  logic [15:0] cfg_packet_size,
  input  logic [31:0] cfg_packet_max_span_us,
  input  logic [31:0] cfg_scale_x,
  input  logic [31:0] cfg_scale_y,
  input  logic [31:0] cfg_phi_on,
  input  logic [31:0] cfg_phi_t_max,
  input  logic [63:0] cfg_inv_tau,
  input  logic [7:0]  cfg_max_iterations,
  input  logic [31:0] cfg_tolerance,
  input  logic [63:0] cfg_merge_radius2,
  input  logic [15:0] cfg_min_cluster_size,
  input  logic [7:0]  cfg_max_clusters,
  input  logic [63:0] cfg_gate2,
  input  logic [7:0]  cfg_confirm_hits,
  input  logic [31:0] cfg_coast_us,
  input  logic [7:0]  cfg_max_tracks,
  input  logic [63:0] cfg_q_third,
  input  logic [63:0] cfg_q_half,
  input  logic [63:0] cfg_q,
  input  logic [63:0] cfg_r,
  input  logic [63:0] cfg_p0_pos,
  input  logic [63:0] cfg_p0_vel,
  // Events in.
  input  logic        in_valid,
  output logic        in_ready,
  input  logic [31:0] in_t,
  input  logic [15:0] in_x,
  input  logic [15:0] in_y,
  input  logic        in_p,
  input  logic        in_flush,
  // Labelled events out, in input order.
  output logic        lab_valid,
  input  logic        lab_ready,
  output logic [31:0] lab_t,
  output logic [15:0] lab_x,
  output logic [15:0] lab_y,
  output logic        lab_p,
  output logic [31:0] lab_label,
  // Track updates out.
  output logic        trk_valid,
  input  logic        trk_ready,
  output logic [31:0] trk_t,
  output logic [31:0] trk_id,
  output logic [31:0] trk_x,
  output logic [31:0] trk_y,
  output logic [31:0] trk_vx,
  output logic [31:0] trk_vy,
  output logic [31:0] trk_zx,
  output logic [31:0] trk_zy,
  // Packet summaries out.
  output logic        pkt_valid,
  input  logic        pkt_ready,
  output logic [31:0] pkt_t_first,
  output logic [31:0] pkt_t_last,
  output logic [15:0] pkt_events,
  output logic [7:0]  pkt_clusters,
  output logic [7:0]  pkt_iterations,
  // Status.
  output logic        idle,                // waiting for a word, nothing held
  output logic [31:0] stat_tracks_started,
  output logic [31:0] stat_unassigned
);
  localparam int FEAT_BITS = FEAT_INT + FEAT_FRAC;
  localparam int FW = FEAT_BITS + 1;
  localparam int PW = $clog2(PENDING_DEPTH + 1);   // counts 0..PENDING_DEPTH
  localparam int NW = $clog2(PACKET_MAX + 1);
  localparam int PI = $clog2(PENDING_DEPTH);       // indexes
  localparam int NI = $clog2(PACKET_MAX);
  localparam logic [63:0] FeatMax = (64'd1 << FEAT_BITS) - 1;

  // ---- memories ---------------------------------------------------------------------------
  // Each has one write port and one registered read port, so that it maps to block RAM.
  // Pending queue: every event since the last release, with its index in the packet or -1.
  localparam int PendW = 32 + 16 + 16 + 1 + 16;
  logic [PendW-1:0] pend_mem [PENDING_DEPTH];
  logic             pend_we;
  logic [PendW-1:0] pend_wdata, pend_rdata;
  // The open packet, and each of its events' cluster.
  logic [64:0] pk_mem [PACKET_MAX];
  logic [64:0] pk_rdata;
  logic signed [7:0] cluster_of [PACKET_MAX];

  // Packet RAM read port (features, centroids) and cluster_of port (merge, centroids, release).
  logic [15:0] rd_pk_i, co_i;
  logic [15:0] rd_pk_x, rd_pk_y;
  logic        rd_pk_p;
  logic [31:0] rd_pk_t;
  logic signed [7:0] co_rdata;

  // ---- the event being handled --------------------------------------------------------------
  logic [31:0] e_t;
  logic [15:0] e_x, e_y;
  logic        e_p;
  logic [NW-1:0] n;          // kept events in the packet
  logic [PW-1:0] pend_n;     // events waiting
  logic [31:0] t_first, t_last;
  logic        append_after;  // the closing event still has to join the next packet

  // ---- filter -------------------------------------------------------------------------------
  logic f_ready, f_start, f_done, f_kept;
  evms_ba_filter #(.MAX_WIDTH(MAX_WIDTH), .MAX_HEIGHT(MAX_HEIGHT), .TS_BITS(TS_BITS), .TS_SHIFT(TS_SHIFT)) u_filter (
    .clk(clk), .rst_n(rst_n), .cfg_enabled(cfg_filter_enabled), .cfg_width(cfg_sensor_width), .cfg_height(cfg_sensor_height),
    .cfg_window(cfg_filter_window), .ready(f_ready), .start(f_start), .t(in_t), .x(in_x), .y(in_y), .done(f_done), .kept(f_kept));

  // ---- shared multiplier and reciprocal -------------------------------------------------------
  logic feat_mul_start;
  logic signed [63:0] feat_mul_a, feat_mul_b;
  logic mul_start, mul_busy, mul_done;  // consumers wait for done, so busy is only for lint
  logic signed [63:0] mul_a, mul_b, mul_p;
  evms_mul #(.DIGIT_BITS(MUL_DIGIT_BITS)) u_mul (
    .clk(clk), .rst_n(rst_n), .start(mul_start), .a(mul_a), .b(mul_b), .busy(mul_busy), .done(mul_done), .p(mul_p));
  logic recip_start, recip_done;
  logic [63:0] recip_x;
  logic [RECIP_FRAC:0] recip_r;
  logic [6:0] recip_m;
  evms_recip #(.T(RECIP_LOG2), .RF(RECIP_FRAC), .MEM_FILE(RECIP_MEM)) u_recip (
    .clk(clk), .rst_n(rst_n), .start(recip_start), .x(recip_x), .done(recip_done), .r(recip_r), .m(recip_m));

  // ---- mean-shift engine ----------------------------------------------------------------------
  logic ms_load_we, ms_start, ms_done;
  logic [15:0] ms_load_i, ms_rd_i;
  logic [FEAT_BITS-1:0] ms_lx, ms_ly, ms_lp, ms_lt;
  logic [7:0] ms_sweeps;
  logic [FW-1:0] ms_rx, ms_ry, ms_rp, ms_rt;
  logic ms_recip_start;
  logic [63:0] ms_recip_x;
  evms_mean_shift #(
    .PACKET_MAX(PACKET_MAX), .LANES(LANES), .ITERATIONS_MAX(ITERATIONS_MAX), .FEAT_BITS(FEAT_BITS), .FEAT_FRAC(FEAT_FRAC),
    .WEIGHT_FRAC(WEIGHT_FRAC), .SUM_FRAC(SUM_FRAC), .EXP_LOG2(EXP_LOG2), .EXP_INTERP(EXP_INTERP_BITS),
    .RECIP_FRAC(RECIP_FRAC), .EXP_MEM(EXP_MEM)
  ) u_mean_shift (
    .clk(clk), .rst_n(rst_n), .load_we(ms_load_we), .load_i(ms_load_i), .load_x(ms_lx), .load_y(ms_ly), .load_p(ms_lp),
    .load_t(ms_lt), .start(ms_start), .n(16'(n)), .cfg_max_iterations(cfg_max_iterations), .cfg_tolerance(cfg_tolerance),
    .done(ms_done), .sweeps(ms_sweeps), .rd_i(ms_rd_i), .rd_x(ms_rx), .rd_y(ms_ry), .rd_p(ms_rp), .rd_t(ms_rt),
    .recip_start(ms_recip_start), .recip_x(ms_recip_x), .recip_done(recip_done), .recip_r(recip_r), .recip_m(recip_m));

  // ---- merging ----------------------------------------------------------------------------------
  logic mg_start, mg_done, mg_co_we;
  logic [15:0] mg_rd_i, mg_co_i;
  logic signed [7:0] mg_co_value;
  logic [7:0] clusters;
  evms_merge #(.CLUSTERS_MAX(CLUSTERS_MAX), .FW(FW)) u_merge (
    .clk(clk), .rst_n(rst_n), .start(mg_start), .n(16'(n)), .cfg_merge_radius2(cfg_merge_radius2),
    .cfg_min_cluster_size(cfg_min_cluster_size), .cfg_max_clusters(cfg_max_clusters), .rd_i(mg_rd_i), .rd_x(ms_rx),
    .rd_y(ms_ry), .rd_p(ms_rp), .rd_t(ms_rt), .co_we(mg_co_we), .co_i(mg_co_i), .co_value(mg_co_value),
    .co_rdata(co_rdata), .done(mg_done), .clusters(clusters));

  // ---- centroids --------------------------------------------------------------------------------
  logic ct_start, ct_done, ct_recip_start, ct_mul_start;
  logic [15:0] ct_rd_i;
  logic [63:0] ct_recip_x;
  logic signed [63:0] ct_mul_a, ct_mul_b;
  logic [7:0] z_c;
  logic [31:0] z_t;
  logic signed [31:0] z_x, z_y;
  evms_centroid #(.CLUSTERS_MAX(CLUSTERS_MAX), .POS_FRAC(POS_FRAC), .RECIP_FRAC(RECIP_FRAC)) u_centroid (
    .clk(clk), .rst_n(rst_n), .start(ct_start), .n(16'(n)), .clusters(clusters), .t0(t_first), .rd_i(ct_rd_i),
    .ev_x(rd_pk_x), .ev_y(rd_pk_y), .ev_t(rd_pk_t), .ev_cluster(co_rdata), .recip_start(ct_recip_start),
    .recip_x(ct_recip_x), .recip_done(recip_done), .recip_r(recip_r), .recip_m(recip_m), .mul_start(ct_mul_start),
    .mul_a(ct_mul_a), .mul_b(ct_mul_b), .mul_done(mul_done), .mul_p(mul_p), .z_c(z_c), .z_t(z_t), .z_x(z_x), .z_y(z_y),
    .done(ct_done));

  // ---- tracker ----------------------------------------------------------------------------------
  logic tk_start, tk_done, tk_recip_start, tk_mul_start;
  logic [63:0] tk_recip_x;
  logic signed [63:0] tk_mul_a, tk_mul_b;
  logic [7:0] id_c;
  logic signed [31:0] id_of;
  evms_tracker #(
    .CLUSTERS_MAX(CLUSTERS_MAX), .TRACKS_MAX(TRACKS_MAX), .POS_FRAC(POS_FRAC), .TICK_LOG2(TICK_LOG2), .COV_FRAC(COV_FRAC),
    .GAIN_FRAC(GAIN_FRAC), .NOISE_FRAC(NOISE_FRAC), .RECIP_FRAC(RECIP_FRAC)
  ) u_tracker (
    .clk(clk), .rst_n(rst_n), .cfg_gate2(cfg_gate2), .cfg_confirm_hits(cfg_confirm_hits), .cfg_coast_us(cfg_coast_us),
    .cfg_max_tracks(cfg_max_tracks), .cfg_q_third(cfg_q_third), .cfg_q_half(cfg_q_half), .cfg_q(cfg_q), .cfg_r(cfg_r),
    .cfg_p0_pos(cfg_p0_pos), .cfg_p0_vel(cfg_p0_vel), .start(tk_start), .packet_time(t_last), .m(clusters), .z_c(z_c),
    .z_t(z_t), .z_x(z_x), .z_y(z_y), .id_c(id_c), .id_of(id_of), .upd_valid(trk_valid), .upd_ready(trk_ready),
    .upd_t(trk_t), .upd_id(trk_id), .upd_x(trk_x), .upd_y(trk_y), .upd_vx(trk_vx), .upd_vy(trk_vy), .upd_zx(trk_zx),
    .upd_zy(trk_zy), .recip_start(tk_recip_start), .recip_x(tk_recip_x), .recip_done(recip_done), .recip_r(recip_r),
    .recip_m(recip_m), .mul_start(tk_mul_start), .mul_a(tk_mul_a), .mul_b(tk_mul_b), .mul_done(mul_done), .mul_p(mul_p),
    .done(tk_done), .tracks_started(stat_tracks_started), .unassigned(stat_unassigned));

  // ---- decay for the time feature -----------------------------------------------------------------
  logic [63:0] decay_u;
  logic [WEIGHT_FRAC:0] decay_w;
  evms_exp_lut #(.L(EXP_LOG2), .WF(WEIGHT_FRAC), .IB(EXP_INTERP_BITS), .UF(DECAY_FRAC), .UW(64), .MEM_FILE(EXP_MEM)) u_decay (
    .clk(clk), .u(decay_u), .w(decay_w));

  // ---- control ------------------------------------------------------------------------------------
  typedef enum logic [4:0] {
    C_IDLE, C_FILTER, C_APPEND, C_CLOSE, C_FEAT_READ, C_FEAT_WAIT, C_FEAT_X, C_FEAT_Y, C_FEAT_AGE, C_FEAT_DECAY1,
    C_FEAT_DECAY2, C_FEAT_T, C_FEAT_STORE, C_MEANSHIFT, C_MERGE, C_CENTROID, C_TRACK, C_PACKET, C_RELEASE_READ,
    C_RELEASE_WAIT, C_RELEASE_CLUSTER, C_RELEASE_SEND
  } state_e;
  state_e state /*verilator public_flat_rd*/;  // read by the cycle profile (sim/rtl_core.h)
  logic [15:0] fi;            // feature index
  logic [PW-1:0] ri;          // release index
  logic [FEAT_BITS-1:0] phi_x, phi_y, phi_p;
  logic [31:0] rel_t;
  logic [15:0] rel_x, rel_y;
  logic        rel_p;
  logic signed [15:0] rel_idx;
  logic [7:0]  iterations;

  always_ff @(posedge clk) begin
    if (pend_we) pend_mem[PI'(pend_n)] <= pend_wdata;
    pend_rdata <= pend_mem[PI'(ri)];
    if (state == C_APPEND) pk_mem[NI'(n)] <= {e_x, e_y, e_p, e_t};
    pk_rdata <= pk_mem[NI'(rd_pk_i)];
    if (mg_co_we) cluster_of[NI'(mg_co_i)] <= mg_co_value;
    co_rdata <= cluster_of[NI'(co_i)];
  end
  assign {rd_pk_x, rd_pk_y, rd_pk_p, rd_pk_t} = pk_rdata;
  // Events join the pending queue when the filter rejects them or when they join the packet.
  assign pend_we = (state == C_FILTER && f_done && !f_kept) || state == C_APPEND;
  assign pend_wdata = {e_t, e_x, e_y, e_p, state == C_APPEND ? 16'(n) : 16'hFFFF};
  assign rd_pk_i = state == C_CENTROID ? ct_rd_i : fi;
  assign co_i = state == C_MERGE ? mg_co_i : (state == C_CENTROID ? ct_rd_i :
                (state == C_RELEASE_WAIT ? pend_rdata[15:0] : 16'(rel_idx)));
  assign ms_rd_i = mg_rd_i;

  // The shared units belong to one stage at a time.
  always_comb begin
    mul_start = 1'b0;
    mul_a = '0;
    mul_b = '0;
    recip_start = 1'b0;
    recip_x = '0;
    if (state == C_CENTROID) begin
      mul_start = ct_mul_start;
      mul_a = ct_mul_a;
      mul_b = ct_mul_b;
      recip_start = ct_recip_start;
      recip_x = ct_recip_x;
    end else if (state == C_TRACK) begin
      mul_start = tk_mul_start;
      mul_a = tk_mul_a;
      mul_b = tk_mul_b;
      recip_start = tk_recip_start;
      recip_x = tk_recip_x;
    end else begin
      // features (the multiplier) and mean shift (the reciprocal)
      mul_start = feat_mul_start;
      mul_a = feat_mul_a;
      mul_b = feat_mul_b;
      recip_start = ms_recip_start;
      recip_x = ms_recip_x;
    end
  end
  function automatic [63:0] clamp_feat(input signed [63:0] v);
    begin
      clamp_feat = v < 0 ? 64'd0 : ($unsigned(v) > FeatMax ? FeatMax : $unsigned(v));
    end
  endfunction
  function automatic signed [63:0] shr_rnd(input signed [63:0] v, input integer s);
    begin
      if (s <= 0) shr_rnd = v <<< (-s);
      else shr_rnd = (v + (64'sd1 <<< (s - 1))) >>> s;
    end
  endfunction

  assign in_ready = state == C_IDLE && f_ready;
  assign idle = in_ready && pend_n == 0 && !lab_valid && !trk_valid && !pkt_valid;
  assign f_start = in_valid && in_ready && !in_flush;
  assign id_c = co_rdata >= 0 ? 8'(co_rdata) : 8'd0;

  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      state <= C_IDLE;
      {e_t, e_x, e_y, e_p} <= '0;
      n <= '0;
      pend_n <= '0;
      t_first <= '0;
      t_last <= '0;
      append_after <= 1'b0;
      fi <= '0;
      ri <= '0;
      {phi_x, phi_y, phi_p} <= '0;
      feat_mul_start <= 1'b0;
      feat_mul_a <= '0;
      feat_mul_b <= '0;
      decay_u <= '0;
      ms_load_we <= 1'b0;
      ms_load_i <= '0;
      {ms_lx, ms_ly, ms_lp, ms_lt} <= '0;
      ms_start <= 1'b0;
      mg_start <= 1'b0;
      ct_start <= 1'b0;
      tk_start <= 1'b0;
      iterations <= '0;
      lab_valid <= 1'b0;
      {lab_t, lab_x, lab_y, lab_p, lab_label} <= '0;
      pkt_valid <= 1'b0;
      {pkt_t_first, pkt_t_last, pkt_events, pkt_clusters, pkt_iterations} <= '0;
      {rel_t, rel_x, rel_y, rel_p} <= '0;
      rel_idx <= '0;
    end else begin
      feat_mul_start <= 1'b0;
      ms_load_we <= 1'b0;
      ms_start <= 1'b0;
      mg_start <= 1'b0;
      ct_start <= 1'b0;
      tk_start <= 1'b0;
      if (lab_valid && lab_ready) lab_valid <= 1'b0;
      if (pkt_valid && pkt_ready) pkt_valid <= 1'b0;
      case (state)
        C_IDLE: if (in_valid && in_ready) begin
          {e_t, e_x, e_y, e_p} <= {in_t, in_x, in_y, in_p};
          append_after <= 1'b0;
          state <= in_flush ? C_CLOSE : C_FILTER;
        end
        C_FILTER: if (f_done) begin
          if (!f_kept) begin
            pend_n <= pend_n + 1'b1;
            state <= (n == 0 || 32'(pend_n) + 1 == PENDING_DEPTH) ? C_CLOSE : C_IDLE;
          end else if (n > 0 && cfg_packet_max_span_us != 0 && e_t - t_first > cfg_packet_max_span_us) begin
            append_after <= 1'b1;
            state <= C_CLOSE;
          end else begin
            state <= C_APPEND;
          end
        end
        C_APPEND: begin
          if (n == 0) t_first <= e_t;
          t_last <= e_t;
          n <= n + 1'b1;
          pend_n <= pend_n + 1'b1;
          append_after <= 1'b0;
          state <= (32'(n) + 1 >= 32'(cfg_packet_size) || 32'(n) + 1 >= PACKET_MAX || 32'(pend_n) + 1 == PENDING_DEPTH)
                   ? C_CLOSE : C_IDLE;
        end
        C_CLOSE: begin
          if (n > 0) begin
            fi <= '0;
            state <= C_FEAT_READ;
          end else begin
            ri <= '0;
            state <= pend_n == 0 ? (append_after ? C_APPEND : C_IDLE) : C_RELEASE_READ;
          end
        end
        // Features of event fi.
        C_FEAT_READ: state <= C_FEAT_WAIT;
        C_FEAT_WAIT: begin
          feat_mul_start <= 1'b1;
          feat_mul_a <= $signed(64'(rd_pk_x));
          feat_mul_b <= $signed(64'(cfg_scale_x));
          state <= C_FEAT_X;
        end
        C_FEAT_X: if (mul_done) begin
          phi_x <= FEAT_BITS'(clamp_feat(shr_rnd(mul_p, COORD_SCALE_FRAC - FEAT_FRAC)));
          feat_mul_start <= 1'b1;
          feat_mul_a <= $signed(64'(rd_pk_y));
          feat_mul_b <= $signed(64'(cfg_scale_y));
          state <= C_FEAT_Y;
        end
        C_FEAT_Y: if (mul_done) begin
          logic [31:0] age, age_clamped;
          phi_y <= FEAT_BITS'(clamp_feat(shr_rnd(mul_p, COORD_SCALE_FRAC - FEAT_FRAC)));
          phi_p <= rd_pk_p ? FEAT_BITS'(clamp_feat($signed(64'(cfg_phi_on)))) : '0;
          age = t_last - rd_pk_t;
          age_clamped = age > 32'h7FFFFFFF ? 32'h7FFFFFFF : age;
          feat_mul_start <= 1'b1;
          feat_mul_a <= $signed(64'(age_clamped));
          feat_mul_b <= $signed(cfg_inv_tau);
          state <= C_FEAT_AGE;
        end
        C_FEAT_AGE: if (mul_done) begin
          decay_u <= mul_p;
          state <= C_FEAT_DECAY1;
        end
        C_FEAT_DECAY1: state <= C_FEAT_DECAY2;
        C_FEAT_DECAY2: state <= C_FEAT_T;
        C_FEAT_T: begin
          feat_mul_start <= 1'b1;
          feat_mul_a <= $signed(64'(cfg_phi_t_max));
          feat_mul_b <= $signed(64'(decay_w));
          state <= C_FEAT_STORE;
        end
        C_FEAT_STORE: if (mul_done) begin
          ms_load_we <= 1'b1;
          ms_load_i <= fi;
          ms_lx <= phi_x;
          ms_ly <= phi_y;
          ms_lp <= phi_p;
          ms_lt <= FEAT_BITS'(clamp_feat(shr_rnd(mul_p, WEIGHT_FRAC)));
          if (32'(fi) + 1 < 32'(n)) begin
            fi <= fi + 1'b1;
            state <= C_FEAT_READ;
          end else begin
            ms_start <= 1'b1;
            state <= C_MEANSHIFT;
          end
        end
        C_MEANSHIFT: if (ms_done) begin
          iterations <= ms_sweeps;
          mg_start <= 1'b1;
          state <= C_MERGE;
        end
        C_MERGE: if (mg_done) begin
          ct_start <= 1'b1;
          state <= C_CENTROID;
        end
        C_CENTROID: if (ct_done) begin
          tk_start <= 1'b1;
          state <= C_TRACK;
        end
        C_TRACK: if (tk_done) state <= C_PACKET;
        C_PACKET: if (!pkt_valid || pkt_ready) begin
          pkt_valid <= 1'b1;
          pkt_t_first <= t_first;
          pkt_t_last <= t_last;
          pkt_events <= 16'(n);
          pkt_clusters <= clusters;
          pkt_iterations <= iterations;
          ri <= '0;
          state <= C_RELEASE_READ;
        end
        // Release pending event ri with its label.
        C_RELEASE_READ: state <= C_RELEASE_WAIT;       // pending[ri] is being read
        C_RELEASE_WAIT: begin                           // ... and cluster_of[its index]
          {rel_t, rel_x, rel_y, rel_p, rel_idx} <= pend_rdata;
          state <= C_RELEASE_CLUSTER;
        end
        C_RELEASE_CLUSTER: state <= C_RELEASE_SEND;   // ids[cluster] settles
        C_RELEASE_SEND: if (!lab_valid || lab_ready) begin
          lab_valid <= 1'b1;
          {lab_t, lab_x, lab_y, lab_p} <= {rel_t, rel_x, rel_y, rel_p};
          lab_label <= rel_idx < 0 || co_rdata < 0 ? 32'hFFFFFFFF : id_of;
          if (32'(ri) + 1 < 32'(pend_n)) begin
            ri <= ri + 1'b1;
            state <= C_RELEASE_READ;
          end else begin
            n <= '0;
            pend_n <= '0;
            state <= append_after ? C_APPEND : C_IDLE;
          end
        end
        default: state <= C_IDLE;
      endcase
    end
  end
endmodule
