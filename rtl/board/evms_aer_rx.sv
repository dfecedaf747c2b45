// DVS128-style parallel AER receiver with a 1 us timestamp counter.
//
// Four-phase handshake, both strobes active low: the sensor drives an address and pulls
// req_n low; we synchronize req_n (two flops), take the address (stable by then: the sender
// holds it while req_n is low), stamp it, and pull ack_n low; the sender releases req_n; we
// release ack_n. The address bits are sampled only after the synchronized request, so they
// need no synchronizer of their own.
//
// Backpressure: an event is acknowledged only when the output takes it (valid/ready), so the
// sensor waits rather than an event being dropped. The timestamp is taken when the request
// arrives, so waiting does not age it.
//
// DVS128 address (16 bits): bit 15 external event (ignored and acknowledged), y = bits 14..8,
// x = bits 7..1, polarity = bit 0 (1 = ON).
module evms_aer_rx #(
  parameter int ClkHz = 12000000
) (
  input  logic        clk,
  input  logic        rst_n,
  input  logic        req_n,
  output logic        ack_n,
  input  logic [15:0] addr,
  output logic        ev_valid,
  input  logic        ev_ready,
  output logic [31:0] ev_t,
  output logic [15:0] ev_x,
  output logic [15:0] ev_y,
  output logic        ev_p,
  output logic [31:0] timestamp,        // microseconds since reset
  output logic [31:0] external_events   // counted, not forwarded
);
  localparam int TicksPerUs = ClkHz / 1000000;
  localparam int TickBits = TicksPerUs > 1 ? $clog2(TicksPerUs) : 1;

  logic [TickBits-1:0] tick_q, tick_d;   // clocks into the current microsecond
  logic [31:0] timestamp_q, timestamp_d;
  assign timestamp = timestamp_q;
  always_comb begin
    tick_d = tick_q + 1'b1;
    timestamp_d = timestamp_q;
    if (32'(tick_q) == TicksPerUs - 1) begin
      tick_d = '0;
      timestamp_d = timestamp_q + 1'b1;
    end
  end

  logic req;
  evms_sync #(.Width(1), .ResetValue(1'b1)) u_req_sync (.clk(clk), .rst_n(rst_n), .d(req_n), .q(req));

  typedef enum logic [1:0] {StWaitReq, StOffer, StAck, StWaitRelease} state_e;
  state_e state_q, state_d;
  logic ack_n_q, ack_n_d;
  logic ev_valid_q, ev_valid_d;
  logic [31:0] ev_t_q, ev_t_d;
  logic [15:0] ev_x_q, ev_x_d, ev_y_q, ev_y_d;
  logic ev_p_q, ev_p_d;
  logic [31:0] external_events_q, external_events_d;
  assign ack_n = ack_n_q;
  assign {ev_valid, ev_t, ev_x, ev_y, ev_p} = {ev_valid_q, ev_t_q, ev_x_q, ev_y_q, ev_p_q};
  assign external_events = external_events_q;

  always_comb begin
    state_d = state_q;
    ack_n_d = ack_n_q;
    {ev_valid_d, ev_t_d, ev_x_d, ev_y_d, ev_p_d} = {ev_valid_q, ev_t_q, ev_x_q, ev_y_q, ev_p_q};
    external_events_d = external_events_q;
    case (state_q)
      StWaitReq: if (!req) begin
        if (addr[15]) begin
          external_events_d = external_events_q + 1'b1;
          state_d = StAck;
        end else begin
          ev_valid_d = 1'b1;
          ev_t_d = timestamp_q;
          ev_x_d = {9'b0, addr[7:1]};
          ev_y_d = {9'b0, addr[14:8]};
          ev_p_d = addr[0];
          state_d = StOffer;
        end
      end
      StOffer: if (ev_ready) begin
        ev_valid_d = 1'b0;
        state_d = StAck;
      end
      StAck: begin
        ack_n_d = 1'b0;
        state_d = StWaitRelease;
      end
      StWaitRelease: if (req) begin
        ack_n_d = 1'b1;
        state_d = StWaitReq;
      end
      default: state_d = StWaitReq;
    endcase
  end

  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      tick_q <= '0;
      timestamp_q <= '0;
      state_q <= StWaitReq;
      ack_n_q <= 1'b1;
      {ev_valid_q, ev_t_q, ev_x_q, ev_y_q, ev_p_q} <= '0;
      external_events_q <= '0;
    end else begin
      tick_q <= tick_d;
      timestamp_q <= timestamp_d;
      state_q <= state_d;
      ack_n_q <= ack_n_d;
      {ev_valid_q, ev_t_q, ev_x_q, ev_y_q, ev_p_q} <= {ev_valid_d, ev_t_d, ev_x_d, ev_y_d, ev_p_d};
      external_events_q <= external_events_d;
    end
  end
endmodule
