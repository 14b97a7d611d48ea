// The exact phase reduction (reference/phase.hpp) and the validity rule of a case on its
// sampling (reference/sampling_validity.hpp), each against something independent: binary128
// arithmetic, the band-limited moments of grid_sea_state, and the rule's own stated limits.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdint>
#include <string>

#include "swell/reference/errors.hpp"
#include "swell/reference/moments.hpp"
#include "swell/reference/phase.hpp"
#include "swell/reference/sampling_validity.hpp"
#include "test_support.hpp"

namespace {

using namespace swell::reference;

// Distance between two phases modulo 2π, in binary128.
double phase_distance(__float128 a, __float128 b, __float128 two_pi) {
  __float128 d = a - b;
  d -= two_pi * __float128(static_cast<long long>(d / two_pi));
  if (d > two_pi / 2) d -= two_pi;
  if (d < -two_pi / 2) d += two_pi;
  return std::abs(double(d));
}

// Over ω t from 1e-3 to 2⁵⁰ rad: the reduced phase equals ω t (the exact product of the two
// doubles, which binary128's 113 bits hold) modulo 2π to 4e-15 rad — a few roundings of O(π)
// sums (phase.hpp) — while fl(ω t) drifts as |ω t| 2⁻⁵³.
TEST(ReducedPhase, EqualsTheExactProductModuloTwoPiUpToTheLargestPhase) {
  const __float128 two_pi = swell::test::two_pi_binary128();
  std::uint64_t state = 12345;
  auto uniform = [&] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return double(state >> 11) * 0x1p-53;
  };
  double worst = 0, worst_rounded = 0;
  for (int i = 0; i < 20000; ++i) {
    const double omega = std::exp(std::log(0.05) + uniform() * std::log(200.0 / 0.05));
    const double target = std::exp(std::log(1e-3) + uniform() * std::log(kLargestPhase / 1e-3));
    const double t = (i % 2 ? 1 : -1) * target / omega;
    const __float128 exact = __float128(omega) * __float128(t);
    const double r = reduced_phase(omega, t);
    EXPECT_LE(std::abs(r), 3.14159265358979 + 0x1p-2);
    const double error = phase_distance(__float128(r), exact, two_pi);
    worst = std::max(worst, error);
    if (std::abs(omega * t) > 1e12) {
      worst_rounded = std::max(worst_rounded, phase_distance(__float128(omega * t), exact, two_pi));
    }
  }
  EXPECT_LT(worst, 4e-15);
  EXPECT_GT(worst_rounded, 1e-6);  // what the reduction exists for
}

// unit_phasor (one sincos) must give exactly std::polar(1, x) = (cos x, sin x): the per-wave
// fits use it, and the gate's reports (GateGolden) were made with sin and cos. 10⁷ arguments:
// reduced phases over [−π − ¼, π + ¼] as the fits pass them, and wide ones up to ±10⁶ rad.
TEST(UnitPhasor, EqualsSeparateSinAndCosBitForBit) {
  std::uint64_t state = 2026;
  auto uniform = [&] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return double(state >> 11) * 0x1p-53;
  };
  // sin and cos called through pointers the compiler cannot see through, so that it does not
  // merge them into a sincos call of its own.
  double (*volatile sine)(double) = static_cast<double (*)(double)>(std::sin);
  double (*volatile cosine)(double) = static_cast<double (*)(double)>(std::cos);
  long mismatches = 0;
  for (int i = 0; i < 10'000'000; ++i) {
    const double x = i % 8 == 0 ? (2 * uniform() - 1) * 1e6 : (2 * uniform() - 1) * (3.1415926535897932 + 0.25);
    const std::complex<double> fast = unit_phasor(x);
    if (fast.real() != cosine(x) || fast.imag() != sine(x)) ++mismatches;
  }
  EXPECT_EQ(mismatches, 0);
}

OceanCase jonswap(int n, double length, double wind_dir = 30) {
  OceanCase c;
  c.grid = Grid::create(n, n, length, length);
  c.spectrum = {"jonswap", {{"hs", 3.0}, {"tp", 8.0}, {"gamma", 3.3}}, {}};
  c.spreading = {"cos2s", {{"s", 10.0}}, {}};
  c.wind_dir_deg = wind_dir;
  return c;
}

// The summary's sums against grid_sea_state's band-limited moments (moments.cpp, its own loop):
// m0 on the grid, and in deep water Σ k² Ψ Δk² = m4/g², which splits evenly between x and y
// when the waves travel at 45° on a square grid (D is symmetric about θw); so do the
// displacements, m0/2 each.
TEST(SamplingSummary, SumsAgreeWithTheBandLimitedMoments) {
  const OceanCase c = jonswap(128, 800, 45);
  const SamplingSummary s = summarize_sampling(c);
  const SeaState band = grid_sea_state(*c.directional_spectrum(), c.grid);
  EXPECT_NEAR(s.m0_on_grid / band.moments.m0, 1, 1e-12);
  EXPECT_NEAR(s.slope_variance / (band.moments.m4 / (2 * 9.81 * 9.81)), 1, 1e-9);
  EXPECT_NEAR(s.displacement_variance / (band.moments.m0 / 2), 1, 1e-9);
  EXPECT_NEAR(s.m0, 9.0 / 16, 1e-9);  // Hs = 3 m, exact normalization
  EXPECT_NEAR(s.fraction, s.m0_on_grid / s.m0, 0);
  EXPECT_DOUBLE_EQ(s.k_min, 2 * 3.14159265358979323846 / 800);
  EXPECT_DOUBLE_EQ(s.k_max, std::hypot(63, 63) * s.k_min);
}

bool refused(const OceanCase& c, const NumberFormat& numbers = kFloat32) {
  try {
    require_valid_sampling(c, numbers);
    return false;
  } catch (const swell::InvalidInput&) {
    return true;
  }
}

// The energy rule refuses exactly the grids whose fraction of m0 is below 1e-6, over patch
// lengths from 1 mm to 100 km (where the grid's band slides past the spectrum both ways).
TEST(SamplingValidity, EnergyRuleRefusesExactlyTheGridsBelowTheFraction) {
  int accepted = 0, refused_count = 0;
  for (double length = 1e-3; length < 1e5; length *= 1.7) {
    const OceanCase c = jonswap(32, length);
    const SamplingSummary s = summarize_sampling(c);
    SCOPED_TRACE(length);
    EXPECT_EQ(refused(c), s.fraction < kSmallestEnergyFraction) << "fraction " << s.fraction;
    (refused(c) ? refused_count : accepted)++;
  }
  EXPECT_GT(accepted, 3);
  EXPECT_GT(refused_count, 3);
}

// Times: accepted just inside ω t = 2⁵⁰ rad, refused just beyond, naming [time].
TEST(SamplingValidity, TimeRuleAtTheLargestPhase) {
  OceanCase c = jonswap(32, 200);
  // The fastest wave that carries energy on 32²: index 15 on both axes (−16 is Nyquist).
  const double omega = c.omega(std::hypot(15 * c.grid.dkx(), 15 * c.grid.dky()));
  c.t0 = kLargestPhase / omega * (1 - 1e-9);
  EXPECT_FALSE(refused(c));
  c.t0 = -kLargestPhase / omega * (1 + 1e-9);
  try {
    require_valid_sampling(c, kFloat32);
    FAIL() << "t0 beyond the largest phase was accepted";
  } catch (const swell::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("[time] t0"), std::string::npos) << e.what();
  }
  c.t0 = 0;
  c.frames = 3;
  c.dt = kLargestPhase / omega;  // the last frame, not t0, is beyond
  EXPECT_TRUE(refused(c));
}

// Range: the Jacobian's λ∂D terms must stay below √(largest)/64 — λ just below is accepted in
// fp64 and refused in fp32, whose limit is 10¹³⁰ times lower; λ below the underflow limit of
// the displacements is refused, λ = 0 is not.
TEST(SamplingValidity, RangeRuleOfEachFormat) {
  OceanCase c = jonswap(32, 200);
  const SamplingSummary s = summarize_sampling(c);
  c.choppiness = std::sqrt(kFloat32.largest) / 64 / std::sqrt(s.strain_variance) * 0.99;
  EXPECT_FALSE(refused(c, kFloat32));
  c.choppiness *= 1.02;
  EXPECT_TRUE(refused(c, kFloat32));
  EXPECT_FALSE(refused(c, kFloat64));
  c.choppiness = kFloat32.smallest_normal / kFloat32.unit_roundoff /
                 std::sqrt(s.displacement_variance) * 0.5;
  EXPECT_TRUE(refused(c, kFloat32));
  EXPECT_FALSE(refused(c, kFloat64));
  c.choppiness = 0;
  EXPECT_FALSE(refused(c, kFloat32));
}

TEST(SamplingValidity, MemoryRuleNamesTheBytes) {
  const std::uint64_t available = available_memory_bytes();
  ASSERT_GT(available, 0u) << "/proc/meminfo has no MemAvailable";
  EXPECT_NO_THROW(require_memory(available / 2, "swell test", "a grid"));
  try {
    require_memory(available * 2, "swell test", "a grid");
    FAIL() << "twice the available memory was accepted";
  } catch (const swell::InvalidInput& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(std::to_string(available * 2)), std::string::npos) << what;
    EXPECT_NE(what.find("available"), std::string::npos) << what;
  }
}

}  // namespace
