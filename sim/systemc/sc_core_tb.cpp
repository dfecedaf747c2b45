// A SystemC testbench for the core (verilator --sc): a clock, a driver thread that offers
// events on the valid/ready input, a monitor that takes labelled events under random
// backpressure, and at the end a word-for-word comparison with the C++ core of the same build
// (hls::Ice40Shape). Exit status 0 when every label matches.
#include <systemc.h>

#include <cstdio>
#include <type_traits>
#include <vector>

#include "Vcore_sc_ice40.h"
#include "hls/core/configs.h"
#include "hls/core/core.h"
#include "rtl/generated/evms_cfg_registers.h"

using S = evms::hls::Ice40Shape;

// A few blobs of events moving across a 128x128 sensor, deterministic.
static std::vector<evms::hls::EventWord> blob_words(int count) {
  std::vector<evms::hls::EventWord> w;
  std::uint64_t state = 12345;
  auto next = [&state] {
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return state;
  };
  for (int i = 0; i < count; ++i) {
    const int blob = i % 3;
    const double s = i * 25e-6;
    const double cx = 30 + blob * 35 + 60 * s * (blob == 1 ? -1 : 1), cy = 40 + blob * 20 + 30 * s;
    const int x = static_cast<int>(cx + static_cast<double>(next() % 7) - 3);
    const int y = static_cast<int>(cy + static_cast<double>(next() % 7) - 3);
    w.push_back({static_cast<std::uint32_t>(1 + i * 25), static_cast<std::uint16_t>(x & 127), static_cast<std::uint16_t>(y & 127),
                 static_cast<std::uint8_t>(next() & 1), false});
  }
  evms::hls::EventWord flush;
  flush.flush = true;
  w.push_back(flush);
  return w;
}

// The registers of the build's defaults for a 128x128 sensor, as the generator wrote them.
static evms::hls::Config registers() { return evms::hls::config_of_rtl_registers(evms::hls::generated::kIce40Registers); }

// The C++ type of a Verilated SystemC port of this many bits.
template <int Bits>
using ScPortType = std::conditional_t<Bits == 1, bool, std::conditional_t<Bits <= 32, uint32_t, uint64_t>>;

SC_MODULE(Testbench) {
  sc_clock clk{"clk", 10, SC_NS};
  sc_signal<bool> rst_n, in_valid, in_ready, lab_valid, lab_ready, trk_valid, trk_ready, trk_confirmed, pkt_valid, pkt_ready, idle;
  // One signal per field of the event and label streams (hls/core/words.h).
#define EVMS_IN_SIGNAL(name, type, bits, reset) sc_signal<ScPortType<bits>> in_##name;
  EVMS_EVENT_WORD_FIELDS(EVMS_IN_SIGNAL)
#undef EVMS_IN_SIGNAL
#define EVMS_LAB_SIGNAL(name, type, bits, reset) sc_signal<ScPortType<bits>> lab_##name;
  EVMS_LABEL_WORD_FIELDS(EVMS_LAB_SIGNAL)
#undef EVMS_LAB_SIGNAL
  sc_signal<uint32_t> trk_t, trk_id, trk_x, trk_y, trk_vx, trk_vy, trk_zx, trk_zy,
      trk_events, trk_x_min, trk_y_min, trk_x_max, trk_y_max, pkt_t_first, pkt_t_last, pkt_events, pkt_clusters, pkt_iterations,
      stat_tracks_started, stat_unassigned;
  sc_signal<uint64_t> trk_var_x, trk_var_y;
  // One signal per register of the RTL core (hls/core/registers.h).
#define EVMS_CFG_SIGNAL(name, type, bits, reset, description) sc_signal<ScPortType<bits>> cfg_##name;
  EVMS_CORE_RTL_REGISTERS(EVMS_CFG_SIGNAL)
#undef EVMS_CFG_SIGNAL

  Vcore_sc_ice40 dut{"dut"};
  std::vector<evms::hls::EventWord> words = blob_words(3000);
  std::vector<evms::hls::LabelWord> labels;
  bool finished = false;

  SC_CTOR(Testbench) {
    dut.clk(clk);
    dut.rst_n(rst_n);
    dut.in_valid(in_valid), dut.in_ready(in_ready), dut.lab_valid(lab_valid), dut.lab_ready(lab_ready);
#define EVMS_BIND_IN(name, type, bits, reset) dut.in_##name(in_##name);
    EVMS_EVENT_WORD_FIELDS(EVMS_BIND_IN)
#undef EVMS_BIND_IN
#define EVMS_BIND_LAB(name, type, bits, reset) dut.lab_##name(lab_##name);
    EVMS_LABEL_WORD_FIELDS(EVMS_BIND_LAB)
#undef EVMS_BIND_LAB
    dut.trk_valid(trk_valid), dut.trk_ready(trk_ready), dut.trk_t(trk_t), dut.trk_id(trk_id), dut.trk_x(trk_x), dut.trk_y(trk_y);
    dut.trk_vx(trk_vx), dut.trk_vy(trk_vy), dut.trk_zx(trk_zx), dut.trk_zy(trk_zy), dut.trk_confirmed(trk_confirmed);
    dut.trk_events(trk_events), dut.trk_x_min(trk_x_min), dut.trk_y_min(trk_y_min), dut.trk_x_max(trk_x_max), dut.trk_y_max(trk_y_max);
    dut.trk_var_x(trk_var_x), dut.trk_var_y(trk_var_y);
    dut.pkt_valid(pkt_valid), dut.pkt_ready(pkt_ready), dut.pkt_t_first(pkt_t_first), dut.pkt_t_last(pkt_t_last);
    dut.pkt_events(pkt_events), dut.pkt_clusters(pkt_clusters), dut.pkt_iterations(pkt_iterations), dut.idle(idle);
    dut.stat_tracks_started(stat_tracks_started), dut.stat_unassigned(stat_unassigned);
#define EVMS_BIND_CFG(name, type, bits, reset, description) dut.cfg_##name(cfg_##name);
    EVMS_CORE_RTL_REGISTERS(EVMS_BIND_CFG)
#undef EVMS_BIND_CFG
    SC_THREAD(drive);
    sensitive << clk.posedge_event();
    SC_THREAD(monitor);
    sensitive << clk.posedge_event();
  }

  void drive() {
    const evms::hls::Config c = registers();
#define EVMS_SET_CFG(name, type, bits, reset, description) cfg_##name = static_cast<ScPortType<bits>>(c.name);
    EVMS_CORE_RTL_REGISTERS(EVMS_SET_CFG)
#undef EVMS_SET_CFG
    rst_n = false;
    for (int i = 0; i < 4; ++i) wait();
    rst_n = true;
    for (const auto& w : words) {
      in_valid = true;
#define EVMS_DRIVE_IN(name, type, bits, reset) in_##name = static_cast<ScPortType<bits>>(w.name);
      EVMS_EVENT_WORD_FIELDS(EVMS_DRIVE_IN)
#undef EVMS_DRIVE_IN
      do wait(); while (!in_ready.read());
    }
    in_valid = false;
    for (int quiet = 0; quiet < 64;) {
      wait();
      quiet = idle.read() ? quiet + 1 : 0;
    }
    finished = true;
    sc_stop();
  }

  void monitor() {
    std::uint64_t state = 99;
    trk_ready = true;
    pkt_ready = true;
    for (;;) {
      state ^= state << 13;
      state ^= state >> 7;
      state ^= state << 17;
      lab_ready = (state & 3) != 0;  // ready three cycles in four
      wait();
      if (lab_valid.read() && lab_ready.read()) {
        evms::hls::LabelWord l;
#define EVMS_TAKE_LAB(name, type, bits, reset) l.name = static_cast<type>(lab_##name.read());
        EVMS_LABEL_WORD_FIELDS(EVMS_TAKE_LAB)
#undef EVMS_TAKE_LAB
        labels.push_back(l);
      }
    }
  }
};

int sc_main(int, char**) {
  Testbench tb("tb");
  sc_start();
  auto core = new evms::hls::Core<S>();  // large: not on the stack
  auto out = new evms::hls::Core<S>::LabelStream();
  evms::hls::Core<S>::TrackStream tracks;
  evms::hls::Core<S>::PacketStream packets;
  core->reset(registers());
  std::vector<evms::hls::LabelWord> want;
  for (const auto& w : tb.words) {
    core->process(w, *out, tracks, packets);
    evms::hls::LabelWord l;
    while (out->read(l)) want.push_back(l);
    evms::hls::TrackWord t;
    while (tracks.read(t)) {
    }
    evms::hls::PacketWord p;
    while (packets.read(p)) {
    }
  }
  int mismatches = 0;
  if (!tb.finished || tb.labels.size() != want.size()) {
    std::printf("SystemC testbench: %zu labels from the RTL, %zu from the C++ core\n", tb.labels.size(), want.size());
    mismatches = 1;
  }
  for (size_t i = 0; i < std::min(tb.labels.size(), want.size()); ++i) {
    const auto &a = tb.labels[i], &b = want[i];
    if (a.t != b.t || a.x != b.x || a.y != b.y || a.p != b.p || a.label != b.label) {
      if (mismatches++ < 5) std::printf("label %zu: rtl %d, c++ %d\n", i, a.label, b.label);
    }
  }
  std::printf("SystemC testbench: %zu events in, %zu labels out, %d mismatches\n", tb.words.size() - 1, tb.labels.size(), mismatches);
  delete core;
  delete out;
  return mismatches == 0 ? 0 : 1;
}
