// The seeded mean-shift climbs of hls/cluster/seeded_climbs.h (SeededClimbs::run), bit for bit,
// without warm seeds (cfg.warm_start false) and without the least-density test (cfg.min_density
// 0, or cfg.density_after_links, where the test follows the links: each mode's support is read
// out for it), built for a part without distributed RAM such as the iCE40 UP5K:
//  - the features, in packet order and in row order with each event's index, are one
//    single-ported memory (common/evms_ram_1rw.sv: the UP5K's SPRAMs); every other per-event
//    word is in block RAM with a registered read: the flags (reached, in the current climb), the
//    first mode with its labelled bit, the climb's list of touched events; so are each mode's
//    position and support and the rows' starts;
//  - the packet is sorted into Bands rows of one bandwidth (by y; the last row takes every
//    event beyond it) by a counting sort, and a step scans the three rows its ball can reach,
//    one contiguous run of the sorted events, an event a clock: not the 2-D grid of cells of
//    rtl/cluster/evms_seeded_climbs.sv, whose tables and row-by-row runs would take more logic
//    than the columns save. The sums are exact integers, so the events a step visits beyond the
//    ball change nothing but the clocks;
//  - the ball is one bandwidth, so only differences below two bandwidths are squared (farther
//    pairs are outside the ball and the merge radius): two (UnitShift + 1)-bit squares;
//  - one divider takes x and then y.
// Schedule: the sort (rtl/cluster/evms_counting_sort.sv: Bands + 1 clocks clearing the row counts;
// 3 an event counting, which clears its flags; Bands + 3 for the prefix sums; 3 an event
// placing); per event seed 2 clocks to read its reached flag; per climb step 3 to find its rows' run, the run's events + 2 through a
// 3-stage pipeline (the sorted event read; its difference to the climb, as its flags are read;
// its squared distance, the test, sums and flags) and, when the ball held events, two divisions
// of SumBits + 2 clocks; per climb one open mode a clock through the same pipeline and 3 more, 1
// to read the nearest mode's support, 1 to decide, touched events + 3 to label.
`include "evms_assert.svh"

module evms_serial_climbs #(
  parameter int PacketMax     = 1024,
  parameter int ModesMax      = 64,
  parameter int IterationsMax = 8,
  parameter int UnitShift     = 14,   // kFeatFrac + kClimbFrac: fraction bits of a climb feature
  parameter int CoordBits     = 19,   // a climb feature's bits: below 2^(CoordBits - UnitShift) bandwidths
  parameter int Bands         = 32,   // rows of one bandwidth the packet is sorted into (kGridSide)
  parameter int FeaturesInSpram = 1   // the features' memory asks Yosys for SPRAMs (common/evms_ram_1rw.sv)
) (
  input  logic                 clk,
  input  logic                 rst_n,
  // The packet's climb features (event i = load_i).
  input  logic                 load_we,
  input  logic [15:0]          load_i,
  input  logic [CoordBits-1:0] load_x,
  input  logic [CoordBits-1:0] load_y,
  // Running.
  input  logic                 start,
  input  logic [15:0]          n,
  input  logic [7:0]           cfg_max_iterations,
  input  logic [31:0]          cfg_tolerance,
  input  logic [63:0]          cfg_merge_radius2,
  output logic                 done,         // one clock
  output logic [15:0]          mode_count,
  output logic [15:0]          climbs,
  output logic [15:0]          steps,
  output logic [15:0]          modes_lost,
  // After done (one clock of latency): event rd_j's mode (-1: none), and mode rd_c's position
  // and support (the most events a climb that joined it held at its last step).
  input  logic [15:0]          rd_j,
  output logic signed [15:0]   rd_mode,
  input  logic [7:0]           rd_c,
  output logic [CoordBits-1:0] rd_mode_x,
  output logic [CoordBits-1:0] rd_mode_y,
  output logic [15:0]          rd_support
);
  localparam int IdxBits = PacketMax > 1 ? $clog2(PacketMax) : 1;
  localparam int CntBits = $clog2(PacketMax + 1);
  localparam int ModeBits = ModesMax > 1 ? $clog2(ModesMax) : 1;
  localparam int ModeCntBits = $clog2(ModesMax + 1);
  localparam int SumBits = CoordBits + CntBits;
  localparam int DistBits = UnitShift + 1;                  // differences below two bandwidths
  localparam int Dist2Bits = 2 * DistBits + 1;
  localparam logic [Dist2Bits-1:0] One = Dist2Bits'(1) << (2 * UnitShift);  // h^2
  localparam int BandBits = $clog2(Bands + 1);             // a row, or the end of the last
  `EVMS_ASSERT_INIT("a feature holds more than two bandwidths", CoordBits > DistBits)
  `EVMS_ASSERT_INIT("the event count must fit the 16-bit index range", CntBits <= 16)
  `EVMS_ASSERT_INIT("the rows must fit the features", Bands <= (1 << (CoordBits - UnitShift)))

  typedef enum logic [4:0] {
    StIdle, StSort, StSeedRead, StSeedCheck, StClimbStart, StStepInit, StRunLow, StRunHigh, StRunEnd, StKernel, StStepEnd,
    StDivideX, StDivideY, StJoinScan, StJoinRead, StJoinDecide, StLabel, StDone
  } state_e;
  state_e state_q;

  // ---- registers -------------------------------------------------------------------------
  logic [15:0]            j_q;               // the event seeds: the event
  logic [CntBits-1:0]     k_q, k_end_q;      // a step's scan: the next sorted event to read, and its run's end
  logic [CoordBits-1:0]   mx_q, my_q;        // the climb
  logic [7:0]             step_q;
  // The distance pipeline: s1 a point at its memory's output (a sorted event in the kernel, whose
  // flags are read then by its index in the packet, which the sorted memory gives; or a mode in
  // the join) and its difference to the climb; s2 the difference registered, its square, and the
  // test (with the kernel's flags). No stage copies a word it does not change: on a UP5K a
  // flip-flop that copies costs a logic cell a bit, and the squares fit in a clock at its pace.
  logic                   s1_valid_q, s2_valid_q;
  logic [IdxBits-1:0]     s2_j_q;                            // the kernel's event
  logic [ModeBits-1:0]    s1_c_q, s2_c_q;                    // the join's mode
  logic [CoordBits-1:0]   s2_x_q, s2_y_q;                    // the point
  logic [DistBits-1:0]    diff_x_q, diff_y_q;
  logic                   diff_far_q;
  logic [SumBits-1:0]     sum_x_q, sum_y_q;
  logic                   x_settled_q;       // the step moved x by at most the tolerance (while y divides)
  logic [CntBits-1:0]     count_q, touched_q;
  logic [ModeCntBits-1:0] scan_c_q, modes_q;
  logic                   best_valid_q;
  logic [ModeBits-1:0]    best_q;
  logic [Dist2Bits-1:0]   best_d2_q;
  logic signed [ModeBits:0] mode_q;          // the climb's mode, -1 when the table was full
  logic [CntBits-1:0]     t_q;               // labelling: the touched entry to read
  logic                   l1_valid_q, l2_valid_q;
  logic [IdxBits-1:0]     l2_j_q;
  logic [15:0]            climbs_q, steps_q, lost_q;

  // The row of a feature: its integer part in bandwidths, the last row beyond.
  function automatic logic [BandBits-1:0] band_of(input logic [CoordBits-1:0] v);
    logic [CoordBits-1:0] b;
    begin
      b = v >> UnitShift;
      band_of = b >= CoordBits'(Bands) ? BandBits'(Bands - 1) : BandBits'(b);
    end
  endfunction

  wire [7:0] iteration_cap = cfg_max_iterations < 8'(IterationsMax) ? cfg_max_iterations : 8'(IterationsMax);
  state_e join_state;
  assign join_state = modes_q == '0 ? StJoinDecide : StJoinScan;
  wire [IdxBits-1:0] j_index = IdxBits'(j_q);

  // ---- memories (common/evms_ram_1w1r; the events' features in common/evms_ram_1rw) --------
  // The packet's features in packet order (the first PacketMax words: the sort and the event
  // seeds read them) and in row order with each event's index in the packet (the next PacketMax:
  // the steps read them), in one single-ported memory (SPRAMs on a UP5K, FeaturesInSpram). No
  // clock both writes and reads it: the load writes while the climbs are idle; the sort reads an
  // event in one clock and writes it to its place two clocks later, while the read data holds;
  // the steps read it in StKernel and the seeds in StSeedRead, and neither writes.
  logic [CoordBits-1:0] phi_x, phi_y, sorted_x, sorted_y;
  logic [IdxBits-1:0]   sorted_j, unused_phi_j, sort_j;
  logic                 sort_place_we;
  logic [IdxBits-1:0]   sort_place_k;
  logic [IdxBits:0]     events_addr;
  always_comb begin
    if (load_we) events_addr = {1'b0, IdxBits'(load_i)};
    else if (sort_place_we) events_addr = {1'b1, sort_place_k};
    else if (state_q == StKernel) events_addr = {1'b1, IdxBits'(k_q)};
    else if (state_q == StSort) events_addr = {1'b0, sort_j};
    else events_addr = {1'b0, j_index};
  end
  evms_ram_1rw #(.Width(2 * CoordBits + IdxBits), .Depth(2 * PacketMax), .Huge(FeaturesInSpram)) u_events (
    .clk, .we(load_we || sort_place_we), .addr(events_addr),
    .wd(load_we ? {load_x, load_y, IdxBits'(load_i)} : {phi_x, phi_y, sort_j}), .rd({sorted_x, sorted_y, sorted_j}));
  assign {phi_x, phi_y, unused_phi_j} = {sorted_x, sorted_y, sorted_j};

  // The sort into rows, and the start of each row's run of sorted events.
  logic                sort_count_read, sort_done, unused_clearing;   // the flags clear with the count
  logic [BandBits-1:0] unused_clear_index;
  logic [CntBits-1:0]  row_start;
  logic [BandBits-1:0] run_ra;
  evms_counting_sort #(.PacketMax(PacketMax), .Keys(Bands)) u_sort (
    .clk, .rst_n, .start(start && (state_q == StIdle || state_q == StDone)), .n, .clearing(unused_clearing), .clear_index(unused_clear_index),
    .count_read(sort_count_read), .j(sort_j), .key(band_of(phi_y)), .place_we(sort_place_we), .place_k(sort_place_k),
    .done(sort_done), .run_ra, .run_start(row_start));

  // Each event's flags: reached by some climb, and in the current climb's list.
  logic               flag_reached, flag_in_climb, flags_we, flags_wd_in_climb;
  logic [IdxBits-1:0] flags_ra, flags_wa;
  evms_ram_1w1r #(.Width(2), .Depth(PacketMax), .CollisionUnused(1)) u_flags (
    .clk, .we(flags_we), .wa(flags_wa), .wd({!sort_count_read, flags_wd_in_climb}), .ra(flags_ra),
    .rd({flag_reached, flag_in_climb}));

  // Each event's first mode, valid where labelled.
  logic                labelled, first_mode_we;
  logic [ModeBits-1:0] first_mode;
  logic [IdxBits-1:0]  first_mode_ra, first_mode_wa;
  evms_ram_1w1r #(.Width(ModeBits + 1), .Depth(PacketMax), .CollisionUnused(1)) u_first_mode (
    .clk, .we(first_mode_we), .wa(first_mode_wa), .wd({!sort_count_read, ModeBits'(mode_q)}), .ra(first_mode_ra),
    .rd({labelled, first_mode}));

  // The current climb's events, in the order it reached them.
  logic [IdxBits-1:0] touched_j;
  logic [Dist2Bits-1:0] dist2;
  wire kernel_at_s2 = s2_valid_q && state_q != StJoinScan;
  wire kernel_in = !diff_far_q && dist2 < One;
  wire touched_we = kernel_at_s2 && kernel_in && !flag_in_climb;   // the flags of s2's event
  evms_ram_1w1r #(.Width(IdxBits), .Depth(PacketMax), .CollisionUnused(1)) u_touched (
    .clk, .we(touched_we), .wa(IdxBits'(touched_q)), .wd(s2_j_q), .ra(IdxBits'(t_q)), .rd(touched_j));

  // The modes: position (written as a mode opens) and support (as it opens, and raised by a
  // join), apart, so that a join writes the support alone and keeps no copy of the position.
  logic [CoordBits-1:0] mode_x, mode_y;
  logic [CntBits-1:0]   mode_support;
  logic                 mode_opens, support_we;
  logic [ModeBits-1:0]  mode_ra, support_wa;
  evms_ram_1w1r #(.Width(2 * CoordBits), .Depth(ModesMax), .CollisionUnused(1)) u_mode_positions (
    .clk, .we(mode_opens), .wa(ModeBits'(modes_q)), .wd({mx_q, my_q}), .ra(mode_ra), .rd({mode_x, mode_y}));
  evms_ram_1w1r #(.Width(CntBits), .Depth(ModesMax), .CollisionUnused(1)) u_mode_supports (
    .clk, .we(support_we), .wa(support_wa), .wd(count_q), .ra(mode_ra), .rd(mode_support));
  assign rd_mode_x = mode_x;
  assign rd_mode_y = mode_y;
  assign rd_support = 16'(mode_support);
  assign rd_mode = labelled ? 16'(first_mode) : -16'sd1;

  // ---- the divider: x, then y -------------------------------------------------------------
  logic div_start, div_done;
  logic [SumBits-1:0] quotient;
  evms_divide_rounded #(.NumBits(SumBits), .DenBits(CntBits)) u_divide (
    .clk, .rst_n, .start(div_start), .num(state_q == StDivideX && div_done ? sum_y_q : sum_x_q), .den(count_q),
    .done(div_done), .quotient(quotient));
  assign div_start = (state_q == StStepEnd && count_q != '0) || (state_q == StDivideX && div_done);

  // ---- the distance pipeline ----------------------------------------------------------------
  // The point at s1: the join's mode or the kernel's event, as their memories give them.
  wire [CoordBits-1:0] point_x = state_q == StJoinScan ? mode_x : sorted_x;
  wire [CoordBits-1:0] point_y = state_q == StJoinScan ? mode_y : sorted_y;
  // |a - b| by one subtraction and its sign (not a comparison and two subtractions).
  function automatic logic [CoordBits-1:0] distance(input logic [CoordBits-1:0] a, input logic [CoordBits-1:0] b);
    logic [CoordBits:0] delta;
    begin
      delta = {1'b0, a} - {1'b0, b};
      distance = delta[CoordBits] ? CoordBits'(-delta) : CoordBits'(delta);
    end
  endfunction
  // A difference at or beyond two bandwidths (far) is outside both the ball and the merge
  // radius, so only the low DistBits of the differences are squared.
  wire [CoordBits-1:0] abs_x = distance(mx_q, point_x);
  wire [CoordBits-1:0] abs_y = distance(my_q, point_y);
  wire far_x = |abs_x[CoordBits-1:DistBits];
  wire far_y = |abs_y[CoordBits-1:DistBits];
  always_ff @(posedge clk) begin
    diff_x_q <= DistBits'(abs_x);
    diff_y_q <= DistBits'(abs_y);
    diff_far_q <= far_x || far_y;
  end
  assign dist2 = Dist2Bits'(diff_x_q) * Dist2Bits'(diff_x_q) + Dist2Bits'(diff_y_q) * Dist2Bits'(diff_y_q);
  wire join_near = !diff_far_q && 64'(dist2) <= cfg_merge_radius2;

  // A step's move on each axis as its mean comes, x's before y's, so that mx_q takes the new x at
  // once with no copy kept: the larger move is within the tolerance when both are.
  wire [CoordBits-1:0] new_mean = CoordBits'(quotient);   // a mean is at most the largest feature
  wire [CoordBits-1:0] move = distance(new_mean, state_q == StDivideX ? mx_q : my_q);
  wire settled = 32'(move) <= cfg_tolerance;

  // ---- memory ports by state ----------------------------------------------------------------
  wire [BandBits-1:0] climb_band = band_of(my_q);
  always_comb begin
    flags_ra = state_q == StKernel ? sorted_j : j_index;   // s1's event, or the seed
    // A step's run: from the start of the row below the climb's to the start of the row above it
    // plus one (the rows clamped to the packet's).
    run_ra = state_q == StRunLow ? (climb_band == '0 ? '0 : climb_band - 1'b1)
                                 : (climb_band + 1'b1 >= BandBits'(Bands) ? BandBits'(Bands) : climb_band + BandBits'(2));
    flags_we = 1'b0;
    flags_wa = s2_j_q;
    flags_wd_in_climb = 1'b0;
    first_mode_ra = state_q == StLabel ? touched_j : IdxBits'(rd_j);
    first_mode_we = 1'b0;
    first_mode_wa = l2_j_q;
    mode_ra = state_q == StJoinScan ? ModeBits'(scan_c_q) : (state_q == StJoinRead ? best_q : ModeBits'(rd_c));
    mode_opens = 1'b0;
    support_we = 1'b0;
    support_wa = best_valid_q ? best_q : ModeBits'(modes_q);
    unique case (state_q)
      StSort: begin   // each event's flags clear while its row is counted
        flags_we = sort_count_read;
        flags_wa = sort_j;
        first_mode_we = sort_count_read;
        first_mode_wa = sort_j;
      end
      StKernel: begin   // a step's last events reach s2 in StKernel
        flags_we = kernel_at_s2 && kernel_in;
        flags_wd_in_climb = 1'b1;
      end
      StJoinDecide: begin
        // Opening a mode, or a join whose climb held more events than the mode's support (read
        // in StJoinRead).
        mode_opens = !best_valid_q && modes_q != ModeCntBits'(ModesMax);
        support_we = best_valid_q ? count_q > mode_support : mode_opens;
      end
      StLabel: begin
        // l1: the touched event leaves the climb (it was reached); l2: it takes the climb's mode
        // unless it has one.
        flags_we = l1_valid_q;
        flags_wa = touched_j;
        first_mode_we = l2_valid_q && !labelled && mode_q >= 0;
      end
      default: ;
    endcase
  end

  // ---- the controller and the datapath -----------------------------------------------------
  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      state_q <= StIdle;
      done <= 1'b0;
      {j_q, k_q, mx_q, my_q, step_q} <= '0;
      {s1_valid_q, s2_valid_q, s2_j_q, k_end_q} <= '0;
      {s1_c_q, s2_c_q, s2_x_q, s2_y_q} <= '0;
      {sum_x_q, sum_y_q, x_settled_q, count_q, touched_q, scan_c_q, modes_q} <= '0;
      {best_valid_q, best_q, best_d2_q} <= '0;
      {t_q, l1_valid_q, l2_valid_q, l2_j_q, climbs_q, steps_q, lost_q} <= '0;
      mode_q <= '0;
    end else begin
      done <= 1'b0;
      // The distance pipeline: only the kernel scan and the join scan issue into s1.
      s1_valid_q <= 1'b0;
      s2_valid_q <= s1_valid_q;
      s2_j_q <= sorted_j;
      s2_c_q <= s1_c_q;
      s2_x_q <= point_x;
      s2_y_q <= point_y;
      if (kernel_at_s2 && kernel_in) begin
        sum_x_q <= sum_x_q + SumBits'(s2_x_q);
        sum_y_q <= sum_y_q + SumBits'(s2_y_q);
        count_q <= count_q + 1'b1;
      end
      if (touched_we) touched_q <= touched_q + 1'b1;
      // The labelling's pipeline: l1 the touched entry read, l2 its first mode read.
      l1_valid_q <= 1'b0;
      l2_valid_q <= l1_valid_q;
      l2_j_q <= touched_j;
      unique case (state_q)
        // Idle, or done with the last packet (its results stay readable until the next start).
        StIdle, StDone: if (start) begin
          {climbs_q, steps_q, lost_q} <= '0;
          modes_q <= '0;
          state_q <= StSort;
        end
        StSort: if (sort_done) begin
          j_q <= '0;
          state_q <= StSeedRead;
        end
        // The event seeds: the first event no climb has reached yet, until none is left.
        StSeedRead: begin
          if (j_q >= n) begin
            done <= 1'b1;
            state_q <= StDone;
          end else begin
            state_q <= StSeedCheck;   // the flags and features of event j_q read
          end
        end
        StSeedCheck: begin
          j_q <= j_q + 1'b1;
          if (flag_reached) begin
            state_q <= StSeedRead;
          end else begin
            mx_q <= phi_x;
            my_q <= phi_y;
            state_q <= StClimbStart;
          end
        end
        // One climb.
        StClimbStart: begin
          climbs_q <= climbs_q + 1'b1;
          step_q <= '0;
          touched_q <= '0;
          count_q <= '0;
          scan_c_q <= '0;
          best_valid_q <= 1'b0;
          state_q <= iteration_cap == '0 ? join_state : StStepInit;
        end
        StStepInit: begin
          sum_x_q <= '0;
          sum_y_q <= '0;
          count_q <= '0;
          state_q <= StRunLow;
        end
        StRunLow: state_q <= StRunHigh;
        StRunHigh: begin
          k_q <= row_start;
          state_q <= StRunEnd;
        end
        StRunEnd: begin
          k_end_q <= row_start;
          state_q <= StKernel;
        end
        StKernel: begin
          // Issue (the sorted memory reads k); the flags' read, the difference, its square, the
          // test, the sums and the flags' write follow in the pipeline. The step ends when its
          // last event is at s2, whose sum is taken in the same clock.
          s1_valid_q <= k_q < k_end_q;
          if (k_q < k_end_q) k_q <= k_q + 1'b1;
          else if (!s1_valid_q) state_q <= StStepEnd;
        end
        StStepEnd: begin
          steps_q <= steps_q + 1'b1;
          state_q <= count_q == '0 ? join_state : StDivideX;
        end
        StDivideX: if (div_done) begin
          mx_q <= new_mean;
          x_settled_q <= settled;
          state_q <= StDivideY;
        end
        StDivideY: if (div_done) begin
          my_q <= new_mean;
          step_q <= step_q + 1'b1;
          if ((x_settled_q && settled) || step_q + 1'b1 >= iteration_cap) state_q <= join_state;
          else state_q <= StStepInit;
        end
        // Join the nearest mode within the merge radius (ties: the older, read first), else open
        // one.
        StJoinScan: begin
          s1_valid_q <= scan_c_q < modes_q;
          s1_c_q <= ModeBits'(scan_c_q);
          if (scan_c_q < modes_q) scan_c_q <= scan_c_q + 1'b1;
          if (s2_valid_q && join_near && (!best_valid_q || dist2 < best_d2_q)) begin
            best_valid_q <= 1'b1;
            best_q <= s2_c_q;
            best_d2_q <= dist2;
          end
          if (scan_c_q == modes_q && !s1_valid_q) state_q <= StJoinRead;   // s2's last test is this clock's
        end
        StJoinRead: state_q <= StJoinDecide;   // the nearest mode's support read
        StJoinDecide: begin
          if (best_valid_q) begin
            mode_q <= $signed((ModeBits + 1)'(best_q));
          end else if (modes_q == ModeCntBits'(ModesMax)) begin
            mode_q <= -1;
            lost_q <= lost_q + 1'b1;
          end else begin
            mode_q <= $signed((ModeBits + 1)'(modes_q));   // below ModesMax here
            modes_q <= modes_q + 1'b1;
          end
          t_q <= '0;
          state_q <= StLabel;
        end
        // The climb's events that have no mode yet take its mode; all leave the climb.
        StLabel: begin
          l1_valid_q <= t_q < touched_q;
          if (t_q < touched_q) t_q <= t_q + 1'b1;
          else if (!l1_valid_q && !l2_valid_q) state_q <= StSeedRead;
        end
        default: state_q <= StIdle;
      endcase
    end
  end

  assign mode_count = 16'(modes_q);
  assign climbs = climbs_q;
  assign steps = steps_q;
  assign modes_lost = lost_q;

  `EVMS_ASSERT("a packet holds at most PacketMax events", !(start && n > 16'(PacketMax)), clk, rst_n)
  `EVMS_ASSERT("a step's sums are complete when it ends: the distance pipeline has drained",
               state_q != StStepEnd || !(s1_valid_q || s2_valid_q), clk, rst_n)
  `EVMS_ASSERT("the join's decision follows its last test: the distance pipeline has drained",
               state_q != StJoinDecide || !(s1_valid_q || s2_valid_q), clk, rst_n)
  `EVMS_ASSERT("the merge radius is below two bandwidths", !start || cfg_merge_radius2 < 64'(4) * 64'(One), clk, rst_n)
endmodule
