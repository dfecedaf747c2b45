// The counting sort that puts a packet's events in key order for the climbs
// (rtl/cluster/evms_seeded_climbs.sv: cells of one bandwidth; evms_serial_climbs.sv: rows of one
// bandwidth), as hls/cluster/seeded_climbs.h (sort_into_cells) sorts them: start[k] .. start[k + 1]
// are key k's events, in packet order within the key. The caller holds the events and their
// sorted copy: it reads event `j` (a registered read) and gives its key the clock after, and
// writes the event to its sorted copy at `place_k` when `place_we` is high.
// Clocks: Keys + 1 clearing the counts, 3 an event counting, Keys + 3 for the prefix sums, 3 an
// event placing. After `done`, start[run_ra] is read out (one clock of latency) for the runs.
`include "evms_assert.svh"

module evms_counting_sort #(
  parameter int PacketMax = 256,
  parameter int Keys      = 1024,
  localparam int IdxBits = PacketMax > 1 ? $clog2(PacketMax) : 1,
  localparam int CntBits = $clog2(PacketMax + 1),
  localparam int KeyBits = $clog2(Keys + 1)
) (
  input  logic               clk,
  input  logic               rst_n,
  input  logic               start,
  input  logic [15:0]        n,
  output logic               clearing,      // the counts clear, clear_index 0 .. Keys, one a clock
  output logic [KeyBits-1:0] clear_index,
  output logic               count_read,    // the count pass's first clock of event j
  output logic [IdxBits-1:0] j,             // the event the caller reads
  input  logic [KeyBits-1:0] key,           // event j's key, from the clock after j is set while j holds
  output logic               place_we,      // the caller's sorted copy takes event j at place_k
  output logic [IdxBits-1:0] place_k,
  output logic               done,          // in the sort's last clock
  input  logic [KeyBits-1:0] run_ra,
  output logic [CntBits-1:0] run_start      // start[run_ra], the clock after
);
  typedef enum logic [3:0] {
    StIdle, StClear, StCountRead, StCountKey, StCountWrite, StPrefix, StPlaceRead, StPlaceNext, StPlaceWrite
  } state_e;
  state_e state_q;
  logic [15:0]        j_q;
  logic [KeyBits:0]   c_q, pc_q;   // clearing and prefix sums: the key read, the key written
  logic               pv_q;        // prefix sums: a read is in flight
  logic [CntBits-1:0] acc_q;       // prefix sum

  // start[k]: where key k's run begins (counts, then their prefix sums); next[k]: where its next
  // event goes while placing.
  logic [CntBits-1:0] start_rd, start_wd, next_rd, next_wd;
  localparam int NextBits = Keys > 1 ? $clog2(Keys) : 1;
  logic [KeyBits-1:0] start_ra, start_wa;
  logic [NextBits-1:0] next_wa;
  logic               start_we, next_we;
  evms_ram_1w1r #(.Width(CntBits), .Depth(Keys + 1), .CollisionUnused(1)) u_start (
    .clk, .we(start_we), .wa(start_wa), .wd(start_wd), .ra(start_ra), .rd(start_rd));
  evms_ram_1w1r #(.Width(CntBits), .Depth(Keys), .CollisionUnused(1)) u_next (
    .clk, .we(next_we), .wa(next_wa), .wd(next_wd), .ra(NextBits'(key)), .rd(next_rd));
  assign run_start = start_rd;

  assign clearing = state_q == StClear;
  assign clear_index = KeyBits'(c_q);
  assign count_read = state_q == StCountRead;
  assign j = IdxBits'(j_q);
  assign place_we = state_q == StPlaceWrite;
  assign place_k = IdxBits'(next_rd);   // below n
  assign done = (state_q == StClear && c_q == (KeyBits + 1)'(Keys) && n == '0) || (state_q == StPlaceWrite && j_q + 1'b1 == n);

  always_comb begin
    start_ra = run_ra;
    start_we = 1'b0;
    start_wa = key + 1'b1;
    start_wd = start_rd + 1'b1;
    next_we = 1'b0;
    next_wa = NextBits'(key);
    next_wd = next_rd + 1'b1;
    unique case (state_q)
      StClear: begin
        start_we = 1'b1;
        start_wa = KeyBits'(c_q);
        start_wd = '0;
      end
      StCountKey: start_ra = key + 1'b1;
      StCountWrite: start_we = 1'b1;   // the caller's read still gives event j's key
      StPrefix: begin
        start_ra = KeyBits'(c_q);
        start_we = pv_q;
        start_wa = KeyBits'(pc_q);
        start_wd = acc_q + start_rd;
        next_we = pv_q && pc_q != (KeyBits + 1)'(Keys);   // start[Keys] is the end, not a key
        next_wa = NextBits'(pc_q);
        next_wd = acc_q + start_rd;
      end
      StPlaceWrite: next_we = 1'b1;
      default: ;
    endcase
  end

  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      state_q <= StIdle;
      {j_q, c_q, pc_q, pv_q, acc_q} <= '0;
    end else begin
      unique case (state_q)
        StIdle: if (start) begin
          c_q <= '0;
          state_q <= StClear;
        end
        StClear: begin
          c_q <= c_q + 1'b1;
          if (c_q == (KeyBits + 1)'(Keys)) begin
            j_q <= '0;
            state_q <= n == '0 ? StIdle : StCountRead;
          end
        end
        StCountRead: state_q <= StCountKey;
        StCountKey: state_q <= StCountWrite;
        StCountWrite: begin
          j_q <= j_q + 1'b1;
          if (j_q + 1'b1 == n) begin
            c_q <= '0;
            pv_q <= 1'b0;
            acc_q <= '0;
            state_q <= StPrefix;
          end else begin
            state_q <= StCountRead;
          end
        end
        StPrefix: begin
          if (pv_q) acc_q <= acc_q + start_rd;
          pv_q <= c_q <= (KeyBits + 1)'(Keys);
          pc_q <= c_q;
          if (c_q <= (KeyBits + 1)'(Keys)) c_q <= c_q + 1'b1;
          if (c_q > (KeyBits + 1)'(Keys) && !pv_q) begin
            j_q <= '0;
            state_q <= StPlaceRead;
          end
        end
        StPlaceRead: state_q <= StPlaceNext;
        StPlaceNext: state_q <= StPlaceWrite;
        StPlaceWrite: begin
          j_q <= j_q + 1'b1;
          state_q <= j_q + 1'b1 == n ? StIdle : StPlaceRead;
        end
        default: state_q <= StIdle;
      endcase
    end
  end

  `EVMS_ASSERT("a packet holds at most PacketMax events", !(start && n > 16'(PacketMax)), clk, rst_n)
  `EVMS_ASSERT("a sort starts when the last one is done", !(start && state_q != StIdle), clk, rst_n)
endmodule
