// A memory with one write port and one registered read port (read data the clock after the
// address), the form Yosys maps to block RAM on iCE40 and Xilinx parts. A read of the address
// being written returns the old word.
module evms_ram_1w1r #(
  parameter int Width = 32,
  parameter int Depth = 256,
  localparam int AddrBits = Depth > 1 ? $clog2(Depth) : 1
) (
  input  logic                clk,
  input  logic                we,
  input  logic [AddrBits-1:0] wa,
  input  logic [Width-1:0]    wd,
  input  logic [AddrBits-1:0] ra,
  output logic [Width-1:0]    rd
);
  logic [Width-1:0] mem [Depth];
  always_ff @(posedge clk) begin
    if (we) mem[wa] <= wd;
    rd <= mem[ra];
  end
endmodule
