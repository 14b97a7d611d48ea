#pragma once
// Small helpers shared by the reference test suites.
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace swell::test {

inline constexpr double kG = 9.81;  // the gravity MHKiT's data and swell's default use
inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Relative difference; two exact zeros (an underflowed tail) agree.
inline double rel(double got, double want) {
  return got == want ? 0.0 : std::abs(got - want) / std::abs(want);
}

// ‖got − want‖₂ / ‖want‖₂ against a long double oracle (the direct sums of the lattice tests).
inline double relative_l2(const std::vector<double>& got, const std::vector<long double>& want) {
  long double error = 0, norm = 0;
  for (std::size_t i = 0; i < got.size(); ++i) {
    error += (got[i] - want[i]) * (got[i] - want[i]);
    norm += want[i] * want[i];
  }
  return static_cast<double>(std::sqrt(error / norm));
}

// 2π in binary128 (GCC's __float128) by Machin's formula π = 16 atan(1/5) − 4 atan(1/239):
// an oracle for phases independent of the constants reference/phase.hpp splits 2π into.
inline __float128 two_pi_binary128() {
  auto arctan_inverse = [](int x) {
    __float128 sum = 0, power = __float128(1) / x;
    for (int k = 0; k < 60; ++k, power /= __float128(x) * x) sum += (k % 2 ? -power : power) / (2 * k + 1);
    return sum;
  };
  return 2 * (16 * arctan_inverse(5) - 4 * arctan_inverse(239));
}

}  // namespace swell::test
