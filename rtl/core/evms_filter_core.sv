// The core cut after its filter (hls/core/filter_core.h): every event leaves labelled noise
// (-1) or passed (hls::kLabelPassedFilter, -3), in input order, and nothing else does. A board
// whose core does not fit its device can run this in evms_core's place (CoreCut 1 in
// rtl/board/evms_board.sv); the host clusters and tracks the verdicts it returns
// (host/backend/board_backend.cpp). It is the intake of evms_core (core/evms_intake.sv)
// without the climb features, so its verdicts are the whole core's.
module evms_filter_core #(
  parameter int MaxWidth       = 128,
  parameter int MaxHeight      = 128,
  parameter int TimestampBits  = 16,
  parameter int TimestampShift = 7,
  parameter int NoiseIntervalLog2 = 15,
  parameter int QueueDepth     = 4     // decided words that wait for the label stream
) (
  input  logic        clk,
  input  logic        rst_n,
  // The filter's registers (hls/core/registers.h).
  `include "evms_filter_cfg_ports.svh"
  // Words in.
  `include "evms_stream_in_sink_ports.svh"
  // Labelled events out, in input order.
  `include "evms_stream_lab_source_ports.svh"
  output logic        idle        // ready (the filter's memory cleared) and no word held
);
  `include "evms_core_labels.svh"

  logic q_valid, q_pop, q_flush, q_kept, intake_empty;
  logic [31:0] unused_climb_x, unused_climb_y;
  evms_intake #(
    .MaxWidth(MaxWidth), .MaxHeight(MaxHeight), .TimestampBits(TimestampBits), .TimestampShift(TimestampShift),
    .NoiseIntervalLog2(NoiseIntervalLog2), .QueueDepth(QueueDepth), .HasClimbScale(0)
  ) u_intake (
    .clk(clk), .rst_n(rst_n),
    `include "evms_filter_cfg_connect.svh"
    .cfg_climb_scale_x(64'd0), .cfg_climb_scale_y(64'd0),
    `include "evms_stream_in_connect.svh"
    .q_valid(q_valid), .q_pop(q_pop), .q_t(lab_t), .q_x(lab_x), .q_y(lab_y), .q_p(lab_p),
    .q_flush(q_flush), .q_kept(q_kept), .q_climb_x(unused_climb_x), .q_climb_y(unused_climb_y), .empty(intake_empty));

  // A flush word has nothing to release here: it leaves the queue unseen.
  assign lab_valid = q_valid && !q_flush;
  assign q_pop = q_valid && (q_flush || lab_ready);
  assign lab_label = q_kept ? LabelPassedFilter : LabelNoise;
  assign idle = intake_empty && in_ready;
endmodule
