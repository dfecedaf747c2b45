// UART receiver, 8 data bits, no parity, one stop bit, LSB first; samples mid-bit. A byte
// whose stop bit is low is a framing error: dropped and counted.
module evms_uart_rx #(
  parameter int ClksPerBit = 4
) (
  input  logic       clk,
  input  logic       rst_n,
  input  logic       rx,
  output logic       valid,
  output logic [7:0] data,
  output logic [31:0] framing_errors
);
  localparam int CountBits = $clog2(ClksPerBit + 1);
  logic line;
  evms_sync #(.Width(1), .ResetValue(1'b1)) u_sync (.clk(clk), .rst_n(rst_n), .d(rx), .q(line));
  typedef enum logic [1:0] {S_IDLE, S_START, S_DATA, S_STOP} state_e;
  state_e state;
  logic [CountBits-1:0] count;
  logic [2:0] bit_i;
  logic [7:0] shift;
  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      state <= S_IDLE;
      count <= '0;
      bit_i <= '0;
      shift <= '0;
      valid <= 1'b0;
      data <= '0;
      framing_errors <= '0;
    end else begin
      valid <= 1'b0;
      case (state)
        S_IDLE: if (!line) begin
          count <= CountBits'(ClksPerBit / 2);
          state <= S_START;
        end
        S_START: if (count == 0) begin
          if (!line) begin
            count <= CountBits'(ClksPerBit - 1);
            bit_i <= '0;
            state <= S_DATA;
          end else begin
            state <= S_IDLE;  // a glitch, not a start bit
          end
        end else count <= count - 1'b1;
        S_DATA: if (count == 0) begin
          shift <= {line, shift[7:1]};
          count <= CountBits'(ClksPerBit - 1);
          bit_i <= bit_i + 1'b1;
          if (bit_i == 3'd7) state <= S_STOP;
        end else count <= count - 1'b1;
        S_STOP: if (count == 0) begin
          if (line) begin
            valid <= 1'b1;
            data <= shift;
          end else begin
            framing_errors <= framing_errors + 1'b1;
          end
          state <= S_IDLE;
        end else count <= count - 1'b1;
        default: state <= S_IDLE;
      endcase
    end
  end
endmodule
