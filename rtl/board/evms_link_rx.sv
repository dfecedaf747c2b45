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
  typedef enum logic [2:0] {S_SYNC1, S_SYNC2, S_TYPE, S_LEN, S_PAYLOAD, S_CRC_LO, S_CRC_HI} state_e;
  state_e state;
  logic [7:0] ftype, flen, pos;
  logic [7:0] header [BatchHeaderBytes];  // an events frame's first bytes; a flush's or reset's payload
  logic [23:0] entry_low;                 // an entry's bytes before its last
  logic [15:0] crc;
  logic [7:0] crc_lo;
  logic [15:0] expected_seq;
  logic resend_asked;  // since the last event taken
  logic [15:0] last_ahead_seq;  // since then: the first number of the last frame ahead, or the flush's
  assign resend_seq = expected_seq;

  // Within an events frame, until its check: the next entry's number and time base, the number
  // expected after the entries taken, how many were taken, and whether one came ahead of the
  // expected number (frames were lost) or found the FIFO full.
  logic [15:0] entry_seq, frame_expected;
  logic [31:0] entry_t;
  logic [7:0] frame_taken;
  logic frame_ahead, frame_overrun;

  // The header's length and the events frame's lengths: one to BatchEntries whole entries.
  logic len_is_events;
  assign len_is_events = byte_data >= 8'(BatchHeaderBytes + BatchEntryBytes) && byte_data <= FrameEventsLen &&
                         ((byte_data - 8'(BatchHeaderBytes)) & 8'(BatchEntryBytes - 1)) == 8'd0;
  `EVMS_ASSERT_INIT("an events entry's length is a power of two", (BatchEntryBytes & (BatchEntryBytes - 1)) == 0)
  // This payload byte ends an entry; the entry, and its event's time.
  logic entry_ends;
  logic [31:0] entry, entry_event_t;
  assign entry_ends = ftype == FrameEventsType && pos >= 8'(BatchHeaderBytes) &&
                      ((pos - 8'(BatchHeaderBytes)) & 8'(BatchEntryBytes - 1)) == 8'(BatchEntryBytes - 1);
  assign entry = {byte_data, entry_low};  // bits 17 and 18 (passed, present) say nothing here
  assign entry_event_t = entry_t + 32'(entry[31:32-BatchGapBits]);
  logic [15:0] entry_ahead;  // as a signed number: > 0 means frames were lost
  assign entry_ahead = entry_seq - frame_expected;

  // The frame that ends with this byte: its check, and a flush's number against expected_seq.
  logic crc_ok, is_events, is_flush, is_reset;
  logic [15:0] flush_ahead, frame_first_seq, since_last_ahead;
  logic frame_started_over;
  assign frame_first_seq = {header[5], header[4]};
  assign since_last_ahead = frame_first_seq - last_ahead_seq;
  assign frame_started_over = since_last_ahead == 16'd0 || since_last_ahead[15];
  assign crc_ok = {byte_data, crc_lo} == crc;
  assign is_events = crc_ok && ftype == FrameEventsType;
  assign is_flush = crc_ok && ftype == FrameFlushType && flen == FrameFlushLen;
  assign is_reset = crc_ok && ftype == FrameResetType && flen == FrameResetLen;
  assign flush_ahead = {header[1], header[0]} - expected_seq;

  // FIFO of {flush, p, y, x, t}, in block RAM; events frames' words held until their check.
  localparam int WordBits = 1 + 1 + 16 + 16 + 32;
  logic push, commit, rollback, fifo_ready;
  logic [WordBits-1:0] push_word;
  evms_fifo #(.Width(WordBits), .Depth(FifoDepth), .Tentative(1'b1)) u_fifo (
    .clk(clk), .rst_n(rst_n && !soft_reset), .in_valid(push), .in_ready(fifo_ready), .in_data(push_word), .in_commit(commit),
    .in_rollback(rollback), .out_valid(ev_valid), .out_ready(ev_ready), .out_data({ev_flush, ev_p, ev_y, ev_x, ev_t}));

  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      state <= S_SYNC1;
      ftype <= '0;
      flen <= '0;
      pos <= '0;
      crc <= 16'hFFFF;
      crc_lo <= '0;
      crc_errors <= '0;
      overruns <= '0;
      events_received <= '0;
      push <= 1'b0;
      commit <= 1'b0;
      rollback <= 1'b0;
      push_word <= '0;
      soft_reset <= 1'b0;
      labels_on_board <= 1'b0;
      expected_seq <= '0;
      resend_asked <= 1'b0;
      resend_valid <= 1'b0;
      last_ahead_seq <= '0;
      for (int k = 0; k < BatchHeaderBytes; k++) header[k] <= '0;
      entry_low <= '0;
      entry_seq <= '0;
      entry_t <= '0;
      frame_expected <= '0;
      frame_taken <= '0;
      frame_ahead <= 1'b0;
      frame_overrun <= 1'b0;
    end else begin
      push <= 1'b0;
      commit <= 1'b0;
      rollback <= 1'b0;
      soft_reset <= 1'b0;
      if (resend_valid && resend_ready) resend_valid <= 1'b0;
      if (byte_valid) begin
        case (state)
          S_SYNC1: if (byte_data == 8'hA5) state <= S_SYNC2;
          S_SYNC2: state <= byte_data == 8'h5A ? S_TYPE : (byte_data == 8'hA5 ? S_SYNC2 : S_SYNC1);
          S_TYPE: begin
            ftype <= byte_data;
            crc <= evms_crc16_pkg::crc16_byte(16'hFFFF, byte_data);
            frame_expected <= expected_seq;
            frame_taken <= '0;
            frame_ahead <= 1'b0;
            frame_overrun <= 1'b0;
            state <= S_LEN;
          end
          S_LEN: begin
            flen <= byte_data;
            crc <= evms_crc16_pkg::crc16_byte(crc, byte_data);
            pos <= '0;
            // An events frame's length must be whole entries before any goes in; other lengths
            // are checked with the frame. No frame of ours is longer than an events frame.
            if (ftype == FrameEventsType ? !len_is_events : byte_data > FrameEventsLen) begin
              crc_errors <= crc_errors + 1'b1;
              state <= S_SYNC1;
            end else begin
              state <= byte_data == 0 ? S_CRC_LO : S_PAYLOAD;
            end
          end
          S_PAYLOAD: begin
            if (pos < 8'(BatchHeaderBytes)) header[pos[$clog2(BatchHeaderBytes)-1:0]] <= byte_data;
            // The header's last bytes: the first event's time, then its number.
            if (pos == 8'd3) entry_t <= {byte_data, header[2], header[1], header[0]};
            if (pos == 8'd5) entry_seq <= {byte_data, header[4]};
            entry_low <= {byte_data, entry_low[23:8]};
            if (entry_ends) begin
              entry_t <= entry_event_t;
              entry_seq <= entry_seq + 1'b1;
              if (entry_ahead == 16'd0 && fifo_ready && !frame_overrun) begin
                push <= 1'b1;
                push_word <= {1'b0, entry[16], 8'd0, entry[15:8], 8'd0, entry[7:0], entry_event_t};
                frame_expected <= frame_expected + 1'b1;
                frame_taken <= frame_taken + 1'b1;
              end else if (entry_ahead == 16'd0) begin
                frame_overrun <= 1'b1;
              end else if (!entry_ahead[15]) begin
                frame_ahead <= 1'b1;
              end
            end
            crc <= evms_crc16_pkg::crc16_byte(crc, byte_data);
            pos <= pos + 1'b1;
            if (pos + 1'b1 == flen) state <= S_CRC_LO;
          end
          S_CRC_LO: begin
            crc_lo <= byte_data;
            state <= S_CRC_HI;
          end
          S_CRC_HI: begin
            if (is_events) begin
              commit <= 1'b1;
              expected_seq <= frame_expected;
              events_received <= events_received + 32'(frame_taken);
              if (frame_taken != 0) resend_asked <= 1'b0;
              if (frame_overrun) begin
                overruns <= overruns + 1'b1;
                resend_valid <= 1'b1;
                resend_asked <= 1'b1;
              end else if (frame_ahead && (!resend_asked || frame_started_over)) begin  // entries are consecutive: none was taken
                resend_valid <= 1'b1;
                resend_asked <= 1'b1;
              end
              if (frame_overrun || frame_ahead) last_ahead_seq <= frame_first_seq;
            end else if (is_flush && flush_ahead == 16'd0 && fifo_ready) begin
              push <= 1'b1;
              commit <= 1'b1;
              push_word <= {1'b1, 1'b0, 16'd0, 16'd0, 32'd0};
            end else if (is_flush && flush_ahead == 16'd0) begin
              overruns <= overruns + 1'b1;
              resend_valid <= 1'b1;
              resend_asked <= 1'b1;
            end else if (is_flush) begin
              resend_valid <= 1'b1;
              resend_asked <= 1'b1;
              last_ahead_seq <= {header[1], header[0]};
            end else if (is_reset) begin
              soft_reset <= 1'b1;
              labels_on_board <= header[0][0];
              expected_seq <= '0;
              resend_asked <= 1'b0;
              resend_valid <= 1'b0;
            end else begin
              rollback <= ftype == FrameEventsType;
              crc_errors <= crc_errors + 1'b1;
            end
            state <= S_SYNC1;
          end
          default: state <= S_SYNC1;
        endcase
      end
    end
  end
endmodule
