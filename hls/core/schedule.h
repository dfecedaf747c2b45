// The hardware schedule of the core, rtl/core/evms_core.sv, as a cycle model: how many clocks
// each stage takes, from what the C++ core did (hls/core/core.h reports every word and, per
// packet, a PacketTrace). The controller runs one stage at a time, so its stages add up; the
// intake (the filter) runs ahead of it through a queue, and the controller's waits for it are
// followed word by word (ScheduleCounter). Every term below is read off a state machine of the
// RTL; tests/sim/test_cosim.cpp (Schedule.*) checks the model against the Verilated RTL stage
// by stage, exactly, when no output is held back.
//
// With n events in a packet, P kernel lanes, C = ceil(n / P), L the multiplier's latency
// (3 clocks for a 64-bit product, pipelined over its digit products, ceil(64 / d) + 1 for d bits
// a clock) and R = 6 the reciprocal's:
//   accept      1 per input word (the controller takes it from the intake's queue)
//   filter      the controller's clocks waiting for the intake: the filter takes 20..22 clocks
//               an event (22 inside the sensor, less on its last row and column; 1 when it is
//               off or the event is outside the sensor), plus 3 for each entry its time
//               scrubber owes (hls/filter/ba_filter.h) or the RAM's size after a long gap, at
//               least 3 with the climb features and 3 more through the queue, but runs while
//               the controller clusters
//   features    5 + 4 (L + 1) per kept event (three products and the decay table)
//   mean shift  3 + sweeps ((n - 1) max(C + 1, R + 10) + C + R + 19) per packet: each point is
//               read (1) and issues C chunks while the previous one's terms drain through the
//               lanes; its sums go to the divider (R + 10 clocks a point), so points start at
//               least R + 10 apart; the sweep waits for the last point's drain and division
//   merge       8 n + (mode, seed) distances + seeds + 4 (a mode's distances drain a three-stage
//               pipeline)
//   centroids   3 n + clusters (R + 2 + 3 (L + 1)) + 4
//   tracking    3 T + 7 + m + births + scans (T + 2) + steps + (1 + a (L + 1)) distances
//               + (2 R + 8 + 30 (L + 1)) matches (+1 when every round matched; a reciprocal
//               per axis) + (T + 2) eviction scans (a birth with no free slot, evict_stale);
//               a distance is taken once per (live track, measurement) pair, with a = 2
//               products (associate_last: two squares) or 4 (the prediction's two first), and
//               each round's scan reads the pair table a pair a clock
//   release     4 per event, and 1 + 1 per packet closing and sending its summary
//   packet control 1 per kept event appended
// where T is the Shape's track slots and m the packet's clusters. Mean shift is the term that
// grows with n: per event it is about sweeps max(n / P + 1, 16).
#pragma once

#include <cstdint>

#include "hls/core/config.h"
#include "hls/core/core.h"
#include "hls/filter/ba_filter.h"

namespace evms::hls {

enum class Stage { kAccept, kFilter, kPacketControl, kFeatures, kMeanShift, kMerge, kCentroid, kTrack, kRelease };
constexpr int kStageCount = 9;
constexpr const char* kStageNames[kStageCount] = {"accept",     "filter", "packet control", "features", "mean shift",
                                                  "merge",      "centroids", "tracking",    "release"};

// The states of the core's controller (rtl/core/evms_core.sv, state_e), in encoding order, each
// with the stage its clocks count in. rtl/generated/evms_core_states.svh is written from this
// list (host/tools/rtl_gen), and sim/rtl_profile.h reads the RTL's state through it. Idle counts
// as accept while the intake's queue has a word for it, and as filter while the queue is empty
// and a word is offered or in the intake.
#define EVMS_CORE_CONTROLLER_STATES(X) \
  X(Idle, kAccept)                     \
  X(Append, kPacketControl)            \
  X(Close, kPacketControl)             \
  X(FeatRead, kFeatures)               \
  X(FeatWait, kFeatures)               \
  X(FeatX, kFeatures)                  \
  X(FeatY, kFeatures)                  \
  X(FeatAge, kFeatures)                \
  X(FeatDecay1, kFeatures)             \
  X(FeatDecay2, kFeatures)             \
  X(FeatT, kFeatures)                  \
  X(FeatStore, kFeatures)              \
  X(MeanShift, kMeanShift)             \
  X(Merge, kMerge)                     \
  X(Climb, kMeanShift)                 \
  X(Link, kMerge)                      \
  X(Dense, kMerge)                     \
  X(Split, kMerge)                     \
  X(Edge, kMerge)                      \
  X(Warm, kMerge)                      \
  X(Centroid, kCentroid)               \
  X(Track, kTrack)                     \
  X(Packet, kPacketControl)            \
  X(ReleaseRead, kRelease)             \
  X(ReleaseWait, kRelease)             \
  X(ReleaseCluster, kRelease)          \
  X(ReleaseSend, kRelease)

#define EVMS_CONTROLLER_STATE_STAGE(state, stage) Stage::stage,
constexpr Stage kControllerStateStage[] = {EVMS_CORE_CONTROLLER_STATES(EVMS_CONTROLLER_STATE_STAGE)};
#undef EVMS_CONTROLLER_STATE_STAGE
#define EVMS_CONTROLLER_STATE_NAME(state, stage) "St" #state,
constexpr const char* kControllerStateNames[] = {EVMS_CORE_CONTROLLER_STATES(EVMS_CONTROLLER_STATE_NAME)};
#undef EVMS_CONTROLLER_STATE_NAME
constexpr int kControllerStates = sizeof(kControllerStateStage) / sizeof(kControllerStateStage[0]);

struct StageCycles {
  double cycles[kStageCount] = {};
  double& operator[](Stage s) { return cycles[static_cast<int>(s)]; }
  double operator[](Stage s) const { return cycles[static_cast<int>(s)]; }
  double& operator[](int s) { return cycles[s]; }
  double operator[](int s) const { return cycles[s]; }
  StageCycles& operator+=(const StageCycles& o) {
    for (int s = 0; s < kStageCount; ++s) cycles[s] += o.cycles[s];
    return *this;
  }
  double total() const {
    double t = 0;
    for (int s = 0; s < kStageCount; ++s) t += cycles[s];
    return t;
  }
};

constexpr int kRecipLatency = 6;  // clocks from a reciprocal's start to its done

// Clocks from a multiplier start to its result: a state that waits for a product lasts one more.
constexpr int multiplier_latency(int digit_bits) { return digit_bits >= 64 ? 3 : (64 + digit_bits - 1) / digit_bits + 1; }

// Clocks of one mean-shift sweep over n points with `lanes` kernel lanes.
constexpr std::int64_t sweep_cycles(int n, int lanes) {
  const std::int64_t chunks = (n + lanes - 1) / lanes;
  const std::int64_t divider = kRecipLatency + 10;              // the divider's clocks a point
  // A point reads its coordinates (1) and issues its chunks; the next point follows at once,
  // but no sooner than a division after the previous one started.
  const std::int64_t period = chunks + 1 > divider ? chunks + 1 : divider;
  // The last point: read, issue, its terms drain (6) and are summed (1), then the division
  // (R + 10) and the buffer swap (1).
  return (n - 1) * period + 1 + chunks + 7 + divider + 1;
}

// The lane counts the model follows at once (a core's own is one of them).
constexpr int kModelLaneCounts[] = {1, 2, 4, 8, 16, 32, 64};
constexpr int kModelLaneCountsN = sizeof(kModelLaneCounts) / sizeof(kModelLaneCounts[0]);
constexpr int model_lane_index(int lanes) {
  for (int l = 0; l < kModelLaneCountsN; ++l) {
    if (kModelLaneCounts[l] == lanes) return l;
  }
  return -1;
}

// The intake's clocks (rtl/core/evms_intake.sv): a word taken at clock A is pushed at
// A + max(F, kIntakeMinClocks) and reaches the head of an empty queue kQueueLatency clocks later.
constexpr std::int64_t kIntakeMinClocks = 3;
constexpr std::int64_t kQueueLatency = 3;

// Counts what the core did (as its Observer) and turns it into cycles for each lane count of
// kModelLaneCounts. The controller's stages add up word by word; the intake runs beside it, and
// the controller's clocks waiting for it ("filter") come from following both, word by word:
//   taken  A_i = max(P_(i-1) + 1, pop_(i-Q) + 1)    (Q = the queue's depth, PacketMax)
//   pushed P_i = A_i + max(F_i, 3)                   (F_i: filter_cycles)
//   popped pop_i = max(P_i + 3, R_i)                 (R_i: the controller is back in its idle state)
//   R_(i+1) = pop_i + the controller's clocks for word i (its take, append, and any packet it closes)
template <class S>
class ScheduleCounter {
 public:
  void configure(const Config& cfg) { cfg_ = cfg; }

  void on_word(const EventWord& w, bool kept) {
    for (int l = 0; l < kModelLaneCountsN; ++l) lanes_[l].finish(word_);
    ++words_;
    if (w.flush) ++flushes_;
    if (kept) ++kept_;
    word_.filter = w.flush ? 1 : filter_cycles(w);
    // The take (accept) and, for a kept event, its append (packet control).
    for (int l = 0; l < kModelLaneCountsN; ++l) lanes_[l].word_cost = 1 + (kept ? 1 : 0);
    word_.open = true;
  }

  void on_close(const PacketTrace& p) {
    if (p.kept > 0) {
      ++packets_;
      sweeps_ += p.sweeps;
    }
    evict_scans_ += p.track.evict_scans;
    for (int l = 0; l < kModelLaneCountsN; ++l) {
      const StageCycles c = close_cycles(p, kModelLaneCounts[l]);
      lanes_[l].closing += c;
      lanes_[l].word_cost += static_cast<std::int64_t>(c.total());
    }
  }

  // The cycles of everything seen so far, on a core with `lanes` kernel lanes (one of
  // kModelLaneCounts; any other gives zeros).
  StageCycles cycles(int lanes = S::kLanes) const {
    StageCycles c;
    const int l = model_lane_index(lanes);
    if (l < 0) return c;
    Timeline t = lanes_[l];
    t.finish(word_);
    c = t.closing;
    c[Stage::kAccept] += static_cast<double>(words_);
    c[Stage::kPacketControl] += static_cast<double>(kept_);
    c[Stage::kFilter] += static_cast<double>(t.waits);
    return c;
  }

  std::int64_t events() const { return words_ - flushes_; }
  std::int64_t words() const { return words_; }
  std::int64_t kept() const { return kept_; }
  std::int64_t packets() const { return packets_; }
  std::int64_t evict_scans() const { return evict_scans_; }
  double mean_sweeps() const { return packets_ ? static_cast<double>(sweeps_) / static_cast<double>(packets_) : 0.0; }

  // The filter's clocks for an event word; follows the time scrubber's state across words.
  int filter_cycles(const EventWord& w) {
    if (!cfg_.filter_enabled || w.x >= cfg_.sensor_width || w.y >= cfg_.sensor_height) return 1;
    // Before the reads, the scrubber's owed entries (three clocks each: address, wait, decide)
    // or the whole RAM's clear, one word a clock.
    int scrub = 0;
    if (filter_started_) {
      const auto owed = BackgroundActivityFilter<S>::time_scrub(filter_last_t_, w.t);
      scrub = owed.clear_all ? BackgroundActivityFilter<S>::kPixels : 3 * owed.entries;
    }
    filter_started_ = true, filter_last_t_ = w.t;
    // The filter registers the event for a clock before it judges it, and waits two clocks for
    // the RAM after the last neighbour inside the sensor it reads; neighbours are read row by
    // row, so the bottom row and the right column end sooner.
    if (w.y + 1 >= cfg_.sensor_height) return scrub + 20;
    return scrub + (w.x + 1 >= cfg_.sensor_width ? 21 : 22);
  }

 private:
  static constexpr int kQueueDepth = S::kPacketMax;

  // The word whose controller clocks are still being counted (its packet may yet close).
  struct OpenWord {
    bool open = false;
    int filter = 0;
  };

  // The intake and the controller, followed word by word at one lane count.
  struct Timeline {
    std::int64_t intake_free = 0;   // the first clock the intake may take the next word
    std::int64_t ready = 0;         // R: the controller is back in its idle state
    std::int64_t waits = 0;         // its clocks there with the queue empty
    std::int64_t word_cost = 0;     // the open word's controller clocks so far
    std::int64_t taken = 0;
    std::int64_t pops[kQueueDepth] = {};  // pop clocks of the last Q words, by word index mod Q
    StageCycles closing;            // the packets' stages (close, features .. tracking, release)

    void finish(const OpenWord& w) {
      if (!w.open) return;
      std::int64_t take = intake_free;
      if (taken >= kQueueDepth && pops[taken % kQueueDepth] + 1 > take) take = pops[taken % kQueueDepth] + 1;
      const std::int64_t pushed = take + (w.filter > kIntakeMinClocks ? w.filter : kIntakeMinClocks);
      const std::int64_t pop = pushed + kQueueLatency > ready ? pushed + kQueueLatency : ready;
      waits += pop - ready;
      ready = pop + word_cost;
      intake_free = pushed + 1;
      pops[taken % kQueueDepth] = pop;
      ++taken;
    }
  };

  // The controller's clocks for closing one packet, stage by stage, with `lanes` kernel lanes.
  StageCycles close_cycles(const PacketTrace& p, int lanes) const {
    constexpr std::int64_t kMul = multiplier_latency(S::kMulDigitBits) + 1;  // a state waiting for a product
    constexpr std::int64_t kSlots = S::kTracksMax;
    StageCycles c;
    c[Stage::kPacketControl] = p.kept > 0 ? 2 : 1;  // close, and the summary
    c[Stage::kRelease] = static_cast<double>(4 * p.events);
    if (p.kept == 0) return c;
    const std::int64_t n = p.kept;
    // The Gaussian path's features; the seeded path's come with the intake.
    c[Stage::kFeatures] = cfg_.seeded ? 0.0 : static_cast<double>(n * (5 + 4 * kMul));
    c[Stage::kMeanShift] = static_cast<double>(3 + p.sweeps * sweep_cycles(static_cast<int>(n), lanes));
    c[Stage::kMerge] = static_cast<double>(8 * n + p.merge.seed_visits + p.merge.seeds + 4);
    c[Stage::kCentroid] = static_cast<double>(3 * n + p.clusters * (kRecipLatency + 2 + 3 * kMul) + 4);
    const std::int64_t distance_products = cfg_.associate_last ? 2 : 4;
    const TrackerTrace& t = p.track;
    c[Stage::kTrack] = static_cast<double>(3 * kSlots + 7 + p.clusters + t.births + t.scans * (kSlots + 2) + t.slot_steps +
                                           (1 + distance_products * kMul) * t.distances +
                                           (2 * kRecipLatency + 8 + 30 * kMul) * t.matches + (t.rounds_capped ? 1 : 0) +
                                           (kSlots + 2) * t.evict_scans);
    return c;
  }

  Config cfg_;
  bool filter_started_ = false;
  std::uint32_t filter_last_t_ = 0;
  OpenWord word_;
  Timeline lanes_[kModelLaneCountsN];
  std::int64_t words_ = 0, flushes_ = 0, packets_ = 0, kept_ = 0, sweeps_ = 0, evict_scans_ = 0;
};

}  // namespace evms::hls
