// Board-to-host half of the serial link (docs/link.md): labelled events (0x81, or with
// LabelsAreVerdicts up to BatchEntries filter's verdicts in one 0x87), track updates (0x82), packet
// summaries (0x83, or with PacketsAreClimbs the words of climbs frames: 0x88 head, 0x89 mode,
// 0x8A up to BatchEntries events' modes), status (0x84), resend requests (0x85) and progress (0x86) as frames
//   0xA5 0x5A TYPE LEN PAYLOAD[LEN] CRC16_LO CRC16_HI
// (CRC-16/CCITT-FALSE over TYPE, LEN and PAYLOAD; little-endian fields). Streams are served
// one frame at a time, status first, then resend requests, packet summaries, track updates,
// labelled events, progress; a stream waits (its valid stays high) while the UART is busy. Label frames carry their number modulo 2^16, counted
// from reset, so that the host finds a label frame the line destroyed.
//
// A verdict frame is streamed: it opens with the first verdict, and as the UART takes the last
// byte of an entry, the next entry is the verdict then waiting, if one is and it is at most
// 2^BatchGapBits - 1 us after the previous one. Once none is, the frame's other entries go
// out absent (zeros). So a busy line carries BatchEntries verdicts a frame, and a verdict
// never waits for a frame to fill. A climbs events frame is streamed alike, an entry a byte: as
// the UART takes each byte, the next entry is the climbs event word then waiting, if one is.
`include "evms_assert.svh"

module evms_link_tx #(
  // 1: the labels are a filter's verdicts (-1 noise, anything else passed) on a sensor of
  // 256x256 at most, sent in verdict frames (4 bytes a verdict) instead of 21-byte label frames.
  parameter int LabelsAreVerdicts = 0,
  // 1: the packet port carries a core cut after its climbs' words (core/evms_climbs_core.sv):
  // {kind (2 bits), word (80)} in its low bits, a head or a mode sent as the kind's frame, the
  // word's bits 79-64 then 63-0, and the events' words streamed into climbs events frames, an
  // entry a byte: present (bit 7) and the event's mode in bits 6-0 (bits 70-64 of its word, which
  // hold it while the climbs open at most 64 modes).
  parameter int PacketsAreClimbs = 0
) (
  input  logic        clk,
  input  logic        rst_n,
  // Labelled events.
  `include "evms_stream_lab_sink_ports.svh"
  // Track updates.
  input  logic        trk_valid,
  output logic        trk_ready,
  input  logic [263:0] trk_payload,   // t, id, x, y, vx, vy, zx, zy (32 bits each, t lowest), state (8)
  // Packet summaries.
  input  logic        pkt_valid,
  output logic        pkt_ready,
  input  logic [95:0] pkt_payload,    // t_first, t_last, events (16), clusters (8), iterations (8); or a climbs word
  // Status.
  input  logic        st_valid,
  output logic        st_ready,
  input  logic [351:0] st_payload,    // eleven 32-bit counters
  // Progress: three 32-bit counters.
  input  logic        pg_valid,
  output logic        pg_ready,
  input  logic [95:0] pg_payload,
  // Resend requests: the number of the event the link's receiver expects.
  input  logic        rs_valid,
  output logic        rs_ready,
  input  logic [15:0] rs_seq,
  // Bytes to the UART.
  output logic        byte_valid,
  input  logic        byte_ready,
  output logic [7:0]  byte_data
);
  `include "evms_link_frames.svh"
  typedef enum logic [2:0] {StIdle, StSync1, StSync2, StType, StLen, StPayload, StCrcLo, StCrcHi} state_e;
  state_e state_q, state_d;
  // As long as the longest frame's, the status's; each frame's payload is zero-extended to it
  // by a sized literal (Yosys 0.23 sizes a width cast in a concatenation by its operand).
  localparam int PayloadBits = 352;
  logic [PayloadBits-1:0] payload_q, payload_d;   // the frame's payload, its next byte lowest
  logic [7:0] ftype_q, ftype_d, flen_q, flen_d, pos_q, pos_d;
  logic [15:0] crc_q, crc_d;
  logic [15:0] label_seq_q, label_seq_d;   // the next label's number
  // A verdict frame: still taking verdicts, and the previous one's time.
  logic verdicts_open_q, verdicts_open_d;
  logic [31:0] verdict_t_q, verdict_t_d;
  logic [31:0] verdict_gap;
  // Whether the verdict waiting is within reach of the previous one, judged a clock after it
  // came (its fields hold while it waits): the ready then reads registers, not a subtraction.
  logic gap_fits_q, gap_known_q;
  logic [7:0] next_pos;
  logic next_is_entry, take_verdict;
  assign verdict_gap = lab_t - verdict_t_q;
  // The UART takes the byte before an entry's first: the header's BatchHeaderBytes, then
  // entries of BatchEntryBytes (a power of two). It is registered: pos_q moves only as the UART
  // takes a byte, once in a character's 10 bits.
  localparam int EntryMask = BatchEntryBytes - 1;
  localparam int EntryPhase = BatchHeaderBytes % BatchEntryBytes;
  logic next_is_entry_q;
  assign next_pos = pos_q + 8'd1;
  assign next_is_entry = {24'd0, next_pos} >= BatchHeaderBytes + BatchEntryBytes && next_pos < flen_q &&
                         ({24'd0, next_pos} & EntryMask) == EntryPhase;
  assign take_verdict = LabelsAreVerdicts != 0 && state_q == StPayload && verdicts_open_q && byte_ready && next_is_entry_q && lab_valid &&
                        gap_known_q && gap_fits_q;
  `EVMS_ASSERT_INIT("a verdict entry's length is a power of two", (BatchEntryBytes & (BatchEntryBytes - 1)) == 0)
  // An entry's fields below its gap: present, passed, polarity, y, x.
  logic [31-BatchGapBits:0] verdict_fields;
  assign verdict_fields = {1'b1, lab_label != 32'hFFFF_FFFF, lab_p, lab_y[7:0], lab_x[7:0]};
  // A climbs events frame: still taking entries. The word waiting is an event's, and its entry.
  logic climbs_open_q, climbs_open_d;
  logic climbs_event_waiting, take_climbs_event;
  logic [7:0] climbs_entry;
  assign climbs_event_waiting = PacketsAreClimbs != 0 && pkt_valid && pkt_payload[81:80] == 2'd2;
  assign climbs_entry = {1'b1, pkt_payload[70:64]};
  assign take_climbs_event = state_q == StPayload && climbs_open_q && byte_ready && climbs_event_waiting && next_pos < flen_q;

  // A climbs word's frame type and length, by its kind (0 head, 1 mode, 2 event).
  function automatic logic [15:0] climbs_frame(input logic [1:0] kind);
    case (kind)
      2'd0: climbs_frame = {FrameClimbsHeadType, FrameClimbsHeadLen};
      2'd1: climbs_frame = {FrameClimbsModeType, FrameClimbsModeLen};
      default: climbs_frame = {FrameClimbsEventsType, FrameClimbsEventsLen};
    endcase
  endfunction

  always_comb begin
    lab_ready = 1'b0;
    trk_ready = 1'b0;
    pkt_ready = 1'b0;
    st_ready = 1'b0;
    rs_ready = 1'b0;
    pg_ready = 1'b0;
    if (state_q == StIdle) begin
      if (st_valid) st_ready = 1'b1;
      else if (rs_valid) rs_ready = 1'b1;
      else if (pkt_valid) pkt_ready = 1'b1;
      else if (trk_valid) trk_ready = 1'b1;
      else if (lab_valid) lab_ready = 1'b1;
      else if (pg_valid) pg_ready = 1'b1;
    end
    if (take_verdict) lab_ready = 1'b1;
    if (take_climbs_event) pkt_ready = 1'b1;
  end

  always_comb begin
    byte_data = 8'h00;
    case (state_q)
      StSync1: byte_data = 8'hA5;
      StSync2: byte_data = 8'h5A;
      StType: byte_data = ftype_q;
      StLen: byte_data = flen_q;
      StPayload: byte_data = payload_q[7:0];
      StCrcLo: byte_data = crc_q[7:0];
      StCrcHi: byte_data = crc_q[15:8];
      default: byte_data = 8'h00;
    endcase
  end
  assign byte_valid = state_q != StIdle;

  always_comb begin
    {state_d, payload_d, ftype_d, flen_d, pos_d, crc_d} = {state_q, payload_q, ftype_q, flen_q, pos_q, crc_q};
    {label_seq_d, verdicts_open_d, verdict_t_d, climbs_open_d} = {label_seq_q, verdicts_open_q, verdict_t_q, climbs_open_q};
    case (state_q)
      StIdle: begin
        verdicts_open_d = 1'b0;  // open only in a verdict frame, from its start
        climbs_open_d = 1'b0;    // ... and in a climbs events frame
        if (st_valid) begin
          {ftype_d, flen_d, payload_d} = {FrameStatusType, FrameStatusLen, st_payload};
          state_d = StSync1;
        end else if (rs_valid) begin
          {ftype_d, flen_d, payload_d} = {FrameResendType, FrameResendLen, 336'd0, rs_seq};
          state_d = StSync1;
        end else if (pkt_valid) begin
          if (PacketsAreClimbs != 0) begin
            {ftype_d, flen_d} = climbs_frame(pkt_payload[81:80]);
            payload_d = {272'd0, pkt_payload[63:0], pkt_payload[79:64]};
            if (climbs_event_waiting) begin
              payload_d = {344'd0, climbs_entry};
              climbs_open_d = 1'b1;
            end
          end else begin
            {ftype_d, flen_d, payload_d} = {FramePacketType, FramePacketLen, 256'd0, pkt_payload};
          end
          state_d = StSync1;
        end else if (trk_valid) begin
          {ftype_d, flen_d, payload_d} = {FrameTrackType, FrameTrackLen, 88'd0, trk_payload};
          state_d = StSync1;
        end else if (lab_valid) begin
          if (LabelsAreVerdicts != 0) begin
            {ftype_d, flen_d, payload_d} = {FrameVerdictType, FrameVerdictLen, 272'd0, {{BatchGapBits{1'b0}}, verdict_fields}, label_seq_q, lab_t};
            verdicts_open_d = 1'b1;
            verdict_t_d = lab_t;
          end else begin
            {ftype_d, flen_d, payload_d} = {FrameLabelType, FrameLabelLen, 232'd0, label_seq_q, lab_label, 7'd0, lab_p, lab_y, lab_x, lab_t};
          end
          label_seq_d = label_seq_q + 1'b1;
          state_d = StSync1;
        end else if (pg_valid) begin
          {ftype_d, flen_d, payload_d} = {FrameProgressType, FrameProgressLen, 256'd0, pg_payload};
          state_d = StSync1;
        end
        crc_d = 16'hFFFF;
        pos_d = '0;
      end
      default: if (byte_ready) begin
        case (state_q)
          StSync1: state_d = StSync2;
          StSync2: state_d = StType;
          StType: begin
            crc_d = evms_crc16_pkg::crc16_byte(crc_q, ftype_q);
            state_d = StLen;
          end
          StLen: begin
            crc_d = evms_crc16_pkg::crc16_byte(crc_q, flen_q);
            state_d = StPayload;
          end
          StPayload: begin
            crc_d = evms_crc16_pkg::crc16_byte(crc_q, payload_q[7:0]);
            // Past the header and the first entry the register holds zeros: an entry taken
            // goes into its lowest bytes, and once none is taken the frame stays closed.
            payload_d = (payload_q >> 8) | {320'd0, take_verdict ? {verdict_gap[BatchGapBits-1:0], verdict_fields} : 32'd0} |
                        {344'd0, take_climbs_event ? climbs_entry : 8'd0};
            if (!take_climbs_event) climbs_open_d = 1'b0;
            if (take_verdict) begin
              verdict_t_d = lab_t;
              label_seq_d = label_seq_q + 1'b1;
            end else if (next_is_entry_q) begin
              verdicts_open_d = 1'b0;
            end
            pos_d = pos_q + 1'b1;
            if (pos_q + 1'b1 == flen_q) state_d = StCrcLo;
          end
          StCrcLo: state_d = StCrcHi;
          StCrcHi: state_d = StIdle;
          default: state_d = StIdle;
        endcase
      end
    endcase
  end

  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      {state_q, payload_q, ftype_q, flen_q, pos_q} <= '0;
      crc_q <= 16'hFFFF;
      {label_seq_q, verdicts_open_q, verdict_t_q, climbs_open_q} <= '0;
      {gap_fits_q, gap_known_q, next_is_entry_q} <= '0;
    end else begin
      {state_q, payload_q, ftype_q, flen_q, pos_q, crc_q} <= {state_d, payload_d, ftype_d, flen_d, pos_d, crc_d};
      {label_seq_q, verdicts_open_q, verdict_t_q, climbs_open_q} <= {label_seq_d, verdicts_open_d, verdict_t_d, climbs_open_d};
      next_is_entry_q <= next_is_entry;
      gap_fits_q <= verdict_gap[31:BatchGapBits] == '0;
      gap_known_q <= lab_valid && !lab_ready;
    end
  end
endmodule
