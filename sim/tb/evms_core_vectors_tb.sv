// A vector testbench of evms_core for a SystemVerilog simulator with no C++ harness (Verilator
// --binary --timing here; xsim, Questa or Xcelium elsewhere; not Icarus Verilog 11, docs/rtl.md):
// it plays the words `evms vectors` wrote from the C++ core (host/cli/cmd_vectors.cpp) into the
// core, with random gaps on its input and random backpressure on its three outputs, and prints
// every output word it takes, one line each, in the format of the C++ core's expected_*.txt.
// The RTL agrees when the files are equal:
//
//   evms vectors SOURCE --core BUILD --out DIR
//   (simulate this module with the build's parameters, which rtl/generated/evms_cfg_ice40.cmake
//    lists for the ice40 build, from rtl/generated/, where the tables' paths start, with
//    +vectors=DIR [+seed=N])
//   diff DIR/expected_labels.txt DIR/rtl_labels.txt   (and _tracks, _packets)
//
// The random patterns come from xorshift32 generators seeded by +seed, so that every simulator
// draws the same ones. Sim.VectorTestbenchEqualsTheCppCore (sim/CMakeLists.txt) runs it.
module evms_core_vectors_tb #(
  parameter int MaxEventWords = 1 << 21,
  `include "evms_core_shape_params.svh"
);
  logic clk = 1'b0;
  // The reset is released once, between clock edges, by the stimulus below.
  /* verilator lint_off SYNCASYNCNET */
  logic rst_n = 1'b0;
  /* verilator lint_on SYNCASYNCNET */
  /* verilator lint_off BLKSEQ */
  always #5 clk = !clk;
  /* verilator lint_on BLKSEQ */

  `include "evms_stream_in_wires.svh"
  `include "evms_stream_lab_wires.svh"
  `include "evms_core_vectors_tb.svh"
  logic idle;
  logic [31:0] stat_tracks_started, stat_unassigned;

  evms_core #(
    `include "evms_core_shape_connect.svh"
  ) dut (.*);

  function automatic logic [31:0] xorshift32(input logic [31:0] s);
    logic [31:0] x;
    x = s ^ (s << 13);
    x = x ^ (x >> 17);
    return x ^ (x << 5);
  endfunction

  string dir;
  int unsigned seed;
  logic [EventWordBits-1:0] event_words [MaxEventWords];
  logic [31:0] event_count [1];
  integer labels_fd, tracks_fd, packets_fd;
  logic [31:0] input_rng, output_rng;
  longint unsigned cycles = 0;
  localparam longint unsigned CycleLimit = 64'd2_000_000_000;

  // Output readies drawn at each falling edge, three times in four; the words are taken at the
  // rising edge.
  always @(negedge clk) begin
    output_rng <= xorshift32(output_rng);
    lab_ready <= output_rng[1:0] != 2'b00;
    trk_ready <= output_rng[3:2] != 2'b00;
    pkt_ready <= output_rng[5:4] != 2'b00;
  end
  always @(posedge clk) begin
    cycles <= cycles + 1;
    if (cycles > CycleLimit) $fatal(1, "evms_core_vectors_tb: no end after %0d cycles", cycles);
    if (rst_n && lab_valid && lab_ready) write_label(labels_fd);
    if (rst_n && trk_valid && trk_ready) write_track(tracks_fd);
    if (rst_n && pkt_valid && pkt_ready) write_packet(packets_fd);
  end

  initial begin
    int quiet;
    if (!$value$plusargs("vectors=%s", dir)) $fatal(1, "evms_core_vectors_tb: +vectors=DIR names the folder evms vectors wrote");
    if (!$value$plusargs("seed=%d", seed)) seed = 1;
    $display("evms_core_vectors_tb: vectors %s, seed %0d", dir, seed);
    input_rng = seed | 32'd1;
    output_rng = (seed * 32'd2654435761) | 32'd1;
    $readmemh({dir, "/cfg.hex"}, cfg_words);
    $readmemh({dir, "/count.hex"}, event_count);
    if (event_count[0] > MaxEventWords) $fatal(1, "evms_core_vectors_tb: %0d event words, more than MaxEventWords", event_count[0]);
    $readmemh({dir, "/events.hex"}, event_words);
    labels_fd = $fopen({dir, "/rtl_labels.txt"}, "w");
    tracks_fd = $fopen({dir, "/rtl_tracks.txt"}, "w");
    packets_fd = $fopen({dir, "/rtl_packets.txt"}, "w");
    in_valid = 1'b0;
    event_word = '0;
    repeat (4) @(negedge clk);
    rst_n = 1'b1;
    for (int i = 0; i < event_count[0]; i++) begin
      // A gap of 0 to 3 clocks before each word.
      input_rng = xorshift32(input_rng);
      repeat (int'(input_rng[1:0])) @(negedge clk);
      event_word = event_words[i];
      in_valid = 1'b1;
      do @(posedge clk); while (!in_ready);
      @(negedge clk);
      in_valid = 1'b0;
    end
    // The last word flushes: done once the core is idle with nothing left to give for 64 clocks.
    quiet = 0;
    while (quiet < 64) begin
      @(negedge clk);
      quiet = (!idle || lab_valid || trk_valid || pkt_valid) ? 0 : quiet + 1;
    end
    $fclose(labels_fd);
    $fclose(tracks_fd);
    $fclose(packets_fd);
    $display("evms_core_vectors_tb: %0d event words in %0d clocks, %0d tracks started, %0d clusters without a free track slot",
             event_count[0], cycles, stat_tracks_started, stat_unassigned);
    $finish;
  end
endmodule
