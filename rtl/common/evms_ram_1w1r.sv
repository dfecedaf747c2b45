// A memory with one write port and one registered read port (read data the clock after the
// address), the form Yosys maps to block RAM on iCE40 and Xilinx parts. A read of the address
// being written returns the old word, unless CollisionUnused says the caller never uses that
// read: then Yosys keeps no copy of the written word and address beside the block RAM to give
// the old word back (no_rw_check; on a UP5K such a copy costs a logic cell a bit), and
// simulation returns the old word inverted, so a caller that did use it fails its cosimulation.
module evms_ram_1w1r #(
  parameter int Width = 32,
  parameter int Depth = 256,
  parameter int CollisionUnused = 0,
  localparam int AddrBits = Depth > 1 ? $clog2(Depth) : 1
) (
  input  logic                clk,
  input  logic                we,
  input  logic [AddrBits-1:0] wa,
  input  logic [Width-1:0]    wd,
  input  logic [AddrBits-1:0] ra,
  output logic [Width-1:0]    rd
);
  if (CollisionUnused != 0) begin : g_collision_unused
    (* no_rw_check *) logic [Width-1:0] mem [Depth];
    always_ff @(posedge clk) begin
      if (we) mem[wa] <= wd;
`ifdef SYNTHESIS
      rd <= mem[ra];
`else
      rd <= we && wa == ra ? ~mem[ra] : mem[ra];
`endif
    end
  end else begin : g_read_old
    logic [Width-1:0] mem [Depth];
    always_ff @(posedge clk) begin
      if (we) mem[wa] <= wd;
      rd <= mem[ra];
    end
  end
endmodule
