// evms::hls::Fixed against SystemC's sc_fixed / sc_ufixed, bit for bit: every quantization
// and overflow mode, exhaustively over small widths and on random values over wide ones.
// Built as C++17 like Debian's libsystemc.
#define SC_INCLUDE_FX
#include <gtest/gtest.h>
#include <systemc.h>

#include <cstdint>
#include <random>

#include "hls/fixed/fixed.h"

int sc_main(int, char**) { return 0; }  // libsystemc wants it; GoogleTest's main runs the tests

namespace evms::hls {
namespace {

constexpr sc_dt::sc_q_mode sc_quant(Quant q) {
  switch (q) {
    case Quant::kTrn: return sc_dt::SC_TRN;
    case Quant::kTrnZero: return sc_dt::SC_TRN_ZERO;
    case Quant::kRnd: return sc_dt::SC_RND;
    case Quant::kRndZero: return sc_dt::SC_RND_ZERO;
    case Quant::kRndInf: return sc_dt::SC_RND_INF;
    case Quant::kRndMinInf: return sc_dt::SC_RND_MIN_INF;
    case Quant::kRndConv: return sc_dt::SC_RND_CONV;
  }
  return sc_dt::SC_TRN;
}

constexpr sc_dt::sc_o_mode sc_ovf(Ovf o) {
  switch (o) {
    case Ovf::kWrap: return sc_dt::SC_WRAP;
    case Ovf::kSat: return sc_dt::SC_SAT;
    case Ovf::kSatZero: return sc_dt::SC_SAT_ZERO;
    case Ovf::kSatSym: return sc_dt::SC_SAT_SYM;
  }
  return sc_dt::SC_WRAP;
}

// The raw bits of an SC fixed-point value (an integer in units of its LSB). Through double:
// exact for the widths here (at most 50 bits); sc_fxval::to_int64 truncates to 32 bits.
template <typename ScFixed>
std::int64_t sc_raw(const ScFixed& v, int frac_bits) {
  sc_dt::sc_fxval scaled = v;
  scaled <<= frac_bits;
  return static_cast<std::int64_t>(scaled.to_double());
}

// Converts every raw value of a source format into the target format with our type and
// with SystemC, comparing the results.
template <int W, int I, bool S, Quant Q, Ovf O, int SW, int SI, bool SS>
void check_conversion_exhaustive() {
  using Src = Fixed<SW, SI, SS>;
  using Dst = Fixed<W, I, S, Q, O>;
  const std::int64_t lo = SS ? -(std::int64_t{1} << (SW - 1)) : 0;
  const std::int64_t hi = SS ? (std::int64_t{1} << (SW - 1)) - 1 : (std::int64_t{1} << SW) - 1;
  for (std::int64_t raw = lo; raw <= hi; ++raw) {
    const Src src = Src::from_raw(raw);
    const Dst ours = src;
    sc_dt::sc_fxval value(static_cast<double>(raw));
    value >>= SW - SI;
    std::int64_t theirs;
    if constexpr (S) {
      sc_dt::sc_fixed<W, I, sc_quant(Q), sc_ovf(O)> sc = value;
      theirs = sc_raw(sc, W - I);
    } else {
      sc_dt::sc_ufixed<W, I, sc_quant(Q), sc_ovf(O)> sc = value;
      theirs = sc_raw(sc, W - I);
    }
    ASSERT_EQ(ours.raw(), theirs) << "source raw " << raw << " (" << src.to_double() << ") into <" << W << "," << I << ","
                                  << S << "> q" << static_cast<int>(Q) << " o" << static_cast<int>(O);
  }
}

template <int W, int I, bool S, Quant Q, Ovf O>
void check_all_sources() {
  check_conversion_exhaustive<W, I, S, Q, O, 10, 4, true>();   // more fraction bits, wider range
  check_conversion_exhaustive<W, I, S, Q, O, 9, 6, false>();
  check_conversion_exhaustive<W, I, S, Q, O, 8, 1, true>();
}

template <int W, int I, bool S, Quant Q>
void check_every_overflow() {
  check_all_sources<W, I, S, Q, Ovf::kWrap>();
  check_all_sources<W, I, S, Q, Ovf::kSat>();
  check_all_sources<W, I, S, Q, Ovf::kSatZero>();
  check_all_sources<W, I, S, Q, Ovf::kSatSym>();
}

template <int W, int I, bool S>
void check_every_mode() {
  check_every_overflow<W, I, S, Quant::kTrn>();
  check_every_overflow<W, I, S, Quant::kTrnZero>();
  check_every_overflow<W, I, S, Quant::kRnd>();
  check_every_overflow<W, I, S, Quant::kRndZero>();
  check_every_overflow<W, I, S, Quant::kRndInf>();
  check_every_overflow<W, I, S, Quant::kRndMinInf>();
  check_every_overflow<W, I, S, Quant::kRndConv>();
}

TEST(FixedVsSystemC, ConversionsExhaustiveSmallWidths) {
  check_every_mode<5, 2, true>();
  check_every_mode<5, 2, false>();
  check_every_mode<6, 0, true>();
  check_every_mode<4, 5, false>();   // integer bits beyond the width
  check_every_mode<6, -1, true>();   // a purely fractional format
}

template <int W1, int I1, bool S1, int W2, int I2, bool S2, int W, int I, bool S, Quant Q, Ovf O>
void check_arithmetic_exhaustive() {
  using A = Fixed<W1, I1, S1>;
  using B = Fixed<W2, I2, S2>;
  using R = Fixed<W, I, S, Q, O>;
  auto range = [](int w, bool s) {
    return std::pair<std::int64_t, std::int64_t>{s ? -(std::int64_t{1} << (w - 1)) : 0,
                                                 s ? (std::int64_t{1} << (w - 1)) - 1 : (std::int64_t{1} << w) - 1};
  };
  const auto [alo, ahi] = range(W1, S1);
  const auto [blo, bhi] = range(W2, S2);
  for (std::int64_t ra = alo; ra <= ahi; ++ra) {
    for (std::int64_t rb = blo; rb <= bhi; ++rb) {
      const A a = A::from_raw(ra);
      const B b = B::from_raw(rb);
      sc_dt::sc_fxval sa(static_cast<double>(ra)), sb(static_cast<double>(rb));
      sa >>= W1 - I1;
      sb >>= W2 - I2;
      const R sum = a + b, diff = a - b, prod = a * b;
      sc_dt::sc_fixed<W, I, sc_quant(Q), sc_ovf(O)> ssum = sa + sb, sdiff = sa - sb, sprod = sa * sb;
      ASSERT_EQ(sum.raw(), sc_raw(ssum, W - I)) << ra << " + " << rb;
      ASSERT_EQ(diff.raw(), sc_raw(sdiff, W - I)) << ra << " - " << rb;
      ASSERT_EQ(prod.raw(), sc_raw(sprod, W - I)) << ra << " * " << rb;
    }
  }
}

TEST(FixedVsSystemC, ArithmeticExhaustiveSmallWidths) {
  check_arithmetic_exhaustive<6, 3, true, 5, 1, false, 7, 3, true, Quant::kRnd, Ovf::kSat>();
  check_arithmetic_exhaustive<6, 3, true, 5, 1, false, 7, 3, true, Quant::kTrn, Ovf::kWrap>();
  check_arithmetic_exhaustive<5, 5, false, 6, 2, true, 6, 4, true, Quant::kRndConv, Ovf::kSatSym>();
  check_arithmetic_exhaustive<6, 0, true, 6, 0, true, 8, 1, true, Quant::kTrnZero, Ovf::kSatZero>();
}

template <int W, int I, bool S, Quant Q, Ovf O>
void check_random_wide(std::mt19937_64& rng) {
  using Src = Fixed<62, 30, true>;
  for (int k = 0; k < 20000; ++k) {
    const std::int64_t raw = static_cast<std::int64_t>(rng()) >> 2;
    const Src src = Src::from_raw(raw);
    const Fixed<W, I, S, Q, O> ours = src;
    sc_dt::sc_fxval value(static_cast<double>(raw >> 10));  // exact: fits a double's 53 bits
    value <<= 10;
    value += sc_dt::sc_fxval(static_cast<double>(raw & 1023));
    value >>= 62 - 30;
    std::int64_t theirs;
    if constexpr (S) {
      sc_dt::sc_fixed<W, I, sc_quant(Q), sc_ovf(O)> sc = value;
      theirs = sc_raw(sc, W - I);
    } else {
      sc_dt::sc_ufixed<W, I, sc_quant(Q), sc_ovf(O)> sc = value;
      theirs = sc_raw(sc, W - I);
    }
    ASSERT_EQ(ours.raw(), theirs) << "raw " << raw;
  }
}

TEST(FixedVsSystemC, RandomValuesWideWidths) {
  std::mt19937_64 rng(20261122);
  check_random_wide<40, 20, true, Quant::kRnd, Ovf::kSat>(rng);
  check_random_wide<32, 28, true, Quant::kTrn, Ovf::kWrap>(rng);
  check_random_wide<48, 12, true, Quant::kRndConv, Ovf::kSatSym>(rng);
  check_random_wide<33, 31, false, Quant::kRndZero, Ovf::kSat>(rng);
  check_random_wide<50, 40, true, Quant::kRndInf, Ovf::kSatZero>(rng);
  check_random_wide<24, 30, false, Quant::kTrnZero, Ovf::kWrap>(rng);
}

TEST(Fixed, FromDoubleIsExact) {
  EXPECT_EQ((Fixed<16, 8>::from_double(1.5).raw()), 384);
  EXPECT_EQ((Fixed<16, 8>::from_double(-1.5).raw()), -384);
  EXPECT_EQ((Fixed<16, 8, true, Quant::kRnd>::from_double(0.001953125).raw()), 1);   // exactly half an LSB rounds up
  EXPECT_EQ((Fixed<16, 8, true, Quant::kTrn>::from_double(0.001953125).raw()), 0);
  EXPECT_EQ((Fixed<8, 4, true, Quant::kTrn, Ovf::kSat>::from_double(1e9).raw()), 127);
  EXPECT_DOUBLE_EQ((Fixed<20, 4>::from_double(-3.25).to_double()), -3.25);
}

}  // namespace
}  // namespace evms::hls

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
