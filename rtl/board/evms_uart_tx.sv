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
  logic [9:0] frame;
  logic [3:0] bit_i;
  logic [CountBits-1:0] count;
  logic busy;
  assign ready = !busy;
  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      frame <= '1;
      bit_i <= '0;
      count <= '0;
      busy <= 1'b0;
      tx <= 1'b1;
    end else if (!busy) begin
      if (valid) begin
        frame <= {1'b1, data, 1'b0};
        tx <= 1'b0;  // start bit
        bit_i <= '0;
        count <= CountBits'(ClksPerBit - 1);
        busy <= 1'b1;
      end
    end else if (count != 0) begin
      count <= count - 1'b1;
    end else if (bit_i == 4'd9) begin
      busy <= 1'b0;  // the stop bit has been held its full time
    end else begin
      tx <= frame[bit_i + 1'b1];
      bit_i <= bit_i + 1'b1;
      count <= CountBits'(ClksPerBit - 1);
    end
  end
endmodule
