#pragma once
// IEEE 754 binary16 ("half"): the storage of GPU textures and of half EXR and float16 .npy
// frames. Decoded exactly; and the test that a value is one, by which float frames whose every
// value is a half are known to have been stored in half (docs/conventions.md, storage precision).
#include <cmath>
#include <cstdint>
#include <limits>

namespace swell::validation {

// One ulp of a half relative to its value, at most: 2⁻¹⁰. A driver that truncates toward zero
// (as GPU drivers may when they write a half texture) errs by up to one ulp, not half of one.
inline constexpr double kHalfUlp = 0x1p-10;

// The value of a half's 16 bits (sign, 5 exponent bits, 10 mantissa bits).
inline double half_bits_to_double(std::uint16_t bits) {
  const double sign = (bits & 0x8000u) ? -1.0 : 1.0;
  const int exponent = (bits >> 10) & 0x1f;
  const int mantissa = bits & 0x3ff;
  if (exponent == 0) return sign * std::ldexp(double(mantissa), -24);  // zero and subnormals
  if (exponent == 0x1f) {
    return mantissa == 0 ? sign * std::numeric_limits<double>::infinity()
                         : std::numeric_limits<double>::quiet_NaN();
  }
  return sign * std::ldexp(double(1024 + mantissa), exponent - 25);
}

// Whether x is exactly a finite half: |x| ≤ 65504 with 11 significant bits, or a multiple of
// 2⁻²⁴ below 2⁻¹⁴ (the subnormals).
inline bool is_half_value(double x) {
  if (!std::isfinite(x)) return false;
  const double a = std::abs(x);
  if (a == 0) return true;
  if (a > 65504) return false;
  if (a < 0x1p-14) {
    const double steps = std::ldexp(a, 24);
    return steps == std::floor(steps);
  }
  int exponent = 0;
  const double significand = std::frexp(a, &exponent);  // [0.5, 1)
  const double bits = std::ldexp(significand, 11);
  return bits == std::floor(bits);
}

}  // namespace swell::validation
