// UART transmitter, 8N1, LSB first, each bit held ClksPerBit cycles, with a valid/ready
// byte input.
module evms_uart_tx #(
  parameter int ClksPerBit = 4
) (
  input  logic       clk,
  input  logic       rst_n,
  input  logic       valid,
  output logic       ready,
  input  logic [7:0] data,
  output logic       tx
);
  localparam int CountBits = $clog2(ClksPerBit + 1);
  logic [9:0] frame_q, frame_d;             // stop bit, data, start bit
  logic [3:0] bit_q, bit_d;                 // bit of the frame on the line
  logic [CountBits-1:0] count_q, count_d;   // clocks left in the current bit
  logic busy_q, busy_d;
  logic tx_q, tx_d;
  assign ready = !busy_q;
  assign tx = tx_q;

  always_comb begin
    frame_d = frame_q;
    bit_d = bit_q;
    count_d = count_q;
    busy_d = busy_q;
    tx_d = tx_q;
    if (!busy_q) begin
      if (valid) begin
        frame_d = {1'b1, data, 1'b0};
        tx_d = 1'b0;  // start bit
        bit_d = '0;
        count_d = CountBits'(ClksPerBit - 1);
        busy_d = 1'b1;
      end
    end else if (count_q != 0) begin
      count_d = count_q - 1'b1;
    end else if (bit_q == 4'd9) begin
      busy_d = 1'b0;  // the stop bit has been held its full time
    end else begin
      tx_d = frame_q[bit_q + 1'b1];
      bit_d = bit_q + 1'b1;
      count_d = CountBits'(ClksPerBit - 1);
    end
  end

  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      frame_q <= '1;
      bit_q <= '0;
      count_q <= '0;
      busy_q <= 1'b0;
      tx_q <= 1'b1;
    end else begin
      frame_q <= frame_d;
      bit_q <= bit_d;
      count_q <= count_d;
      busy_q <= busy_d;
      tx_q <= tx_d;
    end
  end
endmodule
