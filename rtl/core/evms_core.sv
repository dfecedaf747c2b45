// The evms core, as hls/core/core.h: filter -> packets -> features -> clustering -> centroids
// -> tracking -> labels, with valid/ready streams and full backpressure: no event is ever
// dropped. The intake (core/evms_intake.sv: the filter, the climb features) runs ahead of the
// controller through a packet-deep queue, so the input waits only when that queue is full.
//
// Clustering takes one of two paths, chosen by cfg_seeded among those the build holds
// (HasGaussianPath, HasSeededPath): the Gaussian mean shift of every event and the merging of
// its modes, or the seeded climbs with the flat kernel (cluster/evms_seeded_climbs.sv), the
// links of clusters that touch (cluster/evms_mode_links.sv), in a build that holds them the polarity
// split (cluster/evms_polarity_split.sv) and the edge join (cluster/evms_edge_join.sv), and the
// clusters kept with their warm seeds for the next packet (cluster/evms_warm_seeds.sv).
//
// Word by word, as the controller takes it from the intake: an event that passed the filter (or
// is noise) joins the pending queue, and,
// when kept, the packet. A packet closes when it holds cfg_packet_size events, when the next
// kept event is more than cfg_packet_max_span_us newer than its first, when the pending queue
// is full, or on a flush word. Closing clusters and tracks the packet, sends its summary, and
// releases every pending event with its label. A noise event that arrives while no packet is
// open is released at once. The parameters are one Shape (hls/core/shape.h), generated into
// rtl/generated/evms_cfg_*.svh.
`include "evms_assert.svh"

module evms_core #(
  `include "evms_core_shape_params.svh"
) (
  input  logic        clk,
  input  logic        rst_n,
  // Registers (hls/core/registers.h).
  `include "evms_core_cfg_ports.svh"
  // Events in.
  `include "evms_stream_in_sink_ports.svh"
  // Labelled events out, in input order.
  `include "evms_stream_lab_source_ports.svh"
  // Track updates out.
  output logic        trk_valid,
  input  logic        trk_ready,
  output logic [31:0] trk_t,
  output logic [31:0] trk_id,
  output logic [31:0] trk_x,
  output logic [31:0] trk_y,
  output logic [31:0] trk_vx,
  output logic [31:0] trk_vy,
  output logic [31:0] trk_zx,
  output logic [31:0] trk_zy,
  output logic        trk_confirmed,        // else tentative (cfg_report_tentative)
  output logic [15:0] trk_events,           // the measurement's event count ...
  output logic [15:0] trk_x_min,            // ... and its bounding box, px
  output logic [15:0] trk_y_min,
  output logic [15:0] trk_x_max,
  output logic [15:0] trk_y_max,
  output logic [63:0] trk_var_x,            // the position variances, CovFrac fraction bits, px^2
  output logic [63:0] trk_var_y,
  // Packet summaries out.
  output logic        pkt_valid,
  input  logic        pkt_ready,
  output logic [31:0] pkt_t_first,
  output logic [31:0] pkt_t_last,
  output logic [15:0] pkt_events,
  output logic [7:0]  pkt_clusters,
  output logic [15:0] pkt_iterations,      // Gaussian sweeps, or seeded climb steps
  // Status.
  output logic        idle,                // waiting for a word, nothing held
  output logic [31:0] stat_tracks_started,
  output logic [31:0] stat_unassigned
);
  localparam int FeatBits = FeatInt + FeatFrac;
  localparam int ModeBits = FeatBits + 1;
  localparam int PendingCountBits = $clog2(PendingDepth + 1);   // counts 0..PendingDepth
  localparam int PacketCountBits = $clog2(PacketMax + 1);
  localparam int PendingIndexBits = $clog2(PendingDepth);       // indexes
  localparam int PacketIndexBits = $clog2(PacketMax);
  localparam logic [63:0] FeatMax = (64'd1 << FeatBits) - 1;
  // The seeded path's climb features: x * cfg_climb_scale_x >> ClimbShift, UnitShift fraction bits.
  localparam int UnitShift = FeatFrac + ClimbFrac;
  localparam int ClimbShift = ClimbScaleFrac - UnitShift;
  localparam int ModeIndexBits = ModesMax > 1 ? $clog2(ModesMax) : 1;
  `EVMS_ASSERT_INIT("a core clusters by at least one path", HasGaussianPath != 0 || HasSeededPath != 0)

  // ---- memories ---------------------------------------------------------------------------
  // Each has one write port and one registered read port, so that it maps to block RAM.
  // Pending queue: every event since the last release, with its index in the packet or -1.
  localparam int PendingWordBits = 32 + 16 + 16 + 1 + 16;   // t, x, y, p, the packet index
  logic [PendingWordBits-1:0] pend_mem [PendingDepth];
  logic             pend_we;
  logic [PendingWordBits-1:0] pend_wdata, pend_rdata_q;
  // The open packet, and each of its events' cluster.
  logic [64:0] pk_mem [PacketMax];
  logic        first_on_pixel_mem [PacketMax];   // per packet event: the first with a mode on its pixel (links)
  logic [64:0] pk_rdata_q;
  logic signed [7:0] cluster_of [PacketMax];

  // Packet RAM read port (features, centroids) and cluster_of port (merge, centroids, release).
  logic [15:0] rd_pk_i, co_i;
  logic [15:0] rd_pk_x, rd_pk_y;
  logic        rd_pk_p;
  logic [31:0] rd_pk_t;
  logic        rd_pk_first;   // the event read is the first with a mode on its pixel (the links write it)
  logic signed [7:0] co_rdata_q;

  // ---- the event being handled --------------------------------------------------------------
  logic [31:0] e_t_q;
  logic [15:0] e_x_q, e_y_q;
  logic        e_p_q;
  logic [31:0] e_climb_x_q, e_climb_y_q;
  logic [PacketCountBits-1:0] n_q;          // kept events in the packet
  logic [PendingCountBits-1:0] pend_n_q;     // events waiting
  logic [31:0] t_first_q, t_last_q;
  logic        append_after_q;  // the closing event still has to join the next packet

  // ---- intake: the filter and the climb features, running ahead in a packet-deep queue ---------
  logic q_valid /*verilator public_flat_rd*/;  // read by the cycle profile (sim/rtl_core.h)
  logic intake_empty /*verilator public_flat_rd*/;
  logic q_pop, q_p, q_flush, q_kept;
  logic [31:0] q_t, q_climb_x, q_climb_y;
  logic [15:0] q_x, q_y;
  evms_intake #(
    .MaxWidth(MaxWidth), .MaxHeight(MaxHeight), .TimestampBits(TimestampBits), .TimestampShift(TimestampShift),
    .NoiseIntervalLog2(NoiseIntervalLog2), .QueueDepth(PacketMax), .HasClimbScale(HasSeededPath), .ClimbShift(ClimbShift)
  ) u_intake (
    .clk(clk), .rst_n(rst_n),
    `include "evms_filter_cfg_connect.svh"
    .cfg_climb_scale_x(cfg_climb_scale_x), .cfg_climb_scale_y(cfg_climb_scale_y),
    `include "evms_stream_in_connect.svh"
    .q_valid(q_valid), .q_pop(q_pop), .q_t(q_t), .q_x(q_x), .q_y(q_y), .q_p(q_p),
    .q_flush(q_flush), .q_kept(q_kept), .q_climb_x(q_climb_x), .q_climb_y(q_climb_y), .empty(intake_empty));

  // ---- shared multiplier and reciprocal -------------------------------------------------------
  logic feat_mul_start_q;
  logic signed [63:0] feat_mul_a_q, feat_mul_b_q;
  logic mul_start, mul_busy, mul_done;  // consumers wait for done, so busy is only for lint
  logic signed [63:0] mul_a, mul_b, mul_p;
  evms_mul #(.DigitBits(MulDigitBits)) u_mul (
    .clk(clk), .rst_n(rst_n), .start(mul_start), .a(mul_a), .b(mul_b), .busy(mul_busy), .done(mul_done), .p(mul_p));
  logic recip_start, recip_done;
  logic [63:0] recip_x;
  logic [RecipFrac:0] recip_r;
  logic [6:0] recip_m;
  evms_recip #(.TableLog2(RecipTableLog2), .RecipFrac(RecipFrac), .TableFile(RecipTableFile)) u_recip (
    .clk(clk), .rst_n(rst_n), .start(recip_start), .x(recip_x), .done(recip_done), .r(recip_r), .m(recip_m));

  // ---- the Gaussian path: mean shift of every event, then merging of the modes ------------------
  logic ms_load_we_q, ms_start_q, ms_done;
  logic [15:0] ms_load_i_q, ms_rd_i;
  logic [FeatBits-1:0] ms_lx_q, ms_ly_q, ms_lp_q, ms_lt_q;
  logic [7:0] ms_sweeps;
  logic ms_recip_start;
  logic [63:0] ms_recip_x;
  logic mg_start_q, mg_done, mg_co_we;
  logic [15:0] mg_rd_i, mg_co_i;
  logic signed [7:0] mg_co_value;
  logic [7:0] mg_clusters;
  if (HasGaussianPath != 0) begin : g_gaussian
    logic [ModeBits-1:0] ms_rx, ms_ry, ms_rp, ms_rt;   // a mode, read by the merging
    evms_mean_shift #(
      .PacketMax(PacketMax), .Lanes(Lanes), .IterationsMax(IterationsMax), .FeatBits(FeatBits), .FeatFrac(FeatFrac),
      .WeightFrac(WeightFrac), .SumFrac(SumFrac), .ExpTableLog2(ExpTableLog2), .ExpInterpBits(ExpInterpBits),
      .RecipFrac(RecipFrac), .ExpTableFile(ExpTableFile)
    ) u_mean_shift (
      .clk(clk), .rst_n(rst_n), .load_we(ms_load_we_q), .load_i(ms_load_i_q), .load_x(ms_lx_q), .load_y(ms_ly_q), .load_p(ms_lp_q),
      .load_t(ms_lt_q), .start(ms_start_q), .n(16'(n_q)), .cfg_max_iterations(cfg_max_iterations), .cfg_tolerance(cfg_tolerance),
      .done(ms_done), .sweeps(ms_sweeps), .rd_i(ms_rd_i), .rd_x(ms_rx), .rd_y(ms_ry), .rd_p(ms_rp), .rd_t(ms_rt),
      .recip_start(ms_recip_start), .recip_x(ms_recip_x), .recip_done(recip_done), .recip_r(recip_r), .recip_m(recip_m));
    evms_merge #(.ClustersMax(ClustersMax), .ModeBits(ModeBits)) u_merge (
      .clk(clk), .rst_n(rst_n), .start(mg_start_q), .n(16'(n_q)), .cfg_merge_radius2(cfg_merge_radius2),
      .cfg_min_cluster_size(cfg_min_cluster_size), .cfg_max_clusters(cfg_max_clusters), .rd_i(mg_rd_i), .rd_x(ms_rx),
      .rd_y(ms_ry), .rd_p(ms_rp), .rd_t(ms_rt), .co_we(mg_co_we), .co_i(mg_co_i), .co_value(mg_co_value),
      .co_rdata(co_rdata_q), .done(mg_done), .clusters(mg_clusters));
  end else begin : g_no_gaussian
    assign {ms_done, ms_sweeps, ms_recip_start, ms_recip_x} = '0;
    assign {mg_done, mg_co_we, mg_rd_i, mg_co_i, mg_co_value, mg_clusters} = '0;
    // What only the Gaussian path reads (waived in core/evms_core.vlt).
    logic unused_gaussian_path;
    assign unused_gaussian_path = ^{ms_load_we_q, ms_load_i_q, ms_lx_q, ms_ly_q, ms_lp_q, ms_lt_q, ms_start_q, ms_rd_i, mg_start_q, cfg_merge_radius2[0]};
  end

  // ---- the seeded path: climbs, links of clusters that touch, clusters kept and warm seeds -------
  // The climbs hold the packet's climb features and each event's first mode. The links read an
  // event's pixel (the packet memory) and first mode (the climbs) and leave each mode's
  // representative on rd_root. The warm seeds read an event's feature and linked mode and a
  // mode's position, write each event's cluster, and leave the next packet's seeds in the climbs.
  logic cl_load_we_q, cl_start_q, cl_done;
  logic [15:0] cl_load_i_q;
  logic [31:0] cl_lx_q, cl_ly_q;
  logic [15:0] cl_mode_count, cl_steps;
  logic [15:0] cl_rd_j;
  logic signed [15:0] cl_rd_mode;
  logic [31:0] cl_rd_x, cl_rd_y, cl_rd_mode_x, cl_rd_mode_y;
  logic lk_ready, lk_start_q, lk_done;
  logic [15:0] lk_ev_j;
  logic [ModeIndexBits-1:0] lk_rd_root;
  logic lk_first_we, lk_first_on_pixel;  // the links say which events are the first on their pixel
  logic [15:0] lk_first_j;
  logic ws_start_q, ws_done, ws_co_we, ws_warm_we;
  logic [15:0] ws_ev_j, ws_co_j;
  logic [7:0] ws_md_c, ws_clusters, ws_warm_k;
  logic signed [7:0] ws_co_value;
  logic signed [15:0] ws_ev_mode;
  logic [31:0] ws_warm_x, ws_warm_y;
  logic [63:0] ws_warm_ball2;
  logic [7:0] warm_count_q;   // the seeds the last seeded packet left
  // The least density on the linked sets (cfg_density_after_links, hls/cluster/sparse_sets.h):
  // the climbs keep every event's mode. StDense first counts each set's events, an event a clock
  // (its mode from the climbs, the mode's set from the links); then it reads each mode's test
  // from the climbs and its set from the links, a mode a clock, and marks the sets that hold a
  // dense mode and at least the packet's least events (the climbs' least, n * cfg_min_density).
  // An event of an unmarked set is noise. Each read's set is registered (dense_set_c_q) before
  // it addresses the counts, so that no path runs from the climbs' and the links' reads through
  // the counts.
  logic dense_after_links;
  assign dense_after_links = HasDensityAfterLinks != 0 && cfg_density_after_links && cfg_min_density != 0;
  logic                   dense_modes_q;      // StDense: counting the events (0), reading the modes (1)
  logic [15:0]            dense_j_q;          // the event StDense reads
  logic                   dense_read_q;       // an event's read is in flight
  logic                   dense_held_q;       // dense_set_c_q and dense_counts_q hold a read
  logic [ModeIndexBits-1:0] dense_set_c_q;    // the read's set
  logic                   dense_counts_q;     // the read counts: an event with a mode, or a dense mode
  logic [ModeIndexBits:0] dense_c_q;          // the mode StDense reads
  logic [ModesMax-1:0]    dense_set_q;        // the sets kept
  // Each set's events, a memory (distributed RAM on the XC7) that is not cleared: a set's count
  // is valid once set_counted_q marks it in the packet, and reads as 0 before.
  logic [15:0]            set_events_q [ModesMax];
  logic [ModesMax-1:0]    set_counted_q;      // the sets counted in this packet
  wire [15:0] set_events = set_counted_q[dense_set_c_q] ? set_events_q[dense_set_c_q] : 16'd0;
  logic [47:0]            cl_least;           // n * cfg_min_density, DensityFrac fraction bits
  logic                   cl_rd_c_sparse;
  logic                   dense_reading;      // in StDense, reading the modes
  // The links' representative of an event's first mode (of mode dense_c_q while StDense reads
  // the modes).
  wire [ModeIndexBits-1:0] first_mode = ModeIndexBits'(cl_rd_mode);
  wire [ModeIndexBits-1:0] links_rd_c = dense_reading ? ModeIndexBits'(dense_c_q) : first_mode;
  logic signed [15:0] linked_mode;
  assign linked_mode = cl_rd_mode < 0 || (dense_after_links && !dense_set_q[lk_rd_root]) ? -16'sd1 : 16'(lk_rd_root);
  // The polarity split (cluster/evms_polarity_split.sv), in a build that holds it and with
  // cfg_split_balance set, runs between the links and the warm seeds: it reads an event's pixel,
  // linked mode and climb features, and the warm seeds then read each event's mode and the moved
  // modes' positions from it.
  logic sp_ready, sp_start_q, sp_done, sp_rd_moved;
  logic [15:0] sp_ev_j, sp_rd_j, sp_mode_count;
  logic signed [15:0] sp_rd_mode;
  logic [31:0] sp_rd_mode_x, sp_rd_mode_y;
  logic split_on;
  assign split_on = HasPolaritySplit != 0 && cfg_split_balance != 0;
  logic signed [15:0] split_mode;   // an event's mode after the links and the split
  assign split_mode = split_on ? sp_rd_mode : linked_mode;
  // The edge join (cluster/evms_edge_join.sv), in a build that holds it and with cfg_edge_radius2
  // set, runs after the split: it reads an event's pixel and mode after the split, and leaves a
  // table from mode to mode that the warm seeds read each event's mode through. The modes keep
  // their positions.
  logic ej_start_q, ej_done;
  logic [15:0] ej_ev_j;
  logic [7:0] ej_rd_into;
  logic edge_on;
  assign edge_on = HasEdgeJoin != 0 && cfg_edge_radius2 != 0;
  assign ws_ev_mode = edge_on && split_mode >= 0 ? $signed(16'(ej_rd_into)) : split_mode;
  logic [15:0] ws_mode_count;
  logic [31:0] ws_md_x, ws_md_y;
  assign ws_mode_count = split_on ? sp_mode_count : cl_mode_count;
  assign ws_md_x = split_on && sp_rd_moved ? sp_rd_mode_x : cl_rd_mode_x;
  assign ws_md_y = split_on && sp_rd_moved ? sp_rd_mode_y : cl_rd_mode_y;
  if (HasSeededPath != 0) begin : g_seeded
    logic [15:0] climbs_unused, modes_lost_unused;
    evms_seeded_climbs #(
      .PacketMax(PacketMax), .ModesMax(ModesMax), .GridSide(GridSide), .ReachMax(ReachMax), .IterationsMax(IterationsMax),
      .UnitShift(UnitShift), .DensityFrac(DensityFrac), .CoordBits(32)
    ) u_climbs (
      .clk(clk), .rst_n(rst_n), .load_we(cl_load_we_q), .load_i(cl_load_i_q), .load_x(cl_lx_q), .load_y(cl_ly_q),
      .warm_we(ws_warm_we), .warm_k(ws_warm_k), .warm_x(ws_warm_x), .warm_y(ws_warm_y), .warm_ball2(ws_warm_ball2),
      .start(cl_start_q), .n(16'(n_q)), .warm_count(warm_count_q), .cfg_warm_start(cfg_warm_start),
      .cfg_max_iterations(cfg_max_iterations), .cfg_tolerance(cfg_tolerance), .cfg_merge_radius2(cfg_merge_radius2),
      .cfg_min_density(cfg_min_density), .cfg_density_after_links(dense_after_links), .done(cl_done), .mode_count(cl_mode_count), .climbs(climbs_unused), .steps(cl_steps), .modes_lost(modes_lost_unused), .least(cl_least),
      .rd_j(cl_rd_j), .rd_mode(cl_rd_mode), .rd_x(cl_rd_x), .rd_y(cl_rd_y), .rd_c(dense_reading ? 8'(dense_c_q) : ws_md_c),
      .rd_mode_x(cl_rd_mode_x), .rd_mode_y(cl_rd_mode_y), .rd_c_sparse(cl_rd_c_sparse));
    evms_mode_links #(
      .MaxWidth(MaxWidth), .MaxHeight(MaxHeight), .PacketMax(PacketMax), .ModesMax(ModesMax), .LinkMax(LinkMax)
    ) u_links (
      .clk(clk), .rst_n(rst_n), .ready(lk_ready), .start(lk_start_q), .n(16'(n_q)), .cfg_link2(cfg_link2),
      .cfg_sensor_width(cfg_sensor_width), .cfg_sensor_height(cfg_sensor_height), .ev_j(lk_ev_j), .ev_x(rd_pk_x),
      .ev_y(rd_pk_y), .ev_mode(cl_rd_mode), .first_we(lk_first_we), .first_j(lk_first_j), .first_on_pixel(lk_first_on_pixel),
      .done(lk_done), .rd_c(links_rd_c), .rd_root(lk_rd_root));
    evms_warm_seeds #(
      .PacketMax(PacketMax), .ModesMax(ModesMax), .ClustersMax(ClustersMax), .UnitShift(UnitShift), .SpreadFrac(SpreadFrac),
      .CoordBits(32)
    ) u_warm_seeds (
      .clk(clk), .rst_n(rst_n), .start(ws_start_q), .n(16'(n_q)), .mode_count(ws_mode_count),
      .cfg_min_cluster_size(cfg_min_cluster_size), .cfg_max_clusters(cfg_max_clusters), .cfg_warm_scale2(cfg_warm_scale2),
      .cfg_warm_ball2_max(cfg_warm_ball2_max), .ev_j(ws_ev_j), .ev_mode(ws_ev_mode), .ev_x(cl_rd_x), .ev_y(cl_rd_y),
      .md_c(ws_md_c), .md_x(ws_md_x), .md_y(ws_md_y), .co_we(ws_co_we), .co_j(ws_co_j), .co_value(ws_co_value),
      .warm_we(ws_warm_we), .warm_k(ws_warm_k), .warm_x(ws_warm_x), .warm_y(ws_warm_y), .warm_ball2(ws_warm_ball2),
      .done(ws_done), .clusters(ws_clusters));
  end else begin : g_no_seeded
    assign {cl_done, cl_mode_count, cl_steps, cl_rd_mode, cl_rd_x, cl_rd_y, cl_rd_mode_x, cl_rd_mode_y, cl_rd_c_sparse, cl_least} = '0;
    assign {lk_done, lk_ev_j, lk_rd_root, lk_first_we, lk_first_j, lk_first_on_pixel} = '0;
    assign lk_ready = 1'b1;
    assign {ws_done, ws_co_we, ws_warm_we, ws_ev_j, ws_co_j, ws_md_c, ws_clusters, ws_warm_k, ws_co_value} = '0;
    assign {ws_warm_x, ws_warm_y, ws_warm_ball2} = '0;
    // What only the seeded path reads (waived in core/evms_core.vlt).
    logic unused_seeded_path;
    assign unused_seeded_path = ^{cfg_warm_start, cfg_min_density, cfg_density_after_links, dense_after_links, dense_c_q, dense_set_q, links_rd_c, dense_reading, cl_rd_c_sparse,
                                  dense_modes_q, dense_j_q, dense_read_q, dense_held_q, dense_set_c_q, dense_counts_q, set_counted_q, set_events, cl_least, cfg_warm_scale2, cfg_warm_ball2_max, cfg_link2, cl_load_we_q, cl_load_i_q, cl_lx_q, cl_ly_q,
                                  cl_start_q, cl_mode_count, cl_rd_j, cl_rd_x, cl_rd_y, cl_rd_mode_x, cl_rd_mode_y, first_mode, lk_start_q,
                                  warm_count_q, ws_ev_mode, ws_md_c, ws_start_q, ws_warm_we, ws_warm_k, ws_warm_x, ws_warm_y,
                                  ws_warm_ball2, linked_mode, ws_mode_count, ws_md_x, ws_md_y};
  end
  if (HasSeededPath != 0 && HasPolaritySplit != 0) begin : g_split
    evms_polarity_split #(
      .MaxWidth(MaxWidth), .MaxHeight(MaxHeight), .PacketMax(PacketMax), .ModesMax(ModesMax), .CoordBits(32),
      .SplitCellFrac(SplitCellFrac), .SplitFractionFrac(SplitFractionFrac)
    ) u_split (
      .clk(clk), .rst_n(rst_n), .ready(sp_ready), .start(sp_start_q), .n(16'(n_q)), .mode_count(cl_mode_count),
      .cfg_split_min_events(cfg_split_min_events), .cfg_split_balance(cfg_split_balance), .cfg_split_share(cfg_split_share),
      .cfg_split_cell_scale_x(cfg_split_cell_scale_x), .cfg_split_cell_scale_y(cfg_split_cell_scale_y),
      .cfg_split_partial(cfg_split_partial), .ev_j(sp_ev_j),
      .ev_x(rd_pk_x), .ev_y(rd_pk_y), .ev_p(rd_pk_p), .ev_mode(linked_mode), .ev_fx(cl_rd_x), .ev_fy(cl_rd_y),
      .done(sp_done), .modes_after(sp_mode_count), .rd_j(sp_rd_j), .rd_mode(sp_rd_mode), .rd_c(ws_md_c),
      .rd_moved(sp_rd_moved), .rd_mode_x(sp_rd_mode_x), .rd_mode_y(sp_rd_mode_y));
  end else begin : g_no_split
    assign {sp_done, sp_ev_j, sp_mode_count, sp_rd_mode, sp_rd_moved, sp_rd_mode_x, sp_rd_mode_y} = '0;
    assign sp_ready = 1'b1;
    // What only the polarity split reads (waived in core/evms_core.vlt).
    logic unused_split;
    assign unused_split = ^{sp_start_q, sp_rd_j, cfg_split_share, cfg_split_min_events, cfg_split_cell_scale_x, cfg_split_cell_scale_y,
                           cfg_split_partial};
  end
  if (HasSeededPath != 0 && HasEdgeJoin != 0) begin : g_edge_join
    logic [15:0] joined_unused;
    evms_edge_join #(
      .PacketMax(PacketMax), .ModesMax(ModesMax), .SplitFractionFrac(SplitFractionFrac), .EdgeSizeRatio(EdgeSizeRatio)
    ) u_edge_join (
      .clk(clk), .rst_n(rst_n), .start(ej_start_q), .n(16'(n_q)), .mode_count(ws_mode_count),
      .cfg_edge_radius2(cfg_edge_radius2), .cfg_edge_balance(cfg_edge_balance), .cfg_edge_min_events(cfg_edge_min_events),
      .ev_j(ej_ev_j), .ev_x(rd_pk_x), .ev_y(rd_pk_y), .ev_p(rd_pk_p), .ev_mode(split_mode), .done(ej_done),
      .joined(joined_unused), .rd_c(8'(split_mode)), .rd_into(ej_rd_into));
  end else begin : g_no_edge_join
    assign {ej_done, ej_ev_j, ej_rd_into} = '0;
    // What only the edge join reads (waived in core/evms_core.vlt).
    logic unused_edge_join;
    assign unused_edge_join = ^{ej_start_q, cfg_edge_balance, cfg_edge_min_events};
  end

  // The path a packet takes, and its clusters. A build with one path takes it whatever
  // cfg_seeded says (the host refuses a cfg_seeded the build cannot follow).
  logic seeded;
  assign seeded = HasSeededPath != 0 && (cfg_seeded || HasGaussianPath == 0);
  logic [7:0] clusters;
  assign clusters = seeded ? ws_clusters : mg_clusters;

  // ---- centroids --------------------------------------------------------------------------------
  logic ct_start_q, ct_done, ct_recip_start, ct_mul_start;
  logic [15:0] ct_rd_i;
  logic [63:0] ct_recip_x;
  logic signed [63:0] ct_mul_a, ct_mul_b;
  logic [7:0] z_c;
  logic [31:0] z_t;
  logic signed [31:0] z_x, z_y;
  logic [15:0] z_events, z_x_min, z_y_min, z_x_max, z_y_max;
  logic signed [63:0] z_r;
  evms_centroid #(
    .ClustersMax(ClustersMax), .PosFrac(PosFrac), .RecipFrac(RecipFrac), .PacketMax(PacketMax), .SpreadFrac(SpreadFrac),
    .HasExact(HasSeededPath != 0), .HasPolarityMidpoint(HasSeededPath != 0 && HasPolarityMidpoint != 0),
    .HasSpreadNoise(HasSpreadNoise != 0), .HasPixelCentre(HasSeededPath != 0 && HasPixelCentre != 0), .CovLog2(CovLog2),
    .PerEventFrac(PerEventFrac), .PerEventLog2(PerEventLog2), .PixelWidth2(PixelWidth2)
  ) u_centroid (
    .clk(clk), .rst_n(rst_n), .start(ct_start_q), .exact(seeded), .n(16'(n_q)), .clusters(clusters), .t0(t_first_q),
    .cfg_midpoint_min(cfg_midpoint_min), .cfg_meas_from_spread(cfg_meas_from_spread),
    .cfg_pixel_centre(cfg_pixel_centre && cfg_link2 != 0),   // the links mark the pixels (hls/core/core.h)
    .cfg_r(cfg_r), .rd_i(ct_rd_i), .ev_x(rd_pk_x), .ev_y(rd_pk_y), .ev_t(rd_pk_t), .ev_p(rd_pk_p), .ev_first(rd_pk_first),
    .ev_cluster(co_rdata_q), .recip_start(ct_recip_start),
    .recip_x(ct_recip_x), .recip_done(recip_done), .recip_r(recip_r), .recip_m(recip_m), .mul_start(ct_mul_start),
    .mul_a(ct_mul_a), .mul_b(ct_mul_b), .mul_done(mul_done), .mul_p(mul_p), .z_c(z_c), .z_t(z_t), .z_x(z_x), .z_y(z_y),
    .z_events(z_events), .z_x_min(z_x_min), .z_y_min(z_y_min), .z_x_max(z_x_max), .z_y_max(z_y_max), .z_r(z_r), .done(ct_done));

  // ---- tracker ----------------------------------------------------------------------------------
  logic tk_start_q, tk_done, tk_recip_start, tk_mul_start;
  logic [63:0] tk_recip_x;
  logic signed [63:0] tk_mul_a, tk_mul_b;
  logic [7:0] id_c;
  logic signed [31:0] id_of;
  evms_tracker #(
    .ClustersMax(ClustersMax), .TracksMax(TracksMax), .PosFrac(PosFrac), .TickLog2(TickLog2), .CovFrac(CovFrac),
    .GainFrac(GainFrac), .NoiseFrac(NoiseFrac), .RecipFrac(RecipFrac), .CovLog2(CovLog2), .GainLog2(GainLog2),
    .PosLog2(PosLog2), .GateDistLog2(GateDistLog2), .MaxDtLog2(MaxDtLog2)
  ) u_tracker (
    .clk(clk), .rst_n(rst_n), .cfg_gate2(cfg_gate2), .cfg_confirm_hits(cfg_confirm_hits), .cfg_coast_us(cfg_coast_us),
    .cfg_max_tracks(cfg_max_tracks), .cfg_associate_last(cfg_associate_last), .cfg_evict_stale(cfg_evict_stale),
    .cfg_gate_boxes(HasGateBoxes != 0 && cfg_gate_boxes),
    .cfg_report_tentative(cfg_report_tentative), .cfg_size_ratio_log2(cfg_size_ratio_log2), .cfg_q_third(cfg_q_third), .cfg_q_half(cfg_q_half), .cfg_q(cfg_q),
    .cfg_p0_pos(cfg_p0_pos), .cfg_p0_vel(cfg_p0_vel), .start(tk_start_q), .packet_time(t_last_q), .m(clusters), .z_c(z_c),
    .z_t(z_t), .z_x(z_x), .z_y(z_y), .z_events(z_events), .z_x_min(z_x_min), .z_y_min(z_y_min), .z_x_max(z_x_max),
    .z_y_max(z_y_max), .z_r(z_r), .id_c(id_c), .id_of(id_of), .upd_valid(trk_valid), .upd_ready(trk_ready),
    .upd_t(trk_t), .upd_id(trk_id), .upd_x(trk_x), .upd_y(trk_y), .upd_vx(trk_vx), .upd_vy(trk_vy), .upd_zx(trk_zx),
    .upd_zy(trk_zy), .upd_confirmed(trk_confirmed), .upd_events(trk_events), .upd_x_min(trk_x_min), .upd_y_min(trk_y_min),
    .upd_x_max(trk_x_max), .upd_y_max(trk_y_max), .upd_var_x(trk_var_x), .upd_var_y(trk_var_y), .recip_start(tk_recip_start), .recip_x(tk_recip_x),
    .recip_done(recip_done), .recip_r(recip_r),
    .recip_m(recip_m), .mul_start(tk_mul_start), .mul_a(tk_mul_a), .mul_b(tk_mul_b), .mul_done(mul_done), .mul_p(mul_p),
    .done(tk_done), .tracks_started(stat_tracks_started), .unassigned(stat_unassigned));

  // ---- decay for the time feature (the Gaussian path's) -------------------------------------------
  logic [63:0] decay_u_q;
  logic [WeightFrac:0] decay_w;
  if (HasGaussianPath != 0) begin : g_decay
    evms_exp_lut #(.TableLog2(ExpTableLog2), .WeightFrac(WeightFrac), .InterpBits(ExpInterpBits), .ArgFrac(DecayFrac), .ArgBits(64), .TableFile(ExpTableFile)) u_decay (
      .clk(clk), .u(decay_u_q), .w(decay_w));
  end else begin : g_no_decay
    assign decay_w = '0;
    logic unused_decay;
    assign unused_decay = ^decay_u_q;
  end

  // ---- control ------------------------------------------------------------------------------------
  `include "evms_core_states.svh"
  `include "evms_core_labels.svh"
  state_e state_q /*verilator public_flat_rd*/;  // read by the cycle profile (sim/rtl_core.h)
  assign dense_reading = state_q == StDense && dense_modes_q;
  wire links_finished = state_q == StLink ? lk_done && !dense_after_links
                                           : dense_modes_q && 16'(dense_c_q) >= cl_mode_count && !dense_held_q;
  // StDense's pass. Its registers clear while the links run, and the sets it keeps stay for the
  // packet's later stages (linked_mode); no reset, as nothing reads them before a pass.
  always_ff @(posedge clk) begin
    if (state_q == StLink) begin
      dense_modes_q <= 1'b0;
      dense_j_q <= '0;
      dense_read_q <= 1'b0;
      dense_held_q <= 1'b0;
      dense_c_q <= '0;
      dense_set_q <= '0;
      set_counted_q <= '0;
    end else if (state_q == StDense && !dense_modes_q) begin
      // Issue event dense_j_q; its mode and set come a clock later, and are counted the next.
      dense_read_q <= dense_j_q < 16'(n_q);
      if (dense_j_q < 16'(n_q)) dense_j_q <= dense_j_q + 1'b1;
      dense_held_q <= dense_read_q;
      dense_set_c_q <= lk_rd_root;
      dense_counts_q <= cl_rd_mode >= 0;
      if (dense_held_q && dense_counts_q) begin
        set_events_q[dense_set_c_q] <= set_events + 1'b1;
        set_counted_q[dense_set_c_q] <= 1'b1;
      end
      if (dense_j_q >= 16'(n_q) && !dense_read_q && !dense_held_q) dense_modes_q <= 1'b1;
    end else if (state_q == StDense) begin
      // Read mode dense_c_q's test and set; mark the set the next clock.
      dense_held_q <= 16'(dense_c_q) < cl_mode_count;
      if (16'(dense_c_q) < cl_mode_count) dense_c_q <= dense_c_q + 1'b1;
      dense_set_c_q <= lk_rd_root;
      dense_counts_q <= !cl_rd_c_sparse;
      if (dense_held_q && dense_counts_q && 48'({set_events, DensityFrac'(0)}) >= cl_least) dense_set_q[dense_set_c_q] <= 1'b1;
    end
  end
  logic [15:0] fi_q;            // feature index
  logic [PendingCountBits-1:0] ri_q;          // release index
  logic [FeatBits-1:0] phi_x_q, phi_y_q, phi_p_q;
  logic [31:0] rel_t_q;
  logic [15:0] rel_x_q, rel_y_q;
  logic        rel_p_q;
  logic signed [15:0] rel_idx_q;
  logic [15:0] iterations_q;

  always_ff @(posedge clk) begin
    if (pend_we) pend_mem[PendingIndexBits'(pend_n_q)] <= pend_wdata;
    pend_rdata_q <= pend_mem[PendingIndexBits'(ri_q)];
    if (state_q == StAppend) pk_mem[PacketIndexBits'(n_q)] <= {e_x_q, e_y_q, e_p_q, e_t_q};
    pk_rdata_q <= pk_mem[PacketIndexBits'(rd_pk_i)];
    if (lk_first_we) first_on_pixel_mem[PacketIndexBits'(lk_first_j)] <= lk_first_on_pixel;
    rd_pk_first <= first_on_pixel_mem[PacketIndexBits'(rd_pk_i)];
    if (mg_co_we) cluster_of[PacketIndexBits'(mg_co_i)] <= mg_co_value;
    if (ws_co_we) cluster_of[PacketIndexBits'(ws_co_j)] <= ws_co_value;
    co_rdata_q <= cluster_of[PacketIndexBits'(co_i)];
  end
  assign {rd_pk_x, rd_pk_y, rd_pk_p, rd_pk_t} = pk_rdata_q;
  // Events join the pending queue when the filter rejects them (taken from the intake's queue)
  // or when they join the packet.
  wire take_noise = q_pop && !q_flush && !q_kept;
  assign pend_we = take_noise || state_q == StAppend;
  wire [15:0] append_index = 16'(n_q);  // named: Yosys 0.23 sizes a cast inside a concatenation by its operand
  assign pend_wdata = state_q == StAppend ? {e_t_q, e_x_q, e_y_q, e_p_q, append_index} : {q_t, q_x, q_y, q_p, 16'hFFFF};
  assign rd_pk_i = state_q == StCentroid ? ct_rd_i : (state_q == StLink ? lk_ev_j : (state_q == StSplit ? sp_ev_j : (state_q == StEdge ? ej_ev_j : fi_q)));
  assign cl_rd_j = state_q == StLink ? lk_ev_j : (state_q == StDense ? dense_j_q : (state_q == StSplit ? sp_ev_j : (state_q == StEdge ? ej_ev_j : ws_ev_j)));
  assign sp_rd_j = state_q == StEdge ? ej_ev_j : ws_ev_j;
  assign co_i = state_q == StMerge ? mg_co_i : (state_q == StCentroid ? ct_rd_i :
                (state_q == StReleaseWait ? pend_rdata_q[15:0] : 16'(rel_idx_q)));
  assign ms_rd_i = mg_rd_i;

  // The shared units belong to one stage at a time.
  always_comb begin
    mul_start = 1'b0;
    mul_a = '0;
    mul_b = '0;
    recip_start = 1'b0;
    recip_x = '0;
    if (state_q == StCentroid) begin
      mul_start = ct_mul_start;
      mul_a = ct_mul_a;
      mul_b = ct_mul_b;
      recip_start = ct_recip_start;
      recip_x = ct_recip_x;
    end else if (state_q == StTrack) begin
      mul_start = tk_mul_start;
      mul_a = tk_mul_a;
      mul_b = tk_mul_b;
      recip_start = tk_recip_start;
      recip_x = tk_recip_x;
    end else begin
      // features (the multiplier) and mean shift (the reciprocal)
      mul_start = feat_mul_start_q;
      mul_a = feat_mul_a_q;
      mul_b = feat_mul_b_q;
      recip_start = ms_recip_start;
      recip_x = ms_recip_x;
    end
  end
  function automatic [63:0] clamp_feat(input signed [63:0] v);
    begin
      clamp_feat = v < 0 ? 64'd0 : ($unsigned(v) > FeatMax ? FeatMax : $unsigned(v));
    end
  endfunction

  // The controller takes a decided word from the intake while idle; the links and the polarity
  // split clear their maps after reset (as the filter does, which holds in_ready low meanwhile).
  assign q_pop = state_q == StIdle && q_valid && lk_ready && sp_ready;
  assign idle = in_ready && intake_empty && state_q == StIdle && lk_ready && sp_ready && pend_n_q == 0 && !lab_valid && !trk_valid && !pkt_valid;
  assign id_c = co_rdata_q >= 0 ? 8'(co_rdata_q) : 8'd0;

  // Issues a * b on the controller's port of the shared multiplier; the product comes back with mul_done.
`define EVMS_FEAT_REQUEST(A, B) begin feat_mul_start_q <= 1'b1; feat_mul_a_q <= (A); feat_mul_b_q <= (B); end
  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      state_q <= StIdle;
      {e_t_q, e_x_q, e_y_q, e_p_q, e_climb_x_q, e_climb_y_q} <= '0;
      n_q <= '0;
      pend_n_q <= '0;
      t_first_q <= '0;
      t_last_q <= '0;
      append_after_q <= 1'b0;
      fi_q <= '0;
      ri_q <= '0;
      {phi_x_q, phi_y_q, phi_p_q} <= '0;
      feat_mul_start_q <= 1'b0;
      feat_mul_a_q <= '0;
      feat_mul_b_q <= '0;
      decay_u_q <= '0;
      ms_load_we_q <= 1'b0;
      ms_load_i_q <= '0;
      {ms_lx_q, ms_ly_q, ms_lp_q, ms_lt_q} <= '0;
      ms_start_q <= 1'b0;
      mg_start_q <= 1'b0;
      cl_load_we_q <= 1'b0;
      cl_load_i_q <= '0;
      {cl_lx_q, cl_ly_q} <= '0;
      cl_start_q <= 1'b0;
      lk_start_q <= 1'b0;
      sp_start_q <= 1'b0;
      ej_start_q <= 1'b0;
      ws_start_q <= 1'b0;
      warm_count_q <= '0;
      ct_start_q <= 1'b0;
      tk_start_q <= 1'b0;
      iterations_q <= '0;
      lab_valid <= 1'b0;
      {lab_t, lab_x, lab_y, lab_p, lab_label} <= '0;
      pkt_valid <= 1'b0;
      {pkt_t_first, pkt_t_last, pkt_events, pkt_clusters, pkt_iterations} <= '0;
      {rel_t_q, rel_x_q, rel_y_q, rel_p_q} <= '0;
      rel_idx_q <= '0;
    end else begin
      feat_mul_start_q <= 1'b0;
      ms_load_we_q <= 1'b0;
      ms_start_q <= 1'b0;
      mg_start_q <= 1'b0;
      cl_load_we_q <= 1'b0;
      cl_start_q <= 1'b0;
      lk_start_q <= 1'b0;
      sp_start_q <= 1'b0;
      ej_start_q <= 1'b0;
      ws_start_q <= 1'b0;
      ct_start_q <= 1'b0;
      tk_start_q <= 1'b0;
      if (lab_valid && lab_ready) lab_valid <= 1'b0;
      if (pkt_valid && pkt_ready) pkt_valid <= 1'b0;
      case (state_q)
        StIdle: if (q_pop) begin
          {e_t_q, e_x_q, e_y_q, e_p_q, e_climb_x_q, e_climb_y_q} <= {q_t, q_x, q_y, q_p, q_climb_x, q_climb_y};
          append_after_q <= 1'b0;
          if (q_flush) begin
            state_q <= StClose;
          end else if (!q_kept) begin
            pend_n_q <= pend_n_q + 1'b1;
            if (n_q == 0 || 32'(pend_n_q) + 1 == PendingDepth) state_q <= StClose;
          end else if (n_q > 0 && cfg_packet_max_span_us != 0 && q_t - t_first_q > cfg_packet_max_span_us) begin
            append_after_q <= 1'b1;
            state_q <= StClose;
          end else begin
            state_q <= StAppend;
          end
        end
        StAppend: begin
          // The seeded path's climb features, computed by the intake, go to the climbs as the
          // event joins the packet.
          cl_load_we_q <= 1'b1;
          cl_load_i_q <= 16'(n_q);
          cl_lx_q <= e_climb_x_q;
          cl_ly_q <= e_climb_y_q;
          if (n_q == 0) t_first_q <= e_t_q;
          t_last_q <= e_t_q;
          n_q <= n_q + 1'b1;
          pend_n_q <= pend_n_q + 1'b1;
          append_after_q <= 1'b0;
          state_q <= (32'(n_q) + 1 >= 32'(cfg_packet_size) || 32'(n_q) + 1 >= PacketMax || 32'(pend_n_q) + 1 == PendingDepth)
                   ? StClose : StIdle;
        end
        StClose: begin
          if (n_q > 0) begin
            fi_q <= '0;
            cl_start_q <= seeded;
            state_q <= seeded ? StClimb : StFeatRead;
          end else begin
            ri_q <= '0;
            state_q <= pend_n_q == 0 ? (append_after_q ? StAppend : StIdle) : StReleaseRead;
          end
        end
        // Features of event fi_q.
        StFeatRead: state_q <= StFeatWait;
        StFeatWait: begin
          `EVMS_FEAT_REQUEST($signed(64'(rd_pk_x)), $signed(64'(cfg_scale_x)))
          state_q <= StFeatX;
        end
        StFeatX: if (mul_done) begin
          phi_x_q <= FeatBits'(clamp_feat(evms_round_pkg::shr_rnd(mul_p, CoordScaleFrac - FeatFrac)));
          `EVMS_FEAT_REQUEST($signed(64'(rd_pk_y)), $signed(64'(cfg_scale_y)))
          state_q <= StFeatY;
        end
        StFeatY: if (mul_done) begin
          logic [31:0] age, age_clamped;
          phi_y_q <= FeatBits'(clamp_feat(evms_round_pkg::shr_rnd(mul_p, CoordScaleFrac - FeatFrac)));
          phi_p_q <= rd_pk_p ? FeatBits'(clamp_feat($signed(64'(cfg_phi_on)))) : '0;
          age = t_last_q - rd_pk_t;
          age_clamped = age > 32'h7FFFFFFF ? 32'h7FFFFFFF : age;
          `EVMS_FEAT_REQUEST($signed(64'(age_clamped)), $signed(cfg_inv_tau))
          state_q <= StFeatAge;
        end
        StFeatAge: if (mul_done) begin
          decay_u_q <= mul_p;
          state_q <= StFeatDecay1;
        end
        StFeatDecay1: state_q <= StFeatDecay2;
        StFeatDecay2: state_q <= StFeatT;
        StFeatT: begin
          `EVMS_FEAT_REQUEST($signed(64'(cfg_phi_t_max)), $signed(64'(decay_w)))
          state_q <= StFeatStore;
        end
        StFeatStore: if (mul_done) begin
          ms_load_we_q <= 1'b1;
          ms_load_i_q <= fi_q;
          ms_lx_q <= phi_x_q;
          ms_ly_q <= phi_y_q;
          ms_lp_q <= phi_p_q;
          ms_lt_q <= FeatBits'(clamp_feat(evms_round_pkg::shr_rnd(mul_p, WeightFrac)));
          if (32'(fi_q) + 1 < 32'(n_q)) begin
            fi_q <= fi_q + 1'b1;
            state_q <= StFeatRead;
          end else begin
            ms_start_q <= 1'b1;
            state_q <= StMeanShift;
          end
        end
        StClimb: if (cl_done) begin
          iterations_q <= cl_steps;
          lk_start_q <= 1'b1;
          state_q <= StLink;
        end
        // The links, then (with the least density on the linked sets) StDense's pass.
        StLink, StDense: if (links_finished) begin
          sp_start_q <= split_on;
          ej_start_q <= !split_on && edge_on;
          ws_start_q <= !split_on && !edge_on;
          state_q <= split_on ? StSplit : (edge_on ? StEdge : StWarm);
        end else if (state_q == StLink && lk_done) begin
          state_q <= StDense;
        end
        StSplit: if (sp_done) begin
          ej_start_q <= edge_on;
          ws_start_q <= !edge_on;
          state_q <= edge_on ? StEdge : StWarm;
        end
        StEdge: if (ej_done) begin
          ws_start_q <= 1'b1;
          state_q <= StWarm;
        end
        StWarm: if (ws_done) begin
          warm_count_q <= ws_clusters;
          ct_start_q <= 1'b1;
          state_q <= StCentroid;
        end
        StMeanShift: if (ms_done) begin
          iterations_q <= 16'(ms_sweeps);
          mg_start_q <= 1'b1;
          state_q <= StMerge;
        end
        StMerge: if (mg_done) begin
          ct_start_q <= 1'b1;
          state_q <= StCentroid;
        end
        StCentroid: if (ct_done) begin
          tk_start_q <= 1'b1;
          state_q <= StTrack;
        end
        StTrack: if (tk_done) state_q <= StPacket;
        StPacket: if (!pkt_valid || pkt_ready) begin
          pkt_valid <= 1'b1;
          pkt_t_first <= t_first_q;
          pkt_t_last <= t_last_q;
          pkt_events <= 16'(n_q);
          pkt_clusters <= clusters;
          pkt_iterations <= iterations_q;
          ri_q <= '0;
          state_q <= StReleaseRead;
        end
        // Release pending event ri_q with its label.
        StReleaseRead: state_q <= StReleaseWait;       // pending[ri_q] is being read
        StReleaseWait: begin                           // ... and cluster_of[its index]
          {rel_t_q, rel_x_q, rel_y_q, rel_p_q, rel_idx_q} <= pend_rdata_q;
          state_q <= StReleaseCluster;
        end
        StReleaseCluster: state_q <= StReleaseSend;   // ids[cluster] settles
        StReleaseSend: if (!lab_valid || lab_ready) begin
          lab_valid <= 1'b1;
          {lab_t, lab_x, lab_y, lab_p} <= {rel_t_q, rel_x_q, rel_y_q, rel_p_q};
          lab_label <= rel_idx_q < 0 || co_rdata_q < 0 ? LabelNoise : id_of;
          if (32'(ri_q) + 1 < 32'(pend_n_q)) begin
            ri_q <= ri_q + 1'b1;
            state_q <= StReleaseRead;
          end else begin
            n_q <= '0;
            pend_n_q <= '0;
            state_q <= append_after_q ? StAppend : StIdle;
          end
        end
        default: state_q <= StIdle;
      endcase
    end
  end
`undef EVMS_FEAT_REQUEST
endmodule
