#pragma once
// Frames as a GPU engine stores them in half precision: every value rounded to a half, toward
// zero (as drivers may) or to nearest — written here independently of swell's reader, which
// only decodes halves and tests for them (swell/validation/io/half.hpp).
#include <cmath>

#include "swell/reference/fields.hpp"

namespace swell::test {

// x rounded to a half (11 significant bits; multiples of 2⁻²⁴ below 2⁻¹⁴). |x| ≤ 65504 assumed.
inline double to_half(double x, bool toward_zero) {
  const double a = std::abs(x);
  if (a == 0) return x;
  int exponent = 0;
  std::frexp(a, &exponent);  // a in [2^(e−1), 2^e)
  const double quantum = a < 0x1p-14 ? 0x1p-24 : std::ldexp(1.0, exponent - 11);
  const double steps = toward_zero ? std::floor(a / quantum) : std::nearbyint(a / quantum);
  return std::copysign(steps * quantum, x);
}

// Every field of every frame rounded to a half, and the sequence marked as what swell's reader
// makes of half frames: float32 arithmetic, one ulp (2⁻¹⁰) per stored value.
inline void store_in_half(reference::FrameSequence& frames, bool toward_zero) {
  for (auto& frame : frames.frames) {
    for (auto& [field, values] : frame.fields) {
      for (double& v : values) v = to_half(v, toward_zero);
    }
  }
  frames.unit_roundoff = 0x1p-24;
  frames.storage_roundoff = 0x1p-10;
}

}  // namespace swell::test
