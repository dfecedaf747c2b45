// Lockstep test of rtl/common/evms_fifo.sv, the queue of the intake, the pending labels, the
// link and the board's frames, against a queue model: every word that comes out is the next word
// released, none comes out before its release, none is lost, and a stream passes one word a
// clock. Each of its forms is built (sim/CMakeLists.txt): over a memory, eight words deep with
// tentative writes, with its output buffer (EVMS_FIFO_SHAPE) and without
// (EVMS_FIFO_UNBUFFERED_SHAPE), and in registers, four deep (EVMS_FIFO_REGISTERS_SHAPE).
// The seed is printed (EVMS_SEED=N repeats a run); a mismatch repeats the run with an FST trace
// (sim/verilated_block.h).
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <deque>
#include <random>
#include <string>
#include <type_traits>

#include "Vfifo.h"
#include "Vfifo_registers.h"
#include "Vfifo_unbuffered.h"
#include "sim/verilated_block.h"

namespace evms {
namespace {

static_assert(EVMS_FIFO_Tentative == 1 && EVMS_FIFO_Width == 16, "sim/CMakeLists.txt builds the queue with tentative writes of 16 bits");
static_assert(EVMS_FIFO_UNBUFFERED_Tentative == 1 && EVMS_FIFO_UNBUFFERED_Width == 16 && EVMS_FIFO_UNBUFFERED_OutputBuffer == 0,
              "sim/CMakeLists.txt builds the queue without its output buffer, with tentative writes of 16 bits");
static_assert(EVMS_FIFO_REGISTERS_Tentative == 0 && EVMS_FIFO_REGISTERS_Width == 16 &&
                  EVMS_FIFO_REGISTERS_Depth <= EVMS_FIFO_REGISTERS_RegistersDepthMax,
              "sim/CMakeLists.txt builds the queue in registers, of 16-bit words");

// The two forms: the words each holds with no reader, and the clocks a word written into an
// empty queue takes to come out.
struct OverMemory {
  using Model = Vfifo;
  static constexpr int kDepth = EVMS_FIFO_Depth;
  static constexpr bool kTentative = true;
  static constexpr int kHeld = kDepth + 2;   // the memory's and the output buffer's
  static constexpr int kFirstOut = 3;        // the write, the memory's read, the buffer
};
struct OverMemoryUnbuffered {
  using Model = Vfifo_unbuffered;
  static constexpr int kDepth = EVMS_FIFO_UNBUFFERED_Depth;
  static constexpr bool kTentative = true;
  static constexpr int kHeld = kDepth + 1;   // the memory's and its read register's
  static constexpr int kFirstOut = 2;        // the write, the memory's read
};
struct InRegisters {
  using Model = Vfifo_registers;
  static constexpr int kDepth = EVMS_FIFO_REGISTERS_Depth;
  static constexpr bool kTentative = false;
  static constexpr int kHeld = kDepth;
  static constexpr int kFirstOut = 1;        // the write
};

// One clock's inputs.
struct Inputs {
  bool write = false, commit = false, rollback = false, read = false;
  std::uint16_t data = 0;
};

// The queue as the RTL documents it: with tentative writes, written words wait until a commit
// releases them (with the word written in the same clock), a rollback forgets those not yet
// released (with the word written in the same clock); without, every word is released as it is
// written. The reader sees released words in order.
struct QueueModel {
  bool tentative_writes = true;
  std::deque<std::uint16_t> tentative, released;
  void clock(const Inputs& in, bool written) {
    if (written) tentative.push_back(in.data);
    if (!tentative_writes) {
      released.insert(released.end(), tentative.begin(), tentative.end());
      tentative.clear();
    } else if (in.rollback) {
      tentative.clear();
    } else if (in.commit) {
      released.insert(released.end(), tentative.begin(), tentative.end());
      tentative.clear();
    }
  }
};

// The queue under test and the model, clock by clock; `difference` holds the first disagreement.
template <class Form>
class Lockstep {
 public:
  explicit Lockstep(const std::string& trace) : fifo_(trace) { model.tentative_writes = Form::kTentative; }

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
  sim::VerilatedBlock<typename Form::Model> fifo_;
};

// A run of random traffic: phases of a few hundred clocks, each with its own rates of writing and
// reading, commits and rollbacks (never both in one clock); then the reader drains the queue.
// Returns the first disagreement (empty: none) and counts the words that came out in `out`.
template <class Form>
std::string random_run(std::uint64_t seed, int run, const std::string& trace, std::uint64_t& out) {
  std::mt19937_64 rng(seed * 1000 + static_cast<std::uint64_t>(run));
  sim::Draws draw{rng};
  Lockstep<Form> q(trace);
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
  for (int k = 0; k < 3 * Form::kDepth + 10; ++k) out += q.clock(Inputs{.read = true});
  if (q.difference.empty() && !q.model.released.empty()) {
    q.difference = std::to_string(q.model.released.size()) + " released words never came out";
  }
  return q.difference;
}

template <class Form>
class Fifo : public ::testing::Test {};
using Forms = ::testing::Types<OverMemory, OverMemoryUnbuffered, InRegisters>;
struct FormName {
  template <class Form>
  static std::string GetName(int) {
    if (std::is_same_v<Form, OverMemory>) return "OverMemory";
    return std::is_same_v<Form, OverMemoryUnbuffered> ? "OverMemoryUnbuffered" : "InRegisters";
  }
};
TYPED_TEST_SUITE(Fifo, Forms, FormName);

TYPED_TEST(Fifo, EveryReleasedWordComesOutOnceInOrderUnderRandomTraffic) {
  const std::uint64_t seed = sim::cosim_seed();
  std::uint64_t words = 0;
  const std::string block = FormName::GetName<TypeParam>(0);
  for (int run = 0; run < 40; ++run) {
    const std::string difference = random_run<TypeParam>(seed, run, "", words);
    std::uint64_t again = 0;
    const std::string verdict = sim::mismatch_traced(block, seed, "run " + std::to_string(run), difference,
                                                     [&](const std::string& trace) { random_run<TypeParam>(seed, run, trace, again); });
    ASSERT_TRUE(verdict.empty()) << verdict;
  }
  // Traffic, not an idle queue: 40 runs of 2,400 clocks pass about 25,000 words.
  EXPECT_GT(words, 10'000u);
  std::printf("%llu words compared\n", static_cast<unsigned long long>(words));
}

// Words written (and committed) every clock and read every clock come out one a clock, as soon
// as the first is through: over a memory, the output buffer never runs dry.
TYPED_TEST(Fifo, AStreamPassesOneWordAClock) {
  Lockstep<TypeParam> q("");
  int first = -1, out = 0;
  for (int k = 0; k < 1000; ++k) {
    if (q.clock(Inputs{.write = true, .commit = true, .read = true, .data = static_cast<std::uint16_t>(k)})) {
      if (first < 0) first = k;
      ++out;
    }
  }
  ASSERT_TRUE(q.difference.empty()) << q.difference;
  ASSERT_GE(first, 0) << "no word came out";
  EXPECT_EQ(first, TypeParam::kFirstOut) << "the first word took " << first << " clocks";
  EXPECT_EQ(out, 1000 - first) << "the stream stalled after its first word";
}

// With no reader, the queue takes the words it holds (over a memory, its Depth and the two of its
// output buffer, or the one of its read register without; in registers, its Depth), then no
// more; the reader then gets all of them in order.
TYPED_TEST(Fifo, HoldsWhatItsFormHoldsThenGivesThemBackInOrder) {
  Lockstep<TypeParam> q("");
  for (int k = 0; k < 4 * TypeParam::kDepth; ++k) q.clock(Inputs{.write = true, .commit = true, .data = static_cast<std::uint16_t>(k)});
  EXPECT_EQ(q.written_total, static_cast<std::uint64_t>(TypeParam::kHeld));
  EXPECT_FALSE(q.in_ready());
  int out = 0;
  for (int k = 0; k < 4 * TypeParam::kDepth; ++k) out += q.clock(Inputs{.read = true});
  ASSERT_TRUE(q.difference.empty()) << q.difference;
  EXPECT_EQ(out, TypeParam::kHeld);
  EXPECT_TRUE(q.model.released.empty());
}

// Tentative words stay out of the reader's sight until a commit releases them, and a rollback
// forgets them: the link's receiver queues a frame's events as they arrive and keeps them from
// the core until the frame's check passes (rtl/board/evms_link_rx.sv).
TEST(FifoOverMemory, TentativeWordsWaitForTheirCommitAndARollbackForgetsThem) {
  Lockstep<OverMemory> q("");
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
