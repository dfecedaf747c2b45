// Lockstep cosimulation of rtl/core/evms_climbs_core.sv, the core cut after its climbs, against
// the C++ core cut at the same place (hls::Core::process_to_climbs, tests/support/core_words.h):
// every verdict word and every climbs frame word (each packet's head, modes and events) equal, in
// order, with random backpressure on both outputs. The seed is drawn anew each run and printed
// (EVMS_SEED=N repeats one); a mismatch repeats the scene with an FST trace in the temporary
// directory (sim/verilated_block.h).
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "Vclimbs_core.h"
#include "hls/core/configs.h"
#include "host/backend/core_config.h"
#include "host/eval/scene_run.h"
#include "host/gen/family.h"
#include "sim/climbs_core_run.h"
#include "tests/support/core_words.h"
#include "tests/support/read_all.h"

namespace evms {
namespace {

using S = hls::Ice40ClimbsShape;
static_assert(EVMS_CLIMBS_CORE_MaxWidth == S::kMaxWidth && EVMS_CLIMBS_CORE_MaxHeight == S::kMaxHeight &&
                  EVMS_CLIMBS_CORE_TimestampBits == S::kTimestampBits && EVMS_CLIMBS_CORE_TimestampShift == S::kTimestampShift &&
                  EVMS_CLIMBS_CORE_PacketMax == S::kPacketMax && EVMS_CLIMBS_CORE_PendingDepth == S::kPendingDepth &&
                  EVMS_CLIMBS_CORE_ModesMax == S::kModesMax && EVMS_CLIMBS_CORE_IterationsMax == S::kIterationsMax &&
                  EVMS_CLIMBS_CORE_UnitShift == S::kFeatFrac + hls::kClimbFrac && EVMS_CLIMBS_CORE_Bands == S::kGridSide,
              "sim/CMakeLists.txt builds the climbs core at the shape the host completes");

// One output word of either stream: a verdict {label, t, x, y, p}, or a frame word (kind 0 head
// {n, modes, steps, climbs, lost}, 1 a mode {x, y, support}, 2 an event {mode}).
using Word = std::array<std::int64_t, 6>;
constexpr std::int64_t kVerdict = -1;

Word verdict_word(const hls::LabelWord& v) { return {kVerdict, v.label, v.t, v.x, v.y, v.p}; }
Word frame_word(const hls::ClimbsWord& w) {
  std::int64_t f[5];
  hls::climbs_word_fields(w, f);
  return {static_cast<std::int64_t>(w.kind), f[0], f[1], f[2], f[3], f[4]};
}

std::vector<Word> frame_words(const hls::ClimbsFrame<S>& f) {
  std::vector<Word> w{{0, f.n, f.mode_count, f.trace.steps, f.trace.climbs, f.trace.modes_lost}};
  for (int c = 0; c < f.mode_count; ++c) w.push_back({1, f.x[c], f.y[c], f.support[c], 0, 0});
  for (int j = 0; j < f.n; ++j) w.push_back({2, f.first_mode[j], 0, 0, 0, 0});
  return w;
}

std::string describe(const Word& w) {
  std::string s = w[0] == kVerdict ? "verdict" : w[0] == 0 ? "head" : w[0] == 1 ? "mode" : "event";
  for (size_t k = 1; k < w.size(); ++k) s.append(" ").append(std::to_string(w[k]));
  return s;
}

struct Outputs {
  std::vector<Word> verdicts, frames;
  std::uint64_t clocks = 0;
};

// The RTL on `words`, with each output ready with probability `ready_p`, until it is idle after
// the last word (sim/climbs_core_run.h).
Outputs run_rtl(const std::vector<hls::EventWord>& words, const hls::Config& cfg, std::uint64_t seed, double ready_p, const std::string& trace) {
  const sim::ClimbsCoreOutputs run = sim::run_climbs_core<Vclimbs_core>(words, cfg, seed, ready_p, trace);
  Outputs out;
  for (const hls::LabelWord& v : run.verdicts) out.verdicts.push_back(verdict_word(v));
  for (const hls::ClimbsWord& w : run.frame_words) out.frames.push_back(frame_word(w));
  out.clocks = run.clocks;
  return out;
}

// The first difference between the model's words and the RTL's, or empty.
std::string difference(const std::vector<Word>& want, const std::vector<Word>& got, const char* stream) {
  for (size_t i = 0; i < want.size(); ++i) {
    if (i >= got.size()) return std::string(stream) + " word " + std::to_string(i) + ": none from the RTL (" + describe(want[i]) + " wanted)";
    if (want[i] != got[i]) return std::string(stream) + " word " + std::to_string(i) + ": " + describe(got[i]) + ", want " + describe(want[i]);
  }
  return got.size() > want.size() ? std::string(stream) + ": " + std::to_string(got.size() - want.size()) + " words more than the model's" : "";
}

// The events' words with a flush mid-stream, and one at the end.
std::vector<hls::EventWord> words_of(const std::vector<Event>& events) { return test::with_flush_midway(test::words_of(events)); }

struct Scene {
  std::string name;
  std::vector<hls::EventWord> words;
  hls::Config cfg;
};

// Each family type's first validation member at 128x128 (its first 0.15 s), with the default
// method's registers at the board's sizes without warm seeds: packets close on their size, their
// span and the flushes. Then two scenes made for the closing rules' edges: a 6x6 block whose
// pixels fire in turn every 10 us under a span of 1,000 us, so that a kept event lands exactly on
// the span (which it does not exceed); and, without a span or the filter's warm-up, 3,000 isolated events the filter
// drops (each leaves at once: no packet is open), then a blob's pixel every 20th word among them,
// which fill the pending queue (4,096 words) before the packet fills. And two real recordings.
std::vector<Scene> scenes(const hls::Config& cfg) {
  std::vector<Scene> out;
  gen::FamilyPins pins;
  pins.width = pins.height = 128;
  for (const char* type : gen::family_types()) {
    gen::SceneConfig config = gen::family_scene(type, gen::split_seed(gen::Split::kValidation, 0), pins);
    config.duration_s = std::min(config.duration_s, 0.15);
    out.push_back({type, words_of(eval::generate_scene(config).events), cfg});
  }
  std::vector<Event> block;
  for (int k = 0; k < 3000; ++k) block.push_back({10 * k, static_cast<std::uint16_t>(60 + k % 6), static_cast<std::uint16_t>(60 + k / 6 % 6), 1});
  Scene ties{"span ties", words_of(block), cfg};
  ties.cfg.packet_max_span_us = 1000;
  out.push_back(ties);
  std::vector<Event> sparse;
  for (int i = 0; i < 12000; ++i) {
    const int k = i / 20;
    if (i % 20 == 0 && i >= 3000) sparse.push_back({50 * i, static_cast<std::uint16_t>(30 + k % 5), static_cast<std::uint16_t>(30 + k / 5 % 5), 0});
    else sparse.push_back({50 * i, static_cast<std::uint16_t>(i % 64 * 2), static_cast<std::uint16_t>(i / 64 % 64 * 2), 1});  // no neighbour
  }
  Scene pending{"pending queue", words_of(sparse), cfg};
  pending.cfg.packet_max_span_us = 0, pending.cfg.filter_warm_up = 0;
  out.push_back(pending);
  // Real recordings at the board's 128x128 (the first 20,000 events there), when
  // ../shared/data/real is present: the middle of the DVXplorer's 640x480, and the corner of the
  // ATIS sample, whose car lies within x 0-53, y 1-60.
  if (const std::string dir = test::shared_data_dir(); !dir.empty()) {
    for (const bool middle : {true, false}) {
      const char* f = middle ? "dvxplorer_indoor.aedat4" : "atis_ncars_sample.dat";
      const std::string path = dir + "/" + f;
      const SensorSize sensor = read::open_source(path, {})->info().sensor;
      read::SourceOptions o;
      o.window.roi = middle ? read::Roi{(sensor.width - 128) / 2, (sensor.height - 128) / 2, 128, 128} : read::Roi{0, 0, 128, 128};
      o.window.limit = 20000;
      out.push_back({f, words_of(test::read_all(path, o)), cfg});
    }
  } else {
    std::printf("../shared/data/real is absent: no real recordings\n");
  }
  return out;
}

// Backpressure: each output ready half the time. The clocks a word are printed for docs/rtl.md.
TEST(ClimbsCoreRtl, EveryVerdictAndClimbsFrameEqualTheCppCoreCutAtTheClimbs) {
  const std::uint64_t seed = sim::cosim_seed();
  const Params p = backend::build_default_params<S>();  // no warm seeds (Shape::kHasWarmSeeds)
  std::uint64_t clocks = 0, events = 0;
  size_t packets = 0;
  for (const Scene& scene : scenes(backend::core_config<S>(p, {128, 128}))) {
    const std::vector<hls::EventWord>& words = scene.words;
    const hls::Config& cfg = scene.cfg;
    std::vector<Word> verdicts, frames;
    for (const hls::LabelWord& v : test::filter_core_verdicts<S>(words, cfg)) verdicts.push_back(verdict_word(v));
    const auto model_frames = test::climbs_core_frames<S>(words, cfg);
    for (const auto& f : model_frames) {
      const auto w = frame_words(f);
      frames.insert(frames.end(), w.begin(), w.end());
    }
    const Outputs got = run_rtl(words, cfg, seed, 0.5, "");
    std::string diff = difference(verdicts, got.verdicts, "verdict");
    if (diff.empty()) diff = difference(frames, got.frames, "climbs frame");
    const std::string verdict = sim::mismatch_traced("climbs_core", seed, scene.name, diff, [&](const std::string& trace) {
      run_rtl(words, cfg, seed, 0.5, trace);
    });
    ASSERT_TRUE(verdict.empty()) << verdict;
    std::printf("%s: %zu words, %zu packets, %.1f clocks a word\n", scene.name.c_str(), words.size(), model_frames.size(),
                static_cast<double>(got.clocks) / static_cast<double>(words.size()));
    clocks += got.clocks, events += words.size(), packets += model_frames.size();
  }
  std::printf("%zu packets, %llu words, %.1f clocks a word with each output ready half the time\n", packets,
              static_cast<unsigned long long>(events), static_cast<double>(clocks) / static_cast<double>(events));
  EXPECT_GT(packets, 20u);
}

}  // namespace
}  // namespace evms
