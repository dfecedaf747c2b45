// Background-activity filter with its per-pixel timestamp RAM, as hls/filter/ba_filter.h.
// One event at a time: start with (t, x, y) -> done with kept, 20 to 22 clocks later (and 3 for
// each entry the scrubber owes; hls/core/schedule.h counts them).
//   - filter off: kept at once, no memory access;
//   - outside the configured sensor: noise, no memory access;
//   - else the event is registered with its time's distances from the scrubber's last time and
//     the warm-up's start (the clock in which start is high does no more, so that the input's
//     path from the link queue through the intake ends at a register, not at the scrubber's and
//     the warm-up's comparisons), and judged from the next clock on. First it scrubs for the
//     time since the last judged event: one entry for each 2^SweepLog2 us boundary crossed (at
//     most the whole RAM), clearing each whose age is at least half the wrap, or, after a gap of
//     more than a quarter of the wrap, clears the whole RAM; then it reads the (up to) 8
//     neighbours inside the sensor and keeps the event when one holds a time t' != 0 with
//     (now - t') mod 2^TimestampBits <= window, where now = t >> TimestampShift; it writes now
//     (or 1 for 0) to the own pixel, then scrubs two more entries;
//   - the noise check: the events no neighbour supported are counted in intervals of 2^NoiseIntervalLog2 us
//     (t[31:NoiseIntervalLog2]); an interval with cfg_noise_count or more of them makes the next one noisy,
//     and there an event needs two supporting neighbours instead of one (cfg_noise_count 0: off);
//   - the quiet window: an interval with fewer than cfg_quiet_count of them (counted against
//     cfg_window) makes the next one quiet, and there an event's supporters are its neighbours
//     within cfg_quiet_window (cfg_quiet_count 0: off);
//   - the warm-up: an event less than cfg_warm_up us after the first event judged is kept
//     (cfg_warm_up 0: off); the first event at or past it ends the warm-up for good.
// After reset the RAM is cleared, one word a cycle; ready stays low until then.
module evms_ba_filter #(
  parameter int MaxWidth  = 240,
  parameter int MaxHeight = 180,
  parameter int TimestampBits    = 16,
  parameter int TimestampShift   = 7,
  parameter int NoiseIntervalLog2 = 15   // the noise check's interval, 2^n us (hls/core/shape.h)
) (
  input  logic        clk,
  input  logic        rst_n,
  input  logic        cfg_enabled,
  input  logic [15:0] cfg_width,
  input  logic [15:0] cfg_height,
  input  logic [31:0] cfg_window,
  input  logic [23:0] cfg_noise_count,
  input  logic [23:0] cfg_quiet_count,
  input  logic [31:0] cfg_quiet_window,
  input  logic [31:0] cfg_warm_up,
  output logic        ready,
  input  logic        start,
  input  logic [31:0] t,
  input  logic [15:0] x,
  input  logic [15:0] y,
  output logic        done,
  output logic        kept
);
  localparam int Pixels = MaxWidth * MaxHeight;
  localparam int AddrBits = $clog2(Pixels);
  localparam logic [TimestampBits-1:0] HalfWrap = TimestampBits'(1) << (TimestampBits - 1);
  // The time scrubber's pace (hls/filter/ba_filter.h): one entry each 2^SweepLog2 us sweeps the
  // RAM within an eighth of the wrap; more than ClearCrossings of them (a gap of more than a
  // quarter of the wrap) clear it whole.
  localparam int WrapLog2 = TimestampBits + TimestampShift;
  localparam int SweepLog2 = WrapLog2 - 3 - AddrBits;
  localparam int CrossedBits = 32 - SweepLog2;
  localparam logic [CrossedBits-1:0] ClearCrossings = CrossedBits'(1) << (AddrBits + 1);
  localparam int OwedBits = AddrBits + 1;

  logic [TimestampBits-1:0] ram [0:Pixels-1];
  logic [AddrBits-1:0]      addr_q, addr_d;
  logic               we_q, we_d;
  logic [TimestampBits-1:0] wdata_q, wdata_d, rdata_q;
  // One port, and no read while writing: the shape of a single-ported RAM whose output holds
  // during a write (an iCE40 SPRAM, a Xilinx block RAM in NO_CHANGE mode). No state reads
  // rdata_q after a write cycle.
  always_ff @(posedge clk) begin
    if (we_q) ram[addr_q] <= wdata_q;
    else rdata_q <= ram[addr_q];
  end

  typedef enum logic [3:0] {StClear, StIdle, StAccept, StRead, StWrite, StScrubRead, StScrubWait, StScrubDecide, StDone} state_e;
  state_e state_q, state_d;
  logic [AddrBits-1:0] clear_addr_q, clear_addr_d, scrub_q, scrub_d;
  // The scrubber: the last judged event's time in 2^SweepLog2 us units, the entries it still
  // owes this event (for time, before the reads; then two after the write), and whether they are
  // the ones before the reads. A whole clear after reset has no event; one after a long gap
  // (started_q) is an event's, whose reads follow it.
  logic [CrossedBits-1:0] last_sweep_q, last_sweep_d;
  logic [OwedBits-1:0]    owed_q, owed_d;
  logic                   owed_before_reads_q, owed_before_reads_d;
  // The accepted event's sweep boundaries crossed since the last judged event's, registered with it.
  logic [CrossedBits-1:0] crossed_q, crossed_d;
  wire  [OwedBits-1:0]    owed = crossed_q >= CrossedBits'(Pixels) ? OwedBits'(Pixels) : OwedBits'(crossed_q);
  logic [3:0]    k_q, k_d;            // neighbour being addressed (0..8)
  logic [1:0]    pending_cmp_q, pending_cmp_d;  // [0]: address registered last cycle; [1]: rdata_q holds that neighbour
  logic [3:0]    supporters_q, supporters_d;   // neighbours that fired within the window, 0..8
  logic [3:0]    quiet_supporters_q, quiet_supporters_d;  // neighbours that fired within the quiet window, 0..8
  // The noise check: the current interval, its unsupported events (saturating), and whether
  // the previous interval was noisy.
  localparam int IntervalBits = 32 - NoiseIntervalLog2;
  localparam logic [23:0] CountMax = '1;
  logic                    started_q, started_d, noisy_q, noisy_d, quiet_q, quiet_d;
  // The warm-up: the first judged event's time, whether the warm-up still runs, and whether it
  // keeps the event being judged.
  logic [31:0]             warm_start_q, warm_start_d;
  logic                    warming_q, warming_d, warm_keep_q, warm_keep_d;
  logic [31:0]             warm_elapsed_q, warm_elapsed_d;   // the accepted event's time since warm_start_q
  wire                     warm_within = warm_elapsed_q < cfg_warm_up;
  logic [IntervalBits-1:0] interval_q, interval_d;
  logic [23:0]             unsupported_q, unsupported_d;
  logic [IntervalBits-1:0] event_interval_q, event_interval_d;   // the accepted event's interval
  logic [TimestampBits-1:0] now_q, now_d;
  wire  [31:0]              age = 32'(TimestampBits'(now_q - rdata_q));  // of the neighbour rdata_q holds
  logic [15:0]   ex_q, ex_d, ey_q, ey_d;

  // Neighbour k_q of the event, and whether it is inside the sensor (and not the pixel itself).
  // k_q / 3 and k_q % 3 by comparison: a '/' or '%' here would synthesize a 32-bit divider.
  // Which of the rows above, at and below the event, and of the columns left of, at and right of
  // it, lie inside the sensor is decided once an event (StAccept), so that choosing a neighbour
  // takes no comparison with the sensor's size.
  logic [1:0]         k_row, k_col;
  logic signed [17:0] nx, ny;
  logic [2:0]         rows_inside_q, rows_inside_d, cols_inside_q, cols_inside_d;
  logic               n_inside;
  assign k_row = k_q >= 4'd6 ? 2'd2 : (k_q >= 4'd3 ? 2'd1 : 2'd0);
  assign k_col = 2'(k_q - 4'(k_row) * 4'd3);
  assign nx = $signed({2'b00, ex_q}) + $signed({16'd0, k_col}) - 18'sd1;
  assign ny = $signed({2'b00, ey_q}) + $signed({16'd0, k_row}) - 18'sd1;
  assign n_inside = k_q != 4 && rows_inside_q[k_row] && cols_inside_q[k_col];

  assign ready = state_q == StIdle;

  logic done_d, kept_d;
  always_comb begin
    state_d = state_q;
    clear_addr_d = clear_addr_q;
    scrub_d = scrub_q;
    last_sweep_d = last_sweep_q;
    crossed_d = crossed_q;
    owed_d = owed_q;
    owed_before_reads_d = owed_before_reads_q;
    done_d = 1'b0;
    kept_d = kept;
    we_d = 1'b0;
    addr_d = addr_q;
    wdata_d = wdata_q;
    k_d = k_q;
    pending_cmp_d = pending_cmp_q;
    supporters_d = supporters_q;
    quiet_supporters_d = quiet_supporters_q;
    started_d = started_q;
    noisy_d = noisy_q;
    quiet_d = quiet_q;
    warm_start_d = warm_start_q;
    warming_d = warming_q;
    warm_keep_d = warm_keep_q;
    warm_elapsed_d = warm_elapsed_q;
    event_interval_d = event_interval_q;
    interval_d = interval_q;
    unsupported_d = unsupported_q;
    now_d = now_q;
    ex_d = ex_q;
    ey_d = ey_q;
    rows_inside_d = rows_inside_q;
    cols_inside_d = cols_inside_q;
    case (state_q)
      StClear: begin
        we_d = 1'b1;
        addr_d = clear_addr_q;
        wdata_d = '0;
        clear_addr_d = clear_addr_q + 1'b1;
        if (32'(clear_addr_q) == Pixels - 1) state_d = started_q ? StRead : StIdle;
      end
      StIdle: if (start) begin
        if (!cfg_enabled) begin
          kept_d = 1'b1;
          done_d = 1'b1;
        end else if (x >= cfg_width || y >= cfg_height) begin
          kept_d = 1'b0;
          done_d = 1'b1;
        end else begin
          ex_d = x;
          ey_d = y;
          now_d = TimestampBits'(t >> TimestampShift);
          last_sweep_d = CrossedBits'(t >> SweepLog2);
          crossed_d = CrossedBits'(t >> SweepLog2) - last_sweep_q;
          event_interval_d = t[31:NoiseIntervalLog2];
          if (!started_q) warm_start_d = t;
          warm_elapsed_d = t - warm_start_q;
          state_d = StAccept;
        end
      end
      StAccept: begin
        // The event itself is inside the sensor (StIdle), so its own row and column are.
        rows_inside_d = {17'(ey_q) + 17'd1 < 17'(cfg_height), 1'b1, ey_q != 0};
        cols_inside_d = {17'(ex_q) + 17'd1 < 17'(cfg_width), 1'b1, ex_q != 0};
        k_d = '0;
        pending_cmp_d = '0;
        supporters_d = '0;
        quiet_supporters_d = '0;
        // Scrubbing owed for the time since the last judged event comes before the reads.
        if (started_q && crossed_q > ClearCrossings) begin
          clear_addr_d = '0;
          state_d = StClear;
        end else if (started_q && owed != 0) begin
          owed_d = owed;
          owed_before_reads_d = 1'b1;
          state_d = StScrubRead;
        end else begin
          state_d = StRead;
        end
        // A new interval latches whether the one before it was noisy.
        if (!started_q) begin
          started_d = 1'b1;
          interval_d = event_interval_q;
          warming_d = cfg_warm_up != 0;
          warm_keep_d = cfg_warm_up != 0;
        end else begin
          if (event_interval_q != interval_q) begin
            noisy_d = cfg_noise_count != 0 && event_interval_q == interval_q + 1'b1 && unsupported_q >= cfg_noise_count;
            quiet_d = cfg_quiet_count != 0 && unsupported_q < cfg_quiet_count;
            interval_d = event_interval_q;
            unsupported_d = '0;
          end
          warm_keep_d = warming_q && warm_within;
          if (!warm_within) warming_d = 1'b0;
        end
      end
      StRead: begin
        // Address neighbour k_q (when inside); the RAM answers two cycles later.
        if (pending_cmp_q[1] && rdata_q != 0 && age <= cfg_window) supporters_d = supporters_q + 1'b1;
        if (pending_cmp_q[1] && rdata_q != 0 && age <= cfg_quiet_window) quiet_supporters_d = quiet_supporters_q + 1'b1;
        pending_cmp_d = {pending_cmp_q[0], 1'b0};
        if (k_q <= 8) begin
          if (n_inside) begin
            addr_d = AddrBits'(32'(ny) * MaxWidth + 32'(nx));
            pending_cmp_d[0] = 1'b1;
          end
          k_d = k_q + 1'b1;
        end else if (pending_cmp_q == 2'b00) begin
          state_d = StWrite;
        end
      end
      StWrite: begin
        we_d = 1'b1;
        addr_d = AddrBits'(32'(ey_q) * MaxWidth + 32'(ex_q));
        wdata_d = now_q == 0 ? TimestampBits'(1) : now_q;
        owed_d = OwedBits'(2);
        owed_before_reads_d = 1'b0;
        state_d = StScrubRead;
      end
      StScrubRead: begin
        addr_d = scrub_q;
        state_d = StScrubWait;
      end
      StScrubWait: state_d = StScrubDecide;
      StScrubDecide: begin
        if (rdata_q != 0 && TimestampBits'(now_q - rdata_q) >= HalfWrap) begin
          we_d = 1'b1;
          wdata_d = '0;
        end
        scrub_d = 32'(scrub_q) == Pixels - 1 ? '0 : scrub_q + 1'b1;
        owed_d = owed_q - 1'b1;
        if (owed_q != 1) state_d = StScrubRead;
        else state_d = owed_before_reads_q ? StRead : StDone;
      end
      StDone: begin
        kept_d = (quiet_q ? quiet_supporters_q : supporters_q) >= (noisy_q ? 4'd2 : 4'd1) || warm_keep_q;
        if (supporters_q == 0 && unsupported_q != CountMax) unsupported_d = unsupported_q + 1'b1;
        done_d = 1'b1;
        state_d = StIdle;
      end
      default: state_d = StIdle;
    endcase
  end

  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      state_q <= StClear;
      clear_addr_q <= '0;
      scrub_q <= '0;
      last_sweep_q <= '0;
      crossed_q <= '0;
      owed_q <= '0;
      owed_before_reads_q <= 1'b0;
      done <= 1'b0;
      kept <= 1'b0;
      we_q <= 1'b0;
      addr_q <= '0;
      wdata_q <= '0;
      k_q <= '0;
      pending_cmp_q <= '0;
      supporters_q <= '0;
      quiet_supporters_q <= '0;
      started_q <= 1'b0;
      noisy_q <= 1'b0;
      quiet_q <= 1'b0;
      warm_start_q <= '0;
      warming_q <= 1'b0;
      warm_keep_q <= 1'b0;
      warm_elapsed_q <= '0;
      event_interval_q <= '0;
      interval_q <= '0;
      unsupported_q <= '0;
      now_q <= '0;
      ex_q <= '0;
      ey_q <= '0;
      rows_inside_q <= '0;
      cols_inside_q <= '0;
    end else begin
      state_q <= state_d;
      clear_addr_q <= clear_addr_d;
      scrub_q <= scrub_d;
      last_sweep_q <= last_sweep_d;
      crossed_q <= crossed_d;
      owed_q <= owed_d;
      owed_before_reads_q <= owed_before_reads_d;
      done <= done_d;
      kept <= kept_d;
      we_q <= we_d;
      addr_q <= addr_d;
      wdata_q <= wdata_d;
      k_q <= k_d;
      pending_cmp_q <= pending_cmp_d;
      supporters_q <= supporters_d;
      quiet_supporters_q <= quiet_supporters_d;
      started_q <= started_d;
      noisy_q <= noisy_d;
      quiet_q <= quiet_d;
      warm_start_q <= warm_start_d;
      warming_q <= warming_d;
      warm_keep_q <= warm_keep_d;
      warm_elapsed_q <= warm_elapsed_d;
      event_interval_q <= event_interval_d;
      interval_q <= interval_d;
      unsupported_q <= unsupported_d;
      now_q <= now_d;
      ex_q <= ex_d;
      ey_q <= ey_d;
      rows_inside_q <= rows_inside_d;
      cols_inside_q <= cols_inside_d;
    end
  end
endmodule
