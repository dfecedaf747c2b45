// The core's intake: the background-activity filter (filter/evms_ba_filter.sv), the seeded
// path's climb features (x and y times their scales, rounded, as hls/cluster/seeded_climbs.h's
// climb_features) and a queue of the words so decided, so that the filter runs ahead while the
// controller clusters a packet. A packet's worth of words (QueueDepth) waits in the queue; the
// input stalls only when it is full.
//
// Schedule (hls/core/schedule.h counts it): a word taken at clock A is pushed at clock
// A + max(F, 3), where F is the filter's clocks (ScheduleCounter::filter_cycles; 1 for a flush
// word, the filter off or an event outside the sensor), and reaches the head of an empty
// queue three clocks later. The next word is taken no sooner than the clock after the push,
// and only while fewer than QueueDepth words are taken and not yet popped.
//
// With QueueDepth 1 there is no queue: the word being decided is the head from its push clock
// until it is popped, and the next word is taken the clock after. A core that waits long for
// each word anyway (core/evms_climbs_core.sv) keeps no second copy of it that way: on a UP5K a
// flip-flop that copies a word costs a logic cell a bit.
`include "evms_assert.svh"

module evms_intake #(
  parameter int MaxWidth       = 240,
  parameter int MaxHeight      = 180,
  parameter int TimestampBits  = 16,
  parameter int TimestampShift = 7,
  parameter int NoiseIntervalLog2 = 15,
  parameter int QueueDepth     = 256,   // 1, or a power of two (common/evms_fifo.sv)
  parameter int HasClimbScale  = 1,   // compute the climb features (a build with the seeded path)
  parameter int ClimbShift     = 21   // kClimbScaleFrac - kFeatFrac - kClimbFrac
) (
  input  logic        clk,
  input  logic        rst_n,
  // The filter's registers (hls/core/registers.h).
  `include "evms_filter_cfg_ports.svh"
  input  logic [63:0] cfg_climb_scale_x,
  input  logic [63:0] cfg_climb_scale_y,
  // Words in.
  `include "evms_stream_in_sink_ports.svh"
  // Decided words out, in input order (first-word-fall-through).
  output logic        q_valid,
  input  logic        q_pop,
  output logic [31:0] q_t,
  output logic [15:0] q_x,
  output logic [15:0] q_y,
  output logic        q_p,
  output logic        q_flush,
  output logic        q_kept,       // passed the filter (an event, not a flush word)
  output logic [31:0] q_climb_x,    // 0 without HasClimbScale
  output logic [31:0] q_climb_y,
  output logic        empty         // no word held anywhere in the intake
);
  localparam int CountBits = $clog2(QueueDepth + 1);
  localparam int ClimbBits = HasClimbScale != 0 ? 64 : 0;
  localparam int WordBits = 32 + 16 + 16 + 1 + 1 + 1 + ClimbBits;

  // ---- the word being decided -----------------------------------------------------------------
  logic        busy_q;                 // a word is taken and not yet released
  logic [1:0]  age_q;                  // clocks since it was taken, less one, saturating at 2
  logic        decided_q, kept_q;      // the filter has answered (a flush word needs no answer)
  logic [31:0] t_q;
  logic [15:0] x_q, y_q;
  logic        p_q, flush_q;
  logic [CountBits-1:0] taken_q;       // taken and not yet popped

  logic f_ready, f_start, f_done, f_kept;
  evms_ba_filter #(.MaxWidth(MaxWidth), .MaxHeight(MaxHeight), .TimestampBits(TimestampBits), .TimestampShift(TimestampShift),
                   .NoiseIntervalLog2(NoiseIntervalLog2)) u_filter (
    .clk(clk), .rst_n(rst_n), .cfg_enabled(cfg_filter_enabled), .cfg_width(cfg_sensor_width), .cfg_height(cfg_sensor_height),
    .cfg_window(cfg_filter_window), .cfg_noise_count(cfg_filter_noise_count), .cfg_quiet_count(cfg_filter_quiet_count),
    .cfg_quiet_window(cfg_filter_quiet_window), .cfg_warm_up(cfg_filter_warm_up), .ready(f_ready), .start(f_start), .t(in_t), .x(in_x), .y(in_y), .done(f_done), .kept(f_kept));

  assign in_ready = f_ready && !busy_q && 32'(taken_q) < QueueDepth;
  wire take = in_valid && in_ready;
  assign f_start = take && !in_flush;
  wire decided = flush_q || decided_q || f_done;
  wire kept = !flush_q && (decided_q ? kept_q : f_kept);
  wire push = busy_q && age_q == 2'd2 && decided;
  // The word being decided leaves the intake: pushed into the queue, or popped from the head.
  wire release_word;

  // ---- climb features: one product a clock, x at A + 1 and y at A + 2 ---------------------------
  // The queue's word: the event, whether it is a flush word or kept, and its climb features.
  logic [WordBits-1:0] push_word, head_word;
  if (HasClimbScale != 0) begin : g_climb_scale
    logic [63:0] product_q;
    logic [31:0] climb_x_q, climb_y;
    // The low 64 bits of a 16 x 64 product, as the C++ core's uint64 arithmetic.
    wire [63:0] factor = age_q == 2'd0 ? 64'(x_q) : 64'(y_q);
    wire [63:0] scale = age_q == 2'd0 ? cfg_climb_scale_x : cfg_climb_scale_y;
    always_ff @(posedge clk or negedge rst_n) begin
      if (!rst_n) begin
        product_q <= '0;
        climb_x_q <= '0;
      end else begin
        if (busy_q && age_q < 2'd2) product_q <= factor * scale;
        if (busy_q && age_q == 2'd1) climb_x_q <= 32'(evms_round_pkg::shr_rnd($signed(product_q), ClimbShift));
      end
    end
    assign climb_y = 32'(evms_round_pkg::shr_rnd($signed(product_q), ClimbShift));
    assign push_word = {t_q, x_q, y_q, p_q, flush_q, kept, climb_x_q, climb_y};
    assign {q_t, q_x, q_y, q_p, q_flush, q_kept, q_climb_x, q_climb_y} = head_word;
  end else begin : g_no_climb_scale
    assign push_word = {t_q, x_q, y_q, p_q, flush_q, kept};
    assign {q_t, q_x, q_y, q_p, q_flush, q_kept} = head_word;
    assign {q_climb_x, q_climb_y} = '0;
    logic unused_climb_scale;
    assign unused_climb_scale = ^{cfg_climb_scale_x, cfg_climb_scale_y};
  end

  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      busy_q <= 1'b0;
      age_q <= '0;
      decided_q <= 1'b0;
      kept_q <= 1'b0;
      {t_q, x_q, y_q, p_q, flush_q} <= '0;
      taken_q <= '0;
    end else begin
      if (take) begin
        busy_q <= 1'b1;
        age_q <= '0;
        decided_q <= 1'b0;
        {t_q, x_q, y_q, p_q, flush_q} <= {in_t, in_x, in_y, in_p, in_flush};
      end else if (busy_q) begin
        if (age_q != 2'd2) age_q <= age_q + 2'd1;
        if (f_done) begin
          decided_q <= 1'b1;
          kept_q <= f_kept;
        end
        if (release_word) busy_q <= 1'b0;
      end
      taken_q <= taken_q + CountBits'(take) - CountBits'(q_valid && q_pop);
    end
  end

  // ---- the queue ----------------------------------------------------------------------------------
  if (QueueDepth == 1) begin : g_head_in_registers
    // The decided word waits where it was decided.
    assign q_valid = push;
    assign head_word = push_word;
    assign release_word = push && q_pop;
  end else begin : g_queue
    // Never full: words are taken only while fewer than QueueDepth wait.
    logic fifo_in_ready;
    evms_fifo #(.Width(WordBits), .Depth(QueueDepth)) u_queue (
      .clk(clk), .rst_n(rst_n), .in_valid(push), .in_ready(fifo_in_ready), .in_data(push_word), .in_commit(1'b0), .in_rollback(1'b0),
      .out_valid(q_valid), .out_ready(q_pop), .out_data(head_word));
    assign release_word = push;
    `EVMS_ASSERT("the intake never pushes into a full queue", !push || fifo_in_ready, clk, rst_n)
  end

  assign empty = taken_q == '0;
endmodule
