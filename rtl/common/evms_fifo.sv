// A first-word-fall-through FIFO. Deeper than RegistersDepthMax, its storage is one write port
// and one registered read port, so that synthesis maps it to block RAM, and (OutputBuffer) a
// two-entry output buffer keeps one word a cycle flowing through the RAM's read latency. Up to
// RegistersDepthMax words it is Depth registers and the head's multiplexer: a RAM and its buffer
// would hold Depth + 3 words in registers for Depth (a block RAM is no cheaper for so few).
//
// With Tentative, words written are held back from the reader until in_commit, which releases
// them and the word written in the same clock; in_rollback forgets those not yet released (a
// frame whose check fails after its words went in). Without it every word is released at once.
`include "evms_assert.svh"

module evms_fifo #(
  parameter int Width = 32,
  parameter int Depth = 512,
  parameter int Tentative = 0,
  parameter int RegistersDepthMax = 4,
  // Memory form: 1, a two-word output buffer, so that the reader's ready reaches only that
  // buffer's logic; 0, none (the memory's read register is the output, and the ready drives its
  // read enable): Width * 2 flip-flops fewer, for a reader whose ready is a short path.
  parameter int OutputBuffer = 1
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
  `EVMS_ASSERT_INIT("a FIFO's depth is a power of two, at least 2", Depth >= 2 && (Depth & (Depth - 1)) == 0)

  if (Depth <= RegistersDepthMax) begin : g_registers
    `EVMS_ASSERT_INIT("a FIFO in registers releases every word at once", Tentative == 0)
    // The slots apart, each with its own write enable: Yosys 0.23 takes no packed arrays, and
    // a part-select written at a variable offset would be a shifter.
    logic [Width-1:0] slots_q [Depth];
    logic [AddrBits:0] head_q, tail_q;   // the next word out and the next slot written
    assign in_ready = (tail_q - head_q) != (AddrBits+1)'(Depth);
    assign out_valid = tail_q != head_q;
    assign out_data = slots_q[head_q[AddrBits-1:0]];
    for (genvar i = 0; i < Depth; i++) begin : g_slot
      always_ff @(posedge clk or negedge rst_n) begin
        if (!rst_n) slots_q[i] <= '0;
        else if (in_valid && in_ready && tail_q[AddrBits-1:0] == AddrBits'(i)) slots_q[i] <= in_data;
      end
    end
    always_ff @(posedge clk or negedge rst_n) begin
      if (!rst_n) begin
        head_q <= '0;
        tail_q <= '0;
      end else begin
        if (in_valid && in_ready) tail_q <= tail_q + 1'b1;
        if (out_valid && out_ready) head_q <= head_q + 1'b1;
      end
    end
    logic unused_tentative;
    assign unused_tentative = ^{in_commit, in_rollback};
  end else begin : g_memory
    // A read never meets the write of its word: the word read is released and the one written
    // is not, or the FIFO is full and takes none (asserted below). So Yosys need not keep the
    // old word in registers for such a clash (no_rw_check).
    (* no_rw_check *) logic [Width-1:0] mem [Depth];
    logic [AddrBits:0] head_q, head_d, tail_q, tail_d;   // RAM read and write positions
    logic [AddrBits:0] released_q, released_d;            // with Tentative: the reader's end
    logic [AddrBits:0] released;                          // the reader's end (tail without Tentative)
    logic [Width-1:0] rdata_q;                            // the RAM's registered read
    logic rd_en, take;

    assign released = Tentative != 0 ? released_q : tail_q;
    wire ram_empty = head_q == released;
    assign in_ready = (tail_q - head_q) != (AddrBits+1)'(Depth);
    assign take = out_valid && out_ready;

    `EVMS_ASSERT("a read never meets the write of its word",
                 !(rd_en && in_valid && in_ready && AddrBits'(head_q) == AddrBits'(tail_q)), clk, rst_n)
    always_ff @(posedge clk) begin
      if (in_valid && in_ready) mem[AddrBits'(tail_q)] <= in_data;
      if (rd_en) rdata_q <= mem[AddrBits'(head_q)];
    end

    always_comb begin
      tail_d = tail_q;
      if (Tentative != 0 && in_rollback) tail_d = released_q;
      else if (in_valid && in_ready) tail_d = tail_q + 1'b1;
      released_d = released_q;
      if (Tentative != 0 && in_commit) released_d = tail_q + (AddrBits+1)'(in_valid && in_ready);
      head_d = rd_en ? head_q + 1'b1 : head_q;
    end
    always_ff @(posedge clk or negedge rst_n) begin
      if (!rst_n) begin
        head_q <= '0;
        tail_q <= '0;
        released_q <= '0;
      end else begin
        head_q <= head_d;
        tail_q <= tail_d;
        released_q <= released_d;
      end
    end

    if (OutputBuffer != 0) begin : g_buffered
      // Output buffer: up to two words in slots 0 and 1, the older in slot ob_head_q.
      logic rd_inflight_q;
      logic [Width-1:0] ob0_q, ob0_d, ob1_q, ob1_d;
      logic ob_landing;   // the slot a word read from the RAM lands in
      logic [1:0] ob_n_q, ob_n_d;
      logic ob_head_q, ob_head_d;
      assign out_valid = ob_n_q != 0;
      assign out_data = ob_head_q ? ob1_q : ob0_q;
      assign ob_landing = ob_head_q ^ ob_n_q[0];
      // Read only when the word will find room in the output buffer when it lands: the buffer's
      // words and the one in flight, less the one taken now, are fewer than two. Written as a test
      // of those two bits rather than a sum, so that the reader's ready (often a long path from
      // the consumer's own logic) meets a LUT, not a carry chain, before this enable's fan-out.
      wire [1:0] ob_filling = ob_n_q + {1'b0, rd_inflight_q};   // at most 2
      assign rd_en = !ram_empty && (ob_filling < 2'd2 || (take && ob_filling == 2'd2));

      always_comb begin
        ob0_d = ob0_q;
        ob1_d = ob1_q;
        if (rd_inflight_q) begin
          if (ob_landing) ob1_d = rdata_q;
          else ob0_d = rdata_q;
        end
        ob_n_d = ob_n_q;
        ob_head_d = ob_head_q;
        case ({rd_inflight_q, take})
          2'b10: ob_n_d = ob_n_q + 1'b1;
          2'b01: begin
            ob_head_d = ~ob_head_q;
            ob_n_d = ob_n_q - 1'b1;
          end
          2'b11: ob_head_d = ~ob_head_q;
          default: ;
        endcase
      end
      always_ff @(posedge clk or negedge rst_n) begin
        if (!rst_n) begin
          rd_inflight_q <= 1'b0;
          ob_n_q <= '0;
          ob_head_q <= 1'b0;
          ob0_q <= '0;
          ob1_q <= '0;
        end else begin
          rd_inflight_q <= rd_en;
          ob_n_q <= ob_n_d;
          ob_head_q <= ob_head_d;
          ob0_q <= ob0_d;
          ob1_q <= ob1_d;
        end
      end
    end else begin : g_unbuffered
      // The memory's read register is the output: the next word is read as the reader takes
      // this one (or as soon as there is one), so a stream still passes one word a clock, but
      // the reader's ready drives the memory's read enable.
      logic rd_held_q;   // rdata_q holds a word not yet taken
      assign out_valid = rd_held_q;
      assign out_data = rdata_q;
      assign rd_en = !ram_empty && (!rd_held_q || take);
      always_ff @(posedge clk or negedge rst_n) begin
        if (!rst_n) rd_held_q <= 1'b0;
        else if (rd_en) rd_held_q <= 1'b1;
        else if (take) rd_held_q <= 1'b0;
      end
    end
  end
endmodule
