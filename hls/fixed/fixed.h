// Fixed-point numbers for the evms core, in the manner of ac_fixed / sc_fixed:
//
//   Fixed<W, I, S, Q, O>   W bits in all, I of them left of the binary point (I may be
//                          negative or larger than W), signed when S, quantized with Q and
//                          overflowing with O when a value is assigned into it.
//
// The value is raw * 2^(I - W). Arithmetic (+, -, *) is exact: its result type is wide enough
// for every result, and quantization and overflow happen only when that result is assigned
// to (or constructed as) a narrower type. Widths are limited to 64 bits signed and 63 bits
// unsigned, and the result of an operation must fit those limits too (a static_assert says
// so). Quantization and overflow modes behave as SystemC's SC_TRN ... SC_RND_CONV and SC_WRAP,
// SC_SAT, SC_SAT_ZERO, SC_SAT_SYM; tests/hls/test_fixed_vs_systemc.cpp checks them bit for bit against
// sc_fixed and sc_ufixed.
//
// HLS: header-only, no heap, no exceptions, no iostreams; every size is a template argument.
#pragma once

#include <cstdint>

namespace evms::hls {

enum class Quant { kTrn, kTrnZero, kRnd, kRndZero, kRndInf, kRndMinInf, kRndConv };
enum class Ovf { kWrap, kSat, kSatZero, kSatSym };

namespace fixed_detail {

using Wide = __int128;

constexpr int max_int(int a, int b) { return a > b ? a : b; }

// v * 2^n. A multiplication, not `v << n`: before C++20 shifting a negative value left is
// undefined, and the SystemC cross-check builds this header as C++17.
constexpr Wide scale_up(Wide v, int n) { return v * (Wide{1} << n); }

// v / 2^shift with the rounding of `q`; shift > 0.
constexpr Wide quantize_right(Wide v, int shift, Quant q) {
  const Wide floor = v >> shift;  // arithmetic shift: rounds toward minus infinity
  const Wide rem = v - scale_up(floor, shift);
  const Wide half = Wide{1} << (shift - 1);
  switch (q) {
    case Quant::kTrn: return floor;
    case Quant::kTrnZero: return (v < 0 && rem != 0) ? floor + 1 : floor;
    case Quant::kRnd: return rem >= half ? floor + 1 : floor;
    case Quant::kRndZero: return rem > half || (rem == half && v < 0) ? floor + 1 : floor;
    case Quant::kRndInf: return rem > half || (rem == half && v >= 0) ? floor + 1 : floor;
    case Quant::kRndMinInf: return rem > half ? floor + 1 : floor;
    case Quant::kRndConv: return rem > half || (rem == half && (floor & 1)) ? floor + 1 : floor;
  }
  return floor;
}

// Brings an exact integer into W bits (signed or not) with overflow mode `o`.
constexpr Wide overflow(Wide v, int w, bool is_signed, Ovf o) {
  const Wide max = is_signed ? (Wide{1} << (w - 1)) - 1 : (Wide{1} << w) - 1;
  const Wide min = is_signed ? -(Wide{1} << (w - 1)) : Wide{0};
  // Symmetric saturation keeps the range symmetric: the most negative code is never produced.
  if (o == Ovf::kSatSym && is_signed && v < -max) return -max;
  if (v >= min && v <= max) return v;
  switch (o) {
    case Ovf::kWrap: {
      const Wide mask = (Wide{1} << w) - 1;
      Wide low = v & mask;
      if (is_signed && (low >> (w - 1)) & 1) low -= Wide{1} << w;
      return low;
    }
    case Ovf::kSat: return v > max ? max : min;
    case Ovf::kSatZero: return 0;
    case Ovf::kSatSym: return v > max ? max : (is_signed ? -max : min);
  }
  return v;
}

// raw value of a number with `from_frac` fraction bits, expressed with `to_frac` bits.
constexpr Wide requantize(Wide raw, int from_frac, int to_frac, Quant q) {
  if (to_frac >= from_frac) return scale_up(raw, to_frac - from_frac);
  return quantize_right(raw, from_frac - to_frac, q);
}

}  // namespace fixed_detail

template <int W, int I, bool S = true, Quant Q = Quant::kTrn, Ovf O = Ovf::kWrap>
class Fixed {
  static_assert(W >= 1 && W <= (S ? 64 : 63), "Fixed: width must be 1..64 (signed) or 1..63 (unsigned)");

 public:
  static constexpr int width = W;
  static constexpr int int_bits = I;
  static constexpr int frac_bits = W - I;
  static constexpr bool is_signed = S;
  static constexpr Quant quant = Q;
  static constexpr Ovf ovf = O;

  constexpr Fixed() = default;

  // From any other fixed type: quantize to our fraction bits, then apply our overflow.
  template <int W2, int I2, bool S2, Quant Q2, Ovf O2>
  constexpr Fixed(const Fixed<W2, I2, S2, Q2, O2>& other)  // NOLINT: implicit like ac_fixed
      : raw_(assign(fixed_detail::requantize(other.raw(), W2 - I2, frac_bits, Q))) {}

  // From an integer.
  constexpr Fixed(int v) : raw_(assign(fixed_detail::requantize(v, 0, frac_bits, Q))) {}  // NOLINT
  constexpr Fixed(long v) : raw_(assign(fixed_detail::requantize(v, 0, frac_bits, Q))) {}  // NOLINT
  constexpr Fixed(long long v) : raw_(assign(fixed_detail::requantize(v, 0, frac_bits, Q))) {}  // NOLINT

  // From a double, exactly: the double's binary value is quantized with Q.
  static constexpr Fixed from_double(double v) {
    if (v == 0) return Fixed();
    const bool negative = v < 0;
    double m = negative ? -v : v;
    int e = 0;
    while (m >= 9007199254740992.0) m *= 0.5, ++e;  // 2^53: bring m to an integer below 2^53
    while (m < 4503599627370496.0) m *= 2.0, --e;   // 2^52
    fixed_detail::Wide mant = static_cast<fixed_detail::Wide>(static_cast<std::int64_t>(m));
    if (negative) mant = -mant;
    // value = mant * 2^e; raw = value * 2^frac_bits = mant * 2^(e + frac_bits)
    const int shift = e + frac_bits;
    fixed_detail::Wide raw = 0;
    if (shift >= 0) {
      if (shift > 60) {
        raw = negative ? -(fixed_detail::Wide{1} << 100) : (fixed_detail::Wide{1} << 100);  // beyond any width: overflow
      } else {
        raw = fixed_detail::scale_up(mant, shift);
      }
    } else if (-shift >= 110) {
      raw = fixed_detail::quantize_right(mant, 110, Q);
    } else {
      raw = fixed_detail::quantize_right(mant, -shift, Q);
    }
    return from_raw(overflow_only(raw));
  }

  // Builds a value from raw bits (taken modulo 2^W, as hardware would).
  static constexpr Fixed from_raw(std::int64_t raw) {
    Fixed f;
    f.raw_ = static_cast<std::int64_t>(fixed_detail::overflow(raw, W, S, Ovf::kWrap));
    return f;
  }

  constexpr std::int64_t raw() const { return raw_; }
  constexpr double to_double() const {
    double v = static_cast<double>(raw_);
    for (int i = 0; i < frac_bits; ++i) v *= 0.5;
    for (int i = 0; i < -frac_bits; ++i) v *= 2.0;
    return v;
  }
  // The integer part, rounded toward minus infinity.
  constexpr std::int64_t to_int() const {
    return frac_bits >= 0 ? static_cast<std::int64_t>(fixed_detail::Wide{raw_} >> frac_bits)
                          : static_cast<std::int64_t>(fixed_detail::scale_up(raw_, -frac_bits));
  }

  static constexpr Fixed max_value() { return from_raw(S ? (std::int64_t{1} << (W - 1)) - 1 : static_cast<std::int64_t>((std::uint64_t{1} << W) - 1)); }
  static constexpr Fixed min_value() { return from_raw(S ? -(std::int64_t{1} << (W - 1)) : 0); }

 private:
  static constexpr std::int64_t overflow_only(fixed_detail::Wide v) {
    return static_cast<std::int64_t>(fixed_detail::overflow(v, W, S, O));
  }
  static constexpr std::int64_t assign(fixed_detail::Wide v) { return overflow_only(v); }

  std::int64_t raw_ = 0;
};

// ---- exact arithmetic -----------------------------------------------------------------------

template <int W1, int I1, bool S1, Quant Q1, Ovf O1, int W2, int I2, bool S2, Quant Q2, Ovf O2>
struct SumType {
  static constexpr int frac = fixed_detail::max_int(W1 - I1, W2 - I2);
  static constexpr int ints = fixed_detail::max_int(I1 + (!S1 && S2), I2 + (!S2 && S1)) + 1;
  using type = Fixed<ints + frac, ints, S1 || S2>;
};

template <int W1, int I1, bool S1, Quant Q1, Ovf O1, int W2, int I2, bool S2, Quant Q2, Ovf O2>
constexpr auto operator+(const Fixed<W1, I1, S1, Q1, O1>& a, const Fixed<W2, I2, S2, Q2, O2>& b) {
  using R = typename SumType<W1, I1, S1, Q1, O1, W2, I2, S2, Q2, O2>::type;
  const auto x = fixed_detail::requantize(a.raw(), W1 - I1, R::frac_bits, Quant::kTrn);
  const auto y = fixed_detail::requantize(b.raw(), W2 - I2, R::frac_bits, Quant::kTrn);
  return R::from_raw(static_cast<std::int64_t>(x + y));
}

template <int W1, int I1, bool S1, Quant Q1, Ovf O1, int W2, int I2, bool S2, Quant Q2, Ovf O2>
constexpr auto operator-(const Fixed<W1, I1, S1, Q1, O1>& a, const Fixed<W2, I2, S2, Q2, O2>& b) {
  // A difference is signed even of unsigned operands.
  using Base = typename SumType<W1, I1, S1, Q1, O1, W2, I2, S2, Q2, O2>::type;
  constexpr bool grow = !(S1 || S2);
  using R = Fixed<Base::width + grow, Base::int_bits + grow, true>;
  const auto x = fixed_detail::requantize(a.raw(), W1 - I1, R::frac_bits, Quant::kTrn);
  const auto y = fixed_detail::requantize(b.raw(), W2 - I2, R::frac_bits, Quant::kTrn);
  return R::from_raw(static_cast<std::int64_t>(x - y));
}

template <int W1, int I1, bool S1, Quant Q1, Ovf O1, int W2, int I2, bool S2, Quant Q2, Ovf O2>
constexpr auto operator*(const Fixed<W1, I1, S1, Q1, O1>& a, const Fixed<W2, I2, S2, Q2, O2>& b) {
  using R = Fixed<W1 + W2, I1 + I2, S1 || S2>;
  return R::from_raw(static_cast<std::int64_t>(fixed_detail::Wide{a.raw()} * fixed_detail::Wide{b.raw()}));
}

template <int W, int I, bool S, Quant Q, Ovf O>
constexpr auto operator-(const Fixed<W, I, S, Q, O>& a) {
  using R = Fixed<W + 1, I + 1, true>;
  return R::from_raw(-a.raw());
}

// Comparisons by value, across types.
template <int W1, int I1, bool S1, Quant Q1, Ovf O1, int W2, int I2, bool S2, Quant Q2, Ovf O2>
constexpr int compare(const Fixed<W1, I1, S1, Q1, O1>& a, const Fixed<W2, I2, S2, Q2, O2>& b) {
  constexpr int frac = fixed_detail::max_int(W1 - I1, W2 - I2);
  const auto x = fixed_detail::requantize(a.raw(), W1 - I1, frac, Quant::kTrn);
  const auto y = fixed_detail::requantize(b.raw(), W2 - I2, frac, Quant::kTrn);
  return x < y ? -1 : (x > y ? 1 : 0);
}
#define EVMS_FIXED_COMPARISON(op)                                                                  \
  template <int W1, int I1, bool S1, Quant Q1, Ovf O1, int W2, int I2, bool S2, Quant Q2, Ovf O2>           \
  constexpr bool operator op(const Fixed<W1, I1, S1, Q1, O1>& a, const Fixed<W2, I2, S2, Q2, O2>& b) {      \
    return compare(a, b) op 0;                                                                             \
  }
EVMS_FIXED_COMPARISON(<)
EVMS_FIXED_COMPARISON(>)
EVMS_FIXED_COMPARISON(<=)
EVMS_FIXED_COMPARISON(>=)
EVMS_FIXED_COMPARISON(==)
EVMS_FIXED_COMPARISON(!=)
#undef EVMS_FIXED_COMPARISON

}  // namespace evms::hls
