// Host-to-board half of the serial link (docs/link.md): frames
//   0xA5 0x5A TYPE LEN PAYLOAD[LEN] CRC16_LO CRC16_HI
// with CRC-16/CCITT-FALSE over TYPE, LEN and PAYLOAD. TYPE 0x01 is an event (t u32, x u16,
// y u16, p u8, seq u16, little-endian), 0x02 a flush (seq u16 of the event after the last),
// 0x03 a reset (mode u8): it empties the FIFO at once and pulses soft_reset, with which the
// board restarts everything behind the link, and sets the run's mode: labels_on_board keeps
// the labels on the board (mode 1) instead of sending one frame for each (mode 0). A frame with a bad check, type or length is dropped and
// counted, and the parser hunts for the next 0xA5 0x5A.
//
// Events are taken in sequence only, so that the core sees exactly the host's stream however
// the line corrupts it (go-back-N): the event numbered expected_seq goes into a FIFO of
// FifoDepth words for the core, an older number is a resent copy and is dropped, and a newer
// one means frames were lost: it is dropped and a resend of expected_seq is asked for once
// (resend_valid, until the link's transmitter takes it), not again until an event is taken.
// A flush whose number is not expected_seq asks again: events before it are missing. The host
// keeps at most FifoDepth events in flight, so the FIFO does not overrun; if it does anyway,
// the word is counted and asked for again.
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
  logic [7:0] payload [11];
  logic [15:0] crc;
  logic [7:0] crc_lo;
  logic [15:0] expected_seq;
  logic resend_asked;  // since the last event taken
  assign resend_seq = expected_seq;

  // The frame that ends with this byte: its check, and its number against expected_seq.
  logic crc_ok, is_event, is_flush, is_reset;
  logic [15:0] frame_seq, seq_ahead;
  assign crc_ok = {byte_data, crc_lo} == crc;
  assign is_event = crc_ok && ftype == FrameEventType && flen == FrameEventLen;
  assign is_flush = crc_ok && ftype == FrameFlushType && flen == FrameFlushLen;
  assign is_reset = crc_ok && ftype == FrameResetType && flen == FrameResetLen;
  assign frame_seq = is_event ? {payload[10], payload[9]} : {payload[1], payload[0]};
  assign seq_ahead = frame_seq - expected_seq;  // as a signed number: > 0 means frames were lost

  // FIFO of {flush, p, y, x, t}, in block RAM.
  localparam int WordBits = 1 + 1 + 16 + 16 + 32;
  logic push, fifo_ready;
  logic [WordBits-1:0] push_word;
  evms_fifo #(.Width(WordBits), .Depth(FifoDepth)) u_fifo (
    .clk(clk), .rst_n(rst_n && !soft_reset), .in_valid(push), .in_ready(fifo_ready), .in_data(push_word), .out_valid(ev_valid),
    .out_ready(ev_ready), .out_data({ev_flush, ev_p, ev_y, ev_x, ev_t}));

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
      push_word <= '0;
      soft_reset <= 1'b0;
      labels_on_board <= 1'b0;
      expected_seq <= '0;
      resend_asked <= 1'b0;
      resend_valid <= 1'b0;
      for (int k = 0; k < 11; k++) payload[k] <= '0;
    end else begin
      push <= 1'b0;
      soft_reset <= 1'b0;
      if (resend_valid && resend_ready) resend_valid <= 1'b0;
      if (byte_valid) begin
        case (state)
          S_SYNC1: if (byte_data == 8'hA5) state <= S_SYNC2;
          S_SYNC2: state <= byte_data == 8'h5A ? S_TYPE : (byte_data == 8'hA5 ? S_SYNC2 : S_SYNC1);
          S_TYPE: begin
            ftype <= byte_data;
            crc <= evms_crc16_pkg::crc16_byte(16'hFFFF, byte_data);
            state <= S_LEN;
          end
          S_LEN: begin
            flen <= byte_data;
            crc <= evms_crc16_pkg::crc16_byte(crc, byte_data);
            pos <= '0;
            if (byte_data > 8'd11) begin
              crc_errors <= crc_errors + 1'b1;  // no frame of ours is that long: resynchronize
              state <= S_SYNC1;
            end else begin
              state <= byte_data == 0 ? S_CRC_LO : S_PAYLOAD;
            end
          end
          S_PAYLOAD: begin
            payload[pos[3:0]] <= byte_data;
            crc <= evms_crc16_pkg::crc16_byte(crc, byte_data);
            pos <= pos + 1'b1;
            if (pos + 1'b1 == flen) state <= S_CRC_LO;
          end
          S_CRC_LO: begin
            crc_lo <= byte_data;
            state <= S_CRC_HI;
          end
          S_CRC_HI: begin
            if ((is_event || is_flush) && seq_ahead == 16'd0 && fifo_ready) begin
              push <= 1'b1;
              push_word <= is_flush ? {1'b1, 1'b0, 16'd0, 16'd0, 32'd0}
                                    : {1'b0, payload[8][0], {payload[7], payload[6]}, {payload[5], payload[4]},
                                       {payload[3], payload[2], payload[1], payload[0]}};
              if (is_event) begin
                expected_seq <= expected_seq + 1'b1;
                events_received <= events_received + 1'b1;
                resend_asked <= 1'b0;
              end
            end else if ((is_event || is_flush) && seq_ahead == 16'd0) begin
              overruns <= overruns + 1'b1;
              resend_valid <= 1'b1;
              resend_asked <= 1'b1;
            end else if (is_flush || (is_event && !seq_ahead[15] && !resend_asked)) begin
              resend_valid <= 1'b1;
              resend_asked <= 1'b1;
            end else if (is_reset) begin
              soft_reset <= 1'b1;
              labels_on_board <= payload[0][0];
              expected_seq <= '0;
              resend_asked <= 1'b0;
              resend_valid <= 1'b0;
            end else if (!is_event) begin
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
