// A first-word-fall-through FIFO whose storage is one write port and one registered read
// port, so that synthesis maps it to block RAM; a two-entry output buffer keeps one word a
// cycle flowing through the RAM's read latency.
//
// With Tentative, words written are held back from the reader until in_commit, which releases
// them and the word written in the same clock; in_rollback forgets those not yet released (a
// frame whose check fails after its words went in). Without it every word is released at once.
module evms_fifo #(
  parameter int Width = 32,
  parameter int Depth = 512,
  parameter bit Tentative = 1'b0
) (
  input  logic             clk,
  input  logic             rst_n,
  input  logic             in_valid,
  output logic             in_ready,
  input  logic [Width-1:0] in_data,
  input  logic             in_commit,
  input  logic             in_rollback,
  output logic             out_valid,
  input  logic             out_ready,
  output logic [Width-1:0] out_data
);
  localparam int AddrBits = $clog2(Depth);

  logic [Width-1:0] mem [Depth];
  logic [AddrBits:0] head, tail;          // RAM read and write positions
  logic [AddrBits:0] released;            // with Tentative: the reader's end (tail without)
  logic [AddrBits:0] released_q;
  logic [Width-1:0] rdata;
  logic rd_en, rd_inflight;

  // Output buffer: up to two words, the older at index ob_head.
  logic [Width-1:0] ob [2];
  logic [1:0] ob_n;
  logic ob_head;

  assign released = Tentative ? released_q : tail;
  wire ram_empty = head == released;
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
      released_q <= '0;
      rd_inflight <= 1'b0;
      ob_n <= '0;
      ob_head <= 1'b0;
      ob[0] <= '0;
      ob[1] <= '0;
    end else begin
      if (Tentative && in_rollback) begin
        tail <= released_q;
      end else if (in_valid && in_ready) begin
        tail <= tail + 1'b1;
      end
      if (Tentative && in_commit) released_q <= tail + (AddrBits+1)'(in_valid && in_ready);
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
