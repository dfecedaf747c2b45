// The board top, generic over the core build: a DVS128-style AER receiver and the host link
// feed the core; the core's labelled events, track updates and packet summaries go back over
// the link. One UART (8N1, ClksPerBit clocks a bit) carries both directions (docs/link.md).
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
// its acknowledge); the link keeps at most LinkFifoDepth events in flight by protocol.
`include "evms_assert.svh"

module evms_board #(
  parameter int ClkHz          = 12000000,
  parameter int ClksPerBit     = 4,
  parameter int LinkFifoDepth  = 512,
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
  logic lk_valid, lk_ready, lk_p, lk_flush, soft_reset, rs_valid, rs_ready;
  logic [31:0] lk_t, crc_errors, overruns, events_received;
  logic [15:0] lk_x, lk_y, rs_seq;
  evms_link_rx #(.FifoDepth(LinkFifoDepth)) u_link_rx (
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
  logic lab_valid, lab_ready, lab_p, trk_valid, trk_ready, trk_confirmed, pkt_valid, pkt_ready, core_idle;
  logic [31:0] lab_t, lab_label, trk_t, trk_id, trk_x, trk_y, trk_vx, trk_vy, trk_zx, trk_zy, pkt_t_first, pkt_t_last;
  logic [15:0] lab_x, lab_y, pkt_events;
  logic [7:0] pkt_clusters;
  logic [15:0] pkt_iterations;
  // The link's packet frame carries 8 bits of iterations: more saturate at 255.
  wire [7:0] pkt_iterations_sent = pkt_iterations > 16'd255 ? 8'd255 : 8'(pkt_iterations);
  logic [31:0] tracks_started, unassigned;
  evms_core #(
    `include "evms_core_shape_connect.svh"
  ) u_core (
    .clk(clk), .rst_n(run_rst_n),
    `include "evms_board_cfg_connect.svh"
    .in_valid(in_valid), .in_ready(in_ready), .in_t(in_t), .in_x(in_x), .in_y(in_y), .in_p(in_p), .in_flush(in_flush),
    .lab_valid(lab_valid), .lab_ready(lab_ready), .lab_t(lab_t), .lab_x(lab_x), .lab_y(lab_y), .lab_p(lab_p),
    .lab_label(lab_label), .trk_valid(trk_valid), .trk_ready(trk_ready), .trk_t(trk_t), .trk_id(trk_id), .trk_x(trk_x),
    .trk_y(trk_y), .trk_vx(trk_vx), .trk_vy(trk_vy), .trk_zx(trk_zx), .trk_zy(trk_zy), .trk_confirmed(trk_confirmed),
    .pkt_valid(pkt_valid),
    .pkt_ready(pkt_ready), .pkt_t_first(pkt_t_first), .pkt_t_last(pkt_t_last), .pkt_events(pkt_events),
    .pkt_clusters(pkt_clusters), .pkt_iterations(pkt_iterations), .idle(core_idle),
    .stat_tracks_started(tracks_started), .stat_unassigned(unassigned));

  // The board runs its build's registers, whose tracker reports confirmed tracks only, so the
  // link's track frame has no state field.
  `EVMS_ASSERT("a board reports confirmed tracks only", !(trk_valid && !trk_confirmed), clk, run_rst_n)

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
    .pkt_ready(pkt_ready), .pkt_payload({pkt_iterations_sent, pkt_clusters, pkt_events, pkt_t_last, pkt_t_first}),
    .st_valid(st_valid), .st_ready(st_ready), .rs_valid(rs_valid), .rs_ready(rs_ready), .rs_seq(rs_seq),
    .st_payload({unassigned, tracks_started, external_events, overruns, framing_errors, crc_errors, events_received, timestamp}),
    .byte_valid(tx_valid), .byte_ready(tx_ready), .byte_data(tx_data));
  evms_uart_tx #(.ClksPerBit(ClksPerBit)) u_uart_tx (
    .clk(clk), .rst_n(run_rst_n), .valid(tx_valid), .ready(tx_ready), .data(tx_data), .tx(uart_tx));

  assign led_busy = !core_idle;
  assign led_error = crc_errors != 0 || framing_errors != 0 || overruns != 0;
endmodule
