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

  logic [TickBits-1:0] tick;
  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      tick <= '0;
      timestamp <= '0;
    end else if (32'(tick) == TicksPerUs - 1) begin
      tick <= '0;
      timestamp <= timestamp + 1'b1;
    end else begin
      tick <= tick + 1'b1;
    end
  end

  logic req;
  evms_sync #(.Width(1), .ResetValue(1'b1)) u_req_sync (.clk(clk), .rst_n(rst_n), .d(req_n), .q(req));

  typedef enum logic [1:0] {S_WAIT_REQ, S_OFFER, S_ACK, S_WAIT_RELEASE} state_e;
  state_e state;
  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      state <= S_WAIT_REQ;
      ack_n <= 1'b1;
      ev_valid <= 1'b0;
      {ev_t, ev_x, ev_y, ev_p} <= '0;
      external_events <= '0;
    end else begin
      case (state)
        S_WAIT_REQ: if (!req) begin
          if (addr[15]) begin
            external_events <= external_events + 1'b1;
            state <= S_ACK;
          end else begin
            ev_valid <= 1'b1;
            ev_t <= timestamp;
            ev_x <= {9'b0, addr[7:1]};
            ev_y <= {9'b0, addr[14:8]};
            ev_p <= addr[0];
            state <= S_OFFER;
          end
        end
        S_OFFER: if (ev_ready) begin
          ev_valid <= 1'b0;
          state <= S_ACK;
        end
        S_ACK: begin
          ack_n <= 1'b0;
          state <= S_WAIT_RELEASE;
        end
        S_WAIT_RELEASE: if (req) begin
          ack_n <= 1'b1;
          state <= S_WAIT_REQ;
        end
        default: state <= S_WAIT_REQ;
      endcase
    end
  end
endmodule
