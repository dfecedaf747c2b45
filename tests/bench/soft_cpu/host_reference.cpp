// The host side of tests/bench/soft_cpu.py: the ice40 build's registers at the default method
// (the bytes of hls::Config, whose layout is the same on x86-64 and RV32 ilp32: the firmware
// checks its size), the scene's first events as a C array, and the checksum of the labels the
// same C++ core gives them on the host, which the firmware must reproduce.
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "hls/core/configs.h"
#include "hls/core/core.h"
#include "host/backend/core_config.h"

using namespace evms;
using Ice40Core = hls::Core<hls::Ice40Shape>;

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: host_reference EVENTS_TXT MAX_EVENTS OUT_HEADER\n");
    return 2;
  }
  const Params p = backend::within_build<hls::Ice40Shape>(Params{}, [](const char*) { return false; });
  const hls::Config cfg = backend::core_config<hls::Ice40Shape>(p, SensorSize{128, 128});
  const int max_events = std::atoi(argv[2]);
  FILE* out = std::fopen(argv[3], "w");
  if (out == nullptr) {
    std::fprintf(stderr, "host_reference: cannot write %s\n", argv[3]);
    return 1;
  }
  const auto* bytes = reinterpret_cast<const unsigned char*>(&cfg);
  std::fprintf(out, "static constexpr unsigned kConfigBytes = %zu;\nalignas(8) static const unsigned char kConfig[] = {", sizeof cfg);
  for (size_t i = 0; i < sizeof cfg; ++i) std::fprintf(out, "%u,", bytes[i]);
  std::fprintf(out, "};\n// t_us, then x | y << 8 | p << 16\nstatic const unsigned kEvents[][2] = {\n");

  static Ice40Core core;
  static Ice40Core::LabelStream labels;
  static Ice40Core::TrackStream tracks;
  static Ice40Core::PacketStream packets;
  core.reset(cfg);
  std::ifstream in(argv[1]);
  std::string line;
  unsigned checksum = 0;
  int events = 0;
  while (events < max_events && std::getline(in, line)) {
    double t_s;
    int x, y, pol;
    if (line.empty() || line[0] == '#' || std::sscanf(line.c_str(), "%lf %d %d %d", &t_s, &x, &y, &pol) != 4) continue;
    hls::EventWord e;
    e.t = static_cast<std::uint32_t>(t_s * 1e6 + 0.5);
    e.x = static_cast<std::uint16_t>(x), e.y = static_cast<std::uint16_t>(y), e.p = static_cast<std::uint8_t>(pol);
    std::fprintf(out, "{%uu,%uu},\n", e.t, static_cast<unsigned>(x | y << 8 | pol << 16));
    core.process(e, labels, tracks, packets);
    ++events;
    for (hls::LabelWord w; labels.read(w);) checksum = checksum * 31 + static_cast<unsigned>(w.label);
    tracks.clear();
    packets.clear();
  }
  std::fprintf(out, "};\n");
  std::fclose(out);
  std::printf("%u\n", checksum);
  return 0;
}
