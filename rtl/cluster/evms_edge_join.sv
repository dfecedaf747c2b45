// The edge join, as hls/cluster/edge_join.h (EdgeJoin::run): a mostly-ON and a mostly-OFF mode
// whose centres lie within reach, neither holding more than EdgeSizeRatio times the other's
// events, and each the other's nearest such, become one (the later into the earlier).
// golden/cluster/edge_join.h states the rule and why. Every test is on integers, as the model's:
//   looked at   events >= cfg_edge_min_events (and not empty)
//   mostly ON   (2 ON - events) << SplitFractionFrac >= cfg_edge_balance * events (OFF: events - 2 ON)
//   centre      16 sum / events, rounded half up (1/16 px)
//   in reach    dx^2 + dy^2 <= cfg_edge_radius2
//   nearest     the least such distance; ties to the lower mode
//
//   count   each event's mode (after the split) and pixel arrive the clock after ev_j, one event
//           a clock; each mode's events, ON events and sums of x and y are counted;
//   lean    each mode in order that is looked at and leans one way goes on the list with its
//           lean and its centre (two evms_divide_rounded, DivBits + 2 clocks);
//   pairs   each listed mode scans the list, one entry a clock, for its nearest of the other
//           lean in reach and of a size within the ratio;
//   into    each mode takes the mode before it that chose it and that it chose, else itself.
// The result is a table from mode to mode (rd_c to rd_into, combinational: the core reads it
// through, on the way from the split's modes to the warm seeds), valid from done until the next
// start; the modes keep their positions, and a mode joined away holds no event.
//
// Schedule: 1 to start; n + 2 to count; 1 a mode to list, and 1 + DivBits + 2 more a listed mode;
// (list + 1) a listed mode to pair; 1 a mode to relabel, and 1 for done.
// The sums (with a valid bit each) and the list are register files written one entry a clock,
// which a board build would map to distributed RAM.
`include "evms_assert.svh"

module evms_edge_join #(
  parameter int PacketMax         = 256,
  parameter int ModesMax          = 64,
  parameter int SplitFractionFrac = 8,   // hls::kSplitFractionFrac
  parameter int EdgeSizeRatio     = 4    // hls::kEdgeSizeRatio
) (
  input  logic                clk,
  input  logic                rst_n,
  input  logic                start,
  input  logic [15:0]         n,
  input  logic [15:0]         mode_count,
  input  logic [63:0]         cfg_edge_radius2,
  input  logic [15:0]         cfg_edge_balance,
  input  logic [15:0]         cfg_edge_min_events,
  // The packet's events, the clock after ev_j (a block RAM's registered read).
  output logic [15:0]         ev_j,
  input  logic [15:0]         ev_x,
  input  logic [15:0]         ev_y,
  input  logic                ev_p,
  input  logic signed [15:0]  ev_mode,   // after the split, -1 for none
  output logic                done,      // one clock
  output logic [15:0]         joined,    // the pairs joined, from done
  // The result, from done: the mode that mode rd_c's events take.
  input  logic [7:0]          rd_c,
  output logic [7:0]          rd_into
);
  localparam int ModeBits = $clog2(ModesMax);
  localparam int CntBits = $clog2(PacketMax + 1);
  localparam int SumBits = 16 + CntBits;        // a mode's sum of pixel coordinates
  localparam int DivBits = SumBits + 5;         // 16 sum, and the divider's numerator is wider than its denominator
  localparam int CentreBits = 20;               // a 16-bit pixel coordinate in 1/16 px
  `EVMS_ASSERT_INIT("modes must be a power of two above one", ModesMax > 1 && (1 << ModeBits) == ModesMax)
  `EVMS_ASSERT_INIT("modes are read by an 8-bit index", ModesMax <= 256)

  typedef enum logic [2:0] { StIdle, StCount, StLean, StLeanWait, StPair, StInto, StDone } state_e;
  state_e state_q, state_d;

  logic [15:0]         j_q, j_d;               // the event addressed
  logic                have_q, have_d;         // the previous address was an event: its data is here
  logic [15:0]         c_q, c_d;               // a mode
  logic [ModeBits:0]   leaning_q, leaning_d;   // the listed modes
  logic [ModeBits:0]   a_q, a_d;               // the listed mode looking for its nearest
  logic [ModeBits:0]   b_q, b_d;               // the listed mode it is compared with
  logic                with_valid_q, with_valid_d;
  logic [ModeBits-1:0] with_q, with_d;         // its nearest so far ...
  logic [63:0]         best_q, best_d;         // ... at this squared distance
  logic [15:0]         joined_q, joined_d;

  // ---- dividers: both axes at once ---------------------------------------------------------------
  logic               div_start, div_done, div_y_done;
  logic [DivBits-1:0] quotient_x, quotient_y;
  logic [ModeBits-1:0] c_mode;
  assign c_mode = ModeBits'(c_q);
  // Per mode: events, ON events, sums of x and y, each entry valid once its mode's first event
  // wrote it (a start clears the valid bits, not the entries).
  logic [ModesMax-1:0] counted_q;
  logic [CntBits-1:0] events_q [ModesMax];
  logic [CntBits-1:0] on_q [ModesMax];
  logic [SumBits-1:0] sum_x_q [ModesMax];
  logic [SumBits-1:0] sum_y_q [ModesMax];
  evms_divide_rounded #(.NumBits(DivBits), .DenBits(CntBits)) u_divide_x (
    .clk, .rst_n, .start(div_start), .num(DivBits'({sum_x_q[c_mode], 4'b0})), .den(events_q[c_mode]), .done(div_done),
    .quotient(quotient_x));
  evms_divide_rounded #(.NumBits(DivBits), .DenBits(CntBits)) u_divide_y (
    .clk, .rst_n, .start(div_start), .num(DivBits'({sum_y_q[c_mode], 4'b0})), .den(events_q[c_mode]), .done(div_y_done),
    .quotient(quotient_y));

  // ---- register files ------------------------------------------------------------------------------
  logic [ModeBits-1:0]   list_q [ModesMax];        // the leaning modes, in mode order
  logic [ModesMax-1:0]   list_off_q;               // ... leaning OFF (else ON)
  logic [CentreBits-1:0] centre_x_q [ModesMax];    // ... and their centres, 1/16 px
  logic [CentreBits-1:0] centre_y_q [ModesMax];
  logic [ModesMax-1:0]   nearest_valid_q;          // per mode: the nearest it chose, if any
  logic [ModeBits-1:0]   nearest_q [ModesMax];
  logic [ModeBits-1:0]   into_q [ModesMax];

  // ---- mode c: looked at, and its lean ----------------------------------------------------------------
  logic [CntBits-1:0] c_events, c_on;
  logic [CntBits:0]   c_surplus;                  // |2 ON - events|
  logic               c_more_on, c_looked, c_leans;
  logic [63:0]        c_needed;
  assign c_events = counted_q[c_mode] ? events_q[c_mode] : '0;
  assign c_on = on_q[c_mode];   // read only where c_events is not 0
  assign c_more_on = 2 * (CntBits + 1)'(c_on) >= (CntBits + 1)'(c_events);
  assign c_surplus = c_more_on ? 2 * (CntBits + 1)'(c_on) - (CntBits + 1)'(c_events) : (CntBits + 1)'(c_events) - 2 * (CntBits + 1)'(c_on);
  assign c_needed = 64'(cfg_edge_balance) * 64'(c_events);
  assign c_looked = c_events != 0 && 32'(c_events) >= 32'(cfg_edge_min_events);
  assign c_leans = c_looked && (64'(c_surplus) << SplitFractionFrac) >= c_needed;

  // ---- the pair (a, b) ------------------------------------------------------------------------------
  logic [ModeBits-1:0]      a_entry, b_entry, a_mode, b_mode;
  logic [CntBits-1:0]       a_events, b_events;
  logic signed [CentreBits:0] dx, dy;
  logic [63:0]              distance2;
  logic                     b_fits, b_nearer;
  assign a_entry = ModeBits'(a_q);
  assign b_entry = ModeBits'(b_q);
  assign a_mode = list_q[a_entry];
  assign b_mode = list_q[b_entry];
  assign a_events = events_q[a_mode];   // a listed mode holds events
  assign b_events = events_q[b_mode];
  assign dx = $signed({1'b0, centre_x_q[a_entry]}) - $signed({1'b0, centre_x_q[b_entry]});
  assign dy = $signed({1'b0, centre_y_q[a_entry]}) - $signed({1'b0, centre_y_q[b_entry]});
  assign distance2 = 64'(dx * dx) + 64'(dy * dy);
  assign b_fits = list_off_q[b_entry] != list_off_q[a_entry] && 32'(a_events) <= EdgeSizeRatio * 32'(b_events) &&
                  32'(b_events) <= EdgeSizeRatio * 32'(a_events) && distance2 <= cfg_edge_radius2;
  // The list is in mode order, so the first of equal distances is the lower mode.
  assign b_nearer = b_fits && (!with_valid_q || distance2 < best_q);

  // ---- mode c's partner: mutual, and before it --------------------------------------------------------
  logic [ModeBits-1:0] c_partner;
  logic                c_joins;
  assign c_partner = nearest_q[c_mode];
  assign c_joins = nearest_valid_q[c_mode] && 16'(c_partner) < c_q && nearest_valid_q[c_partner] && nearest_q[c_partner] == c_mode;

  // ---- control --------------------------------------------------------------------------------------
  always_comb begin
    state_d = state_q;
    j_d = j_q;
    have_d = 1'b0;
    c_d = c_q;
    leaning_d = leaning_q;
    a_d = a_q;
    b_d = b_q;
    with_valid_d = with_valid_q;
    with_d = with_q;
    best_d = best_q;
    joined_d = joined_q;
    div_start = 1'b0;
    done = 1'b0;
    case (state_q)
      StIdle: if (start) begin
        j_d = '0;
        state_d = StCount;
      end
      // Event j is addressed; event j - 1 is here when have_q (and is counted below).
      StCount: begin
        if (j_q != n) begin
          j_d = j_q + 1'b1;
          have_d = 1'b1;
        end else if (!have_q) begin
          c_d = '0;
          leaning_d = '0;
          state_d = StLean;
        end
      end
      StLean: begin
        if (c_q == mode_count) begin
          a_d = '0;
          b_d = '0;
          with_valid_d = 1'b0;
          c_d = '0;
          joined_d = '0;
          state_d = leaning_q == 0 ? StInto : StPair;
        end else if (c_leans) begin
          div_start = 1'b1;
          state_d = StLeanWait;
        end else begin
          c_d = c_q + 1'b1;
        end
      end
      StLeanWait: if (div_done) begin
        leaning_d = leaning_q + 1'b1;
        c_d = c_q + 1'b1;
        state_d = StLean;
      end
      StPair: begin
        if (b_q == leaning_q) begin
          a_d = a_q + 1'b1;
          b_d = '0;
          with_valid_d = 1'b0;
          if (a_q + 1'b1 == leaning_q) state_d = StInto;
        end else begin
          if (b_nearer) begin
            with_valid_d = 1'b1;
            with_d = b_mode;
            best_d = distance2;
          end
          b_d = b_q + 1'b1;
        end
      end
      StInto: begin
        if (c_q == mode_count) begin
          state_d = StDone;
        end else begin
          if (c_joins) joined_d = joined_q + 1'b1;
          c_d = c_q + 1'b1;
        end
      end
      StDone: begin
        done = 1'b1;
        state_d = StIdle;
      end
      default: state_d = StIdle;
    endcase
  end

  // The register files, written by the states above: one entry a clock (a start clears the valid
  // bits and the choices, packed vectors, in one clock).
  wire count_event = state_q == StCount && have_q && ev_mode >= 0;
  wire [ModeBits-1:0] ev_m = ModeBits'(ev_mode);
  wire ev_m_counted = counted_q[ev_m];
  always_ff @(posedge clk) begin
    if (state_q == StIdle && start) begin
      counted_q <= '0;
    end else if (count_event) begin
      counted_q[ev_m] <= 1'b1;
    end
  end
  always_ff @(posedge clk) begin
    if (count_event) begin
      events_q[ev_m] <= (ev_m_counted ? events_q[ev_m] : '0) + 1'b1;
      on_q[ev_m] <= (ev_m_counted ? on_q[ev_m] : '0) + CntBits'(ev_p);
      sum_x_q[ev_m] <= (ev_m_counted ? sum_x_q[ev_m] : '0) + SumBits'(ev_x);
      sum_y_q[ev_m] <= (ev_m_counted ? sum_y_q[ev_m] : '0) + SumBits'(ev_y);
    end
  end
  wire [ModeBits-1:0] listed = ModeBits'(leaning_q);
  always_ff @(posedge clk) begin
    if (state_q == StLeanWait && div_done) begin
      list_q[listed] <= c_mode;
      list_off_q[listed] <= !c_more_on;
      centre_x_q[listed] <= CentreBits'(quotient_x);
      centre_y_q[listed] <= CentreBits'(quotient_y);
    end
  end
  wire chosen = state_q == StPair && b_q == leaning_q;
  always_ff @(posedge clk) begin
    if (state_q == StIdle && start) begin
      nearest_valid_q <= '0;
    end else if (chosen) begin
      nearest_valid_q[a_mode] <= with_valid_q;
      nearest_q[a_mode] <= with_q;
    end
  end
  always_ff @(posedge clk) begin
    if (state_q == StInto && c_q != mode_count) into_q[c_mode] <= c_joins ? c_partner : c_mode;
  end

  assign ev_j = j_q;
  assign joined = joined_q;
  assign rd_into = 8'(into_q[ModeBits'(rd_c)]);
  `EVMS_ASSERT("start only when idle", !start || state_q == StIdle, clk, rst_n)
  `EVMS_ASSERT("a mode must be below the mode count", !count_event || ev_mode < $signed(mode_count), clk, rst_n)
  `EVMS_ASSERT("the mode count must fit the table", !(state_q == StIdle && start) || 32'(mode_count) <= ModesMax, clk, rst_n)
  `EVMS_ASSERT("a centre must fit its register", !(state_q == StLeanWait && div_done) || (quotient_x >> CentreBits) == 0 && (quotient_y >> CentreBits) == 0, clk, rst_n)

  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      state_q <= StIdle;
      j_q <= '0;
      have_q <= 1'b0;
      c_q <= '0;
      leaning_q <= '0;
      a_q <= '0;
      b_q <= '0;
      with_valid_q <= 1'b0;
      with_q <= '0;
      best_q <= '0;
      joined_q <= '0;
    end else begin
      state_q <= state_d;
      j_q <= j_d;
      have_q <= have_d;
      c_q <= c_d;
      leaning_q <= leaning_d;
      a_q <= a_d;
      b_q <= b_d;
      with_valid_q <= with_valid_d;
      with_q <= with_d;
      best_q <= best_d;
      joined_q <= joined_d;
    end
  end
endmodule
