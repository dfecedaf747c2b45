// The hardware schedule of the core, rtl/core/evms_core.sv, as a cycle model: how many clocks
// each stage takes, from what the C++ core did (hls/core/core.h reports every word and, per
// packet, a PacketTrace). The RTL runs one stage at a time, so the stages add up. Every term
// below is read off a state machine of the RTL; sim/ checks the model against the Verilated
// RTL stage by stage (tests/sim/test_schedule.cpp), exactly, when no output is held back.
//
// With n events in a packet, P kernel lanes, C = ceil(n / P), L the multiplier's latency
// (3 clocks for a 64-bit product, pipelined over its digit products, ceil(64 / d) + 1 for d bits
// a clock) and R = 6 the reciprocal's:
//   accept      1 per input word
//   filter      19..21 per event (21 inside the sensor, less on its last row and column),
//               1 when the filter is off or the event is outside the sensor
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

namespace evms::hls {

enum class Stage { kAccept, kFilter, kPacketControl, kFeatures, kMeanShift, kMerge, kCentroid, kTrack, kRelease };
constexpr int kStageCount = 9;
constexpr const char* kStageNames[kStageCount] = {"accept",     "filter", "packet control", "features", "mean shift",
                                                  "merge",      "centroids", "tracking",    "release"};

// The states of the core's controller (rtl/core/evms_core.sv, state_e), in encoding order, each
// with the stage its clocks count in. rtl/generated/evms_core_states.svh is written from this
// list (host/tools/rtl_gen), and sim/rtl_profile.h reads the RTL's state through it. Idle counts
// as accept only while a word is offered.
#define EVMS_CORE_CONTROLLER_STATES(X) \
  X(Idle, kAccept)                     \
  X(Filter, kFilter)                   \
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
  X(ClimbRead, kFeatures)              \
  X(ClimbWait, kFeatures)              \
  X(ClimbX, kFeatures)                 \
  X(ClimbY, kFeatures)                 \
  X(MeanShift, kMeanShift)             \
  X(Merge, kMerge)                     \
  X(Climb, kMeanShift)                 \
  X(Link, kMerge)                      \
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

// Counts what the core did (as its Observer) and turns it into cycles for any lane count.
template <class S>
class ScheduleCounter {
 public:
  void configure(const Config& cfg) { cfg_ = cfg; }

  void on_word(const EventWord& w) {
    ++words_;
    if (w.flush) {
      ++flushes_;
      return;
    }
    filter_ += filter_cycles(w, cfg_);
  }

  void on_close(const PacketTrace& p) {
    ++closes_;
    released_ += p.events;
    if (p.kept == 0) return;
    ++packets_;
    kept_ += p.kept;
    ++sweeps_of_[p.kept][p.sweeps];
    sweeps_ += p.sweeps;
    seed_visits_ += p.merge.seed_visits;
    seeds_ += p.merge.seeds;
    clusters_ += p.clusters;
    scans_ += p.track.scans;
    slot_steps_ += p.track.slot_steps;
    distances_ += p.track.distances;
    matches_ += p.track.matches;
    capped_ += p.track.rounds_capped ? 1 : 0;
    births_ += p.track.births;
    evict_scans_ += p.track.evict_scans;
  }

  // The cycles of everything seen so far, on a core with `lanes` kernel lanes.
  StageCycles cycles(int lanes = S::kLanes) const {
    constexpr std::int64_t kMul = multiplier_latency(S::kMulDigitBits) + 1;  // a state waiting for a product
    constexpr std::int64_t kSlots = S::kTracksMax;
    StageCycles c;
    c[Stage::kAccept] = static_cast<double>(words_);
    c[Stage::kFilter] = static_cast<double>(filter_);
    c[Stage::kPacketControl] = static_cast<double>(kept_ + closes_ + packets_);
    c[Stage::kFeatures] = static_cast<double>(kept_ * (5 + 4 * kMul));
    double mean_shift = 0;
    for (int n = 1; n <= S::kPacketMax; ++n) {
      for (int k = 0; k <= S::kIterationsMax; ++k) {
        if (sweeps_of_[n][k] != 0) mean_shift += static_cast<double>(sweeps_of_[n][k]) * static_cast<double>(3 + k * sweep_cycles(n, lanes));
      }
    }
    c[Stage::kMeanShift] = mean_shift;
    c[Stage::kMerge] = static_cast<double>(8 * kept_ + seed_visits_ + seeds_ + 4 * packets_);
    c[Stage::kCentroid] = static_cast<double>(3 * kept_ + clusters_ * (kRecipLatency + 2 + 3 * kMul) + 4 * packets_);
    const std::int64_t distance_products = cfg_.associate_last ? 2 : 4;
    c[Stage::kTrack] = static_cast<double>(packets_ * (3 * kSlots + 7) + clusters_ + births_ + scans_ * (kSlots + 2) + slot_steps_ +
                                           (1 + distance_products * kMul) * distances_ + (2 * kRecipLatency + 8 + 30 * kMul) * matches_ +
                                           capped_ + (kSlots + 2) * evict_scans_);
    c[Stage::kRelease] = static_cast<double>(4 * released_);
    return c;
  }

  std::int64_t events() const { return words_ - flushes_; }
  std::int64_t words() const { return words_; }
  std::int64_t kept() const { return kept_; }
  std::int64_t packets() const { return packets_; }
  std::int64_t evict_scans() const { return evict_scans_; }
  double mean_sweeps() const { return packets_ ? static_cast<double>(sweeps_) / static_cast<double>(packets_) : 0.0; }

  static int filter_cycles(const EventWord& w, const Config& cfg) {
    if (!cfg.filter_enabled || w.x >= cfg.sensor_width || w.y >= cfg.sensor_height) return 1;
    // The filter waits two clocks for the RAM after the last neighbour inside the sensor it
    // reads; neighbours are read row by row, so the bottom row and the right column end sooner.
    if (w.y + 1 >= cfg.sensor_height) return 19;
    return w.x + 1 >= cfg.sensor_width ? 20 : 21;
  }

 private:
  Config cfg_;
  std::int64_t words_ = 0, flushes_ = 0, filter_ = 0, closes_ = 0, released_ = 0, packets_ = 0, kept_ = 0;
  std::int64_t sweeps_ = 0, seed_visits_ = 0, seeds_ = 0, clusters_ = 0;
  std::int64_t scans_ = 0, slot_steps_ = 0, distances_ = 0, matches_ = 0, capped_ = 0, births_ = 0, evict_scans_ = 0;
  std::uint32_t sweeps_of_[S::kPacketMax + 1][S::kIterationsMax + 1] = {};
};

}  // namespace evms::hls
