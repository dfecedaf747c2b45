// Background-activity filter with its per-pixel timestamp RAM, as hls/filter/ba_filter.h.
// One event at a time: start with (t, x, y) -> done with kept, about 15 cycles later.
//   - filter off: kept at once, no memory access;
//   - outside the configured sensor: noise, no memory access;
//   - else first scrub for the time since the last judged event: one entry for each 2^SweepLog2
//     us boundary crossed (at most the whole RAM), clearing each whose age is at least half the
//     wrap, or, after a gap of more than a quarter of the wrap, clear the whole RAM; then read the
//     (up to) 8 neighbours inside the sensor, keep when one holds a time t' != 0 with
//     (now - t') mod 2^TimestampBits <= window, where now = t >> TimestampShift; write now (or 1
//     for 0) to the own pixel; then scrub two more entries;
//   - the noise check: the events no neighbour supported are counted in intervals of 2^15 us
//     (t[31:15]); an interval with cfg_noise_count or more of them makes the next one noisy,
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
  parameter int TimestampShift   = 7
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
  logic [AddrBits-1:0]      addr;
  logic               we;
  logic [TimestampBits-1:0] wdata, rdata;
  // One port, and no read while writing: the shape of a single-ported RAM whose output holds
  // during a write (an iCE40 SPRAM, a Xilinx block RAM in NO_CHANGE mode). No state reads
  // rdata after a write cycle.
  always_ff @(posedge clk) begin
    if (we) ram[addr] <= wdata;
    else rdata <= ram[addr];
  end

  typedef enum logic [3:0] {S_CLEAR, S_IDLE, S_READ, S_WRITE, S_SCRUB_READ, S_SCRUB_WAIT, S_SCRUB_DECIDE, S_DONE} state_e;
  state_e state;
  logic [AddrBits-1:0] clear_addr, scrub;
  // The scrubber: the last judged event's time in 2^SweepLog2 us units, the entries it still
  // owes this event (for time, before the reads; then two after the write), and whether they are
  // the ones before the reads. A whole clear after reset has no event; one after a long gap
  // (started_q) is an event's, whose reads follow it.
  logic [CrossedBits-1:0] last_sweep_q;
  logic [OwedBits-1:0]    owed_q;
  logic                   owed_before_reads_q;
  wire  [CrossedBits-1:0] crossed = CrossedBits'(t >> SweepLog2) - last_sweep_q;
  wire  [OwedBits-1:0]    owed = crossed >= CrossedBits'(Pixels) ? OwedBits'(Pixels) : OwedBits'(crossed);
  logic [3:0]    k;            // neighbour being addressed (0..8)
  logic [1:0]    pending_cmp;  // [0]: address registered last cycle; [1]: rdata holds that neighbour
  logic [3:0]    supporters;   // neighbours that fired within the window, 0..8
  logic [3:0]    quiet_supporters;  // neighbours that fired within the quiet window, 0..8
  // The noise check: the current interval, its unsupported events (saturating), and whether
  // the previous interval was noisy.
  localparam int IntervalBits = 17;
  localparam logic [23:0] CountMax = '1;
  logic                    started_q, noisy_q, quiet_q;
  // The warm-up: the first judged event's time, whether the warm-up still runs, and whether it
  // keeps the event being judged.
  logic [31:0]             warm_start_q;
  logic                    warming_q, warm_keep_q;
  wire                     warm_within = t - warm_start_q < cfg_warm_up;
  logic [IntervalBits-1:0] interval_q;
  logic [23:0]             unsupported_q;
  wire  [IntervalBits-1:0] interval = t[31:15];
  logic [TimestampBits-1:0] now;
  wire  [31:0]              age = 32'(TimestampBits'(now - rdata));  // of the neighbour rdata holds
  logic [15:0]   ex, ey;

  // Neighbour k of the event, and whether it is inside the sensor (and not the pixel itself).
  // k / 3 and k % 3 by comparison: a '/' or '%' here would synthesize a 32-bit divider.
  logic [1:0]         k_row, k_col;
  logic signed [17:0] nx, ny;
  logic               n_inside;
  assign k_row = k >= 4'd6 ? 2'd2 : (k >= 4'd3 ? 2'd1 : 2'd0);
  assign k_col = 2'(k - 4'(k_row) * 4'd3);
  assign nx = $signed({2'b00, ex}) + $signed({16'd0, k_col}) - 18'sd1;
  assign ny = $signed({2'b00, ey}) + $signed({16'd0, k_row}) - 18'sd1;
  assign n_inside = k != 4 && nx >= 0 && ny >= 0 && nx < $signed({2'b00, cfg_width}) && ny < $signed({2'b00, cfg_height});

  assign ready = state == S_IDLE;

  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      state <= S_CLEAR;
      clear_addr <= '0;
      scrub <= '0;
      last_sweep_q <= '0;
      owed_q <= '0;
      owed_before_reads_q <= 1'b0;
      done <= 1'b0;
      kept <= 1'b0;
      we <= 1'b0;
      addr <= '0;
      wdata <= '0;
      k <= '0;
      pending_cmp <= '0;
      supporters <= '0;
      quiet_supporters <= '0;
      started_q <= 1'b0;
      noisy_q <= 1'b0;
      quiet_q <= 1'b0;
      warm_start_q <= '0;
      warming_q <= 1'b0;
      warm_keep_q <= 1'b0;
      interval_q <= '0;
      unsupported_q <= '0;
      now <= '0;
      ex <= '0;
      ey <= '0;
    end else begin
      done <= 1'b0;
      we <= 1'b0;
      case (state)
        S_CLEAR: begin
          we <= 1'b1;
          addr <= clear_addr;
          wdata <= '0;
          clear_addr <= clear_addr + 1'b1;
          if (32'(clear_addr) == Pixels - 1) state <= started_q ? S_READ : S_IDLE;
        end
        S_IDLE: if (start) begin
          if (!cfg_enabled) begin
            kept <= 1'b1;
            done <= 1'b1;
          end else if (x >= cfg_width || y >= cfg_height) begin
            kept <= 1'b0;
            done <= 1'b1;
          end else begin
            ex <= x;
            ey <= y;
            now <= TimestampBits'(t >> TimestampShift);
            k <= '0;
            pending_cmp <= '0;
            supporters <= '0;
            quiet_supporters <= '0;
            last_sweep_q <= CrossedBits'(t >> SweepLog2);
            // Scrubbing owed for the time since the last judged event comes before the reads.
            if (started_q && crossed > ClearCrossings) begin
              clear_addr <= '0;
              state <= S_CLEAR;
            end else if (started_q && owed != 0) begin
              owed_q <= owed;
              owed_before_reads_q <= 1'b1;
              state <= S_SCRUB_READ;
            end else begin
              state <= S_READ;
            end
            // A new interval latches whether the one before it was noisy.
            if (!started_q) begin
              started_q <= 1'b1;
              interval_q <= interval;
              warm_start_q <= t;
              warming_q <= cfg_warm_up != 0;
              warm_keep_q <= cfg_warm_up != 0;
            end else begin
              if (interval != interval_q) begin
                noisy_q <= cfg_noise_count != 0 && interval == interval_q + 1'b1 && unsupported_q >= cfg_noise_count;
                quiet_q <= cfg_quiet_count != 0 && unsupported_q < cfg_quiet_count;
                interval_q <= interval;
                unsupported_q <= '0;
              end
              warm_keep_q <= warming_q && warm_within;
              if (!warm_within) warming_q <= 1'b0;
            end
          end
        end
        S_READ: begin
          // Address neighbour k (when inside); the RAM answers two cycles later.
          if (pending_cmp[1] && rdata != 0 && age <= cfg_window) supporters <= supporters + 1'b1;
          if (pending_cmp[1] && rdata != 0 && age <= cfg_quiet_window) quiet_supporters <= quiet_supporters + 1'b1;
          pending_cmp <= {pending_cmp[0], 1'b0};
          if (k <= 8) begin
            if (n_inside) begin
              addr <= AddrBits'(32'(ny) * MaxWidth + 32'(nx));
              pending_cmp[0] <= 1'b1;
            end
            k <= k + 1'b1;
          end else if (pending_cmp == 2'b00) begin
            state <= S_WRITE;
          end
        end
        S_WRITE: begin
          we <= 1'b1;
          addr <= AddrBits'(32'(ey) * MaxWidth + 32'(ex));
          wdata <= now == 0 ? TimestampBits'(1) : now;
          owed_q <= OwedBits'(2);
          owed_before_reads_q <= 1'b0;
          state <= S_SCRUB_READ;
        end
        S_SCRUB_READ: begin
          addr <= scrub;
          state <= S_SCRUB_WAIT;
        end
        S_SCRUB_WAIT: state <= S_SCRUB_DECIDE;
        S_SCRUB_DECIDE: begin
          if (rdata != 0 && TimestampBits'(now - rdata) >= HalfWrap) begin
            we <= 1'b1;
            wdata <= '0;
          end
          scrub <= 32'(scrub) == Pixels - 1 ? '0 : scrub + 1'b1;
          owed_q <= owed_q - 1'b1;
          if (owed_q != 1) state <= S_SCRUB_READ;
          else state <= owed_before_reads_q ? S_READ : S_DONE;
        end
        S_DONE: begin
          kept <= (quiet_q ? quiet_supporters : supporters) >= (noisy_q ? 4'd2 : 4'd1) || warm_keep_q;
          if (supporters == 0 && unsupported_q != CountMax) unsupported_q <= unsupported_q + 1'b1;
          done <= 1'b1;
          state <= S_IDLE;
        end
        default: state <= S_IDLE;
      endcase
    end
  end
endmodule
