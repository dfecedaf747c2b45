// The arithmetic units, each against its stated error bound: exhaustively where the input
// space allows, densely where not (the ac_math way).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "hls/cluster/tables.h"
#include "hls/core/configs.h"
#include "hls/core/shape.h"
#include "hls/fixed/stream.h"
#include "hls/math/cexp.h"
#include "hls/math/exp_table.h"
#include "hls/math/isqrt.h"
#include "hls/math/reciprocal.h"
#include "hls/math/round.h"

namespace evms::hls {
namespace {

TEST(ConstexprExp, MatchesTheLibraryOnTheTableRange) {
  double worst = 0;
  for (int i = 0; i <= 160000; ++i) {
    const double x = i * 1e-4;
    worst = std::max(worst, std::abs(cexp_neg(x) - std::exp(-x)) / std::exp(-x));
  }
  EXPECT_LT(worst, 2e-13);
}

// The kernel's exp(-u) over every input the default core can present: u with 22 fraction bits
// (squared 11-bit features) on [0, 16). Stated bound: h^2/8 + 2^-WF + h 2^-IB = 2.6e-4.
TEST(ExpTable, ErrorBoundExhaustive) {
  constexpr ExpTable<9, 16, 8> table;
  constexpr int kUf = 22;
  const double h = 16.0 / 512;
  const double bound = h * h / 8 + std::ldexp(1.0, -16) + h * std::ldexp(1.0, -8);
  double worst = 0;
  for (std::uint64_t u = 0; u < (std::uint64_t{16} << kUf); ++u) {
    const double x = std::ldexp(static_cast<double>(u), -kUf);
    const double got = std::ldexp(static_cast<double>(table.lookup<kUf>(u)), -16);
    worst = std::max(worst, std::abs(got - std::exp(-x)));
  }
  EXPECT_LE(worst, bound);
  EXPECT_GT(worst, bound / 8) << "the bound is meant to be tight";
  EXPECT_EQ(table.lookup<kUf>(std::uint64_t{16} << kUf), 0u);
  EXPECT_EQ(table.lookup<kUf>(0), 1u << 16);
}

// The decay's exp(-dt / tau): 32 fraction bits, densely (every 2^10-th input).
TEST(ExpTable, ErrorBoundDecayInputs) {
  constexpr ExpTable<9, 16, 8> table;
  const double h = 16.0 / 512;
  const double bound = h * h / 8 + std::ldexp(1.0, -16) + h * std::ldexp(1.0, -8);
  double worst = 0;
  for (std::uint64_t u = 0; u < (std::uint64_t{16} << 32); u += 1021) {
    const double got = std::ldexp(static_cast<double>(table.lookup<32>(u)), -16);
    worst = std::max(worst, std::abs(got - std::exp(-std::ldexp(static_cast<double>(u), -32))));
  }
  EXPECT_LE(worst, bound);
}

// evms_exp_lut (rtl/math) takes v[i] - v[i+1] in WF + 1 bits, which holds only while the
// samples never increase; every build's table is checked.
template <class S>
void expect_samples_never_increase(const char* build) {
  const auto& table = Tables<S>::exp;
  for (int i = 0; i < table.kEntries; ++i) {
    ASSERT_GE(table.v[i], table.v[i + 1]) << build << " build, sample " << i;
  }
}
TEST(ExpTable, SamplesNeverIncrease) {
  expect_samples_never_increase<HostShape>("host");
  expect_samples_never_increase<ArtyShape>("arty");
  expect_samples_never_increase<Ice40Shape>("ice40");
}

// Stated bound: relative error below 2^-(RF - 3) = 2^-17 for T = 8, RF = 20.
TEST(Reciprocal, RelativeErrorExhaustiveBelow2To20) {
  constexpr Reciprocal<8, 20> recip;
  double worst = 0;
  for (std::uint64_t x = 1; x < (1u << 20); ++x) {
    const auto r = recip.reciprocal(x);
    const double got = std::ldexp(static_cast<double>(r.r), -(20 + r.m));
    worst = std::max(worst, std::abs(got * static_cast<double>(x) - 1.0));
  }
  EXPECT_LT(worst, std::ldexp(1.0, -17));
}

TEST(Reciprocal, RelativeErrorRandomWide) {
  constexpr Reciprocal<8, 20> recip;
  std::mt19937_64 rng(5);
  double worst = 0;
  for (int k = 0; k < 2000000; ++k) {
    const std::uint64_t x = (rng() >> (rng() % 40 + 1)) | 1;
    const auto r = recip.reciprocal(x);
    const double got = std::ldexp(static_cast<double>(r.r), -(20 + r.m));
    worst = std::max(worst, std::abs(got * static_cast<double>(x) - 1.0));
  }
  EXPECT_LT(worst, std::ldexp(1.0, -17));
}

TEST(Reciprocal, DivisionRoundsToWithinOneUnit) {
  constexpr Reciprocal<8, 20> recip;
  std::mt19937_64 rng(6);
  for (int k = 0; k < 1000000; ++k) {
    const std::uint64_t x = rng() % 5000000 + 1, num = rng() % (std::uint64_t{1} << 32);
    const double exact = static_cast<double>(num) * 2048.0 / static_cast<double>(x);
    const double got = static_cast<double>(recip.divide<11>(num, x));
    ASSERT_LE(std::abs(got - exact), 1.0 + exact * std::ldexp(1.0, -17)) << num << " / " << x;
  }
}

// floor(sqrt(v)): r^2 <= v < (r + 1)^2, every v below 2^20 and random v of every width to 2^126.
TEST(Isqrt, FloorOfTheRootExhaustiveBelow2To20AndRandomToEveryWidth) {
  auto check = [](__int128 v) {
    const __int128 r = isqrt(v);
    ASSERT_LE(r * r, v) << static_cast<double>(v);
    ASSERT_GT((r + 1) * (r + 1), v) << static_cast<double>(v);
  };
  for (__int128 v = 0; v < (__int128{1} << 20); ++v) check(v);
  std::mt19937_64 rng(20261207);
  for (int bits = 21; bits <= 126; ++bits) {
    for (int k = 0; k < 2000; ++k) {
      const __int128 v = ((__int128{rng()} << 64) | rng()) & ((__int128{1} << bits) - 1);
      check(v);
      check(v | (__int128{1} << (bits - 1)));  // the full width
    }
    const __int128 top = (__int128{1} << bits) - 1, root = isqrt(top);
    check(top), check(root * root), check(root * root - 1);  // around a square
  }
}

TEST(Round, ShiftsRoundHalfUp) {
  EXPECT_EQ(shr_rnd(5, 1), 3);
  EXPECT_EQ(shr_rnd(-5, 1), -2);
  EXPECT_EQ(shr_rnd(-6, 1), -3);
  EXPECT_EQ(shr_rnd(7, 0), 7);
  EXPECT_EQ(shr_rnd(3, -2), 12);
  EXPECT_EQ(clamp_sym(-100, 10), -10);
}

TEST(Stream, BehavesLikeABoundedFifo) {
  Stream<int, 3> s;
  EXPECT_TRUE(s.empty());
  EXPECT_TRUE(s.write(1));
  EXPECT_TRUE(s.write(2));
  EXPECT_TRUE(s.write(3));
  EXPECT_TRUE(s.full());
  EXPECT_FALSE(s.write(4));
  EXPECT_TRUE(s.overflowed());
  int v = 0;
  for (int want : {1, 2, 3}) {
    ASSERT_TRUE(s.read(v));
    EXPECT_EQ(v, want);
  }
  EXPECT_FALSE(s.read(v));
  EXPECT_TRUE(s.write(5));  // wraps around the ring
  ASSERT_TRUE(s.read(v));
  EXPECT_EQ(v, 5);
}

}  // namespace
}  // namespace evms::hls
