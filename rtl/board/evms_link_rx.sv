// Host-to-board half of the serial link (docs/link.md): frames
//   0xA5 0x5A TYPE LEN PAYLOAD[LEN] CRC16_LO CRC16_HI
// with CRC-16/CCITT-FALSE over TYPE, LEN and PAYLOAD. TYPE 0x01 carries 1 to BatchEntries events
// (the first one's time u32 and number u16, then an entry of a u32 each: x, y, polarity,
// present, and the microseconds since the previous event; host/link/link_frames.h), 0x02 is a
// flush (seq u16 of the event after the last), 0x03 a reset (mode u8): it empties the FIFO at
// once and pulses soft_reset, with which the board restarts everything behind the link, and sets
// the run's mode: labels_on_board keeps the labels on the board (mode 1) instead of sending one
// for each (mode 0). A frame with a bad check, type or length is dropped and counted, and the
// parser hunts for the next 0xA5 0x5A.
//
// Events are taken in sequence only, so that the core sees exactly the host's stream however
// the line corrupts it (go-back-N): the event numbered expected_seq goes into a FIFO of
// FifoDepth words for the core, an older number is a resent copy and is dropped, and a newer
// one means frames were lost: it is dropped and a resend of expected_seq is asked for once
// (resend_valid, until the link's transmitter takes it), not again until an event is taken or
// the host is seen to have started over: an events frame ahead whose first number is not after
// the previous ahead frame's (last_ahead_seq) is a resend whose first frame the line destroyed,
// and waiting for the host's silence timer would cost it 500 ms.
// A flush whose number is not expected_seq asks again: events before it are missing. The host
// keeps at most FifoDepth events in flight, so the FIFO does not overrun; if it does anyway,
// the word is counted and asked for again.
//
// An events frame's entries go into the FIFO as they arrive, held back from the core until the
// frame's check passes (evms_fifo's Tentative writes) and forgotten if it fails, so no frame is
// buffered whole.
`include "evms_assert.svh"

module evms_link_rx #(
  parameter int FifoDepth = 512
) (
  input  logic        clk,
  input  logic        rst_n,
  input  logic        byte_valid,
  input  logic [7:0]  byte_data,
  output logic        ev_valid,
  input  logic        ev_ready,
  output logic [31:0] ev_t,
  output logic [15:0] ev_x,
  output logic [15:0] ev_y,
  output logic        ev_p,
  output logic        ev_flush,
  output logic        soft_reset,
  output logic        labels_on_board,
  // A resend frame asking for the events from resend_seq on.
  output logic        resend_valid,
  input  logic        resend_ready,
  output logic [15:0] resend_seq,
  output logic [31:0] crc_errors,
  output logic [31:0] overruns,
  output logic [31:0] events_received
);
  `include "evms_link_frames.svh"
  typedef enum logic [2:0] {StSync1, StSync2, StType, StLen, StPayload, StCrcLo, StCrcHi} state_e;
  state_e state_q, state_d;
  logic [7:0] ftype_q, ftype_d, flen_q, flen_d, pos_q, pos_d;   // the frame's type, length, and payload byte
  // An events frame's first bytes, or a flush's or reset's payload: byte k in bits 8k + 7..8k.
  logic [8*BatchHeaderBytes-1:0] header_q, header_d;
  logic [23:0] entry_low_q, entry_low_d;   // an entry's bytes before its last
  logic [15:0] crc_q, crc_d;
  logic [7:0] crc_lo_q, crc_lo_d;
  logic [15:0] expected_seq_q, expected_seq_d;
  logic resend_asked_q, resend_asked_d;  // since the last event taken
  logic [15:0] last_ahead_seq_q, last_ahead_seq_d;  // since then: the first number of the last frame ahead, or the flush's
  logic [31:0] crc_errors_q, crc_errors_d, overruns_q, overruns_d, events_received_q, events_received_d;
  logic soft_reset_q, soft_reset_d, labels_on_board_q, labels_on_board_d, resend_valid_q, resend_valid_d;
  assign resend_seq = expected_seq_q;
  assign {crc_errors, overruns, events_received} = {crc_errors_q, overruns_q, events_received_q};
  assign {soft_reset, labels_on_board, resend_valid} = {soft_reset_q, labels_on_board_q, resend_valid_q};

  // Within an events frame, until its check: the next entry's number and time base, the number
  // expected after the entries taken, how many were taken, and whether one came ahead of the
  // expected number (frames were lost) or found the FIFO full.
  logic [15:0] entry_seq_q, entry_seq_d, frame_expected_q, frame_expected_d;
  logic [31:0] entry_t_q, entry_t_d;
  logic [7:0] frame_taken_q, frame_taken_d;
  logic frame_ahead_q, frame_ahead_d, frame_overrun_q, frame_overrun_d;

  // The header's length and the events frame's lengths: one to BatchEntries whole entries.
  logic len_is_events;
  assign len_is_events = byte_data >= 8'(BatchHeaderBytes + BatchEntryBytes) && byte_data <= FrameEventsLen &&
                         ((byte_data - 8'(BatchHeaderBytes)) & 8'(BatchEntryBytes - 1)) == 8'd0;
  `EVMS_ASSERT_INIT("an events entry's length is a power of two", (BatchEntryBytes & (BatchEntryBytes - 1)) == 0)
  // This payload byte ends an entry; the entry, and its event's time.
  logic entry_ends;
  logic [31:0] entry, entry_event_t;
  assign entry_ends = ftype_q == FrameEventsType && pos_q >= 8'(BatchHeaderBytes) &&
                      ((pos_q - 8'(BatchHeaderBytes)) & 8'(BatchEntryBytes - 1)) == 8'(BatchEntryBytes - 1);
  assign entry = {byte_data, entry_low_q};  // bits 17 and 18 (passed, present) say nothing here
  assign entry_event_t = entry_t_q + 32'(entry[31:32-BatchGapBits]);
  logic [15:0] entry_ahead;  // as a signed number: > 0 means frames were lost
  assign entry_ahead = entry_seq_q - frame_expected_q;

  // The frame that ends with this byte: its check, and a flush's number against expected_seq_q.
  logic crc_ok, is_events, is_flush, is_reset;
  logic [15:0] flush_ahead, frame_first_seq, since_last_ahead;
  logic frame_started_over;
  assign frame_first_seq = header_q[47:32];
  assign since_last_ahead = frame_first_seq - last_ahead_seq_q;
  assign frame_started_over = since_last_ahead == 16'd0 || since_last_ahead[15];
  assign crc_ok = {byte_data, crc_lo_q} == crc_q;
  assign is_events = crc_ok && ftype_q == FrameEventsType;
  assign is_flush = crc_ok && ftype_q == FrameFlushType && flen_q == FrameFlushLen;
  assign is_reset = crc_ok && ftype_q == FrameResetType && flen_q == FrameResetLen;
  assign flush_ahead = header_q[15:0] - expected_seq_q;

  // FIFO of {flush, p, y, x, t}, in block RAM; events frames' words held until their check. No
  // output buffer: the core's ready is a short path, and the buffer would be 132 flip-flops.
  localparam int WordBits = 1 + 1 + 16 + 16 + 32;
  logic push_q, push_d, commit_q, commit_d, rollback_q, rollback_d, fifo_ready;
  logic [WordBits-1:0] push_word_q, push_word_d;
  evms_fifo #(.Width(WordBits), .Depth(FifoDepth), .Tentative(1), .OutputBuffer(0)) u_fifo (
    .clk(clk), .rst_n(rst_n && !soft_reset_q), .in_valid(push_q), .in_ready(fifo_ready), .in_data(push_word_q), .in_commit(commit_q),
    .in_rollback(rollback_q), .out_valid(ev_valid), .out_ready(ev_ready), .out_data({ev_flush, ev_p, ev_y, ev_x, ev_t}));

  always_comb begin
    {state_d, ftype_d, flen_d, pos_d, header_d, entry_low_d, crc_d, crc_lo_d} = {state_q, ftype_q, flen_q, pos_q, header_q, entry_low_q, crc_q, crc_lo_q};
    {expected_seq_d, resend_asked_d, last_ahead_seq_d} = {expected_seq_q, resend_asked_q, last_ahead_seq_q};
    {crc_errors_d, overruns_d, events_received_d} = {crc_errors_q, overruns_q, events_received_q};
    {labels_on_board_d, push_word_d} = {labels_on_board_q, push_word_q};
    {entry_seq_d, frame_expected_d, entry_t_d, frame_taken_d, frame_ahead_d, frame_overrun_d} =
        {entry_seq_q, frame_expected_q, entry_t_q, frame_taken_q, frame_ahead_q, frame_overrun_q};
    {push_d, commit_d, rollback_d, soft_reset_d} = '0;
    resend_valid_d = resend_valid_q && !resend_ready;
    if (byte_valid) begin
      case (state_q)
        StSync1: if (byte_data == 8'hA5) state_d = StSync2;
        StSync2: state_d = byte_data == 8'h5A ? StType : (byte_data == 8'hA5 ? StSync2 : StSync1);
        StType: begin
          ftype_d = byte_data;
          crc_d = evms_crc16_pkg::crc16_byte(16'hFFFF, byte_data);
          frame_expected_d = expected_seq_q;
          frame_taken_d = '0;
          frame_ahead_d = 1'b0;
          frame_overrun_d = 1'b0;
          state_d = StLen;
        end
        StLen: begin
          flen_d = byte_data;
          crc_d = evms_crc16_pkg::crc16_byte(crc_q, byte_data);
          pos_d = '0;
          // An events frame's length must be whole entries before any goes in; other lengths
          // are checked with the frame. No frame of ours is longer than an events frame.
          if (ftype_q == FrameEventsType ? !len_is_events : byte_data > FrameEventsLen) begin
            crc_errors_d = crc_errors_q + 1'b1;
            state_d = StSync1;
          end else begin
            state_d = byte_data == 0 ? StCrcLo : StPayload;
          end
        end
        StPayload: begin
          for (int k = 0; k < BatchHeaderBytes; k++) if (pos_q == 8'(k)) header_d[8*k +: 8] = byte_data;
          // The header's last bytes: the first event's time, then its number.
          if (pos_q == 8'd3) entry_t_d = {byte_data, header_q[23:0]};
          if (pos_q == 8'd5) entry_seq_d = {byte_data, header_q[39:32]};
          entry_low_d = {byte_data, entry_low_q[23:8]};
          if (entry_ends) begin
            entry_t_d = entry_event_t;
            entry_seq_d = entry_seq_q + 1'b1;
            if (entry_ahead == 16'd0 && fifo_ready && !frame_overrun_q) begin
              push_d = 1'b1;
              push_word_d = {1'b0, entry[16], 8'd0, entry[15:8], 8'd0, entry[7:0], entry_event_t};
              frame_expected_d = frame_expected_q + 1'b1;
              frame_taken_d = frame_taken_q + 1'b1;
            end else if (entry_ahead == 16'd0) begin
              frame_overrun_d = 1'b1;
            end else if (!entry_ahead[15]) begin
              frame_ahead_d = 1'b1;
            end
          end
          crc_d = evms_crc16_pkg::crc16_byte(crc_q, byte_data);
          pos_d = pos_q + 1'b1;
          if (pos_q + 1'b1 == flen_q) state_d = StCrcLo;
        end
        StCrcLo: begin
          crc_lo_d = byte_data;
          state_d = StCrcHi;
        end
        StCrcHi: begin
          if (is_events) begin
            commit_d = 1'b1;
            expected_seq_d = frame_expected_q;
            events_received_d = events_received_q + 32'(frame_taken_q);
            if (frame_taken_q != 0) resend_asked_d = 1'b0;
            if (frame_overrun_q) begin
              overruns_d = overruns_q + 1'b1;
              resend_valid_d = 1'b1;
              resend_asked_d = 1'b1;
            end else if (frame_ahead_q && (!resend_asked_q || frame_started_over)) begin  // entries are consecutive: none was taken
              resend_valid_d = 1'b1;
              resend_asked_d = 1'b1;
            end
            if (frame_overrun_q || frame_ahead_q) last_ahead_seq_d = frame_first_seq;
          end else if (is_flush && flush_ahead == 16'd0 && fifo_ready) begin
            push_d = 1'b1;
            commit_d = 1'b1;
            push_word_d = {1'b1, 1'b0, 16'd0, 16'd0, 32'd0};
          end else if (is_flush && flush_ahead == 16'd0) begin
            overruns_d = overruns_q + 1'b1;
            resend_valid_d = 1'b1;
            resend_asked_d = 1'b1;
          end else if (is_flush) begin
            resend_valid_d = 1'b1;
            resend_asked_d = 1'b1;
            last_ahead_seq_d = header_q[15:0];
          end else if (is_reset) begin
            soft_reset_d = 1'b1;
            labels_on_board_d = header_q[0];
            expected_seq_d = '0;
            resend_asked_d = 1'b0;
            resend_valid_d = 1'b0;
          end else begin
            rollback_d = ftype_q == FrameEventsType;
            crc_errors_d = crc_errors_q + 1'b1;
          end
          state_d = StSync1;
        end
        default: state_d = StSync1;
      endcase
    end
  end

  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      {state_q, ftype_q, flen_q, pos_q, header_q, entry_low_q, crc_lo_q} <= '0;
      crc_q <= 16'hFFFF;
      {expected_seq_q, resend_asked_q, last_ahead_seq_q} <= '0;
      {crc_errors_q, overruns_q, events_received_q} <= '0;
      {labels_on_board_q, push_word_q} <= '0;
      {entry_seq_q, frame_expected_q, entry_t_q, frame_taken_q, frame_ahead_q, frame_overrun_q} <= '0;
      {push_q, commit_q, rollback_q, soft_reset_q, resend_valid_q} <= '0;
    end else begin
      {state_q, ftype_q, flen_q, pos_q, header_q, entry_low_q, crc_q, crc_lo_q} <= {state_d, ftype_d, flen_d, pos_d, header_d, entry_low_d, crc_d, crc_lo_d};
      {expected_seq_q, resend_asked_q, last_ahead_seq_q} <= {expected_seq_d, resend_asked_d, last_ahead_seq_d};
      {crc_errors_q, overruns_q, events_received_q} <= {crc_errors_d, overruns_d, events_received_d};
      {labels_on_board_q, push_word_q} <= {labels_on_board_d, push_word_d};
      {entry_seq_q, frame_expected_q, entry_t_q, frame_taken_q, frame_ahead_q, frame_overrun_q} <=
          {entry_seq_d, frame_expected_d, entry_t_d, frame_taken_d, frame_ahead_d, frame_overrun_d};
      {push_q, commit_q, rollback_q, soft_reset_q, resend_valid_q} <= {push_d, commit_d, rollback_d, soft_reset_d, resend_valid_d};
    end
  end
endmodule
