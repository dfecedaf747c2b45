// Lockstep test of rtl/common/evms_fifo.sv, the queue of the intake, the pending labels, the
// link and the board's frames, against a queue model: every word that comes out is the next word
// released, none comes out before its release, none is lost, and the output buffer keeps one word
// a clock flowing through the memory's read latency. The block is built eight words deep with
// tentative writes (sim/CMakeLists.txt: EVMS_FIFO_SHAPE). The seed is printed (EVMS_SEED=N
// repeats a run); a mismatch repeats the run with an FST trace (sim/verilated_block.h).
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <deque>
#include <random>
#include <string>

#include "Vfifo.h"
#include "sim/verilated_block.h"

namespace evms {
namespace {

constexpr int kDepth = EVMS_FIFO_Depth;
static_assert(EVMS_FIFO_Tentative == 1 && EVMS_FIFO_Width == 16, "sim/CMakeLists.txt builds the queue with tentative writes of 16 bits");

// One clock's inputs.
struct Inputs {
  bool write = false, commit = false, rollback = false, read = false;
  std::uint16_t data = 0;
};

// The queue as the RTL documents it: written words wait until a commit releases them (with the
// word written in the same clock), a rollback forgets those not yet released (with the word
// written in the same clock), and the reader sees released words in order.
struct QueueModel {
  std::deque<std::uint16_t> tentative, released;
  void clock(const Inputs& in, bool written) {
    if (written) tentative.push_back(in.data);
    if (in.rollback) {
      tentative.clear();
    } else if (in.commit) {
      released.insert(released.end(), tentative.begin(), tentative.end());
      tentative.clear();
    }
  }
};

// The queue under test and the model, clock by clock; `difference` holds the first disagreement.
class Lockstep {
 public:
  explicit Lockstep(const std::string& trace) : fifo_(trace) {}

  // Applies one clock's inputs; returns whether a word came out.
  bool clock(const Inputs& in) {
    fifo_->in_valid = in.write;
    fifo_->in_data = in.data;
    fifo_->in_commit = in.commit;
    fifo_->in_rollback = in.rollback;
    fifo_->out_ready = in.read;
    fifo_->clk = 0;
    fifo_->eval();
    const bool written = in.write && fifo_->in_ready;
    const bool taken = fifo_->out_valid && in.read;
    if (taken && difference.empty()) {
      if (model.released.empty()) {
        difference = "clock " + std::to_string(clocks) + ": word " + std::to_string(fifo_->out_data) + " came out before any was released";
      } else if (fifo_->out_data != model.released.front()) {
        difference = "clock " + std::to_string(clocks) + ": word " + std::to_string(fifo_->out_data) + " came out, the model's next is " +
                     std::to_string(model.released.front());
      }
    }
    if (taken && !model.released.empty()) model.released.pop_front();
    model.clock(in, written);
    written_total += written;
    fifo_.tick();
    ++clocks;
    return taken;
  }
  bool in_ready() {
    fifo_->clk = 0;
    fifo_->eval();
    return fifo_->in_ready;
  }

  QueueModel model;
  std::string difference;
  std::uint64_t clocks = 0, written_total = 0;

 private:
  sim::VerilatedBlock<Vfifo> fifo_;
};

// A run of random traffic: phases of a few hundred clocks, each with its own rates of writing and
// reading, commits and rollbacks (never both in one clock); then the reader drains the queue.
// Returns the first disagreement (empty: none) and counts the words that came out in `out`.
std::string random_run(std::uint64_t seed, int run, const std::string& trace, std::uint64_t& out) {
  std::mt19937_64 rng(seed * 1000 + static_cast<std::uint64_t>(run));
  sim::Draws draw{rng};
  Lockstep q(trace);
  for (int phase = 0; phase < 8; ++phase) {
    const double p_write = draw.one_of({0.1, 0.5, 0.9, 1.0}), p_read = draw.one_of({0.0, 0.1, 0.5, 0.9, 1.0});
    const double p_commit = draw.one_of({0.05, 0.3, 1.0}), p_rollback = draw.one_of({0.0, 0.02, 0.1});
    for (int k = 0; k < 300; ++k) {
      Inputs in;
      in.write = draw.uniform(0, 1) < p_write;
      in.data = static_cast<std::uint16_t>(q.written_total);  // each word written a number of its own
      in.read = draw.uniform(0, 1) < p_read;
      in.rollback = draw.uniform(0, 1) < p_rollback;
      in.commit = !in.rollback && draw.uniform(0, 1) < p_commit;
      out += q.clock(in);
    }
  }
  for (int k = 0; k < 3 * kDepth + 10; ++k) out += q.clock(Inputs{.read = true});
  if (q.difference.empty() && !q.model.released.empty()) {
    q.difference = std::to_string(q.model.released.size()) + " released words never came out";
  }
  return q.difference;
}

TEST(Fifo, EveryReleasedWordComesOutOnceInOrderUnderRandomTraffic) {
  const std::uint64_t seed = sim::cosim_seed();
  std::uint64_t words = 0;
  for (int run = 0; run < 40; ++run) {
    const std::string difference = random_run(seed, run, "", words);
    std::uint64_t again = 0;
    const std::string verdict = sim::mismatch_traced("fifo", seed, "run " + std::to_string(run), difference,
                                                     [&](const std::string& trace) { random_run(seed, run, trace, again); });
    ASSERT_TRUE(verdict.empty()) << verdict;
  }
  // Traffic, not an idle queue: 40 runs of 2,400 clocks pass about 25,000 words.
  EXPECT_GT(words, 10'000u);
  std::printf("%llu words compared\n", static_cast<unsigned long long>(words));
}

// Words written with every clock's commit and read every clock come out one a clock, as soon as
// the first is through the memory's read latency: the output buffer never runs dry.
TEST(Fifo, AStreamPassesOneWordAClock) {
  Lockstep q("");
  int first = -1, out = 0;
  for (int k = 0; k < 1000; ++k) {
    if (q.clock(Inputs{.write = true, .commit = true, .read = true, .data = static_cast<std::uint16_t>(k)})) {
      if (first < 0) first = k;
      ++out;
    }
  }
  ASSERT_TRUE(q.difference.empty()) << q.difference;
  ASSERT_GE(first, 0) << "no word came out";
  EXPECT_LE(first, 3) << "the first word took " << first << " clocks";
  EXPECT_EQ(out, 1000 - first) << "the stream stalled after its first word";
}

// With no reader, the queue takes its memory's Depth words and the two of its output buffer, then
// no more; the reader then gets all of them in order.
TEST(Fifo, HoldsItsDepthAndItsOutputBufferThenGivesThemBackInOrder) {
  Lockstep q("");
  for (int k = 0; k < 4 * kDepth; ++k) q.clock(Inputs{.write = true, .commit = true, .data = static_cast<std::uint16_t>(k)});
  EXPECT_EQ(q.written_total, static_cast<std::uint64_t>(kDepth + 2));
  EXPECT_FALSE(q.in_ready());
  int out = 0;
  for (int k = 0; k < 4 * kDepth; ++k) out += q.clock(Inputs{.read = true});
  ASSERT_TRUE(q.difference.empty()) << q.difference;
  EXPECT_EQ(out, kDepth + 2);
  EXPECT_TRUE(q.model.released.empty());
}

// Tentative words stay out of the reader's sight until a commit releases them, and a rollback
// forgets them: the link's receiver queues a frame's events as they arrive and keeps them from
// the core until the frame's check passes (rtl/board/evms_link_rx.sv).
TEST(Fifo, TentativeWordsWaitForTheirCommitAndARollbackForgetsThem) {
  Lockstep q("");
  for (std::uint16_t k = 0; k < 3; ++k) q.clock(Inputs{.write = true, .read = true, .data = k});
  int out = 0;
  for (int k = 0; k < 10; ++k) out += q.clock(Inputs{.read = true});
  EXPECT_EQ(out, 0) << "a word came out before its commit";
  q.clock(Inputs{.write = true, .commit = true, .read = true, .data = 3});  // releases 0..3
  for (int k = 0; k < 10; ++k) out += q.clock(Inputs{.read = true});
  EXPECT_EQ(out, 4);
  for (std::uint16_t k = 4; k < 7; ++k) q.clock(Inputs{.write = true, .read = true, .data = k});
  q.clock(Inputs{.write = true, .rollback = true, .read = true, .data = 7});  // forgets 4..7
  q.clock(Inputs{.write = true, .commit = true, .read = true, .data = 8});
  for (int k = 0; k < 10; ++k) out += q.clock(Inputs{.read = true});
  ASSERT_TRUE(q.difference.empty()) << q.difference;
  EXPECT_EQ(out, 5) << "the rolled-back words came out, or the committed one did not";
  EXPECT_TRUE(q.model.released.empty());
}

}  // namespace
}  // namespace evms
