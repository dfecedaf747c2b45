// The core cut after its seeded climbs (hls::Core::process_to_climbs, hls/core/core.h), for a
// part that holds the filter and the mean shift but not the rest of the core, such as the iCE40
// UP5K. It returns two streams, each in order:
//  - every event's verdict (noise, -1, or passed the filter, -3: hls/core/filter_core.h), at
//    once, from the intake (core/evms_intake.sv) with the climb features;
//  - for each packet that holds events, its climbs frame (hls::ClimbsFrame): a head word, a word
//    a mode, a word an event of the packet.
// A packet opens, fills and closes by hls::Core's rules (its size, its span, a full pending queue
// of PendingDepth words, a flush word); the pending words are the host's to keep, so only their
// count is here. Closing runs cluster/evms_serial_climbs.sv on the packet's features and sends
// the frame; the next word waits in the intake meanwhile, decided. The host completes each packet from its
// frame (hls::Core::process_climbed), which gives the whole core's words when warm seeds are off,
// as the serial climbs have none (the host tests the least density on the frame's supports).
// The iCEBreaker's board runs it (CoreCut 1 in rtl/board/evms_board.sv).
`include "evms_assert.svh"

module evms_climbs_core #(
  parameter int MaxWidth       = 128,
  parameter int MaxHeight      = 128,
  parameter int TimestampBits  = 16,
  parameter int TimestampShift = 7,
  parameter int NoiseIntervalLog2 = 15,
  parameter int QueueDepth     = 1,     // decided words that wait while a packet is closed (core/evms_intake.sv)
  parameter int PacketMax      = 1024,  // kPacketMax
  parameter int PendingDepth   = 4096,  // kPendingDepth: words, kept or not, that close a packet
  parameter int ModesMax       = 64,
  parameter int IterationsMax  = 8,
  parameter int UnitShift      = 14,    // kFeatFrac + kClimbFrac
  parameter int CoordBits      = 19,    // a climb feature's bits: below 2^(CoordBits - UnitShift) bandwidths
  parameter int Bands          = 32     // kGridSide
) (
  input  logic        clk,
  input  logic        rst_n,
  // The registers a core cut after its climbs reads (hls/core/registers.h).
  `include "evms_climbs_cfg_ports.svh"
  // Words in.
  `include "evms_stream_in_sink_ports.svh"
  // Each event's verdict, in input order.
  `include "evms_stream_lab_source_ports.svh"
  // Each packet's climbs frame, in packet order: ClimbsHead {n, modes, steps, climbs, modes lost};
  // ClimbsMode {x, y (32 bits each), support (16)} a mode; ClimbsEvent {mode (16, -1: none)} an
  // event of the packet, in packet order. Fields from the top bit; the rest is zero.
  output logic        clm_valid,
  input  logic        clm_ready,
  output logic [1:0]  clm_kind,
  output logic [79:0] clm_data,
  output logic        idle        // ready (the filter's memory cleared), no word held, no packet closing
);
  `include "evms_core_labels.svh"
  localparam logic [1:0] ClimbsHead = 2'd0, ClimbsMode = 2'd1, ClimbsEvent = 2'd2;
  localparam int CntBits = $clog2(PacketMax + 1);
  localparam int PendBits = $clog2(PendingDepth + 1);

  // ---- the intake: the filter's verdicts and the climb features --------------------------------
  logic        q_valid, q_pop, q_flush, q_kept, intake_empty;
  logic [31:0] q_t, q_climb_x, q_climb_y;
  logic [15:0] q_x, q_y;
  logic        q_p;
  evms_intake #(
    .MaxWidth(MaxWidth), .MaxHeight(MaxHeight), .TimestampBits(TimestampBits), .TimestampShift(TimestampShift),
    .NoiseIntervalLog2(NoiseIntervalLog2), .QueueDepth(QueueDepth), .HasClimbScale(1), .ClimbShift(40 - UnitShift)
  ) u_intake (
    .clk(clk), .rst_n(rst_n),
    `include "evms_filter_cfg_connect.svh"
    .cfg_climb_scale_x(cfg_climb_scale_x), .cfg_climb_scale_y(cfg_climb_scale_y),
    `include "evms_stream_in_connect.svh"
    .q_valid(q_valid), .q_pop(q_pop), .q_t(q_t), .q_x(q_x), .q_y(q_y), .q_p(q_p),
    .q_flush(q_flush), .q_kept(q_kept), .q_climb_x(q_climb_x), .q_climb_y(q_climb_y), .empty(intake_empty));

  // ---- the controller ---------------------------------------------------------------------------
  // StTake: the head word's verdict goes out and the word is planned; a packet closes before it
  // (StStart ...) or it joins the pending count and the packet (StAdd) and the packet closes
  // after it. Closing: StStart, StRun (the climbs), StHead, StModes, StEvents. An event word
  // leaves the intake in StAdd, not before: until then its time and features are read at
  // the intake's head, with no copy here. A flush word leaves as it is taken.
  typedef enum logic [2:0] {StTake, StAdd, StStart, StRun, StHead, StModes, StEvents} state_e;
  state_e state_d, state_q;

  logic [CntBits-1:0]  n_d, n_q;                 // events in the open packet
  logic [PendBits-1:0] pending_d, pending_q;     // words since the last close (the host holds them)
  logic [31:0]         t_first_d, t_first_q;     // the open packet's first event's time
  // The taken word (every word but a flush joins the pending count): whether it joins the
  // packet, and whether the packet closes after it.
  logic                into_packet_d, into_packet_q, close_after_d, close_after_q;
  logic                resume_add_d, resume_add_q;   // after the close: add the taken word
  logic [15:0]         index_d, index_q;         // the mode or event being sent
  logic                read_ok_d, read_ok_q;     // the climbs' readout holds index_q's word

  // The climbs.
  logic        climbs_start, climbs_done, load_we;
  logic [15:0] mode_count, climbs, steps, modes_lost, rd_support;
  logic signed [15:0] rd_mode;
  logic [CoordBits-1:0] rd_mode_x, rd_mode_y;
  evms_serial_climbs #(.PacketMax(PacketMax), .ModesMax(ModesMax), .IterationsMax(IterationsMax), .UnitShift(UnitShift),
                       .CoordBits(CoordBits), .Bands(Bands)) u_climbs (
    .clk, .rst_n, .load_we, .load_i(16'(n_q)), .load_x(q_climb_x[CoordBits-1:0]), .load_y(q_climb_y[CoordBits-1:0]),
    .start(climbs_start), .n(16'(n_q)), .cfg_max_iterations, .cfg_tolerance, .cfg_merge_radius2, .done(climbs_done),
    .mode_count, .climbs, .steps, .modes_lost, .rd_j(index_q), .rd_mode, .rd_c(8'(index_q)), .rd_mode_x, .rd_mode_y, .rd_support);

  // The word at the intake's head, planned as hls::Core::plan_word.
  wire take = state_q == StTake && q_valid && (q_flush || lab_ready);
  // The head word lies beyond the span of a packet of n events that began at t_first_q.
  function automatic logic beyond_span(input logic [CntBits-1:0] n);
    beyond_span = n != '0 && cfg_packet_max_span_us != '0 && q_t - t_first_q > cfg_packet_max_span_us;
  endfunction
  wire span_exceeded_now = beyond_span(n_q);
  logic span_exceeded;
  if (QueueDepth == 1) begin : g_span_registered
    // The head word's time is loaded at least two clocks before the word is valid (core/
    // evms_intake.sv). The open packet's count changes as a word joins it or the packet closes,
    // and its first time as its first event joins, clocks before the next head is valid. So the
    // test of the next count (n_d) and this first time, a clock ahead, is the head's whenever the
    // head is valid, and the plan's path starts at a register, not at a subtraction.
    logic span_exceeded_q;
    always_ff @(posedge clk or negedge rst_n) begin
      if (!rst_n) span_exceeded_q <= 1'b0;
      else span_exceeded_q <= beyond_span(n_d);
    end
    assign span_exceeded = span_exceeded_q;
    `EVMS_ASSERT("the registered span test is the head word's", !q_valid || span_exceeded_q == span_exceeded_now, clk, rst_n)
  end else begin : g_span_now
    assign span_exceeded = span_exceeded_now;
  end
  wire close_before = q_flush || (q_kept && span_exceeded);
  // Counts after the close before the word, if any.
  wire [CntBits-1:0]  n_base = close_before ? '0 : n_q;
  wire [PendBits-1:0] pending_base = close_before ? '0 : pending_q;
  wire [CntBits:0]    n_after = {1'b0, n_base} + 1'b1;
  wire [PendBits:0]   pending_after = {1'b0, pending_base} + 1'b1;
  wire close_after_kept = 32'(n_after) >= 32'(cfg_packet_size) || 32'(n_after) >= PacketMax || 32'(pending_after) == PendingDepth;
  wire close_after_noise = n_q == '0 || 32'(pending_after) == PendingDepth;

  assign q_pop = (take && q_flush) || state_q == StAdd;
  assign lab_valid = state_q == StTake && q_valid && !q_flush;
  assign {lab_t, lab_x, lab_y, lab_p} = {q_t, q_x, q_y, q_p};
  assign lab_label = q_kept ? LabelPassedFilter : LabelNoise;

  assign load_we = state_q == StAdd && into_packet_q;
  assign climbs_start = state_q == StStart;

  always_comb begin
    state_d = state_q;
    n_d = n_q;
    pending_d = pending_q;
    t_first_d = t_first_q;
    into_packet_d = into_packet_q;
    close_after_d = close_after_q;
    resume_add_d = resume_add_q;
    index_d = index_q;
    read_ok_d = 1'b0;
    clm_valid = 1'b0;
    clm_kind = ClimbsHead;
    clm_data = '0;
    unique case (state_q)
      StTake: if (take) begin
        into_packet_d = q_kept && !q_flush;
        close_after_d = q_flush ? 1'b0 : (q_kept ? close_after_kept : close_after_noise);
        resume_add_d = !q_flush;
        if (close_before && n_q != '0) state_d = StStart;
        else if (q_flush) pending_d = '0;
        else state_d = StAdd;
      end
      // The word joins the pending count (and, when kept, the packet; its features were written
      // this clock); the packet closes after it, or the next word is taken.
      StAdd: begin
        if (into_packet_q) begin
          if (n_q == '0) t_first_d = q_t;
          n_d = n_q + 1'b1;
        end
        pending_d = pending_q + 1'b1;
        resume_add_d = 1'b0;
        state_d = StTake;
        if (close_after_q) begin
          if (n_q != '0 || into_packet_q) state_d = StStart;
          else pending_d = '0;
        end
      end
      StStart: state_d = StRun;
      StRun: if (climbs_done) state_d = StHead;
      StHead: begin
        clm_valid = 1'b1;
        clm_kind = ClimbsHead;
        clm_data = {16'(n_q), mode_count, steps, climbs, modes_lost};
        if (clm_ready) begin
          index_d = '0;
          state_d = mode_count != '0 ? StModes : StEvents;
        end
      end
      // Each word is read from the climbs the clock its index is set (read_ok_q the clock after):
      // the modes' words, then the events'.
      StModes, StEvents: begin
        read_ok_d = 1'b1;
        clm_valid = read_ok_q;
        clm_kind = state_q == StModes ? ClimbsMode : ClimbsEvent;
        clm_data = state_q == StModes ? {32'(rd_mode_x), 32'(rd_mode_y), rd_support} : {rd_mode, 64'd0};
        if (read_ok_q && clm_ready) begin
          read_ok_d = 1'b0;
          index_d = index_q + 1'b1;
          if (state_q == StModes && index_q + 1'b1 == mode_count) begin
            index_d = '0;
            state_d = StEvents;
          end else if (state_q == StEvents && 32'(index_q) + 1 == 32'(n_q)) begin
            // The packet is closed: the taken word joins the next one (a span's close), or not.
            n_d = '0;
            pending_d = '0;
            state_d = resume_add_q ? StAdd : StTake;
          end
        end
      end
      default: state_d = StTake;
    endcase
  end

  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      state_q <= StTake;
      n_q <= '0;
      pending_q <= '0;
      t_first_q <= '0;
      {into_packet_q, close_after_q, resume_add_q, read_ok_q} <= '0;
      index_q <= '0;
    end else begin
      state_q <= state_d;
      n_q <= n_d;
      pending_q <= pending_d;
      t_first_q <= t_first_d;
      {into_packet_q, close_after_q, resume_add_q, read_ok_q} <= {into_packet_d, close_after_d, resume_add_d, read_ok_d};
      index_q <= index_d;
    end
  end

  assign idle = intake_empty && in_ready && state_q == StTake;

  `EVMS_ASSERT("a kept event's climb features fit CoordBits",
               !(load_we && ((q_climb_x >> CoordBits) != '0 || (q_climb_y >> CoordBits) != '0)), clk, rst_n)
  `EVMS_ASSERT("a closed packet holds events", !(climbs_start && n_q == '0), clk, rst_n)
endmodule
