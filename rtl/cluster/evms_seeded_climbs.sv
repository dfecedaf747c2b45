// Seeded mean-shift climbs with a flat kernel, as hls/cluster/seeded_climbs.h (SeededClimbs::run),
// bit for bit: the events' climb features (x, y in bandwidth units, UnitShift fraction bits)
// are sorted into a GridSide x GridSide grid of one-bandwidth cells; the warm seeds climb with
// their own balls and then every event no climb has reached yet climbs with the ball of radius
// one bandwidth. A climb step sums the events in the ball over the 2 reach + 1 rows of cells
// around the climb's cell, moves to their mean (exact division, rounded half up), and stops on
// an empty ball, a move within the tolerance or the iteration cap. The converged climb joins
// the nearest mode within the merge radius or opens one; the events it reached that have no
// mode yet take it. A mode's support is the most events a climb that joined it held at its
// last step; an event of a mode whose support is below n * cfg_min_density reads as noise
// (the sum is made while the flags clear, the test at each join: no clock more). With
// cfg_density_after_links the events keep their modes and the core reads each mode's test
// (rd_c_sparse) to make it on the linked sets instead (hls/cluster/sparse_sets.h).
//
// Schedule:
//   sort    rtl/cluster/evms_counting_sort.sv: Cells + 1 clearing the cell counts, 3 an event
//           counting, Cells + 3 for the prefix sums, 3 an event placing;
//   climbs  per step: per row of cells 3 to read its run, one event a clock and 1 more, through
//           a 4-stage pipeline (read; difference to the climb; squares; test and accumulate)
//           that drains while the next row's run is read, 2 to drain after the last row, and
//           when the ball held events a divide of SumBits + 2 clocks (x and y at once);
//           per climb: one open mode a clock through the same pipeline, 2 to drain, 1 to
//           decide, touched events + 2 to label.
// The kernel's events and the join's modes share the pipeline's difference and squared-distance
// registers: a memory's read, the subtraction, the squares and the comparisons are each a
// clock's path of their own.
// Memories have one write port and a registered read port (common/evms_ram_1w1r). The per-event
// flags (reached, in the current climb, labelled) are one-bit memories with one address each and
// a combinational read (distributed RAM on a Xilinx part, not 256 registers with a decoder and a
// multiplexer each); they are cleared while the grid's counts are (Cells + 1 >= PacketMax clocks).
`include "evms_assert.svh"

module evms_seeded_climbs #(
  parameter int PacketMax     = 256,
  parameter int ModesMax      = 64,
  parameter int GridSide      = 32,
  parameter int ReachMax      = 8,
  parameter int IterationsMax = 8,
  parameter int UnitShift     = 19,   // kFeatFrac + kClimbFrac: fraction bits of a climb feature
  parameter int DensityFrac   = 24,   // fraction bits of cfg_min_density (kDensityFrac)
  parameter int CoordBits     = 32
) (
  input  logic                 clk,
  input  logic                 rst_n,
  // The packet's climb features (event i = load_i).
  input  logic                 load_we,
  input  logic [15:0]          load_i,
  input  logic [CoordBits-1:0] load_x,
  input  logic [CoordBits-1:0] load_y,
  // The warm seeds: the previous packet's modes and the squared radius of each one's ball.
  input  logic                 warm_we,
  input  logic [7:0]           warm_k,
  input  logic [CoordBits-1:0] warm_x,
  input  logic [CoordBits-1:0] warm_y,
  input  logic [63:0]          warm_ball2,
  // Running.
  input  logic                 start,
  input  logic [15:0]          n,
  input  logic [7:0]           warm_count,
  input  logic                 cfg_warm_start,
  input  logic [7:0]           cfg_max_iterations,
  input  logic [31:0]          cfg_tolerance,
  input  logic [63:0]          cfg_merge_radius2,
  input  logic [31:0]          cfg_min_density,   // DensityFrac fraction bits; 0: off
  input  logic                 cfg_density_after_links,   // leave the test to the core (rd_c_sparse)
  output logic                 done,         // one clock
  output logic [15:0]          mode_count,
  output logic [15:0]          climbs,
  output logic [15:0]          steps,
  output logic [15:0]          modes_lost,
  output logic [47:0]          least,        // n * cfg_min_density (DensityFrac fraction bits), from the sort on
  // After done (one clock of latency): event rd_j's mode (-1: none) and feature, and mode rd_c.
  input  logic [15:0]          rd_j,
  output logic signed [15:0]   rd_mode,
  output logic [CoordBits-1:0] rd_x,
  output logic [CoordBits-1:0] rd_y,
  input  logic [7:0]           rd_c,
  output logic [CoordBits-1:0] rd_mode_x,
  output logic [CoordBits-1:0] rd_mode_y,
  output logic                 rd_c_sparse    // mode rd_c is below the least density (combinational)
);
  localparam int IdxBits = PacketMax > 1 ? $clog2(PacketMax) : 1;
  localparam int CntBits = $clog2(PacketMax + 1);
  localparam int Cells = GridSide * GridSide;
  localparam int CellBits = $clog2(Cells + 1);
  localparam int AxisBits = $clog2(GridSide + 1) + 1;       // signed cell coordinates
  localparam int ReachBits = $clog2(ReachMax + 1);
  localparam int ModeBits = ModesMax > 1 ? $clog2(ModesMax) : 1;
  localparam int ModeCntBits = $clog2(ModesMax + 1);
  localparam int SumBits = CoordBits + CntBits;
  localparam int DistBits = UnitShift + ReachBits;          // differences squared: below 2^ReachBits bandwidths
  localparam logic [63:0] One = 64'(1) << (2 * UnitShift);  // h^2
  `EVMS_ASSERT_INIT("a squared ball radius must fit 64 bits", 2 * UnitShift + 2 * $clog2(ReachMax + 1) < 64)
  `EVMS_ASSERT_INIT("the grid's cells must fit the 16-bit event index range", CntBits <= 16)
  `EVMS_ASSERT_INIT("the grid's clearing must reach every event's flags", Cells + 1 >= PacketMax)

  typedef enum logic [4:0] {
    StIdle, StSort, StSeedWarm, StSeedWarmLoad, StSeedEvent, StSeedEventLoad, StClimbStart, StStepInit, StRowLow, StRowHigh,
    StRowRange, StKernel, StStepEnd, StDivide, StJoinScan, StJoinDecide, StLabel, StDone
  } state_e;
  state_e state_q;

  // The cell of a coordinate: its integer part in bandwidths, clamped to the grid.
  function automatic [AxisBits-1:0] cell_of(input [CoordBits-1:0] v);
    logic [CoordBits-1:0] c;
    begin
      c = v >> UnitShift;
      cell_of = c >= CoordBits'(GridSide) ? AxisBits'(GridSide - 1) : AxisBits'(c);
    end
  endfunction

  // ---- registers -------------------------------------------------------------------------
  logic [15:0]          j_q;                 // event index of the sort passes and the event seeds
  logic [7:0]           seed_k_q;            // warm seed index
  logic                 seeding_warm_q;
  logic [CoordBits-1:0] mx_q, my_q;
  logic [63:0]          ball2_q;
  logic [ReachBits-1:0] reach_q;
  logic [7:0]           step_q;
  logic [AxisBits-1:0]  row_q, row_last_q, x0_q, x1_q;
  logic [CntBits-1:0]   k_q, k_end_q;        // the row's run of sorted events
  // The distance pipeline: s1 a point read (an event in the kernel, a mode in the join), s2 its
  // difference to the climb registered (diff_*_q), s3 its squared distance (dist2_q). Stages s2
  // and s3 advance every clock, so a row's last events finish while the next row's run is read.
  logic                 s1_valid_q, s2_valid_q, s3_valid_q;
  logic [CoordBits-1:0] s2_x_q, s2_y_q, s3_x_q, s3_y_q;   // the kernel's event at s2 and s3, and its index
  logic [IdxBits-1:0]   s2_j_q, s3_j_q;
  logic [ModeBits-1:0]  s1_c_q, s2_c_q, s3_c_q;           // the join's mode at s1, s2 and s3
  logic [SumBits-1:0]   sum_x_q, sum_y_q;
  logic [CntBits-1:0]   count_q, touched_q;
  logic [ModeCntBits-1:0] scan_c_q;         // the join's next mode to read
  logic                 best_valid_q;
  logic [ModeBits-1:0]  best_q;
  logic [63:0]          best_d2_q;
  logic [ModeCntBits-1:0] modes_q;
  logic signed [ModeBits:0] mode_q;          // the climb's mode, -1 when the table was full
  logic [CntBits-1:0]   t_q;                 // labelling: touched index read
  logic                 lv_q;                // labelling: a read is in flight
  logic [15:0]          climbs_q, steps_q, lost_q;
  // A mode's support (the most events a climb that joined it held at its last step) and whether
  // that is below the packet's least, n * cfg_min_density, summed while the flags clear.
  localparam int LeastBits = CntBits + 32;
  logic [LeastBits-1:0] least_q;
  logic [CntBits-1:0]   support_q [ModesMax];
  logic                 sparse_q [ModesMax];
  assign least = 48'(least_q);

  // Where a converged climb goes: the scan of the open modes, or straight to opening one.
  state_e join_state;
  assign join_state = modes_q == '0 ? StJoinDecide : StJoinScan;
  wire [7:0] iteration_cap = cfg_max_iterations < 8'(IterationsMax) ? cfg_max_iterations : 8'(IterationsMax);

  // ---- memories (common/evms_ram_1w1r) ----------------------------------------------------
  // The event index of the sort passes and the event seeds, as a memory address (a named wire:
  // Yosys 0.23 sizes a cast inside a concatenation by the operand, not the cast).
  wire [IdxBits-1:0] j_index = IdxBits'(j_q);

  // The packet's features.
  logic [CoordBits-1:0] phi_x_q, phi_y_q;
  logic [IdxBits-1:0]   phi_ra;
  evms_ram_1w1r #(.Width(2 * CoordBits), .Depth(PacketMax)) u_phi (
    .clk, .we(load_we), .wa(IdxBits'(load_i)), .wd({load_x, load_y}), .ra(phi_ra), .rd({phi_x_q, phi_y_q}));
  assign rd_x = phi_x_q;
  assign rd_y = phi_y_q;

  // The sort into cells (common to evms_serial_climbs' rows), and the start of each cell's run of
  // sorted events. The clearing of its counts clears the per-event flags (Cells + 1 >= PacketMax)
  // and sums the packet's least density.
  logic                sort_clearing, sort_place_we, sort_done, unused_count_read;   // the flags clear with the counts
  logic [CellBits-1:0] sort_clear_index, start_ra;
  logic [IdxBits-1:0]  sort_j;
  logic [IdxBits-1:0]  sort_place_k;
  logic [CntBits-1:0]  start_q;
  evms_counting_sort #(.PacketMax(PacketMax), .Keys(Cells)) u_sort (
    .clk, .rst_n, .start(start && (state_q == StIdle || state_q == StDone)), .n, .clearing(sort_clearing),
    .clear_index(sort_clear_index), .count_read(unused_count_read), .j(sort_j), .key(count_cell), .place_we(sort_place_we),
    .place_k(sort_place_k), .done(sort_done), .run_ra(start_ra), .run_start(start_q));

  // The events in cell order, with their packet index.
  logic [CoordBits-1:0] sorted_x_q, sorted_y_q;
  logic [IdxBits-1:0]   event_q;
  evms_ram_1w1r #(.Width(2 * CoordBits + IdxBits), .Depth(PacketMax)) u_sorted (
    .clk, .we(sort_place_we), .wa(sort_place_k), .wd({phi_x_q, phi_y_q, sort_j}), .ra(IdxBits'(k_q)),
    .rd({sorted_x_q, sorted_y_q, event_q}));

  // The per-event flags. Each has one address a state chooses; StClear writes zeros.
  wire               flags_clearing = sort_clearing && 32'(sort_clear_index) < PacketMax;
  wire [IdxBits-1:0] clear_index = IdxBits'(sort_clear_index);
  logic [IdxBits-1:0] touched_rd_q;
  logic reached_mem [PacketMax], in_climb_mem [PacketMax], labelled_mem [PacketMax];
  // A kernel event at s3: the pipeline's last stage outside the join scan (a row's last events
  // finish while the next row's run is read).
  wire               kernel_at_s3 = s3_valid_q && state_q != StJoinScan;
  // reached: set by the kernel, read by the event seeds.
  wire [IdxBits-1:0] reached_addr = flags_clearing ? clear_index : kernel_at_s3 ? s3_j_q : j_index;
  wire               reached = reached_mem[reached_addr];
  wire               reached_we = flags_clearing || (kernel_at_s3 && kernel_in);
  // in_climb: set by the kernel, cleared by the labelling.
  wire [IdxBits-1:0] in_climb_addr = flags_clearing ? clear_index : state_q == StLabel ? touched_rd_q : s3_j_q;
  wire               in_climb = in_climb_mem[in_climb_addr];
  // labelled: read and set by the labelling, read through rd_j after done.
  wire [IdxBits-1:0] labelled_addr = flags_clearing ? clear_index : state_q == StLabel ? touched_rd_q : IdxBits'(rd_j);
  wire               labelled = labelled_mem[labelled_addr];

  // The current climb's events, in the order it reached them.
  wire touched_we = kernel_at_s3 && kernel_in && !in_climb;
  evms_ram_1w1r #(.Width(IdxBits), .Depth(PacketMax)) u_touched (
    .clk, .we(touched_we), .wa(IdxBits'(touched_q)), .wd(s3_j_q), .ra(IdxBits'(t_q)), .rd(touched_rd_q));

  // Each event's mode, valid where labelled.
  logic [ModeBits-1:0] first_mode_q;
  wire first_mode_we = lv_q && !labelled && mode_q >= 0;
  evms_ram_1w1r #(.Width(ModeBits), .Depth(PacketMax)) u_first_mode (
    .clk, .we(first_mode_we), .wa(touched_rd_q), .wd(ModeBits'(mode_q)), .ra(IdxBits'(rd_j)), .rd(first_mode_q));
  logic rd_labelled_q;
  always_ff @(posedge clk) begin
    rd_labelled_q <= labelled;
    if (reached_we) reached_mem[reached_addr] <= !flags_clearing;
    if (flags_clearing || touched_we || (state_q == StLabel && lv_q)) in_climb_mem[in_climb_addr] <= touched_we && !flags_clearing;
    if (flags_clearing || first_mode_we) labelled_mem[labelled_addr] <= !flags_clearing;
  end
  // An event of a sparse mode reads as noise, unless the core tests the density on the linked
  // sets (rtl/core/evms_core.sv, StDense).
  assign rd_mode = rd_labelled_q && (cfg_density_after_links || !sparse_q[first_mode_q]) ? 16'(first_mode_q) : -16'sd1;
  assign rd_c_sparse = sparse_q[ModeBits'(rd_c)];

  // A converged climb's support becomes its mode's when the mode opens, or when it is more than the
  // joined mode's (count_q holds the climb's last step's events at the join).
  wire [ModeBits-1:0] support_c = best_valid_q ? best_q : ModeBits'(modes_q);
  wire support_we = state_q == StJoinDecide && (best_valid_q ? count_q > support_q[best_q] : modes_q != ModeCntBits'(ModesMax));
  always_ff @(posedge clk) begin
    if (support_we) begin
      support_q[support_c] <= count_q;
      sparse_q[support_c] <= LeastBits'({count_q, DensityFrac'(0)}) < least_q;
    end
  end

  // The modes.
  logic [CoordBits-1:0] mode_x_q, mode_y_q;
  logic [ModeBits-1:0]  mode_ra;
  wire mode_we = state_q == StJoinDecide && !best_valid_q && modes_q != ModeCntBits'(ModesMax);
  evms_ram_1w1r #(.Width(2 * CoordBits), .Depth(ModesMax)) u_modes (
    .clk, .we(mode_we), .wa(ModeBits'(modes_q)), .wd({mx_q, my_q}), .ra(mode_ra), .rd({mode_x_q, mode_y_q}));
  assign rd_mode_x = mode_x_q;
  assign rd_mode_y = mode_y_q;

  // The warm seeds.
  logic [CoordBits-1:0] warm_x_q, warm_y_q;
  logic [63:0]          warm_b2_q;
  evms_ram_1w1r #(.Width(2 * CoordBits + 64), .Depth(ModesMax)) u_warm (
    .clk, .we(warm_we), .wa(ModeBits'(warm_k)), .wd({warm_x, warm_y, warm_ball2}), .ra(ModeBits'(seed_k_q)),
    .rd({warm_x_q, warm_y_q, warm_b2_q}));

  // ---- the two dividers: the step's new position ------------------------------------------
  logic div_start, div_done, div_y_done;
  logic [SumBits-1:0] quotient_x, quotient_y;
  evms_divide_rounded #(.NumBits(SumBits), .DenBits(CntBits)) u_divide_x (
    .clk, .rst_n, .start(div_start), .num(sum_x_q), .den(count_q), .done(div_done), .quotient(quotient_x));
  evms_divide_rounded #(.NumBits(SumBits), .DenBits(CntBits)) u_divide_y (
    .clk, .rst_n, .start(div_start), .num(sum_y_q), .den(count_q), .done(div_y_done), .quotient(quotient_y));
  assign div_start = state_q == StStepEnd && count_q != '0;

  // ---- combinational: addresses, the kernel test, the reach of a ball ------------------------
  // The ball's reach in cells: the least r >= 1 with (r bandwidths)^2 >= ball2, at most ReachMax.
  logic [ReachBits-1:0] reach_of_ball;
  always_comb begin
    reach_of_ball = ReachBits'(ReachMax);
    for (int r = ReachMax - 1; r >= 1; r--) begin
      if ((64'(r * r) << (2 * UnitShift)) >= ball2_q) reach_of_ball = ReachBits'(r);
    end
  end

  // Squared distances. A ball reaches at most ReachMax bandwidths and the merge radius is below
  // 2^ReachBits bandwidths (both asserted below), so a difference of 2^DistBits or more puts a
  // pair outside either whatever the other coordinate: only DistBits-bit differences are squared.
  function automatic logic [DistBits-1:0] magnitude(input [CoordBits-1:0] a, input [CoordBits-1:0] b, output logic far);
    logic [CoordBits-1:0] d;
    begin
      d = a > b ? a - b : b - a;
      far = d >= CoordBits'(64'(1) << DistBits);
      magnitude = DistBits'(d);
    end
  endfunction
  // The point at s1: the join's mode, or the kernel's event (in a kernel row or the next row's
  // three clocks of setup, where the row's last events drain).
  wire [CoordBits-1:0] point_x = state_q == StJoinScan ? mode_x_q : sorted_x_q;
  wire [CoordBits-1:0] point_y = state_q == StJoinScan ? mode_y_q : sorted_y_q;
  logic far_x, far_y;
  logic [DistBits-1:0] diff_x, diff_y;
  always_comb begin
    diff_x = magnitude(mx_q, point_x, far_x);
    diff_y = magnitude(my_q, point_y, far_y);
  end
  logic [DistBits-1:0] diff_x_q, diff_y_q;
  logic                diff_far_q, dist2_far_q;
  logic [63:0]         dist2_q;
  always_ff @(posedge clk) begin
    diff_x_q <= diff_x;
    diff_y_q <= diff_y;
    diff_far_q <= far_x || far_y;
    dist2_q <= 64'(diff_x_q) * 64'(diff_x_q) + 64'(diff_y_q) * 64'(diff_y_q);
    dist2_far_q <= diff_far_q;
  end
  wire kernel_in = !dist2_far_q && dist2_q < ball2_q;
  wire join_near = !dist2_far_q && dist2_q <= cfg_merge_radius2;

  // The climb's cell and the rows and columns of cells its ball reaches, clamped to the grid.
  wire signed [AxisBits:0] climb_cx = $signed({1'b0, cell_of(mx_q)});
  wire signed [AxisBits:0] climb_cy = $signed({1'b0, cell_of(my_q)});
  wire signed [AxisBits:0] climb_r = $signed((AxisBits + 1)'(reach_q));
  wire signed [AxisBits:0] last_cell = (AxisBits + 1)'(GridSide - 1);

  wire [CoordBits-1:0] new_x = CoordBits'(quotient_x), new_y = CoordBits'(quotient_y);
  wire [CoordBits-1:0] move_x = new_x > mx_q ? new_x - mx_q : mx_q - new_x;
  wire [CoordBits-1:0] move_y = new_y > my_q ? new_y - my_q : my_q - new_y;
  wire [CoordBits-1:0] move = move_x > move_y ? move_x : move_y;

  wire [CellBits-1:0] row_base = CellBits'(row_q) * CellBits'(GridSide);
  wire [CellBits-1:0] count_cell = CellBits'(cell_of(phi_y_q)) * CellBits'(GridSide) + CellBits'(cell_of(phi_x_q));

  always_comb begin
    phi_ra = state_q == StIdle || state_q == StDone ? IdxBits'(rd_j) : state_q == StSort ? sort_j : j_index;
    mode_ra = state_q == StJoinScan ? ModeBits'(scan_c_q) : ModeBits'(rd_c);
    start_ra = state_q == StRowLow ? row_base + CellBits'(x0_q) : row_base + CellBits'(x1_q) + 1'b1;   // StRowHigh
  end

  // ---- the controller and the datapath -----------------------------------------------------
  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      state_q <= StIdle;
      done <= 1'b0;
      {j_q, seed_k_q, seeding_warm_q} <= '0;
      {mx_q, my_q, ball2_q, reach_q, step_q, row_q, row_last_q, x0_q, x1_q, k_q, k_end_q} <= '0;
      {s1_valid_q, s2_valid_q, s3_valid_q, s2_x_q, s2_y_q, s3_x_q, s3_y_q, s2_j_q, s3_j_q, s1_c_q, s2_c_q, s3_c_q} <= '0;
      {sum_x_q, sum_y_q, count_q, touched_q, scan_c_q, best_valid_q, best_q, best_d2_q} <= '0;
      {modes_q, t_q, lv_q, climbs_q, steps_q, lost_q} <= '0;
      mode_q <= '0;
      least_q <= '0;
    end else begin
      done <= 1'b0;
      // The distance pipeline: only the kernel rows and the join scan issue into s1.
      s1_valid_q <= 1'b0;
      s2_valid_q <= s1_valid_q;
      s3_valid_q <= s2_valid_q;
      s2_x_q <= sorted_x_q;
      s2_y_q <= sorted_y_q;
      s2_j_q <= event_q;
      s2_c_q <= s1_c_q;
      s3_x_q <= s2_x_q;
      s3_y_q <= s2_y_q;
      s3_j_q <= s2_j_q;
      s3_c_q <= s2_c_q;
      if (kernel_at_s3 && kernel_in) begin
        sum_x_q <= sum_x_q + SumBits'(s3_x_q);
        sum_y_q <= sum_y_q + SumBits'(s3_y_q);
        count_q <= count_q + 1'b1;
      end
      if (touched_we) touched_q <= touched_q + 1'b1;
      unique case (state_q)
        // Idle, or done with the last packet (its results stay readable until the next start).
        StIdle, StDone: if (start) begin
          {climbs_q, steps_q, lost_q} <= '0;
          modes_q <= '0;
          least_q <= '0;
          state_q <= StSort;
        end
        // Sorting into cells (u_sort); its clearing sums the least density.
        StSort: begin
          if (sort_clearing && 16'(sort_clear_index) < n) least_q <= least_q + LeastBits'(cfg_min_density);
          if (sort_done) begin
            j_q <= '0;
            seed_k_q <= '0;
            seeding_warm_q <= 1'b1;
            state_q <= StSeedWarm;
          end
        end
        // Seeds: the warm ones, then every event not reached yet.
        StSeedWarm: begin
          if (cfg_warm_start && seed_k_q < warm_count && seed_k_q < 8'(ModesMax)) begin
            state_q <= StSeedWarmLoad;
          end else begin
            seeding_warm_q <= 1'b0;
            j_q <= '0;
            state_q <= StSeedEvent;
          end
        end
        StSeedWarmLoad: begin
          mx_q <= warm_x_q;
          my_q <= warm_y_q;
          ball2_q <= warm_b2_q;
          seed_k_q <= seed_k_q + 1'b1;
          state_q <= StClimbStart;
        end
        StSeedEvent: begin
          if (j_q >= n) begin
            done <= 1'b1;
            state_q <= StDone;
          end else if (reached) begin
            j_q <= j_q + 1'b1;
          end else begin
            state_q <= StSeedEventLoad;
          end
        end
        StSeedEventLoad: begin
          mx_q <= phi_x_q;
          my_q <= phi_y_q;
          ball2_q <= One;
          j_q <= j_q + 1'b1;
          state_q <= StClimbStart;
        end
        // One climb.
        StClimbStart: begin
          climbs_q <= climbs_q + 1'b1;
          reach_q <= reach_of_ball;
          step_q <= '0;
          touched_q <= '0;
          count_q <= '0;
          state_q <= iteration_cap == '0 ? join_state : StStepInit;
          scan_c_q <= '0;
          best_valid_q <= 1'b0;
        end
        StStepInit: begin
          row_q <= climb_cy - climb_r < 0 ? '0 : AxisBits'(climb_cy - climb_r);
          row_last_q <= climb_cy + climb_r > last_cell ? AxisBits'(last_cell) : AxisBits'(climb_cy + climb_r);
          x0_q <= climb_cx - climb_r < 0 ? '0 : AxisBits'(climb_cx - climb_r);
          x1_q <= climb_cx + climb_r > last_cell ? AxisBits'(last_cell) : AxisBits'(climb_cx + climb_r);
          sum_x_q <= '0;
          sum_y_q <= '0;
          count_q <= '0;
          state_q <= StRowLow;
        end
        StRowLow: state_q <= StRowHigh;
        StRowHigh: begin
          k_q <= start_q;
          state_q <= StRowRange;
        end
        StRowRange: begin
          k_end_q <= start_q;
          state_q <= StKernel;
        end
        StKernel: begin
          // Issue (the memories read k); the difference, its square, the test and the sums follow
          // in the pipeline. The next row starts after the last issue; the step ends when the last
          // event is at s3, whose sum is taken in the same clock.
          s1_valid_q <= k_q < k_end_q;
          if (k_q < k_end_q) k_q <= k_q + 1'b1;
          if (k_q >= k_end_q) begin
            if (row_q != row_last_q) begin
              row_q <= row_q + 1'b1;
              state_q <= StRowLow;
            end else if (!s1_valid_q && !s2_valid_q) begin   // s3's last sum is this clock's
              state_q <= StStepEnd;
            end
          end
        end
        StStepEnd: begin
          steps_q <= steps_q + 1'b1;
          state_q <= count_q == '0 ? join_state : StDivide;
        end
        StDivide: if (div_done) begin
          mx_q <= new_x;
          my_q <= new_y;
          step_q <= step_q + 1'b1;
          if (move <= cfg_tolerance || step_q + 1'b1 >= iteration_cap) begin
            state_q <= join_state;
          end else begin
            state_q <= StStepInit;
          end
        end
        // Join the nearest mode within the merge radius (ties: the older, read first), else open
        // one: issue (the modes' memory reads scan_c), the difference, the test.
        StJoinScan: begin
          s1_valid_q <= scan_c_q < modes_q;
          s1_c_q <= ModeBits'(scan_c_q);
          if (scan_c_q < modes_q) scan_c_q <= scan_c_q + 1'b1;
          if (s3_valid_q && join_near && (!best_valid_q || dist2_q < best_d2_q)) begin
            best_valid_q <= 1'b1;
            best_q <= s3_c_q;
            best_d2_q <= dist2_q;
          end
          if (scan_c_q == modes_q && !s1_valid_q && !s2_valid_q) state_q <= StJoinDecide;   // s3's last test is this clock's
        end
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
          lv_q <= 1'b0;
          state_q <= StLabel;
        end
        // The climb's events that have no mode yet take its mode; all leave the climb.
        StLabel: begin
          lv_q <= t_q < touched_q;
          if (t_q < touched_q) t_q <= t_q + 1'b1;
          if (t_q >= touched_q && !lv_q) state_q <= seeding_warm_q ? StSeedWarm : StSeedEvent;
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
               state_q != StStepEnd || !(s1_valid_q || s2_valid_q || s3_valid_q), clk, rst_n)
  `EVMS_ASSERT("the join's decision follows its last test: the distance pipeline has drained",
               state_q != StJoinDecide || !(s1_valid_q || s2_valid_q || s3_valid_q), clk, rst_n)
  `EVMS_ASSERT("a ball reaches at most ReachMax bandwidths", state_q != StClimbStart || ball2_q <= 64'(ReachMax * ReachMax) * One, clk, rst_n)
  `EVMS_ASSERT("the merge radius is below 2^ReachBits bandwidths", !start || cfg_merge_radius2 < (64'(1) << (2 * DistBits)), clk, rst_n)
endmodule
