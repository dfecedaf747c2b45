// UART receiver, 8 data bits, no parity, one stop bit, LSB first. A byte whose stop bit is low
// is a framing error: dropped and counted.
//
// Where it samples: the synchronized line first reads low 0 to 1 clock after the start bit's
// edge, and each bit is read ClksPerBit / 2 clocks after that, and every ClksPerBit clocks on:
// 0 to 1 clock after the bit's middle (at 4 clocks a bit, 0 to a quarter of a bit late). A sender
// 2 % fast or slow moves the middle of the stop bit by a fifth of a bit, so its bytes still
// arrive (tests/sim/test_uart_rx.cpp plays such senders at every phase of the clock).
`include "evms_assert.svh"
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
  `EVMS_ASSERT_INIT("a bit lasts at least 3 clocks, so that its middle can be found", ClksPerBit >= 3)
  logic line;
  evms_sync #(.Width(1), .ResetValue(1'b1)) u_sync (.clk(clk), .rst_n(rst_n), .d(rx), .q(line));

  typedef enum logic [1:0] {StIdle, StStart, StData, StStop} state_e;
  state_e state_q, state_d;
  logic [CountBits-1:0] count_q, count_d;   // clocks left in the current bit
  logic [2:0] bit_q, bit_d;                 // data bit being received
  logic [7:0] shift_q, shift_d;
  logic valid_q, valid_d;
  logic [7:0] data_q, data_d;
  logic [31:0] framing_errors_q, framing_errors_d;
  assign valid = valid_q;
  assign data = data_q;
  assign framing_errors = framing_errors_q;

  always_comb begin
    state_d = state_q;
    count_d = count_q;
    bit_d = bit_q;
    shift_d = shift_q;
    valid_d = 1'b0;
    data_d = data_q;
    framing_errors_d = framing_errors_q;
    case (state_q)
      StIdle: if (!line) begin
        count_d = CountBits'(ClksPerBit / 2 - 1);
        state_d = StStart;
      end
      StStart: if (count_q == 0) begin
        if (!line) begin
          count_d = CountBits'(ClksPerBit - 1);
          bit_d = '0;
          state_d = StData;
        end else begin
          state_d = StIdle;  // a glitch, not a start bit
        end
      end else count_d = count_q - 1'b1;
      StData: if (count_q == 0) begin
        shift_d = {line, shift_q[7:1]};
        count_d = CountBits'(ClksPerBit - 1);
        bit_d = bit_q + 1'b1;
        if (bit_q == 3'd7) state_d = StStop;
      end else count_d = count_q - 1'b1;
      StStop: if (count_q == 0) begin
        if (line) begin
          valid_d = 1'b1;
          data_d = shift_q;
        end else begin
          framing_errors_d = framing_errors_q + 1'b1;
        end
        state_d = StIdle;
      end else count_d = count_q - 1'b1;
      default: state_d = StIdle;
    endcase
  end

  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      state_q <= StIdle;
      count_q <= '0;
      bit_q <= '0;
      shift_q <= '0;
      valid_q <= 1'b0;
      data_q <= '0;
      framing_errors_q <= '0;
    end else begin
      state_q <= state_d;
      count_q <= count_d;
      bit_q <= bit_d;
      shift_q <= shift_d;
      valid_q <= valid_d;
      data_q <= data_d;
      framing_errors_q <= framing_errors_d;
    end
  end
endmodule
