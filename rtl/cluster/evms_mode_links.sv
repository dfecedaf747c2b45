// Clusters that touch become one, as hls/cluster/link.h (ModeLinks::run): two modes join when
// an event of one lies within the link distance (dx^2 + dy^2 <= cfg_link2, whole pixels) of an
// event of the other, and every mode's representative is the oldest (smallest) mode of its set.
//
// The result is a partition, and the smallest member of each set, so it does not depend on the
// order of the joins; this block joins in its own order and gives the C++ model's roots:
//   roots  root[c], one register per mode, always the smallest mode of c's set; a join of the
//          sets of a and b rewrites every root equal to the larger of their roots, in one clock
//          (an equivalence table, as connected-component labelling hardware keeps);
//   map    the packet's pixels: a valid bit and the mode last written, PixelsPerWord pixels a
//          word, even words in one memory and odd words in another, so that any run of
//          2 LinkMax + 1 pixels of a row is two words read in one clock;
//   write  each event with a mode reads its pixel's word; a marked pixel joins the two modes
//          (the clock after, while the next event is read); the pixel takes the event's mode,
//          and a pixel marked now goes on the list with the event's mode. Each event's first_*
//          write says whether it is the first with a mode on its pixel (the pixel centre,
//          cluster/evms_centroid.sv);
//   scan   each listed pixel (its set: the members of its listed mode's set, registered) reads
//          the rows y0 .. y0 + LinkMax (within the sensor and the link distance), registers the
//          row's window, and joins its set with every marked pixel within reach ahead of it (the
//          rows below, and to its right in its own row), one join every two clocks (find the
//          first pixel outside the set and register its mode; join, widening the set), until
//          none of them lies outside its set;
//   clear  each listed pixel's word is written zero, so the map is clear for the next packet
//          (after reset, every word is: BankDepth clocks before ready).
//
// Schedule: 1 to start; 2 clocks an event (read its word; mark); per listed pixel 2
// to read it, 1 to read its first row and 2 per row of its window (register the window; search
// it while the next row is read), plus two clocks per join; 1 a listed pixel to clear.
// The packet's events (x, y, the first mode from evms_seeded_climbs) are read through ev_j, with
// the registered read of a block RAM: ev_x, ev_y and ev_mode belong to the ev_j of the clock before.
`include "evms_assert.svh"

module evms_mode_links #(
  parameter int MaxWidth      = 240,
  parameter int MaxHeight     = 180,
  parameter int PacketMax     = 256,
  parameter int ModesMax      = 64,
  parameter int LinkMax       = 4,
  parameter int PixelsPerWord = 16
) (
  input  logic                         clk,
  input  logic                         rst_n,
  output logic                         ready,     // idle: start is taken
  input  logic                         start,
  input  logic [15:0]                  n,
  input  logic [31:0]                  cfg_link2,
  input  logic [15:0]                  cfg_sensor_width,
  input  logic [15:0]                  cfg_sensor_height,
  // The packet's events.
  output logic [15:0]                  ev_j,
  input  logic [15:0]                  ev_x,
  input  logic [15:0]                  ev_y,
  input  logic signed [15:0]           ev_mode,
  // Event first_j is (first_on_pixel) or is not the packet's first event with a mode on its
  // pixel: written once for every event of the write pass.
  output logic                         first_we,
  output logic [15:0]                  first_j,
  output logic                         first_on_pixel,
  output logic                         done,      // one clock
  // After done, while idle: the representative of mode rd_c (combinational).
  input  logic [$clog2(ModesMax)-1:0]  rd_c,
  output logic [$clog2(ModesMax)-1:0]  rd_root
);
  localparam int ModeBits = $clog2(ModesMax);
  localparam int SlotBits = 1 + ModeBits;                   // valid, mode
  localparam int WordBits = PixelsPerWord * SlotBits;
  localparam int SlotIndexBits = $clog2(PixelsPerWord);
  localparam int WordsPerRow = (MaxWidth + PixelsPerWord - 1) / PixelsPerWord;
  localparam int BankWordsPerRow = (WordsPerRow + 1) / 2;
  localparam int BankDepth = MaxHeight * BankWordsPerRow;
  localparam int BankAddrBits = $clog2(BankDepth);
  localparam int ListIndexBits = PacketMax > 1 ? $clog2(PacketMax) : 1;
  localparam int ListCountBits = $clog2(PacketMax + 1);
  localparam int Window = 2 * LinkMax + 1;
  localparam int DyBits = $clog2(LinkMax + 2);
  localparam int HalfWidthBits = DyBits + 1;               // signed: -1 .. LinkMax
  `EVMS_ASSERT_INIT("a row of the window must lie within two words", 2 * LinkMax <= PixelsPerWord)
  `EVMS_ASSERT_INIT("pixels a word must be a power of two", (1 << SlotIndexBits) == PixelsPerWord)
  `EVMS_ASSERT_INIT("modes must be a power of two above one", ModesMax > 1 && (1 << ModeBits) == ModesMax)
  `EVMS_ASSERT_INIT("the map's words must be counted by the 16-bit event counter", BankDepth <= 65536)

  typedef enum logic [3:0] {
    StReset, StIdle, StWriteAddr, StWriteData, StWriteMark, StScanRead, StScanLoad, StRowRead, StRowLoad, StRowJoin,
    StRowApply, StClear, StDone
  } state_e;
  state_e state_q, state_d;

  // ---- the pixel map ----------------------------------------------------------------------------
  logic                    bank_we [2];
  logic [BankAddrBits-1:0] bank_wa, bank_ra [2];
  logic [WordBits-1:0]     bank_wd, bank_rd [2];
  for (genvar b = 0; b < 2; b++) begin : g_bank
    evms_ram_1w1r #(.Width(WordBits), .Depth(BankDepth)) u_bank (
      .clk(clk), .we(bank_we[b]), .wa(bank_wa), .wd(bank_wd), .ra(bank_ra[b]), .rd(bank_rd[b]));
  end
  // The bank and address of word w of row y; a word beyond the row (w = -1 or WordsPerRow)
  // reads word 0, whose pixels the window then masks as outside the sensor.
  function automatic [BankAddrBits-1:0] word_addr(input logic [15:0] y, input logic signed [16:0] w);
    logic signed [16:0] w_in_row;
    begin
      w_in_row = (w < 0 || w >= 17'(WordsPerRow)) ? 17'sd0 : w;
      word_addr = BankAddrBits'(32'(y) * BankWordsPerRow + 32'(w_in_row[16:1]));
    end
  endfunction

  // ---- the list of pixels this packet marked ---------------------------------------------------
  logic                     list_we;
  logic [ListIndexBits-1:0] list_wa, list_ra;
  // {mode, y, x}: the mode that marked the pixel. Every later mode written there joined its set,
  // so it stands for the pixel's set in the scan.
  localparam int ListBits = ModeBits + 32;
  logic [ListBits-1:0]      list_wd, list_rd;
  evms_ram_1w1r #(.Width(ListBits), .Depth(PacketMax)) u_list (
    .clk(clk), .we(list_we), .wa(list_wa), .wd(list_wd), .ra(list_ra), .rd(list_rd));

  // ---- registers ----------------------------------------------------------------------------------
  logic [15:0]              j_q, j_d;             // the event being written
  logic [15:0]              x_q, x_d, y_q, y_d;   // its pixel, or the listed pixel being scanned
  logic [ModeBits-1:0]      mode_q, mode_d;       // its mode, or the listed pixel's mode
  // The modes in the listed pixel's set: set when its scan starts, widened by each join, so
  // that the search reads registers, not the roots.
  logic [ModesMax-1:0]      own_set_q, own_set_d;
  logic [ListCountBits-1:0] listed_q, listed_d;
  logic [ListCountBits-1:0] k_q, k_d;             // the listed pixel being scanned or cleared
  logic [DyBits-1:0]        dy_q, dy_d;
  // The scan's window row, registered from the map's read so that the map's block RAM and the
  // window's shift are a clock's logic and the search over the set another.
  logic [Window*SlotBits-1:0] window_q, window_d;
  logic                     clearing_q, clearing_d;   // list_rd holds a pixel to clear
  logic                     join_pending_q, join_pending_d;   // the write step joins mode_q and outside_q
  // The mode of the pixel a row's search found outside the listed pixel's set, joined the next
  // clock: the search (the window, the set's members, the first outside) and the join (the
  // roots' rewrite) are each a clock's logic, not one path through both.
  logic [ModeBits-1:0]      outside_q, outside_d;

  // ---- roots: one join a clock ------------------------------------------------------------------
  logic [ModeBits-1:0] root_q [ModesMax];
  logic                join_en;
  // The roots have read ports for the two modes a join joins, both registers: mode_q (the
  // event's mode in the write step, the listed pixel's in the scan) and outside_q (the mode found
  // outside its set), and rd_c's (its own, so that what reads rd_root is not timed through the
  // joins).
  logic [ModeBits-1:0] root_a, root_b, join_lo, join_hi;
  assign root_a = root_q[mode_q];
  assign root_b = root_q[outside_q];
  assign join_lo = root_a < root_b ? root_a : root_b;
  assign join_hi = root_a < root_b ? root_b : root_a;
  always_ff @(posedge clk) begin
    for (int c = 0; c < ModesMax; c++) begin
      if (start) root_q[c] <= ModeBits'(c);
      else if (join_en && root_q[c] == join_hi) root_q[c] <= join_lo;
    end
  end
  assign rd_root = root_q[rd_c];

  // The largest dx <= LinkMax with dx^2 + dy^2 <= link2 along each row of the window (-1: none).
  // A link2 beyond 2 LinkMax^2 reaches the whole window, so the comparisons take it clamped.
  localparam int LinkSquareMax = 2 * LinkMax * LinkMax;
  localparam int LinkSquareBits = $clog2(LinkSquareMax + 1);
  logic [LinkSquareBits-1:0] link2_window;
  assign link2_window = cfg_link2 > 32'(LinkSquareMax) ? LinkSquareBits'(LinkSquareMax) : LinkSquareBits'(cfg_link2);
  logic signed [HalfWidthBits-1:0] half_width [LinkMax + 1];
  always_comb begin
    for (int dy = 0; dy <= LinkMax; dy++) begin
      half_width[dy] = -1;
      for (int dx = 0; dx <= LinkMax; dx++) if (LinkSquareBits'(dx * dx + dy * dy) <= link2_window) half_width[dy] = HalfWidthBits'(dx);
    end
  end

  // ---- the write step's word and slot ----------------------------------------------------------
  logic signed [16:0] ev_word;
  logic [SlotIndexBits-1:0] ev_slot;
  logic [WordBits-1:0] mark_word, marked_word;
  logic [SlotBits-1:0] mark_slot;
  assign ev_word = {1'b0, x_q >> SlotIndexBits};
  assign ev_slot = x_q[SlotIndexBits-1:0];
  assign mark_word = bank_rd[ev_word[0]];
  assign mark_slot = mark_word[32'(ev_slot) * SlotBits +: SlotBits];
  always_comb begin
    marked_word = mark_word;
    marked_word[32'(ev_slot) * SlotBits +: SlotBits] = {1'b1, mode_q};
  end

  // ---- the scan's window row -------------------------------------------------------------------
  // The window's first pixel x0 - LinkMax lies in word win_word (signed: -1 left of the sensor);
  // seg holds words win_word and win_word + 1, and window holds its slots win_offset .. win_offset
  // + 2 LinkMax: window position i (dx = i - LinkMax).
  logic signed [16:0] win_start, win_word;
  logic [SlotIndexBits-1:0] win_offset;
  logic [2*WordBits-1:0] seg;
  logic [Window*SlotBits-1:0] window;
  // The row read: dy in StRowRead, the next row (dy + 1) while dy's is searched in StRowJoin, so
  // that a row with nothing outside the set goes straight to registering the next one.
  logic [DyBits-1:0] row_dy;
  logic [15:0] row_y;
  logic row_exists;
  assign win_start = $signed(17'(x_q)) - 17'(LinkMax);
  assign win_word = win_start >>> SlotIndexBits;
  assign win_offset = win_start[SlotIndexBits-1:0];
  assign seg = win_word[0] ? {bank_rd[0], bank_rd[1]} : {bank_rd[1], bank_rd[0]};
  assign window = (Window*SlotBits)'(seg >> (32'(win_offset) * SlotBits));
  assign row_dy = state_q == StRowJoin ? dy_q + 1'b1 : dy_q;
  assign row_y = y_q + 16'(row_dy);
  assign row_exists = 32'(row_dy) <= LinkMax && half_width[row_dy] >= 0 && row_y < cfg_sensor_height;

  // The modes whose root is root_a's, and root_b's.
  logic [ModesMax-1:0] set_of_a, set_of_b;
  always_comb for (int c = 0; c < ModesMax; c++) begin
    set_of_a[c] = root_q[c] == root_a;
    set_of_b[c] = root_q[c] == root_b;
  end
  // The window positions i (dx = i - LinkMax) in reach: within the row's half width, within the
  // sensor (room_left, room_right: the pixels beside x0 up to LinkMax), and ahead of x0 in its own
  // row.
  localparam int WindowBits = $clog2(Window + 1);
  logic [WindowBits-1:0] room_left, room_right, reach, reach_lo, reach_hi;
  logic [15:0] right_of_x0;
  assign right_of_x0 = cfg_sensor_width - 16'd1 - x_q;
  assign room_left = x_q < 16'(LinkMax) ? WindowBits'(x_q) : WindowBits'(LinkMax);
  assign room_right = right_of_x0 < 16'(LinkMax) ? WindowBits'(right_of_x0) : WindowBits'(LinkMax);
  assign reach = WindowBits'(half_width[dy_q]);       // half_width >= 0 in StRowJoin
  assign reach_lo = dy_q == 0 ? WindowBits'(LinkMax + 1) : WindowBits'(LinkMax) - (room_left < reach ? room_left : reach);
  assign reach_hi = WindowBits'(LinkMax) + (room_right < reach ? room_right : reach);
  logic                outside_found;
  logic [ModeBits-1:0] outside_mode;
  always_comb begin
    outside_found = 1'b0;
    outside_mode = '0;
    for (int i = Window - 1; i >= 0; i--) begin
      logic [SlotBits-1:0] slot;
      slot = window_q[i * SlotBits +: SlotBits];
      if (slot[ModeBits] && !own_set_q[slot[ModeBits-1:0]] && WindowBits'(i) >= reach_lo && WindowBits'(i) <= reach_hi) begin
        outside_found = 1'b1;
        outside_mode = slot[ModeBits-1:0];
      end
    end
  end

  // ---- control --------------------------------------------------------------------------------------
  always_comb begin
    state_d = state_q;
    j_d = j_q;
    x_d = x_q;
    y_d = y_q;
    mode_d = mode_q;
    listed_d = listed_q;
    k_d = k_q;
    dy_d = dy_q;
    clearing_d = 1'b0;
    join_pending_d = 1'b0;
    join_en = 1'b0;
    outside_d = outside_q;
    window_d = window_q;
    own_set_d = own_set_q;
    bank_we[0] = 1'b0;
    bank_we[1] = 1'b0;
    bank_wa = word_addr(y_q, ev_word);
    bank_wd = marked_word;
    bank_ra[0] = word_addr(ev_y, {1'b0, ev_x >> SlotIndexBits});
    bank_ra[1] = bank_ra[0];
    // A row of the window: read in StRowRead or StRowJoin (row_dy), registered in StRowLoad.
    if (state_q == StRowRead || state_q == StRowJoin) begin
      bank_ra[win_word[0]] = word_addr(row_y, win_word);
      bank_ra[!win_word[0]] = word_addr(row_y, win_word + 17'sd1);
    end
    list_we = 1'b0;
    list_wa = ListIndexBits'(listed_q);
    list_wd = {mode_q, y_q, x_q};
    list_ra = ListIndexBits'(k_q);
    // An event without a mode is written in StWriteData (j_q), one with a mode in StWriteMark
    // (j_q has moved on to the next event).
    first_we = 1'b0;
    first_j = j_q - 16'd1;
    first_on_pixel = !mark_slot[ModeBits];
    done = 1'b0;
    case (state_q)
      // After reset the map is cleared word by word (j counts them): the model's map starts
      // clear, and so must a block RAM whatever it held.
      StReset: begin
        bank_we[0] = 1'b1;
        bank_we[1] = 1'b1;
        bank_wa = BankAddrBits'(j_q);
        bank_wd = '0;
        j_d = j_q + 1'b1;
        if (32'(j_q) + 1 == BankDepth) state_d = StIdle;
      end
      StIdle: if (start) begin
        j_d = '0;
        listed_d = '0;
        state_d = cfg_link2 == 0 ? StDone : StWriteAddr;
      end
      StWriteAddr: state_d = StWriteData;
      // Event j's pixel and mode are here: read its word, or pass an event without a mode. The
      // join the event before found (mode_q, outside_q) is made now.
      StWriteData: begin
        join_en = join_pending_q;
        if (j_q == n) begin
          k_d = '0;
          state_d = StScanRead;
        end else begin
          x_d = ev_x;
          y_d = ev_y;
          mode_d = ModeBits'(ev_mode);
          j_d = j_q + 1'b1;
          state_d = ev_mode < 0 ? StWriteAddr : StWriteMark;
          if (ev_mode < 0) begin
            first_we = 1'b1;
            first_j = j_q;
            first_on_pixel = 1'b0;
          end
        end
      end
      // Its word is here (and event j + 1's pixel is being read): a marked pixel's mode is joined
      // the next clock (the map's read and the roots' rewrite are not one path), an unmarked
      // pixel is listed, and the event's mode is written there.
      StWriteMark: begin
        first_we = 1'b1;
        if (mark_slot[ModeBits]) begin
          join_pending_d = 1'b1;
          outside_d = mark_slot[ModeBits-1:0];
        end else begin
          list_we = 1'b1;
          listed_d = listed_q + 1'b1;
        end
        bank_we[ev_word[0]] = 1'b1;
        state_d = StWriteData;
      end
      StScanRead: state_d = k_q == listed_q ? StClear : StScanLoad;
      StScanLoad: begin
        {mode_d, y_d, x_d} = list_rd;
        dy_d = '0;
        state_d = StRowRead;
      end
      StRowRead: begin
        own_set_d = set_of_a;
        if (row_exists) begin
          state_d = StRowLoad;
        end else begin
          k_d = k_q + 1'b1;
          state_d = StScanRead;
        end
      end
      StRowLoad: begin
        window_d = window;
        state_d = StRowJoin;
      end
      StRowJoin: begin
        if (outside_found) begin
          outside_d = outside_mode;
          state_d = StRowApply;
        end else if (row_exists) begin   // the next row, read this clock
          dy_d = dy_q + 1'b1;
          state_d = StRowLoad;
        end else begin
          k_d = k_q + 1'b1;
          state_d = StScanRead;
        end
      end
      StRowApply: begin
        join_en = 1'b1;
        own_set_d = own_set_q | set_of_b;
        state_d = StRowJoin;
      end
      // One listed pixel a clock: list_rd holds the one read the clock before.
      StClear: begin
        if (clearing_q) begin
          bank_we[list_rd[SlotIndexBits]] = 1'b1;
          bank_wa = word_addr(list_rd[31:16], {1'b0, list_rd[15:0] >> SlotIndexBits});
          bank_wd = '0;
        end
        if (k_q != 0) begin      // k runs down from listed; k - 1 is read now
          list_ra = ListIndexBits'(k_q - 1'b1);
          k_d = k_q - 1'b1;
          clearing_d = 1'b1;
        end else if (!clearing_q) begin
          state_d = StDone;
        end
      end
      StDone: begin
        done = 1'b1;
        state_d = StIdle;
      end
      default: state_d = StIdle;
    endcase
  end
  `EVMS_ASSERT("start only when ready", !start || state_q == StIdle, clk, rst_n)
  `EVMS_ASSERT("an event must lie within the map", state_q != StWriteMark || (x_q < 16'(MaxWidth) && y_q < 16'(MaxHeight)), clk, rst_n)
  `EVMS_ASSERT("a mode must be below ModesMax", state_q != StWriteData || j_q == n || ev_mode < $signed(16'(ModesMax)), clk, rst_n)

  assign ev_j = j_q;
  assign ready = state_q == StIdle;

  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      state_q <= StReset;
      j_q <= '0;
      x_q <= '0;
      y_q <= '0;
      mode_q <= '0;
      listed_q <= '0;
      k_q <= '0;
      dy_q <= '0;
      clearing_q <= 1'b0;
      join_pending_q <= 1'b0;
      outside_q <= '0;
      window_q <= '0;
      own_set_q <= '0;
    end else begin
      state_q <= state_d;
      j_q <= j_d;
      x_q <= x_d;
      y_q <= y_d;
      mode_q <= mode_d;
      listed_q <= listed_d;
      k_q <= k_d;
      dy_q <= dy_d;
      clearing_q <= clearing_d;
      join_pending_q <= join_pending_d;
      outside_q <= outside_d;
      window_q <= window_d;
      own_set_q <= own_set_d;
    end
  end
endmodule
