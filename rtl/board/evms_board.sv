// The board top, generic over the core build: a DVS128-style AER receiver and the host link
// feed the core; the core's outputs go back over the link. One UART (8N1, ClksPerBit clocks a
// bit) carries both directions (docs/link.md).
//
//   AER pins --> evms_aer_rx --+                                  labels -------------------+
//                              +--> evms_core --+                                            +--> evms_link_tx --> UART tx
//   UART rx --> evms_link_rx --+                +--> tracks, packets --> batch gate, queue --+
//                (link events first, then AER)
//
// A reset frame from the host restarts the core and the link's queues (a new run on a board
// that ran before, or after an aborted one), sets the run's mode, and is answered by a status
// frame once the core is idle. The link takes events in sequence only and asks the host to
// resend what the line lost (evms_link_rx.sv), so the core sees the host's stream exactly.
// After a flush from the host, once the core has released everything, a status frame tells
// the host that the flush is complete.
//
// The two modes:
// - labels (mode 0): every label goes to the host, and every track update and packet summary;
//   the link's pace holds the core back (backpressure reaches the AER sender, which waits for
//   its acknowledge), and nothing is lost. The link keeps at most LinkFifoDepth events in
//   flight by protocol.
// - tracks (mode 1): the labels stay on the board, counted, and the core never waits for the
//   link, so it runs at the sensor's rate. A packet's track updates and its summary go out
//   together, as a batch, when the queue is empty as the batch begins; otherwise the whole
//   batch is skipped (and counted), so what reaches the host is always whole packets.
// A board whose core is cut (CoreCut) returns every event's verdict in verdict frames (0x87)
// in both modes, and no track or packet frames; a core cut after its climbs also returns each
// packet's climbs frame: a link frame for its head (0x88) and each mode (0x89), and its events'
// modes up to 32 a frame (0x8A).
// In both modes, when the line is free and the counts have changed, a progress frame (link
// events the core took, events labelled with a track, events labelled noise) tells the host
// that the board is working; in tracks mode it acknowledges the host's events in place of
// their labels.
`include "evms_assert.svh"

module evms_board #(
  parameter int ClkHz          = 12000000,
  parameter int ClksPerBit     = 4,
  parameter int LinkFifoDepth  = 2048,
  // Where the core stops, for a build too large for its device (EVMS_BOARD_BUILDS in
  // hls/core/configs.h): 0 the whole core; 1 after its climbs (core/evms_climbs_core.sv), the
  // host completing each packet from its climbs frame. A cut core reads the CutCfg* registers,
  // its build's cut shape's values.
  parameter int CoreCut = 0,
  // The registers' reset values and the core build (rtl/generated/evms_cfg_<build>.svh).
  `include "evms_board_cfg_params.svh"
  `include "evms_core_shape_params.svh"
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
  // The host keeps LinkFifoDepth events in flight and waits for their labels; the core holds up
  // to PendingDepth of them unlabelled until their packet closes (which only more events do, or
  // a full pending queue), and its intake up to a packet's more.
  // A cut core answers each event with its verdict at once, so its queues hold none unanswered.
  localparam int CutClimbs = 1;
  `EVMS_ASSERT_INIT("the link queue must be deeper than the core's pending and intake queues", CoreCut != 0 || LinkFifoDepth > PendingDepth + PacketMax)
  `EVMS_ASSERT_INIT("a verdict frame holds x and y in a byte each", CoreCut == 0 || (MaxWidth <= 256 && MaxHeight <= 256))
  `EVMS_ASSERT_INIT("the core stops after its climbs or nowhere", CoreCut == 0 || CoreCut == CutClimbs)

  // ---- sources ------------------------------------------------------------------------------
  logic aer_valid, aer_ready, aer_p;
  logic [31:0] aer_t, timestamp, external_events;
  logic [15:0] aer_x, aer_y;
  evms_aer_rx #(.ClkHz(ClkHz)) u_aer (
    .clk(clk), .rst_n(rst_n), .req_n(aer_req_n), .ack_n(aer_ack_n), .addr(aer_addr), .ev_valid(aer_valid),
    .ev_ready(aer_ready), .ev_t(aer_t), .ev_x(aer_x), .ev_y(aer_y), .ev_p(aer_p), .timestamp(timestamp),
    .external_events(external_events));

  logic rx_valid;
  logic [7:0] rx_data;
  logic [31:0] framing_errors;
  evms_uart_rx #(.ClksPerBit(ClksPerBit)) u_uart_rx (
    .clk(clk), .rst_n(rst_n), .rx(uart_rx), .valid(rx_valid), .data(rx_data), .framing_errors(framing_errors));
  logic lk_valid, lk_ready, lk_p, lk_flush, soft_reset, labels_on_board, rs_valid, rs_ready;
  logic [31:0] lk_t, crc_errors, overruns, events_received;
  logic [15:0] lk_x, lk_y, rs_seq;
  evms_link_rx #(.FifoDepth(LinkFifoDepth)) u_link_rx (
    .clk(clk), .rst_n(rst_n), .byte_valid(rx_valid), .byte_data(rx_data), .ev_valid(lk_valid), .ev_ready(lk_ready),
    .ev_t(lk_t), .ev_x(lk_x), .ev_y(lk_y), .ev_p(lk_p), .ev_flush(lk_flush), .soft_reset(soft_reset), .labels_on_board(labels_on_board),
    .resend_valid(rs_valid), .resend_ready(rs_ready), .resend_seq(rs_seq), .crc_errors(crc_errors), .overruns(overruns),
    .events_received(events_received));

  // Link words first (the host owns the stream while it sends), then the sensor.
  `include "evms_stream_in_wires.svh"
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
  `include "evms_stream_lab_wires.svh"
  logic trk_valid, trk_ready, trk_confirmed, pkt_valid, pkt_ready, core_idle;
  logic [31:0] trk_t, trk_id, trk_x, trk_y, trk_vx, trk_vy, trk_zx, trk_zy, pkt_t_first, pkt_t_last;
  logic [15:0] pkt_events;
  logic [7:0] pkt_clusters;
  logic [15:0] pkt_iterations;
  // The link's packet frame carries 8 bits of iterations: more saturate at 255.
  wire [7:0] pkt_iterations_sent = pkt_iterations > 16'd255 ? 8'd255 : 8'(pkt_iterations);
  wire [95:0] pkt_payload_sent = {pkt_iterations_sent, pkt_clusters, pkt_events, pkt_t_last, pkt_t_first};
  logic [31:0] tracks_started, unassigned;
  // A core cut after its climbs: its climbs frames' words, to the link in place of packet summaries.
  logic clm_valid, clm_ready;
  logic [1:0] clm_kind;
  logic [79:0] clm_data;
  if (CoreCut == CutClimbs) begin : g_climbs_core
    // Every event comes back as a verdict, each packet as its climbs frame; no track or packet
    // words. Its packet, pending and mode sizes are its own defaults, the cut shape's
    // (hls::Ice40ClimbsShape), not this board's whole core's.
    evms_climbs_core #(
      .MaxWidth(MaxWidth), .MaxHeight(MaxHeight), .TimestampBits(TimestampBits), .TimestampShift(TimestampShift),
      .NoiseIntervalLog2(NoiseIntervalLog2)
    ) u_core (
      .clk(clk), .rst_n(run_rst_n),
      `include "evms_board_climbs_cfg_connect.svh"
      `include "evms_stream_in_connect.svh"
      `include "evms_stream_lab_connect.svh"
      .clm_valid(clm_valid), .clm_ready(clm_ready), .clm_kind(clm_kind), .clm_data(clm_data),
      .idle(core_idle));
    assign {trk_valid, trk_t, trk_id, trk_x, trk_y, trk_vx, trk_vy, trk_zx, trk_zy, trk_confirmed} = '0;
    assign {pkt_valid, pkt_t_first, pkt_t_last, pkt_events, pkt_clusters, pkt_iterations} = '0;
    assign {tracks_started, unassigned} = '0;
    logic unused_ready;  // nothing waits on the frame queue's ready
    assign unused_ready = ^{trk_ready, pkt_ready};
  end else begin : g_core
    evms_core #(
      `include "evms_core_shape_connect.svh"
    ) u_core (
      .clk(clk), .rst_n(run_rst_n),
      `include "evms_board_cfg_connect.svh"
      `include "evms_stream_in_connect.svh"
      `include "evms_stream_lab_connect.svh"
      .trk_valid(trk_valid), .trk_ready(trk_ready), .trk_t(trk_t), .trk_id(trk_id), .trk_x(trk_x),
      .trk_y(trk_y), .trk_vx(trk_vx), .trk_vy(trk_vy), .trk_zx(trk_zx), .trk_zy(trk_zy), .trk_confirmed(trk_confirmed),
      // The link's track frames end at the state: the measurement's count and box and the
      // variances stay on the board (docs/link.md).
      .trk_events(), .trk_x_min(), .trk_y_min(), .trk_x_max(), .trk_y_max(), .trk_var_x(), .trk_var_y(),
      .pkt_valid(pkt_valid),
      .pkt_ready(pkt_ready), .pkt_t_first(pkt_t_first), .pkt_t_last(pkt_t_last), .pkt_events(pkt_events),
      .pkt_clusters(pkt_clusters), .pkt_iterations(pkt_iterations), .idle(core_idle),
      .stat_tracks_started(tracks_started), .stat_unassigned(unassigned));
    assign {clm_valid, clm_kind, clm_data} = '0;
    logic unused_clm_ready;
    assign unused_clm_ready = clm_ready;
  end

  // ---- labels: to the link, or counted on the board ------------------------------------------------
  `include "evms_core_labels.svh"
  // A cut core sends its verdicts in either mode: the host needs them.
  logic keep_labels, tx_lab_valid, tx_lab_ready;
  assign keep_labels = labels_on_board && CoreCut == 0;
  assign tx_lab_valid = lab_valid && !keep_labels;
  assign lab_ready = keep_labels || tx_lab_ready;
  logic [31:0] labelled_q, noise_q, link_taken_q;  // since the run's reset
  // What the counts count: a label leaving the core, an event taken from the link.
  wire label_taken = lab_valid && lab_ready;
  wire link_event_taken = lk_valid && lk_ready && !lk_flush;
  always_ff @(posedge clk or negedge run_rst_n) begin
    if (!run_rst_n) begin
      labelled_q <= '0;
      noise_q <= '0;
      link_taken_q <= '0;
    end else begin
      if (label_taken) begin
        if (lab_label == LabelNoise) noise_q <= noise_q + 1'b1;
        else labelled_q <= labelled_q + 1'b1;
      end
      if (link_event_taken) link_taken_q <= link_taken_q + 1'b1;
    end
  end

  // ---- track updates and packet summaries: the batch gate and the frame queue ------------------------
  // A packet's track updates come before its summary (rtl/core/evms_core.sv: StTrack, then
  // StPacket), so a batch runs from the first word after a summary to the next summary. The
  // queue holds a whole batch: at most one update a cluster, and the summary.
  localparam int FrameQueueDepth = 1 << $clog2(ClustersMax + 2);
  localparam int FrameWordBits = 1 + 264;  // {is packet summary, the frame's payload}
  logic q_in_valid, q_in_ready, q_out_valid, q_out_ready, q_out_is_packet;
  logic [263:0] q_out_payload;
  logic batch_open_q, batch_open_d, batch_sent_q, batch_sent_d;
  logic [31:0] batches_skipped_q, batches_skipped_d;
  // Words in the queue, counted here: the queue's own out_valid lags a push by its RAM's latency.
  logic [$clog2(FrameQueueDepth):0] queued_q;
  logic queue_push, queue_pop;
  assign queue_push = q_in_valid && q_in_ready;
  assign queue_pop = q_out_valid && q_out_ready;
  logic word_valid, word_is_packet, word_admitted, word_taken;
  logic [FrameWordBits-1:0] word;
  wire [7:0] trk_state = {7'd0, trk_confirmed};
  assign word_valid = trk_valid || pkt_valid;
  assign word_is_packet = !trk_valid;
  assign word = word_is_packet ? {1'b1, 168'd0, pkt_payload_sent}
                               : {1'b0, trk_state, trk_zy, trk_zx, trk_vy, trk_vx, trk_y, trk_x, trk_id, trk_t};
  // In tracks mode a batch is sent only if the queue is empty as it begins; in labels mode
  // every batch is sent, and the queue's pace holds the core back.
  assign word_admitted = !labels_on_board || (batch_open_q ? batch_sent_q : queued_q == '0);
  assign q_in_valid = word_valid && word_admitted;
  assign word_taken = word_valid && (word_admitted ? q_in_ready : 1'b1);
  assign trk_ready = trk_valid && word_taken;
  assign pkt_ready = !trk_valid && pkt_valid && word_taken;
  // An admitted batch starts in an empty queue deep enough for it, so in tracks mode the queue
  // never holds the core back.
  `EVMS_ASSERT("a batch fits the frame queue", !(labels_on_board && q_in_valid && !q_in_ready), clk, run_rst_n)

  always_comb begin
    batch_open_d = batch_open_q;
    batch_sent_d = batch_sent_q;
    batches_skipped_d = batches_skipped_q;
    if (word_taken) begin
      batch_open_d = !word_is_packet;
      batch_sent_d = word_admitted;
      if (word_is_packet && !word_admitted) batches_skipped_d = batches_skipped_q + 1'b1;
    end
  end
  always_ff @(posedge clk or negedge run_rst_n) begin
    if (!run_rst_n) begin
      batch_open_q <= 1'b0;
      batch_sent_q <= 1'b0;
      batches_skipped_q <= '0;
      queued_q <= '0;
    end else begin
      if (queue_push && !queue_pop) queued_q <= queued_q + 1'b1;
      else if (queue_pop && !queue_push) queued_q <= queued_q - 1'b1;
      batch_open_q <= batch_open_d;
      batch_sent_q <= batch_sent_d;
      batches_skipped_q <= batches_skipped_d;
    end
  end

  // No output buffer: the link's ready is a short path, and the buffer would be 530 flip-flops.
  evms_fifo #(.Width(FrameWordBits), .Depth(FrameQueueDepth), .OutputBuffer(0)) u_frame_queue (
    .clk(clk), .rst_n(run_rst_n), .in_valid(q_in_valid), .in_ready(q_in_ready), .in_data(word), .in_commit(1'b0), .in_rollback(1'b0),
    .out_valid(q_out_valid), .out_ready(q_out_ready), .out_data({q_out_is_packet, q_out_payload}));
  logic tx_trk_ready, tx_pkt_ready;
  assign q_out_ready = q_out_is_packet ? tx_pkt_ready : tx_trk_ready;

  // ---- progress ----------------------------------------------------------------------------------------
  // In both modes, so that a board busy with a packet is never silent (the host resends what
  // is unanswered after a silence); in tracks mode it also acknowledges the link's events.
  // Whether the counts changed since a progress frame last took them: set by each count, cleared
  // as a frame takes them (a count in that same clock sets it again). A flag, where comparing
  // with the counts sent would keep 96 more flip-flops.
  wire [95:0] progress_now = {noise_q, labelled_q, link_taken_q};
  logic pg_valid, pg_ready, progress_changed_q;
  assign pg_valid = progress_changed_q;
  always_ff @(posedge clk or negedge run_rst_n) begin
    if (!run_rst_n) progress_changed_q <= 1'b0;
    else if (label_taken || link_event_taken) progress_changed_q <= 1'b1;
    else if (pg_ready) progress_changed_q <= 1'b0;
  end

  // ---- status after a flush ---------------------------------------------------------------------
  logic flush_pending_q, flush_pending_d, st_valid_q, st_valid_d, st_ready;
  always_comb begin
    flush_pending_d = flush_pending_q;
    st_valid_d = st_valid_q && !st_ready;
    if (in_valid && in_ready && in_flush) flush_pending_d = 1'b1;
    if (flush_pending_q && core_idle && !in_valid && queued_q == '0 && !st_valid_q) begin
      st_valid_d = 1'b1;
      flush_pending_d = 1'b0;
    end
  end
  always_ff @(posedge clk or negedge run_rst_n) begin
    if (!run_rst_n) begin
      flush_pending_q <= 1'b1;  // after a reset, a status frame tells the host the board is ready
      st_valid_q <= 1'b0;
    end else begin
      flush_pending_q <= flush_pending_d;
      st_valid_q <= st_valid_d;
    end
  end

  // ---- link back to the host ----------------------------------------------------------------------
  logic tx_valid, tx_ready;
  logic [7:0] tx_data;
  // A core cut after its climbs has no packet summaries: its climbs words take their port.
  logic tx_pkt_valid;
  logic [95:0] tx_pkt_payload;
  assign tx_pkt_valid = CoreCut == CutClimbs ? clm_valid : q_out_valid && q_out_is_packet;
  assign tx_pkt_payload = CoreCut == CutClimbs ? {14'd0, clm_kind, clm_data} : q_out_payload[95:0];
  assign clm_ready = tx_pkt_ready;
  evms_link_tx #(.LabelsAreVerdicts(CoreCut == CutClimbs ? 1 : 0), .PacketsAreClimbs(CoreCut == CutClimbs ? 1 : 0)) u_link_tx (
    .clk(clk), .rst_n(run_rst_n), .lab_valid(tx_lab_valid), .lab_ready(tx_lab_ready), .lab_t(lab_t), .lab_x(lab_x),
    .lab_y(lab_y), .lab_p(lab_p), .lab_label(lab_label), .trk_valid(q_out_valid && !q_out_is_packet), .trk_ready(tx_trk_ready),
    .trk_payload(q_out_payload), .pkt_valid(tx_pkt_valid), .pkt_ready(tx_pkt_ready),
    .pkt_payload(tx_pkt_payload), .st_valid(st_valid_q), .st_ready(st_ready), .rs_valid(rs_valid), .rs_ready(rs_ready),
    .rs_seq(rs_seq),
    .st_payload({batches_skipped_q, noise_q, labelled_q, unassigned, tracks_started, external_events, overruns, framing_errors,
                 crc_errors, events_received, timestamp}),
    .pg_valid(pg_valid), .pg_ready(pg_ready), .pg_payload(progress_now), .byte_valid(tx_valid), .byte_ready(tx_ready),
    .byte_data(tx_data));
  evms_uart_tx #(.ClksPerBit(ClksPerBit)) u_uart_tx (
    .clk(clk), .rst_n(run_rst_n), .valid(tx_valid), .ready(tx_ready), .data(tx_data), .tx(uart_tx));

  assign led_busy = !core_idle;
  assign led_error = crc_errors != 0 || framing_errors != 0 || overruns != 0;
endmodule
