// The polarity split, as hls/cluster/polarity_split.h (PolaritySplit::run): the large parts of a
// cluster's events (8-connected sets of cells) fall into groups, each part holding both
// polarities a group of its own and the others one group together (with cfg_split_partial low, a
// cluster with any such part keeps one group); a cluster of two or more groups becomes one
// cluster per group, and each small part joins the group of the large part whose centre is
// nearest. golden/cluster/polarity_split.h states the rule and why.
//
// The C++ model finds the parts over the cluster's events; this block over the cells they occupy,
// which gives the same parts in the same order: a part's smallest event is the first event of its
// first-occupied cell, and the cells are numbered in the order of their first events.
//   count  each event's mode after the links is copied into this block's mode memory, and each
//          mode's events are counted (registers);
//   cells  per cluster of at least 2 cfg_split_min_events events, each of its events (in event
//          order, found by a pass over the packet) reads its cell in the cell map; an empty cell
//          takes the next cell number and goes on the list; the event's cell and the cell's sums
//          (events, ON events, x, y) are kept;
//   links  each listed cell reads its four neighbours ahead of it (right, and the row below) and
//          joins their sets: root[] is always the smallest cell of each set, and a join rewrites
//          every root equal to the larger of the two in one clock (an equivalence table, as
//          evms_mode_links.sv keeps for the modes);
//   clear  each listed cell is cleared from the list, so the map is clear for the next cluster
//          (after reset, every cell is: Cells clocks before ready), and each cell's sums are
//          added to its root's;
//   large  the roots, in order, are the parts: large with cfg_split_min_events events and
//          cfg_split_share of the cluster (SplitFractionFrac fraction bits), and balanced when
//          |2 ON - events| << SplitFractionFrac < cfg_split_balance * events; each large part
//          takes its group: a new one when balanced (or cfg_split_partial is low), else the one
//          group of the parts that are not, opened by the first of them;
//   near   when the cluster splits, every part's centre (1/16 px, rounded half up) is divided
//          out, and each small part takes the large part with the smallest squared distance
//          (the first of equals);
//   move   each of the cluster's events takes its group's mode (the first group keeps the
//          cluster's, the others open modes after the existing ones) and adds its climb features
//          to that mode's sums;
//   modes  each new position is its sums' mean, rounded half up, and the mode is marked moved.
// A cluster whose groups or large parts would not fit in ModesMax modes stays whole (a large
// part keeps its centre in a ModesMax-entry table).
//
// Schedule: 1 to start; 2 clocks an event to count; per cluster checked, 2 an event of the packet
// and 1 more per event of the cluster (cells), 1 + 2 per neighbour within the map per cell
// (links), 2 per cell (clear), 1 per cell (large); a cluster that splits adds 2 divisions of
// DivBits + 2 clocks per part and one clock per large part per small part, 2 an event of the
// packet (move) and the divisions of its groups' modes.
// The packet's events (pixel and polarity, linked mode, climb features) are read through ev_j
// with the registered read of a block RAM; an event is not held: it stays on the read ports
// while ev_j does. After done, while idle, the result is read with the
// same timing: rd_mode (the event's mode) at rd_j, and at rd_c rd_moved, and where it is set the
// mode's new position rd_mode_x, rd_mode_y; a mode not moved keeps the climbs' position.
`include "evms_assert.svh"

module evms_polarity_split #(
  parameter int MaxWidth          = 1280,
  parameter int MaxHeight         = 720,
  parameter int PacketMax         = 256,
  parameter int ModesMax          = 64,
  parameter int CoordBits         = 32,   // a climb feature
  parameter int SplitCellFrac     = 16,   // hls::kSplitCellFrac
  parameter int SplitFractionFrac = 8     // hls::kSplitFractionFrac
) (
  input  logic                        clk,
  input  logic                        rst_n,
  output logic                        ready,     // the map is clear: start is taken while idle
  input  logic                        start,
  input  logic [15:0]                 n,
  input  logic [15:0]                 mode_count,
  input  logic [15:0]                 cfg_split_min_events,
  input  logic [15:0]                 cfg_split_balance,
  input  logic [15:0]                 cfg_split_share,
  input  logic [31:0]                 cfg_split_cell_scale_x,
  input  logic [31:0]                 cfg_split_cell_scale_y,
  input  logic                        cfg_split_partial,
  // The packet's events.
  output logic [15:0]                 ev_j,
  input  logic [15:0]                 ev_x,
  input  logic [15:0]                 ev_y,
  input  logic                        ev_p,
  input  logic signed [15:0]          ev_mode,   // after the links, -1 for none
  input  logic [CoordBits-1:0]        ev_fx,
  input  logic [CoordBits-1:0]        ev_fy,
  output logic                        done,      // one clock
  output logic [15:0]                 modes_after,
  // The result, after done.
  input  logic [15:0]                 rd_j,
  output logic signed [15:0]          rd_mode,
  input  logic [7:0]                  rd_c,
  output logic                        rd_moved,
  output logic [CoordBits-1:0]        rd_mode_x,
  output logic [CoordBits-1:0]        rd_mode_y
);
  localparam int CellsX = MaxWidth / 2 + 1;
  localparam int CellsY = MaxHeight / 2 + 1;
  localparam int Cells = CellsX * CellsY;
  localparam int CellBits = $clog2(Cells);
  localparam int CxBits = $clog2(CellsX);
  localparam int CyBits = $clog2(CellsY);
  localparam int PartBits = PacketMax > 1 ? $clog2(PacketMax) : 1;   // a cell's number in the cluster
  localparam int EventBits = PacketMax > 1 ? $clog2(PacketMax) : 1;
  localparam int CntBits = $clog2(PacketMax + 1);
  localparam int ModeBits = $clog2(ModesMax);
  localparam int SumBits = 16 + CntBits;                  // a part's sum of pixel coordinates
  localparam int CentreBits = SumBits + 4 + 1;            // 1/16 px, and a sign for differences
  localparam int MeanBits = CoordBits + CntBits;          // a part's sum of climb features
  localparam int DivBits = MeanBits > SumBits + 5 ? MeanBits + 1 : SumBits + 6;
  `EVMS_ASSERT_INIT("modes must be a power of two above one", ModesMax > 1 && (1 << ModeBits) == ModesMax)
  `EVMS_ASSERT_INIT("modes are read by an 8-bit index", ModesMax <= 256)
  `EVMS_ASSERT_INIT("cells are counted by the packet's events", PacketMax > 1)

  typedef enum logic [4:0] {
    StReset, StIdle, StCountAddr, StCountData, StCluster, StCellAddr, StCellData, StCellMap, StLinkAddr, StLinkList,
    StLinkRead, StLinkData, StClearAddr, StClearData, StLarge, StLargeCentre, StLargeCentreWait, StSmall, StSmallWait,
    StNearest, StMoveAddr, StMoveData, StMean, StMeanWait, StDone
  } state_e;
  state_e state_q, state_d;

  logic [15:0]         j_q, j_d;                 // event
  logic [15:0]         c_q, c_d;                 // the cluster being checked
  logic [15:0]         count_q, count_d;         // modes so far
  logic [CntBits-1:0]  k_q, k_d;                 // a cell (part)
  logic [CntBits-1:0]  cells_q, cells_d;         // the cluster's cells
  logic [CntBits-1:0]  large_q, large_d;         // its large parts
  logic                balanced_q, balanced_d;   // every large part so far holds both polarities
  logic [CntBits-1:0]  groups_q, groups_d;       // the groups its large parts fall into so far
  logic                one_pol_q, one_pol_d;     // the group of the parts of one polarity is open ...
  logic [ModeBits-1:0] one_pol_group_q, one_pol_group_d;   // ... and is this one
  logic [ModeBits:0]   m_q, m_d;                 // a large part
  logic [1:0]          ahead_q, ahead_d;         // the neighbour being read
  logic [CxBits-1:0]   cx_q, cx_d;               // the listed cell being linked
  logic [CyBits-1:0]   cy_q, cy_d;
  logic [CellBits-1:0] cell_q, cell_d;           // the cell being cleared after reset
  logic [CentreBits-1:0] small_x_q, small_x_d, small_y_q, small_y_d;   // the small part's centre
  logic [63:0]         best_q, best_d;           // the nearest large part's squared distance so far
  logic [ModeBits-1:0] best_m_q, best_m_d;

  // ---- dividers: both axes at once ---------------------------------------------------------------
  logic               div_start, div_done, div_y_done;
  logic [DivBits-1:0] div_num_x, div_num_y, quotient_x, quotient_y;
  logic [CntBits-1:0] div_den;
  evms_divide_rounded #(.NumBits(DivBits), .DenBits(CntBits)) u_divide_x (
    .clk, .rst_n, .start(div_start), .num(div_num_x), .den(div_den), .done(div_done), .quotient(quotient_x));
  evms_divide_rounded #(.NumBits(DivBits), .DenBits(CntBits)) u_divide_y (
    .clk, .rst_n, .start(div_start), .num(div_num_y), .den(div_den), .done(div_y_done), .quotient(quotient_y));

  // ---- memories ---------------------------------------------------------------------------------
  // The cell map: occupied, and the cell's number.
  logic                  map_we;
  logic [CellBits-1:0]   map_wa, map_ra;
  wire [PartBits-1:0]    cells_part = PartBits'(cells_q);   // the next cell's number
  logic [PartBits:0]     map_wd, map_rd;
  evms_ram_1w1r #(.Width(PartBits + 1), .Depth(Cells)) u_map (
    .clk, .we(map_we), .wa(map_wa), .wd(map_wd), .ra(map_ra), .rd(map_rd));
  // The cluster's cells in the order they were taken: {row, column}.
  logic                     list_we;
  logic [CyBits+CxBits-1:0] list_rd;
  evms_ram_1w1r #(.Width(CyBits + CxBits), .Depth(PacketMax)) u_list (
    .clk, .we(list_we), .wa(PartBits'(cells_q)), .wd({ev_cy, ev_cx}), .ra(PartBits'(k_q)), .rd(list_rd));
  // Each event's cell (while its cluster is checked) and its mode.
  logic                  cell_of_we, mode_we;
  logic [PartBits-1:0]   cell_of_wd, cell_of_rd;
  logic [EventBits-1:0]  mode_ra;
  logic signed [15:0]    mode_wd, mode_rd;
  evms_ram_1w1r #(.Width(PartBits), .Depth(PacketMax)) u_cell_of (
    .clk, .we(cell_of_we), .wa(EventBits'(j_q)), .wd(cell_of_wd), .ra(EventBits'(j_q)), .rd(cell_of_rd));
  evms_ram_1w1r #(.Width(16), .Depth(PacketMax)) u_mode (
    .clk, .we(mode_we), .wa(EventBits'(j_q)), .wd(mode_wd), .ra(mode_ra), .rd(mode_rd));
  // The moved modes' positions (named: Yosys 0.23 sizes a cast inside a concatenation by its operand).
  wire [CoordBits-1:0] mean_x_new = CoordBits'(quotient_x), mean_y_new = CoordBits'(quotient_y);
  logic                   mode_xy_we;
  logic [ModeBits-1:0]    mode_xy_wa;
  logic [2*CoordBits-1:0] mode_xy_rd;
  evms_ram_1w1r #(.Width(2 * CoordBits), .Depth(ModesMax)) u_mode_xy (
    .clk, .we(mode_xy_we), .wa(mode_xy_wa), .wd({mean_x_new, mean_y_new}), .ra(ModeBits'(rd_c)),
    .rd(mode_xy_rd));
  assign mode_ra = state_q == StIdle ? EventBits'(rd_j) : EventBits'(j_q);
  assign rd_mode = mode_rd;
  assign {rd_mode_x, rd_mode_y} = mode_xy_rd;

  // ---- register files ------------------------------------------------------------------------------
  logic [CntBits-1:0]   size_q [ModesMax];        // each mode's events
  logic [ModesMax-1:0]  moved_q;
  logic [PacketMax*PartBits-1:0] root_q, root_d;   // per cell t (bits t PartBits up), the smallest cell of its set
  // Per cell, then per part at its root: events, ON events, and the sums of x and y.
  logic [CntBits-1:0]   part_events_q [PacketMax];
  logic [CntBits-1:0]   part_on_q [PacketMax];
  logic [SumBits-1:0]   part_x_q [PacketMax];
  logic [SumBits-1:0]   part_y_q [PacketMax];
  logic [PacketMax-1:0] is_large_q;
  logic [ModeBits-1:0]  target_q [PacketMax];     // per part: the group its events go to
  logic [ModeBits-1:0]  group_q [ModesMax];       // per large part: its group
  logic [PartBits-1:0]  large_root_q [ModesMax];
  logic [CentreBits-1:0] large_x_q [ModesMax];    // the large parts' centres, 1/16 px
  logic [CentreBits-1:0] large_y_q [ModesMax];
  logic [MeanBits-1:0]  mean_x_q [ModesMax];      // the groups' sums of climb features
  logic [MeanBits-1:0]  mean_y_q [ModesMax];
  logic [CntBits-1:0]   mean_n_q [ModesMax];
  always_ff @(posedge clk) rd_moved <= moved_q[ModeBits'(rd_c)];

  // ---- the event's cell, a neighbour's, and the join of two sets -----------------------------------
  logic [CxBits-1:0]   ev_cx;
  logic [CyBits-1:0]   ev_cy;
  logic [CellBits-1:0] ev_cell;
  assign ev_cx = CxBits'((64'(ev_x) * 64'(cfg_split_cell_scale_x)) >> SplitCellFrac);
  assign ev_cy = CyBits'((64'(ev_y) * 64'(cfg_split_cell_scale_y)) >> SplitCellFrac);
  assign ev_cell = CellBits'(32'(ev_cy) * CellsX + 32'(ev_cx));
  // The four neighbours ahead of a cell: (1, 0), (-1, 1), (0, 1), (1, 1); the other four see it.
  logic [CxBits:0] near_x;
  logic [CyBits:0] near_y;
  logic            near_in_map;
  assign near_x = ahead_q == 2'd1 ? (CxBits + 1)'(cx_q) - 1'b1 : (CxBits + 1)'(cx_q) + (CxBits + 1)'(ahead_q != 2'd2);
  assign near_y = (CyBits + 1)'(cy_q) + (CyBits + 1)'(ahead_q != 2'd0);
  assign near_in_map = !(ahead_q == 2'd1 && cx_q == 0) && 32'(near_x) < CellsX && 32'(near_y) < CellsY;
  logic [PartBits-1:0] join_a, join_b, join_lo, join_hi;
  logic                join_en;
  assign join_a = k_root;
  assign join_b = root_q[32'(map_rd[PartBits-1:0]) * PartBits +: PartBits];
  assign join_lo = join_a < join_b ? join_a : join_b;
  assign join_hi = join_a < join_b ? join_b : join_a;

  // ---- the part k: large, balanced ----------------------------------------------------------------
  logic [CntBits-1:0] k_events, k_on, cluster_size;
  logic [PartBits-1:0] k_part, k_root;
  logic               k_is_root, k_is_large, k_is_balanced;
  logic [CntBits:0]   k_imbalance;
  assign k_part = PartBits'(k_q);
  assign k_events = part_events_q[k_part];
  assign k_on = part_on_q[k_part];
  assign cluster_size = size_q[ModeBits'(c_q)];
  assign k_root = root_q[32'(k_part) * PartBits +: PartBits];
  assign k_is_root = k_root == k_part;
  assign k_is_large = k_is_root && 32'(k_events) >= 32'(cfg_split_min_events) &&
                      (64'(k_events) << SplitFractionFrac) >= 64'(cfg_split_share) * 64'(cluster_size);
  assign k_imbalance = 2 * (CntBits + 1)'(k_on) >= (CntBits + 1)'(k_events) ? 2 * (CntBits + 1)'(k_on) - (CntBits + 1)'(k_events)
                                                                                : (CntBits + 1)'(k_events) - 2 * (CntBits + 1)'(k_on);
  assign k_is_balanced = (64'(k_imbalance) << SplitFractionFrac) < 64'(cfg_split_balance) * 64'(k_events);
  // Large part k's group: its own, or the one group of the parts of one polarity.
  logic                k_own_group;
  logic [ModeBits-1:0] k_group;
  assign k_own_group = k_is_balanced || !cfg_split_partial || !one_pol_q;
  assign k_group = k_own_group ? ModeBits'(groups_q) : one_pol_group_q;
  logic split_ok;   // the cluster splits, once its parts are numbered
  assign split_ok = large_q >= 2 && (cfg_split_partial ? groups_q >= 2 : balanced_q) && fits;
  // The squared distance from the small part's centre to large part m's.
  logic [ModeBits-1:0] m_part;
  logic signed [CentreBits:0] dx, dy;
  logic [63:0] distance2;
  assign m_part = ModeBits'(m_q);
  assign dx = $signed({1'b0, small_x_q}) - $signed({1'b0, large_x_q[m_part]});
  assign dy = $signed({1'b0, small_y_q}) - $signed({1'b0, large_y_q[m_part]});
  assign distance2 = 64'(dx * dx) + 64'(dy * dy);
  // The mode group m takes, and whether the cluster's groups fit in the mode table.
  logic [15:0] m_mode;
  assign m_mode = m_q == 0 ? c_q : count_q + 16'(m_q) - 16'd1;
  logic fits;
  assign fits = 32'(count_q) + 32'(groups_q) - 1 <= ModesMax && 32'(large_q) <= ModesMax;
  // The event's part, while moving it.
  logic [ModeBits-1:0] ev_target;
  assign ev_target = target_q[root_q[32'(cell_of_rd) * PartBits +: PartBits]];

  // ---- control --------------------------------------------------------------------------------------
  always_comb begin
    state_d = state_q;
    j_d = j_q;
    c_d = c_q;
    count_d = count_q;
    k_d = k_q;
    cells_d = cells_q;
    large_d = large_q;
    balanced_d = balanced_q;
    groups_d = groups_q;
    one_pol_d = one_pol_q;
    one_pol_group_d = one_pol_group_q;
    m_d = m_q;
    ahead_d = ahead_q;
    cx_d = cx_q;
    cy_d = cy_q;
    cell_d = cell_q;
    small_x_d = small_x_q;
    small_y_d = small_y_q;
    best_d = best_q;
    best_m_d = best_m_q;
    map_we = 1'b0;
    map_wa = cell_q;
    map_wd = '0;
    map_ra = ev_cell;
    list_we = 1'b0;
    cell_of_we = 1'b0;
    cell_of_wd = '0;
    mode_we = 1'b0;
    mode_wd = ev_mode;
    mode_xy_we = 1'b0;
    mode_xy_wa = ModeBits'(m_mode);
    join_en = 1'b0;
    div_start = 1'b0;
    div_num_x = '0;
    div_num_y = '0;
    div_den = '0;
    done = 1'b0;
    case (state_q)
      // Every cell of the map to empty.
      StReset: begin
        map_we = 1'b1;
        cell_d = cell_q + 1'b1;
        if (32'(cell_q) + 1 >= Cells) state_d = StIdle;
      end
      StIdle: if (start) begin
        j_d = '0;
        count_d = mode_count;
        state_d = StCountAddr;
      end
      StCountAddr: state_d = j_q == n ? StCluster : StCountData;
      // Event j's linked mode is here: keep it, count it.
      StCountData: begin
        mode_we = 1'b1;
        j_d = j_q + 1'b1;
        state_d = StCountAddr;
      end
      StCluster: begin
        j_d = '0;
        k_d = '0;
        cells_d = '0;
        if (c_q == mode_count) begin
          state_d = StDone;
        end else if (32'(cluster_size) < 2 * 32'(cfg_split_min_events)) begin
          c_d = c_q + 1'b1;
        end else begin
          state_d = StCellAddr;
        end
      end
      StCellAddr: begin
        k_d = '0;
        state_d = j_q == n ? StLinkAddr : StCellData;
      end
      // Event j and its mode are here: a member reads its cell.
      StCellData: begin
        if (mode_rd == $signed(c_q)) begin
          state_d = StCellMap;
        end else begin
          j_d = j_q + 1'b1;
          state_d = StCellAddr;
        end
      end
      // Its cell's entry is here (the event is still on the read ports): an empty cell takes the
      // next number.
      StCellMap: begin
        cell_of_we = 1'b1;
        if (!map_rd[PartBits]) begin
          map_we = 1'b1;
          map_wa = ev_cell;
          map_wd = {1'b1, cells_part};
          list_we = 1'b1;
          cell_of_wd = PartBits'(cells_q);
          cells_d = cells_q + 1'b1;
        end else begin
          cell_of_wd = map_rd[PartBits-1:0];
        end
        j_d = j_q + 1'b1;
        state_d = StCellAddr;
      end
      // Cell k's position is being read.
      StLinkAddr: begin
        if (k_q == cells_q) begin
          k_d = '0;
          state_d = StClearAddr;
        end else begin
          state_d = StLinkList;
        end
      end
      StLinkList: begin
        {cy_d, cx_d} = list_rd;
        ahead_d = '0;
        state_d = StLinkRead;
      end
      StLinkRead: begin
        map_ra = CellBits'(32'(near_y) * CellsX + 32'(near_x));
        if (near_in_map) begin
          state_d = StLinkData;
        end else begin
          ahead_d = ahead_q + 1'b1;
          if (ahead_q == 2'd3) begin
            k_d = k_q + 1'b1;
            state_d = StLinkAddr;
          end
        end
      end
      // The neighbour's entry is here: an occupied neighbour joins cell k's set.
      StLinkData: begin
        join_en = map_rd[PartBits];
        ahead_d = ahead_q + 1'b1;
        if (ahead_q == 2'd3) begin
          k_d = k_q + 1'b1;
          state_d = StLinkAddr;
        end else begin
          state_d = StLinkRead;
        end
      end
      StClearAddr: begin
        if (k_q == cells_q) begin
          k_d = '0;
          large_d = '0;
          balanced_d = 1'b1;
          groups_d = '0;
          one_pol_d = 1'b0;
          state_d = StLarge;
        end else begin
          state_d = StClearData;
        end
      end
      // Cell k's position is here: empty it (its sums go to its root, in the register files).
      StClearData: begin
        map_we = 1'b1;
        map_wa = CellBits'(32'(list_rd[CxBits+:CyBits]) * CellsX + 32'(list_rd[CxBits-1:0]));
        k_d = k_q + 1'b1;
        state_d = StClearAddr;
      end
      StLarge: begin
        if (k_q != cells_q) begin
          if (k_is_large) begin
            large_d = large_q + 1'b1;
            balanced_d = balanced_q && k_is_balanced;
            if (k_own_group) groups_d = groups_q + 1'b1;
            if (!k_is_balanced && cfg_split_partial && !one_pol_q) begin
              one_pol_d = 1'b1;
              one_pol_group_d = ModeBits'(groups_q);
            end
          end
          k_d = k_q + 1'b1;
        end else if (split_ok) begin
          m_d = '0;
          state_d = StLargeCentre;
        end else begin
          c_d = c_q + 1'b1;
          state_d = StCluster;
        end
      end
      // The large parts' centres.
      StLargeCentre: begin
        if (32'(m_q) == 32'(large_q)) begin
          k_d = '0;
          state_d = StSmall;
        end else begin
          div_start = 1'b1;
          div_num_x = DivBits'({part_x_q[large_root_q[m_part]], 4'b0});
          div_num_y = DivBits'({part_y_q[large_root_q[m_part]], 4'b0});
          div_den = part_events_q[large_root_q[m_part]];
          state_d = StLargeCentreWait;
        end
      end
      StLargeCentreWait: if (div_done) begin
        m_d = m_q + 1'b1;
        state_d = StLargeCentre;
      end
      // Each small part's centre, then its nearest large part.
      StSmall: begin
        if (k_q == cells_q) begin
          j_d = '0;
          state_d = StMoveAddr;
        end else if (k_is_root && !is_large_q[k_part]) begin
          div_start = 1'b1;
          div_num_x = DivBits'({part_x_q[k_part], 4'b0});
          div_num_y = DivBits'({part_y_q[k_part], 4'b0});
          div_den = k_events;
          state_d = StSmallWait;
        end else begin
          k_d = k_q + 1'b1;
        end
      end
      StSmallWait: if (div_done) begin
        small_x_d = CentreBits'(quotient_x);
        small_y_d = CentreBits'(quotient_y);
        m_d = '0;
        state_d = StNearest;
      end
      StNearest: begin
        if (m_q == 0 || distance2 < best_q) begin
          best_d = distance2;
          best_m_d = m_part;
        end
        m_d = m_q + 1'b1;
        if (32'(m_q) + 1 == 32'(large_q)) begin
          k_d = k_q + 1'b1;
          state_d = StSmall;
        end
      end
      StMoveAddr: begin
        m_d = '0;
        state_d = j_q == n ? StMean : StMoveData;
      end
      // Event j, its mode and its cell are here: a member takes its part's mode.
      StMoveData: begin
        if (mode_rd == $signed(c_q)) begin
          mode_we = 1'b1;
          mode_wd = ev_target == 0 ? $signed(c_q) : $signed(count_q + 16'(ev_target) - 16'd1);
        end
        j_d = j_q + 1'b1;
        state_d = StMoveAddr;
      end
      // The groups' modes' positions.
      StMean: begin
        if (32'(m_q) == 32'(groups_q)) begin
          count_d = count_q + 16'(groups_q) - 16'd1;
          c_d = c_q + 1'b1;
          state_d = StCluster;
        end else begin
          div_start = 1'b1;
          div_num_x = DivBits'(mean_x_q[m_part]);
          div_num_y = DivBits'(mean_y_q[m_part]);
          div_den = mean_n_q[m_part];
          state_d = StMeanWait;
        end
      end
      StMeanWait: if (div_done) begin
        mode_xy_we = 1'b1;
        m_d = m_q + 1'b1;
        state_d = StMean;
      end
      StDone: begin
        done = 1'b1;
        c_d = '0;
        state_d = StIdle;
      end
      default: state_d = StIdle;
    endcase
  end

  // The register files, written by the states above (a clear or a join writes a whole file in
  // one clock).
  wire new_cell = state_q == StCellMap && !map_rd[PartBits];
  wire [PartBits-1:0] old_cell = map_rd[PartBits-1:0];
  always_ff @(posedge clk) begin
    if (state_q == StIdle && start) begin
      for (int c = 0; c < ModesMax; c++) size_q[c] <= '0;
    end else if (state_q == StCountData && ev_mode >= 0) begin
      size_q[ModeBits'(ev_mode)] <= size_q[ModeBits'(ev_mode)] + 1'b1;
    end
  end
  // The whole table is rewritten by a join only (the test is outside the loop, so that a
  // simulator does not walk the table every clock).
  always_comb begin
    root_d = root_q;
    if (new_cell) begin
      root_d[32'(cells_part) * PartBits +: PartBits] = cells_part;
    end else if (join_en) begin
      for (int t = 0; t < PacketMax; t++) begin
        if (root_q[32'(t) * PartBits +: PartBits] == join_hi) root_d[32'(t) * PartBits +: PartBits] = join_lo;
      end
    end
  end
  always_ff @(posedge clk) root_q <= root_d;
  // A cell's sums go to its root, a smaller cell, whose own sums are whole by then.
  wire merge_cell = state_q == StClearData && !k_is_root;
  always_ff @(posedge clk) begin
    if (new_cell) begin
      part_events_q[PartBits'(cells_q)] <= CntBits'(1);
      part_on_q[PartBits'(cells_q)] <= CntBits'(ev_p);
      part_x_q[PartBits'(cells_q)] <= SumBits'(ev_x);
      part_y_q[PartBits'(cells_q)] <= SumBits'(ev_y);
    end else if (state_q == StCellMap) begin
      part_events_q[old_cell] <= part_events_q[old_cell] + 1'b1;
      part_on_q[old_cell] <= part_on_q[old_cell] + CntBits'(ev_p);
      part_x_q[old_cell] <= part_x_q[old_cell] + SumBits'(ev_x);
      part_y_q[old_cell] <= part_y_q[old_cell] + SumBits'(ev_y);
    end else if (merge_cell) begin
      part_events_q[k_root] <= part_events_q[k_root] + k_events;
      part_on_q[k_root] <= part_on_q[k_root] + k_on;
      part_x_q[k_root] <= part_x_q[k_root] + part_x_q[k_part];
      part_y_q[k_root] <= part_y_q[k_root] + part_y_q[k_part];
    end
  end
  always_ff @(posedge clk) begin
    if (state_q == StLarge && k_q != cells_q) begin
      is_large_q[k_part] <= k_is_large;
      if (k_is_large) begin
        target_q[k_part] <= k_group;
        if (32'(large_q) < ModesMax) begin
          large_root_q[ModeBits'(large_q)] <= k_part;
          group_q[ModeBits'(large_q)] <= k_group;
        end
      end
    end
    if (state_q == StNearest && 32'(m_q) + 1 == 32'(large_q)) target_q[k_part] <= group_q[m_q == 0 || distance2 < best_q ? m_part : best_m_q];
    if (state_q == StLargeCentreWait && div_done) begin
      large_x_q[m_part] <= CentreBits'(quotient_x);
      large_y_q[m_part] <= CentreBits'(quotient_y);
    end
  end
  wire clear_means = state_q == StLargeCentre && 32'(m_q) == 32'(large_q);
  wire move_event = state_q == StMoveData && mode_rd == $signed(c_q);
  always_ff @(posedge clk) begin
    if (clear_means) begin
      for (int m = 0; m < ModesMax; m++) begin
        mean_x_q[m] <= '0;
        mean_y_q[m] <= '0;
        mean_n_q[m] <= '0;
      end
    end else if (move_event) begin
      mean_x_q[ev_target] <= mean_x_q[ev_target] + MeanBits'(ev_fx);
      mean_y_q[ev_target] <= mean_y_q[ev_target] + MeanBits'(ev_fy);
      mean_n_q[ev_target] <= mean_n_q[ev_target] + 1'b1;
    end
  end
  always_ff @(posedge clk) begin
    if (state_q == StIdle && start) moved_q <= '0;
    else if (mode_xy_we) moved_q[mode_xy_wa] <= 1'b1;
  end

  assign ready = state_q != StReset;
  assign ev_j = j_q;
  assign modes_after = count_q;
  `EVMS_ASSERT("start only when idle", !start || state_q == StIdle, clk, rst_n)
  `EVMS_ASSERT("a mode must be below the mode count", !(state_q == StCountData && ev_mode >= 0) || ev_mode < $signed(mode_count), clk, rst_n)
  `EVMS_ASSERT("a cell scale must keep cells within the map", !(state_q == StCellData) || 32'(ev_cell) < Cells, clk, rst_n)

  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      state_q <= StReset;
      j_q <= '0;
      c_q <= '0;
      count_q <= '0;
      k_q <= '0;
      cells_q <= '0;
      large_q <= '0;
      balanced_q <= 1'b1;
      groups_q <= '0;
      one_pol_q <= 1'b0;
      one_pol_group_q <= '0;
      m_q <= '0;
      ahead_q <= '0;
      cx_q <= '0;
      cy_q <= '0;
      cell_q <= '0;
      small_x_q <= '0;
      small_y_q <= '0;
      best_q <= '0;
      best_m_q <= '0;
    end else begin
      state_q <= state_d;
      j_q <= j_d;
      c_q <= c_d;
      count_q <= count_d;
      k_q <= k_d;
      cells_q <= cells_d;
      large_q <= large_d;
      balanced_q <= balanced_d;
      groups_q <= groups_d;
      one_pol_q <= one_pol_d;
      one_pol_group_q <= one_pol_group_d;
      m_q <= m_d;
      ahead_q <= ahead_d;
      cx_q <= cx_d;
      cy_q <= cy_d;
      cell_q <= cell_d;
      small_x_q <= small_x_d;
      small_y_q <= small_y_d;
      best_q <= best_d;
      best_m_q <= best_m_d;
    end
  end
endmodule
