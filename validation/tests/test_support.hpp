#pragma once
// Small helpers shared by the reference test suites.
#include <cmath>
#include <limits>

namespace swell::test {

inline constexpr double kG = 9.81;  // the gravity MHKiT's data and swell's default use
inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Relative difference; two exact zeros (an underflowed tail) agree.
inline double rel(double got, double want) {
  return got == want ? 0.0 : std::abs(got - want) / std::abs(want);
}

}  // namespace swell::test
