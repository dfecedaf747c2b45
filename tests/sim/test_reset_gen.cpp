// The board tops' reset (rtl/board/evms_reset_gen.sv): its clock's lock and its button, both
// asynchronous to the clock, put the design in reset at once, between clock edges, and it leaves
// the reset only on a clock edge, 2 + 2^HoldClocksLog2 clocks after both are high, the count
// restarted by every bounce of the button. The inputs change between edges here, and rst_n is
// read both before and after each edge.
#include <gtest/gtest.h>

#include <memory>

#include <verilated.h>

#include "Vreset_gen.h"

namespace evms {
namespace {

constexpr int kHoldClocks = 2 + (1 << EVMS_RESET_HoldClocksLog2);  // the synchronizer's two, then the count

class ResetGen {
 public:
  ResetGen() : context_(std::make_unique<VerilatedContext>()), model_(std::make_unique<Vreset_gen>(context_.get())) {
    model_->clk = 0;
    model_->clk_locked = 0;
    model_->button_n = 1;
    model_->eval();
  }
  ~ResetGen() { model_->final(); }
  // Sets the inputs between clock edges and lets them act without an edge.
  void set(bool locked, bool button_n) {
    model_->clk_locked = locked;
    model_->button_n = button_n;
    model_->eval();
  }
  bool rst_n() const { return model_->rst_n; }
  // One clock: rising edge, then falling.
  void tick() {
    model_->clk = 1;
    model_->eval();
    model_->clk = 0;
    model_->eval();
  }
  // Clocks until rst_n is high, at most `limit`; the clocks it took, or -1. rst_n must not rise
  // between edges: it is read after each input change and each edge.
  int clocks_to_release(int limit) {
    for (int k = 1; k <= limit; ++k) {
      if (rst_n()) return -2;  // high before this clock's edge: not released on an edge
      tick();
      if (rst_n()) return k;
    }
    return -1;
  }

 private:
  std::unique_ptr<VerilatedContext> context_;
  std::unique_ptr<Vreset_gen> model_;
};

TEST(ResetGen, ThePowerUpResetEndsOnAnEdgeOnceTheClockIsSteady) {
  ResetGen r;
  EXPECT_FALSE(r.rst_n());
  for (int k = 0; k < 100; ++k) r.tick();
  EXPECT_FALSE(r.rst_n()) << "out of reset before the clock's lock";
  r.set(true, true);
  EXPECT_FALSE(r.rst_n());
  EXPECT_EQ(r.clocks_to_release(1000), kHoldClocks);
  for (int k = 0; k < 100; ++k) r.tick();
  EXPECT_TRUE(r.rst_n());
}

TEST(ResetGen, TheButtonEntersTheResetAtOnceAndLeavesItOnAnEdge) {
  ResetGen r;
  r.set(true, true);
  ASSERT_EQ(r.clocks_to_release(1000), kHoldClocks);
  r.set(true, false);  // pressed between edges
  EXPECT_FALSE(r.rst_n()) << "the button did not reset at once";
  for (int k = 0; k < 5; ++k) r.tick();
  EXPECT_FALSE(r.rst_n());
  r.set(true, true);  // released between edges
  EXPECT_EQ(r.clocks_to_release(1000), kHoldClocks);
  // A bouncing release: each bounce restarts the count, which ends kHoldClocks after the last.
  r.set(true, false);
  for (int bounce = 0; bounce < 4; ++bounce) {
    r.set(true, true);
    r.tick();
    r.tick();
    EXPECT_FALSE(r.rst_n());
    r.set(true, false);
    r.tick();
  }
  r.set(true, true);
  EXPECT_EQ(r.clocks_to_release(1000), kHoldClocks);
}

TEST(ResetGen, LosingTheClocksLockResetsAtOnce) {
  ResetGen r;
  r.set(true, true);
  ASSERT_EQ(r.clocks_to_release(1000), kHoldClocks);
  r.set(false, true);
  EXPECT_FALSE(r.rst_n());
  r.set(true, true);
  EXPECT_EQ(r.clocks_to_release(1000), kHoldClocks);
}

}  // namespace
}  // namespace evms
