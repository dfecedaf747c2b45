// What the block-level cosimulations (tests/sim/test_seeded_climbs.cpp, test_mode_links.cpp,
// test_polarity_split.cpp, test_edge_join.cpp, test_warm_seeds.cpp) share: the run's seed, drawn
// anew and printed (EVMS_SEED=N repeats a run), the verdict of a run's lockstep check, the
// draws their packets are made of, a run's results and clocks, and one Verilated block with its
// clock, its reset, its start and done and, when a mismatch is being repeated, an FST trace.
#pragma once

#include <verilated.h>
#include <verilated_fst_c.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <initializer_list>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace evms::sim {

inline std::uint64_t cosim_seed() {
  const char* pinned = std::getenv("EVMS_SEED");
  const std::uint64_t seed = pinned ? std::strtoull(pinned, nullptr, 10) : std::random_device{}();
  std::printf("seed %llu\n", static_cast<unsigned long long>(seed));
  return seed;
}

// Where the trace of a failed run of `block` goes.
inline std::string cosim_trace_path(const std::string& block, std::uint64_t seed) {
  return (std::filesystem::temp_directory_path() / ("evms_" + block + "_" + std::to_string(seed) + ".fst")).string();
}

// The lockstep check's verdict on one run of a block: empty when the RTL gave what the model
// gave (`difference` empty); otherwise the run is repeated with an FST trace (`retrace(path)`)
// and the verdict names the seed, the run (`what`), the first difference and the trace.
template <class Retrace>
std::string mismatch_traced(const std::string& block, std::uint64_t seed, const std::string& what, const std::string& difference,
                            Retrace retrace) {
  if (difference.empty()) return "";
  const std::string trace = cosim_trace_path(block, seed);
  retrace(trace);
  return "seed " + std::to_string(seed) + ", " + what + ": " + difference + "; trace in " + trace;
}

// Draws on the run's generator.
struct Draws {
  std::mt19937_64& rng;
  int below(int k) { return static_cast<int>(rng() % static_cast<std::uint64_t>(k)); }
  double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); }
  template <class T>
  T one_of(std::initializer_list<T> values) {
    return values.begin()[below(static_cast<int>(values.size()))];
  }
  // A usual sensor up to 1280x720, never taller than wide: {width, height}.
  std::pair<int, int> sensor() {
    const int width = one_of({128, 240, 346, 640, 1280});
    return {width, std::min(width, one_of({128, 180, 260, 480, 720}))};
  }
};

// What a block gave over a run of packets, and the clocks it took for their events.
template <class Result>
struct BlockRun {
  std::vector<Result> results;
  std::uint64_t cycles = 0, events = 0;
};

// Where a run's results first differ: "packet K: " and what `describe(want, got)` says of that
// packet's two results; empty when every packet's are equal.
template <class Result, class Describe>
std::string first_packet_difference(const std::vector<Result>& want, const std::vector<Result>& got, Describe describe) {
  for (size_t k = 0; k < want.size(); ++k) {
    if (k >= got.size()) return "packet " + std::to_string(k) + ": no result from the RTL";
    if (!(want[k] == got[k])) return "packet " + std::to_string(k) + ": " + describe(want[k], got[k]);
  }
  return "";
}

// The lockstep check of a block over `runs` runs of packets: run r is `draw(r)`, the model's
// results are `model(run)`, the RTL's `rtl(run, trace_path)` (a BlockRun), and a packet's
// results differ as `describe` says (first_packet_difference). The first run that differs ends
// the check with mismatch_traced's verdict; `tally(run, want)` sees each run that agreed.
struct RunsCompared {
  std::string verdict;   // empty: every run agreed
  std::uint64_t cycles = 0, events = 0;
};
template <class Draw, class Model, class Rtl, class Describe, class Tally>
RunsCompared compare_runs(const std::string& block, std::uint64_t seed, int runs, Draw draw, Model model, Rtl rtl, Describe describe,
                          Tally tally) {
  RunsCompared c;
  for (int r = 0; r < runs; ++r) {
    const auto run = draw(r);
    const auto want = model(run);
    const auto got = rtl(run, std::string());
    c.verdict = mismatch_traced(block, seed, "run " + std::to_string(r), first_packet_difference(want, got.results, describe),
                                [&](const std::string& trace) { rtl(run, trace); });
    if (!c.verdict.empty()) return c;
    c.cycles += got.cycles, c.events += got.events;
    tally(run, want);
  }
  return c;
}

template <class Model>
class VerilatedBlock {
 public:
  // An empty trace_path: no trace.
  explicit VerilatedBlock(const std::string& trace_path) : context_(std::make_unique<VerilatedContext>()) {
    if (!trace_path.empty()) context_->traceEverOn(true);
    model_ = std::make_unique<Model>(context_.get());
    if (!trace_path.empty()) {
      fst_ = std::make_unique<VerilatedFstC>();
      model_->trace(fst_.get(), 99);
      fst_->open(trace_path.c_str());
    }
    model_->rst_n = 0;
    tick();
    model_->rst_n = 1;
  }
  ~VerilatedBlock() {
    if (fst_) fst_->close();
    model_->final();
  }
  VerilatedBlock(const VerilatedBlock&) = delete;
  VerilatedBlock& operator=(const VerilatedBlock&) = delete;

  Model* operator->() { return model_.get(); }

  // Clocks until the block's ready is set: a block that clears a memory after reset.
  void tick_until_ready() {
    for (std::uint64_t k = 0; !model_->ready; ++k) {
      if (k > 10'000'000) throw std::runtime_error("the block never left reset");
      tick();
    }
  }

  // Raises start for one clock and clocks until the block's one-clock done, each clock by
  // `clock` (tick(), or a tick that also answers the block's memory reads); returns the clocks.
  template <class Clock>
  std::uint64_t run_until_done(Clock&& clock, std::uint64_t limit) {
    model_->start = 1;
    clock();
    model_->start = 0;
    std::uint64_t clocks = 1;
    for (; !model_->done; ++clocks) {
      if (clocks > limit) throw std::runtime_error("the block did not finish");
      clock();
    }
    return clocks;
  }
  void tick() {
    model_->clk = 0;
    model_->eval();
    if (fst_) fst_->dump(time_++);
    model_->clk = 1;
    model_->eval();
    if (fst_) fst_->dump(time_++);
  }

 private:
  std::unique_ptr<VerilatedContext> context_;
  std::unique_ptr<Model> model_;
  std::unique_ptr<VerilatedFstC> fst_;
  std::uint64_t time_ = 0;
};

}  // namespace evms::sim
