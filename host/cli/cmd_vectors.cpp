// evms vectors SOURCE --core BUILD --out DIR : the words of a run of a core build's C++ core, for
// the vector testbench (sim/tb/evms_core_vectors_tb.sv) in another simulator. DIR gets:
//   cfg.hex                the registers, one 64-bit hex word a line (hls/core/registers.h order)
//   count.hex              the number of event words
//   events.hex             the event words (hls/core/words.h's fields, most significant first)
//   expected_labels.txt    the C++ core's output words, one line each, fields in decimal
//   expected_tracks.txt    (signed where the C++ type is), as the testbench prints the RTL's
//   expected_packets.txt   into rtl_*.txt (rtl/generated/evms_core_vectors_tb.svh)
// The core is the build's RTL Shape, and the method the one --backend rtl runs.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "hls/core/configs.h"
#include "host/backend/core_backend.h"
#include "host/backend/fixed_backend.h"
#include "host/cli/commands.h"
#include "host/cli/common.h"

namespace evms::cli {
namespace {

struct VectorsOptions {
  std::string source;
  std::string core = "host";
  std::string out;
  read::SourceOptions source_options;
  Method method;
};

// A field as the testbench prints it: a signed type's value as a signed number, an unsigned
// one's low `bits` bits (the RTL port's width).
template <class T>
void print_word_field(std::ostream& o, T value, int bits, bool first) {
  if (!first) o << ' ';
  if constexpr (std::is_signed_v<T>) {
    o << static_cast<long long>(value);
  } else {
    const unsigned long long v = static_cast<unsigned long long>(value);
    o << (bits >= 64 ? v : v & ((1ull << bits) - 1));
  }
}

std::ofstream open_vector_file(const std::string& path) {
  std::ofstream f(path, std::ios::binary);
  if (!f) throw std::runtime_error(path + ": cannot write");
  return f;
}

template <class S>
void vectors(const VectorsOptions& o) {
  SensorSize sensor;
  const std::vector<Event> events = read_all_events(o.source, o.source_options, sensor);
  if (events.empty()) throw std::runtime_error(o.source + ": no events");
  const Params method = o.method.resolve(sensor);
  const Params params = backend::fit_core_build("rtl", o.core, method, o.method);
  if (std::string unsupported = backend::rtl_unsupported(params, o.core); !unsupported.empty()) throw std::invalid_argument(unsupported);
  const hls::Config cfg = backend::core_config<S>(params, sensor);
  const std::vector<hls::EventWord> words = backend::core_words_of<S>(events);
  std::filesystem::create_directories(o.out);

  std::ofstream registers = open_vector_file(o.out + "/cfg.hex");
  char hex[32];
#define EVMS_WRITE_REGISTER(name, type, bits, reset, description)                                     \
  std::snprintf(hex, sizeof hex, "%016llx\n", static_cast<unsigned long long>(static_cast<std::uint64_t>(cfg.name))); \
  registers << hex;
  EVMS_CORE_RTL_REGISTERS(EVMS_WRITE_REGISTER)
#undef EVMS_WRITE_REGISTER
  std::snprintf(hex, sizeof hex, "%08zx\n", words.size());
  open_vector_file(o.out + "/count.hex") << hex;
  // Each event word as one binary number of its fields, most significant first, in hex digits.
  std::ofstream event_file = open_vector_file(o.out + "/events.hex");
  for (const hls::EventWord& w : words) {
    std::string bits;
#define EVMS_EVENT_BITS(name, type, width, reset) \
  for (int b = (width) - 1; b >= 0; --b) bits += ((static_cast<unsigned long long>(w.name) >> b) & 1) ? '1' : '0';
    EVMS_EVENT_WORD_FIELDS(EVMS_EVENT_BITS)
#undef EVMS_EVENT_BITS
    bits.insert(0, (4 - bits.size() % 4) % 4, '0');
    std::string digits;
    for (size_t i = 0; i < bits.size(); i += 4) {
      digits += "0123456789abcdef"[(bits[i] - '0') * 8 + (bits[i + 1] - '0') * 4 + (bits[i + 2] - '0') * 2 + (bits[i + 3] - '0')];
    }
    event_file << digits << '\n';
  }

  backend::HostCore<S> core(cfg);
  std::ofstream labels = open_vector_file(o.out + "/expected_labels.txt"), tracks = open_vector_file(o.out + "/expected_tracks.txt"),
                packets = open_vector_file(o.out + "/expected_packets.txt");
  std::size_t n_labels = 0, n_tracks = 0, n_packets = 0;
  // One line a word: its fields in the order of hls/core/words.h.
#define EVMS_PRINT(name, type, bits, reset) print_word_field(file, word.name, bits, first), first = false;
  const auto print_label = [](std::ostream& file, const hls::LabelWord& word) {
    bool first = true;
    EVMS_LABEL_WORD_FIELDS(EVMS_PRINT)
    file << '\n';
  };
  const auto print_track = [](std::ostream& file, const hls::TrackWord& word) {
    bool first = true;
    EVMS_TRACK_WORD_FIELDS(EVMS_PRINT)
    file << '\n';
  };
  const auto print_packet = [](std::ostream& file, const hls::PacketWord& word) {
    bool first = true;
    EVMS_PACKET_WORD_FIELDS(EVMS_PRINT)
    file << '\n';
  };
#undef EVMS_PRINT
  for (const hls::EventWord& w : words) {
    core.process(w);
    core.drain([&](const hls::LabelWord& l) { print_label(labels, l), ++n_labels; },
               [&](const hls::TrackWord& t) { print_track(tracks, t), ++n_tracks; },
               [&](const hls::PacketWord& p) { print_packet(packets, p), ++n_packets; });
  }
  for (std::ofstream* f : {&registers, &event_file, &labels, &tracks, &packets}) {
    f->flush();
    if (!*f) throw std::runtime_error(o.out + ": a write failed");
  }
  std::printf("build       %s (its RTL: packets of %d, %d clusters, %d tracks)\n", o.core.c_str(), params.packet_size, params.max_clusters,
              params.max_tracks);
  std::printf("words       %s event words in; %s labels, %s track updates, %s packet summaries out\n", grouped(static_cast<std::int64_t>(words.size())).c_str(),
              grouped(static_cast<std::int64_t>(n_labels)).c_str(), grouped(static_cast<std::int64_t>(n_tracks)).c_str(),
              grouped(static_cast<std::int64_t>(n_packets)).c_str());
  std::printf("outputs     %s/cfg.hex, count.hex, events.hex and expected_{labels,tracks,packets}.txt\n", o.out.c_str());
  std::printf("testbench   sim/tb/evms_core_vectors_tb.sv at rtl/generated/evms_cfg_%s.cmake's parameters, run from rtl/generated/ with "
              "+vectors=%s, writes rtl_{labels,tracks,packets}.txt there: each equals its expected_ file\n",
              o.core.c_str(), o.out.c_str());
}

}  // namespace

void register_vectors(CLI::App& app) {
  auto o = std::make_shared<VectorsOptions>();
  auto* cmd = app.add_subcommand("vectors", "the words of a core build's C++ core on a source, for the RTL's vector testbench in another simulator");
  cmd->add_option("source", o->source, "event file or URI")->required();
  add_core_build_option(*cmd, "--core", o->core, "core build: host, arty or ice40 (hls/core/configs.h), in its RTL's sizes");
  cmd->add_option("--out", o->out, "folder for the vectors")->required();
  add_source_options(*cmd, o->source_options);
  add_method_options(*cmd, o->method);
  cmd->callback([o] {
#define EVMS_VECTORS_OF_BUILD(name, fixed, rtl, width, height, description) \
  if (o->core == #name) return vectors<hls::rtl>(*o);
    EVMS_CORE_BUILDS(EVMS_VECTORS_OF_BUILD)
#undef EVMS_VECTORS_OF_BUILD
  });
}

}  // namespace evms::cli
