// A memory with one port that either writes or reads (registered: read data the clock after the
// address), whose read data holds while it writes: the form Yosys maps to an iCE40 UP5K's
// SPRAM (SB_SPRAM256KA, 16K x 16 each) or a Xilinx block RAM in NO_CHANGE mode. With Huge, the
// memory asks Yosys for SPRAMs (ram_style "huge") where its cost model would pick 4-kbit block
// RAMs for a shallow memory.
module evms_ram_1rw #(
  parameter int Width = 16,
  parameter int Depth = 256,
  parameter int Huge  = 0,
  localparam int AddrBits = Depth > 1 ? $clog2(Depth) : 1
) (
  input  logic                clk,
  input  logic                we,
  input  logic [AddrBits-1:0] addr,
  input  logic [Width-1:0]    wd,
  output logic [Width-1:0]    rd
);
  if (Huge != 0) begin : g_huge
    (* ram_style = "huge" *) logic [Width-1:0] mem [Depth];
    always_ff @(posedge clk) begin
      if (we) mem[addr] <= wd;
      else rd <= mem[addr];
    end
  end else begin : g_block
    logic [Width-1:0] mem [Depth];
    always_ff @(posedge clk) begin
      if (we) mem[addr] <= wd;
      else rd <= mem[addr];
    end
  end
endmodule
