// The firmware side of tests/bench/soft_cpu.py: the ice40 core (hls::Core<Ice40Shape>, the same
// source as every other build of it) run bare on an RV32IM CPU over the events and registers
// that host_reference wrote to scene.h. It prints the labels' checksum, which must equal the
// host's, and the bytes of stack it used, then exits: under qemu-riscv32's user mode, through
// Linux's write and exit system calls.
#include "hls/core/configs.h"
#include "hls/core/core.h"
#include "scene.h"

using namespace evms::hls;
using Ice40Core = Core<Ice40Shape>;
static_assert(sizeof(Config) == kConfigBytes, "the host's hls::Config layout differs from RV32's");

static Ice40Core core;
static Ice40Core::LabelStream labels;
static Ice40Core::TrackStream tracks;
static Ice40Core::PacketStream packets;

extern "C" unsigned char __stack_bottom[], __stack_top[];
extern "C" void (*__init_array_start[])(), (*__init_array_end[])();
static constexpr unsigned char kStackPaint = 0xA5;  // the byte _start paints the stack with (its li t1)

static long system_call(long number, long a0, long a1, long a2) {
  register long r_a0 asm("a0") = a0;
  register long r_a1 asm("a1") = a1;
  register long r_a2 asm("a2") = a2;
  register long r_a7 asm("a7") = number;
  asm volatile("ecall" : "+r"(r_a0) : "r"(r_a1), "r"(r_a2), "r"(r_a7) : "memory");
  return r_a0;
}

static int put_decimal(char* out, unsigned v) {
  char digits[12];
  int n = 0, k = 0;
  do digits[n++] = static_cast<char>('0' + v % 10), v /= 10;
  while (v != 0);
  while (n > 0) out[k++] = digits[--n];
  return k;
}

extern "C" int run() {
  for (auto* constructor = __init_array_start; constructor != __init_array_end; ++constructor) (*constructor)();
  Config cfg;
  __builtin_memcpy(&cfg, kConfig, sizeof cfg);
  core.reset(cfg);
  unsigned checksum = 0;
  for (const auto& word : kEvents) {
    EventWord e;
    e.t = word[0];
    e.x = static_cast<std::uint16_t>(word[1] & 0xFF);
    e.y = static_cast<std::uint16_t>(word[1] >> 8 & 0xFF);
    e.p = static_cast<std::uint8_t>(word[1] >> 16 & 1);
    core.process(e, labels, tracks, packets);
    for (LabelWord w; labels.read(w);) checksum = checksum * 31 + static_cast<unsigned>(w.label);
    tracks.clear();
    packets.clear();
  }
  unsigned untouched = 0;
  while (__stack_bottom[untouched] == kStackPaint) ++untouched;
  char line[40];
  int k = put_decimal(line, checksum);
  line[k++] = ' ';
  k += put_decimal(line + k, static_cast<unsigned>(__stack_top - __stack_bottom) - untouched);
  line[k++] = '\n';
  system_call(64, 1, reinterpret_cast<long>(line), k);  // write(1, line, k)
  system_call(93, 0, 0, 0);                              // exit(0)
  return 0;
}

// Paints the stack, so that run() can tell how much of it was used, then runs.
extern "C" [[noreturn]] __attribute__((naked, section(".text.start"))) void _start() {
  asm volatile(
      "la sp, __stack_top\n"
      "la t0, __stack_bottom\n"
      "li t1, 0xA5\n"
      "1: sb t1, 0(t0)\n"
      "addi t0, t0, 1\n"
      "bltu t0, sp, 1b\n"
      "call run\n");
}
