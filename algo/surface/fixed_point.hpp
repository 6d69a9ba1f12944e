// Fixed<F>: a signed Q-format number, 64-bit two's complement with F
// fractional bits (Q(63-F).F), saturating arithmetic, usable as an Eigen
// scalar. It exists so the geometry that a rover computer without an FPU
// would run (triangulation, plane fits, clustering) can be instantiated and
// checked against double (docs/reconstruction.md states the error).
//   - + - * / saturate to [-max, max] (max = 2^(63-F) - 2^-F); never wrap.
//   - * and / round to nearest using a 128-bit intermediate.
//   - x / 0 saturates to +-max (0 / 0 = 0); sqrt of a negative is 0;
//     log of a non-positive value is -max.
//   - Construction from double/int is explicit so no float math slips in.
// Memory: 8 bytes, no heap. Pure integer operations except the explicit
// conversions to and from double.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <compare>
#include <cstdint>
#include <limits>

#include "algo/mesh/linalg3.hpp"

namespace petra {

namespace fixed_detail {
__extension__ using int128 = __int128;  // g++ extension; exists on x86-64 and aarch64
__extension__ using uint128 = unsigned __int128;

inline constexpr std::int64_t kMaxRaw = std::numeric_limits<std::int64_t>::max();
inline constexpr std::int64_t kMinRaw = -kMaxRaw;  // symmetric: negation never overflows

constexpr std::int64_t saturate(int128 v) {
  if (v > kMaxRaw) return kMaxRaw;
  if (v < kMinRaw) return kMinRaw;
  return static_cast<std::int64_t>(v);
}

// Integer square root of a non-negative 128-bit value (floor).
constexpr std::uint64_t isqrt128(uint128 v) {
  if (v == 0) return 0;
  // Bit-by-bit method: at most 64 iterations, no division.
  uint128 result = 0;
  uint128 bit = static_cast<uint128>(1) << 126;
  while (bit > v) bit >>= 2;
  while (bit != 0) {
    if (v >= result + bit) {
      v -= result + bit;
      result = (result >> 1) + bit;
    } else {
      result >>= 1;
    }
    bit >>= 2;
  }
  return static_cast<std::uint64_t>(result);
}
}  // namespace fixed_detail

template <int F>
class Fixed {
  static_assert(F >= 8 && F <= 48, "Fixed<F>: 8..48 fractional bits");

 public:
  using raw_type = std::int64_t;
  static constexpr int kFracBits = F;
  static constexpr raw_type kOneRaw = raw_type{1} << F;

  constexpr Fixed() = default;
  explicit Fixed(double v) : raw_(from_double(v)) {}
  explicit constexpr Fixed(int v) : raw_(fixed_detail::saturate(fixed_detail::int128{v} << F)) {}
  explicit constexpr Fixed(long v) : raw_(fixed_detail::saturate(fixed_detail::int128{v} << F)) {}
  explicit constexpr Fixed(long long v)
      : raw_(fixed_detail::saturate(fixed_detail::int128{v} << F)) {}
  explicit constexpr Fixed(unsigned long v)
      : raw_(fixed_detail::saturate(fixed_detail::int128{v} << F)) {}

  static constexpr Fixed from_raw(raw_type r) {
    Fixed x;
    x.raw_ = r < fixed_detail::kMinRaw ? fixed_detail::kMinRaw : r;
    return x;
  }
  static constexpr Fixed max() { return from_raw(fixed_detail::kMaxRaw); }
  static constexpr Fixed lowest() { return from_raw(fixed_detail::kMinRaw); }
  static constexpr Fixed resolution() { return from_raw(1); }

  constexpr raw_type raw() const { return raw_; }
  constexpr double to_double() const {
    return static_cast<double>(raw_) / static_cast<double>(kOneRaw);
  }
  explicit constexpr operator double() const { return to_double(); }
  explicit constexpr operator float() const { return static_cast<float>(to_double()); }
  explicit constexpr operator int() const { return static_cast<int>(raw_ >> F); }  // floor
  constexpr bool saturated() const {
    return raw_ == fixed_detail::kMaxRaw || raw_ == fixed_detail::kMinRaw;
  }

  friend constexpr Fixed operator+(Fixed a, Fixed b) {
    return from_raw(fixed_detail::saturate(fixed_detail::int128{a.raw_} + b.raw_));
  }
  friend constexpr Fixed operator-(Fixed a, Fixed b) {
    return from_raw(fixed_detail::saturate(fixed_detail::int128{a.raw_} - b.raw_));
  }
  friend constexpr Fixed operator-(Fixed a) { return from_raw(-a.raw_); }
  friend constexpr Fixed operator+(Fixed a) { return a; }
  friend constexpr Fixed operator*(Fixed a, Fixed b) {
    const fixed_detail::int128 p = fixed_detail::int128{a.raw_} * b.raw_;
    // Round half away from zero so that (-a)*b == -(a*b).
    const fixed_detail::int128 half = fixed_detail::int128{1} << (F - 1);
    const fixed_detail::int128 q = p >= 0 ? (p + half) >> F : -((-p + half) >> F);
    return from_raw(fixed_detail::saturate(q));
  }
  friend constexpr Fixed operator/(Fixed a, Fixed b) {
    if (b.raw_ == 0) return a.raw_ == 0 ? Fixed{} : (a.raw_ > 0 ? max() : lowest());
    fixed_detail::int128 n = fixed_detail::int128{a.raw_} << F;
    fixed_detail::int128 d = b.raw_;
    const bool negative = (n < 0) != (d < 0);
    if (n < 0) n = -n;
    if (d < 0) d = -d;
    const fixed_detail::int128 q = (n + d / 2) / d;
    return from_raw(fixed_detail::saturate(negative ? -q : q));
  }
  constexpr Fixed& operator+=(Fixed b) { return *this = *this + b; }
  constexpr Fixed& operator-=(Fixed b) { return *this = *this - b; }
  constexpr Fixed& operator*=(Fixed b) { return *this = *this * b; }
  constexpr Fixed& operator/=(Fixed b) { return *this = *this / b; }

  friend constexpr bool operator==(Fixed a, Fixed b) { return a.raw_ == b.raw_; }
  friend constexpr auto operator<=>(Fixed a, Fixed b) { return a.raw_ <=> b.raw_; }

 private:
  static raw_type from_double(double v) {
    if (std::isnan(v)) return 0;
    const double scaled = std::ldexp(v, F);
    if (scaled >= 9.2e18) return fixed_detail::kMaxRaw;
    if (scaled <= -9.2e18) return fixed_detail::kMinRaw;
    return static_cast<raw_type>(std::llround(scaled));
  }

  raw_type raw_ = 0;
};

// Free functions found by argument-dependent lookup (Eigen's numext and the
// templated algorithms call sqrt/abs/log unqualified).
template <int F>
constexpr Fixed<F> abs(Fixed<F> x) {
  return x.raw() < 0 ? -x : x;
}

template <int F>
constexpr Fixed<F> sqrt(Fixed<F> x) {
  if (x.raw() <= 0) return Fixed<F>{};
  const fixed_detail::uint128 wide = static_cast<fixed_detail::uint128>(x.raw()) << F;
  return Fixed<F>::from_raw(static_cast<std::int64_t>(fixed_detail::isqrt128(wide)));
}

// Natural logarithm by the binary digit-by-digit method: integer part from
// the leading bit, F fractional bits of log2 by repeated squaring.
template <int F>
constexpr Fixed<F> log(Fixed<F> x) {
  if (x.raw() <= 0) return Fixed<F>::lowest();
  using fixed_detail::int128;
  std::int64_t raw = x.raw();
  int msb = 63 - __builtin_clzll(static_cast<unsigned long long>(raw));
  const int int_part = msb - F;  // x = 2^int_part * m, m in [1, 2)
  // m in Q2.60 for precision independent of F.
  constexpr int kM = 60;
  int128 m = int_part >= 0 ? (int128{raw} << (kM - F)) >> int_part
                           : (int128{raw} << (kM - F)) << (-int_part);
  int128 frac = 0;  // log2(m) in Q.kM
  for (int bit = kM - 1; bit >= kM - F - 4 && bit >= 0; --bit) {
    m = (m * m) >> kM;
    if (m >= (int128{2} << kM)) {
      m >>= 1;
      frac |= int128{1} << bit;
    }
  }
  // ln(x) = (int_part + frac) * ln 2, in Q.kM then rounded to Q.F.
  constexpr int128 kLn2 = 799144290325165979;  // round(ln 2 * 2^60)
  const int128 log2_q = (int128{int_part} << kM) + frac;
  const int128 ln_q = (log2_q * kLn2) >> kM;
  const int128 half = int128{1} << (kM - F - 1);
  return Fixed<F>::from_raw(fixed_detail::saturate((ln_q + half) >> (kM - F)));
}

template <int F>
constexpr bool isfinite(Fixed<F> x) {
  return !x.saturated();
}

// The two formats the project instantiates: Q31.32 (range +-2.1e9,
// resolution 2.3e-10) and Q47.16 (range +-1.4e14, resolution 1.5e-5).
using Q31_32 = Fixed<32>;
using Q47_16 = Fixed<16>;

// to_double for Fixed (the double overload is in algo/mesh/linalg3.hpp).
template <int F>
double to_double(Fixed<F> v) {
  return v.to_double();
}

}  // namespace petra

namespace Eigen {
template <int F>
struct NumTraits<petra::Fixed<F>> : GenericNumTraits<petra::Fixed<F>> {
  using Real = petra::Fixed<F>;
  using NonInteger = petra::Fixed<F>;
  using Literal = petra::Fixed<F>;
  using Nested = petra::Fixed<F>;
  enum {
    IsComplex = 0,
    IsInteger = 0,
    IsSigned = 1,
    RequireInitialization = 1,
    ReadCost = 1,
    AddCost = 2,
    MulCost = 4
  };
  static Real epsilon() { return Real::resolution(); }
  static Real dummy_precision() { return Real::from_raw(Real::kOneRaw >> (F / 2)); }
  static Real highest() { return Real::max(); }
  static Real lowest() { return Real::lowest(); }
  static int digits10() { return static_cast<int>(F * 0.30103); }
  static Real infinity() { return Real::max(); }
  static Real quiet_NaN() { return Real{}; }
};
}  // namespace Eigen
