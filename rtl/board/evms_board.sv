// The board top, generic over the core build: a DVS128-style AER receiver and the host link
// feed the core; the core's labelled events, track updates and packet summaries go back over
// the link. One UART (8N1, CLKS_PER_BIT clocks a bit) carries both directions (docs/link.md).
//
//   AER pins --> evms_aer_rx --+                               +--> evms_link_tx --> UART tx
//                              +--> evms_core (labels, tracks, packets) --+
//   UART rx --> evms_link_rx --+   (link events first, then AER)
//
// A reset frame from the host restarts the core and the link's queues (a new run on a board
// that ran before, or after an aborted one) and is answered by a status frame once the core is
// idle. The link takes events in sequence only and asks the host to resend what the line lost
// (evms_link_rx.sv), so the core sees the host's stream exactly. After a flush from the host, once the core has released everything, a status frame
// (timestamp, events received, check errors, framing errors, overruns, external AER events,
// tracks started, clusters without a track slot) tells the host that the flush is complete. Backpressure reaches the AER sender (it waits for
// its acknowledge); the link keeps at most LINK_FIFO_DEPTH events in flight by protocol.
module evms_board #(
  parameter int CLK_HZ           = 12000000,
  parameter int CLKS_PER_BIT     = 4,
  parameter int LINK_FIFO_DEPTH  = 512,
  parameter int MUL_DIGIT_BITS   = 64,
  // The core build (rtl/generated/evms_cfg_*.svh).
  parameter int MAX_WIDTH = 240, parameter int MAX_HEIGHT = 180, parameter int TS_BITS = 16, parameter int TS_SHIFT = 7,
  parameter int PACKET_MAX = 256, parameter int PENDING_DEPTH = 1024, parameter int LANES = 8, parameter int ITERATIONS_MAX = 8,
  parameter int CLUSTERS_MAX = 16, parameter int TRACKS_MAX = 16, parameter int FEAT_INT = 5, parameter int FEAT_FRAC = 11,
  parameter int WEIGHT_FRAC = 16, parameter int EXP_LOG2 = 9, parameter int EXP_INTERP_BITS = 8, parameter int SUM_FRAC = 16,
  parameter int RECIP_LOG2 = 8, parameter int RECIP_FRAC = 20, parameter int DECAY_FRAC = 32, parameter int COORD_SCALE_FRAC = 20,
  parameter int POS_FRAC = 12, parameter int TICK_LOG2 = 14, parameter int COV_FRAC = 16, parameter int GAIN_FRAC = 20,
  parameter int NOISE_FRAC = 32, parameter EXP_MEM = "exp_9_16.mem", parameter RECIP_MEM = "recip_8_20.mem",
  // Register values (the defaults of the build).
  parameter int DEF_SENSOR_WIDTH = 128, parameter int DEF_SENSOR_HEIGHT = 128, parameter int DEF_FILTER_ENABLED = 1,
  parameter int DEF_FILTER_WINDOW = 78, parameter int DEF_PACKET_SIZE = 256, parameter int DEF_PACKET_MAX_SPAN_US = 0,
  parameter int DEF_SCALE_X = 0, parameter int DEF_SCALE_Y = 0, parameter int DEF_PHI_ON = 0, parameter int DEF_PHI_T_MAX = 0,
  parameter logic [63:0] DEF_INV_TAU = 0, parameter int DEF_MAX_ITERATIONS = 8, parameter int DEF_TOLERANCE = 0,
  parameter logic [63:0] DEF_MERGE_RADIUS2 = 0, parameter int DEF_MIN_CLUSTER_SIZE = 8, parameter int DEF_MAX_CLUSTERS = 16,
  parameter logic [63:0] DEF_GATE2 = 0, parameter int DEF_CONFIRM_HITS = 3, parameter int DEF_COAST_US = 100000,
  parameter int DEF_MAX_TRACKS = 16, parameter logic [63:0] DEF_Q_THIRD = 0, parameter logic [63:0] DEF_Q_HALF = 0,
  parameter logic [63:0] DEF_Q = 0, parameter logic [63:0] DEF_R = 0, parameter logic [63:0] DEF_P0_POS = 0,
  parameter logic [63:0] DEF_P0_VEL = 0
) (
  input  logic        clk,
  input  logic        rst_n,
  // AER from the sensor.
  input  logic        aer_req_n,
  output logic        aer_ack_n,
  input  logic [15:0] aer_addr,
  // Host link.
  input  logic        uart_rx,
  output logic        uart_tx,
  // Activity.
  output logic        led_busy,
  output logic        led_error
);
  // ---- sources ------------------------------------------------------------------------------
  logic aer_valid, aer_ready, aer_p;
  logic [31:0] aer_t, timestamp, external_events;
  logic [15:0] aer_x, aer_y;
  evms_aer_rx #(.CLK_HZ(CLK_HZ)) u_aer (
    .clk(clk), .rst_n(rst_n), .req_n(aer_req_n), .ack_n(aer_ack_n), .addr(aer_addr), .ev_valid(aer_valid),
    .ev_ready(aer_ready), .ev_t(aer_t), .ev_x(aer_x), .ev_y(aer_y), .ev_p(aer_p), .timestamp(timestamp),
    .external_events(external_events));

  logic rx_valid;
  logic [7:0] rx_data;
  logic [31:0] framing_errors;
  evms_uart_rx #(.CLKS_PER_BIT(CLKS_PER_BIT)) u_uart_rx (
    .clk(clk), .rst_n(rst_n), .rx(uart_rx), .valid(rx_valid), .data(rx_data), .framing_errors(framing_errors));
  logic lk_valid, lk_ready, lk_p, lk_flush, soft_reset, rs_valid, rs_ready;
  logic [31:0] lk_t, crc_errors, overruns, events_received;
  logic [15:0] lk_x, lk_y, rs_seq;
  evms_link_rx #(.FIFO_DEPTH(LINK_FIFO_DEPTH)) u_link_rx (
    .clk(clk), .rst_n(rst_n), .byte_valid(rx_valid), .byte_data(rx_data), .ev_valid(lk_valid), .ev_ready(lk_ready),
    .ev_t(lk_t), .ev_x(lk_x), .ev_y(lk_y), .ev_p(lk_p), .ev_flush(lk_flush), .soft_reset(soft_reset),
    .resend_valid(rs_valid), .resend_ready(rs_ready), .resend_seq(rs_seq), .crc_errors(crc_errors), .overruns(overruns),
    .events_received(events_received));

  // Link words first (the host owns the stream while it sends), then the sensor.
  logic in_valid, in_ready, in_p, in_flush;
  logic [31:0] in_t;
  logic [15:0] in_x, in_y;
  assign in_valid = lk_valid || aer_valid;
  assign {in_t, in_x, in_y, in_p, in_flush} = lk_valid ? {lk_t, lk_x, lk_y, lk_p, lk_flush} : {aer_t, aer_x, aer_y, aer_p, 1'b0};
  assign lk_ready = in_ready;
  assign aer_ready = in_ready && !lk_valid;

  // The reset frame's pulse, registered, resets everything behind the link: the core, the
  // outgoing frames and the status logic. Counters of link errors keep counting.
  logic run_rst_n;
  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) run_rst_n <= 1'b0;
    else run_rst_n <= !soft_reset;
  end

  // ---- the core ---------------------------------------------------------------------------------
  logic lab_valid, lab_ready, lab_p, trk_valid, trk_ready, pkt_valid, pkt_ready, core_idle;
  logic [31:0] lab_t, lab_label, trk_t, trk_id, trk_x, trk_y, trk_vx, trk_vy, trk_zx, trk_zy, pkt_t_first, pkt_t_last;
  logic [15:0] lab_x, lab_y, pkt_events;
  logic [7:0] pkt_clusters, pkt_iterations;
  logic [31:0] tracks_started, unassigned;
  evms_core #(
    .MAX_WIDTH(MAX_WIDTH), .MAX_HEIGHT(MAX_HEIGHT), .TS_BITS(TS_BITS), .TS_SHIFT(TS_SHIFT), .PACKET_MAX(PACKET_MAX),
    .PENDING_DEPTH(PENDING_DEPTH), .LANES(LANES), .ITERATIONS_MAX(ITERATIONS_MAX), .CLUSTERS_MAX(CLUSTERS_MAX),
    .TRACKS_MAX(TRACKS_MAX), .FEAT_INT(FEAT_INT), .FEAT_FRAC(FEAT_FRAC), .WEIGHT_FRAC(WEIGHT_FRAC), .EXP_LOG2(EXP_LOG2),
    .EXP_INTERP_BITS(EXP_INTERP_BITS), .SUM_FRAC(SUM_FRAC), .RECIP_LOG2(RECIP_LOG2), .RECIP_FRAC(RECIP_FRAC),
    .DECAY_FRAC(DECAY_FRAC), .COORD_SCALE_FRAC(COORD_SCALE_FRAC), .POS_FRAC(POS_FRAC), .TICK_LOG2(TICK_LOG2),
    .COV_FRAC(COV_FRAC), .GAIN_FRAC(GAIN_FRAC), .NOISE_FRAC(NOISE_FRAC), .MUL_DIGIT_BITS(MUL_DIGIT_BITS),
    .EXP_MEM(EXP_MEM), .RECIP_MEM(RECIP_MEM)
  ) u_core (
    .clk(clk), .rst_n(run_rst_n),
    .cfg_sensor_width(16'(DEF_SENSOR_WIDTH)), .cfg_sensor_height(16'(DEF_SENSOR_HEIGHT)),
    .cfg_filter_enabled(DEF_FILTER_ENABLED != 0), .cfg_filter_window(32'(DEF_FILTER_WINDOW)),
    .cfg_packet_size(16'(DEF_PACKET_SIZE)), .cfg_packet_max_span_us(32'(DEF_PACKET_MAX_SPAN_US)),
    .cfg_scale_x(32'(DEF_SCALE_X)), .cfg_scale_y(32'(DEF_SCALE_Y)), .cfg_phi_on(32'(DEF_PHI_ON)),
    .cfg_phi_t_max(32'(DEF_PHI_T_MAX)), .cfg_inv_tau(DEF_INV_TAU), .cfg_max_iterations(8'(DEF_MAX_ITERATIONS)),
    .cfg_tolerance(32'(DEF_TOLERANCE)), .cfg_merge_radius2(DEF_MERGE_RADIUS2), .cfg_min_cluster_size(16'(DEF_MIN_CLUSTER_SIZE)),
    .cfg_max_clusters(8'(DEF_MAX_CLUSTERS)), .cfg_gate2(DEF_GATE2), .cfg_confirm_hits(8'(DEF_CONFIRM_HITS)),
    .cfg_coast_us(32'(DEF_COAST_US)), .cfg_max_tracks(8'(DEF_MAX_TRACKS)), .cfg_q_third(DEF_Q_THIRD),
    .cfg_q_half(DEF_Q_HALF), .cfg_q(DEF_Q), .cfg_r(DEF_R), .cfg_p0_pos(DEF_P0_POS), .cfg_p0_vel(DEF_P0_VEL),
    .in_valid(in_valid), .in_ready(in_ready), .in_t(in_t), .in_x(in_x), .in_y(in_y), .in_p(in_p), .in_flush(in_flush),
    .lab_valid(lab_valid), .lab_ready(lab_ready), .lab_t(lab_t), .lab_x(lab_x), .lab_y(lab_y), .lab_p(lab_p),
    .lab_label(lab_label), .trk_valid(trk_valid), .trk_ready(trk_ready), .trk_t(trk_t), .trk_id(trk_id), .trk_x(trk_x),
    .trk_y(trk_y), .trk_vx(trk_vx), .trk_vy(trk_vy), .trk_zx(trk_zx), .trk_zy(trk_zy), .pkt_valid(pkt_valid),
    .pkt_ready(pkt_ready), .pkt_t_first(pkt_t_first), .pkt_t_last(pkt_t_last), .pkt_events(pkt_events),
    .pkt_clusters(pkt_clusters), .pkt_iterations(pkt_iterations), .idle(core_idle),
    .stat_tracks_started(tracks_started), .stat_unassigned(unassigned));

  // ---- status after a flush ---------------------------------------------------------------------
  logic flush_pending, st_valid, st_ready;
  always_ff @(posedge clk or negedge run_rst_n) begin
    if (!run_rst_n) begin
      flush_pending <= 1'b1;  // after a reset, a status frame tells the host the board is ready
      st_valid <= 1'b0;
    end else begin
      if (in_valid && in_ready && in_flush) flush_pending <= 1'b1;
      if (flush_pending && core_idle && !in_valid && !st_valid) begin
        st_valid <= 1'b1;
        flush_pending <= 1'b0;
      end
      if (st_valid && st_ready) st_valid <= 1'b0;
    end
  end

  // ---- link back to the host ----------------------------------------------------------------------
  logic tx_valid, tx_ready;
  logic [7:0] tx_data;
  evms_link_tx u_link_tx (
    .clk(clk), .rst_n(run_rst_n), .lab_valid(lab_valid), .lab_ready(lab_ready), .lab_t(lab_t), .lab_x(lab_x), .lab_y(lab_y),
    .lab_p(lab_p), .lab_label(lab_label), .trk_valid(trk_valid), .trk_ready(trk_ready),
    .trk_payload({trk_zy, trk_zx, trk_vy, trk_vx, trk_y, trk_x, trk_id, trk_t}), .pkt_valid(pkt_valid),
    .pkt_ready(pkt_ready), .pkt_payload({pkt_iterations, pkt_clusters, pkt_events, pkt_t_last, pkt_t_first}),
    .st_valid(st_valid), .st_ready(st_ready), .rs_valid(rs_valid), .rs_ready(rs_ready), .rs_seq(rs_seq),
    .st_payload({unassigned, tracks_started, external_events, overruns, framing_errors, crc_errors, events_received, timestamp}),
    .byte_valid(tx_valid), .byte_ready(tx_ready), .byte_data(tx_data));
  evms_uart_tx #(.CLKS_PER_BIT(CLKS_PER_BIT)) u_uart_tx (
    .clk(clk), .rst_n(run_rst_n), .valid(tx_valid), .ready(tx_ready), .data(tx_data), .tx(uart_tx));

  assign led_busy = !core_idle;
  assign led_error = crc_errors != 0 || framing_errors != 0 || overruns != 0;
endmodule
