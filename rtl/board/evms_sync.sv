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
  logic [Width-1:0] meta_q;   // may be metastable: read only by the second flop
  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      meta_q <= ResetValue;
      q <= ResetValue;
    end else begin
      meta_q <= d;
      q <= meta_q;
    end
  end
endmodule
