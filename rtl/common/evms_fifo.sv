// A first-word-fall-through FIFO whose storage is one write port and one registered read
// port, so that synthesis maps it to block RAM; a two-entry output buffer keeps one word a
// cycle flowing through the RAM's read latency.
module evms_fifo #(
  parameter int Width = 32,
  parameter int Depth = 512
) (
  input  logic             clk,
  input  logic             rst_n,
  input  logic             in_valid,
  output logic             in_ready,
  input  logic [Width-1:0] in_data,
  output logic             out_valid,
  input  logic             out_ready,
  output logic [Width-1:0] out_data
);
  localparam int AddrBits = $clog2(Depth);

  logic [Width-1:0] mem [Depth];
  logic [AddrBits:0] head, tail;          // RAM read and write positions
  logic [Width-1:0] rdata;
  logic rd_en, rd_inflight;

  // Output buffer: up to two words, the older at index ob_head.
  logic [Width-1:0] ob [2];
  logic [1:0] ob_n;
  logic ob_head;

  wire ram_empty = head == tail;
  assign in_ready = (tail - head) != (AddrBits+1)'(Depth);
  assign out_valid = ob_n != 0;
  assign out_data = ob[ob_head];
  wire take = out_valid && out_ready;
  // Read only when the word will find room in the output buffer when it lands.
  assign rd_en = !ram_empty && (32'(ob_n) + 32'(rd_inflight) - 32'(take)) < 2;

  always_ff @(posedge clk) begin
    if (in_valid && in_ready) mem[AddrBits'(tail)] <= in_data;
    if (rd_en) rdata <= mem[AddrBits'(head)];
  end

  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      head <= '0;
      tail <= '0;
      rd_inflight <= 1'b0;
      ob_n <= '0;
      ob_head <= 1'b0;
      ob[0] <= '0;
      ob[1] <= '0;
    end else begin
      if (in_valid && in_ready) tail <= tail + 1'b1;
      if (rd_en) head <= head + 1'b1;
      rd_inflight <= rd_en;
      case ({rd_inflight, take})
        2'b10: begin
          ob[ob_head ^ ob_n[0]] <= rdata;
          ob_n <= ob_n + 1'b1;
        end
        2'b01: begin
          ob_head <= ~ob_head;
          ob_n <= ob_n - 1'b1;
        end
        2'b11: begin
          ob[ob_head ^ ob_n[0]] <= rdata;
          ob_head <= ~ob_head;
        end
        default: ;
      endcase
    end
  end
endmodule
