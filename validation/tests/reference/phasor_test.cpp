// The spectrum assembly's phasors (impls/include/swell/impls/phasor.hpp) against glibc's cos and
// sin of reference::reduced_phase: that phase is right to ≈ 2e-15 rad for every |ωt| ≤ 2⁵⁰
// (reference/phase.hpp; the synthesizer's late-time tests check it against binary128 phases),
// and glibc's cos and sin are within 1 ulp, so the reference is good to ≈ 3e-15 — far below
// both bounds here.
//
// The phases cover what a case can give: ω from 0.01 to 100 rad/s (deep-water waves of 600 km
// to 6 mm) and t from −10⁹ to 10⁹ s, the quadrant boundaries q·π/2 where the reduction switches
// polynomial and sign, and the largest phase a case may reach (2⁵⁰ rad).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include "swell/impls/phasor.hpp"
#include "swell/reference/phase.hpp"

namespace {

using swell::reference::kLargestPhase;
using swell::reference::reduced_phase;

struct Wave {
  double omega, t;
};

std::vector<Wave> phases_a_case_can_give() {
  std::vector<Wave> waves;
  std::mt19937_64 rng(20261204);
  std::uniform_real_distribution<double> log_omega(std::log(0.01), std::log(100.0));
  std::uniform_real_distribution<double> log10_t(-3.0, 9.0);
  for (int k = 0; k < 400000; ++k) {
    const double t = std::pow(10.0, log10_t(rng)) * (k % 2 ? -1 : 1);
    waves.push_back({std::exp(log_omega(rng)), t});
  }
  // ωt within a few ulps, and within 2e-7 relative, of q·π/2 for small and large q.
  for (long q = -40; q <= 40; ++q) {
    for (double scale : {1.0, 1e6, 1e12}) {
      const double boundary = double(q) * scale * std::numbers::pi / 2;
      const double size = std::max(1.0, std::abs(boundary));
      for (double nudge : {-2e-7, -4e-16, 0.0, 4e-16, 2e-7}) {
        waves.push_back({1.0, boundary + nudge * size});
      }
    }
  }
  waves.push_back({1.0, kLargestPhase});
  waves.push_back({0.5, -2 * kLargestPhase});
  waves.push_back({3.0, 0.0});
  return waves;
}

// The largest |computed − reference| over the phases, of cos and sin together.
template <typename Real>
double largest_error(const std::vector<Wave>& waves) {
  double largest = 0;
  for (const Wave& w : waves) {
    Real c, s;
    swell::impls::phasor(w.omega, w.t, c, s);
    const double x = reduced_phase(w.omega, w.t);
    largest = std::max({largest, std::abs(double(c) - std::cos(x)), std::abs(double(s) - std::sin(x))});
  }
  return largest;
}

// fp32 spectra: the phase reduced in double, sin and cos in float. The bound 2⁻²³ (one ulp of
// float just below 1; half an ulp is what rounding an exact value gives): r rounded to float
// costs ≤ 2⁻²⁵, the polynomials' own error < 1e-8, their float evaluation ≈ 1 ulp of the
// result (≤ 2⁻²⁴). A wrong coefficient, a lost c2 term or a wrong quadrant lands far above it.
TEST(PhasorTest, FloatIsWithinOneUlpOfFloatForEveryPhaseACaseCanGive) {
  const double error = largest_error<float>(phases_a_case_can_give());
  std::printf("fp32 phasor: largest error %.3g (bound 2^-23 = %.3g)\n", error, 0x1p-23);
  EXPECT_LE(error, 0x1p-23);
}

// fp64 spectra: fdlibm's double kernels after reduced_phase. Bound 4 ulps of 1 (2⁻⁵⁰): the
// kernels are within 1 ulp, the Cody–Waite step adds a rounding of r, and the reference's own
// cos/sin are within 1 ulp.
TEST(PhasorTest, DoubleIsWithinFourUlpsForEveryPhaseACaseCanGive) {
  const double error = largest_error<double>(phases_a_case_can_give());
  std::printf("fp64 phasor: largest error %.3g (bound 2^-50 = %.3g)\n", error, 0x1p-50);
  EXPECT_LE(error, 0x1p-50);
}

}  // namespace
