// Two-flop synchronizer for asynchronous inputs (AER request, UART receive line).
module evms_sync #(
  parameter int Width = 1,
  parameter logic [Width-1:0] ResetValue = '0
) (
  input  logic             clk,
  input  logic             rst_n,
  input  logic [Width-1:0] d,
  output logic [Width-1:0] q
);
  logic [Width-1:0] meta;
  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      meta <= ResetValue;
      q <= ResetValue;
    end else begin
      meta <= d;
      q <= meta;
    end
  end
endmodule
