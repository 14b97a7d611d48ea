// Dispersion relation ω² = (g k + (τ/ρ) k³) tanh(k h) (docs/conventions.md §Dispersion), tested
// against closed forms written out here, a finite difference of those closed forms, the
// textbook group velocity and its deep/shallow limits. The MHKiT table (ValData1.json) is in
// external_data_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "test_support.hpp"
#include "swell/reference/dispersion.hpp"
#include "swell/reference/errors.hpp"

namespace {

using swell::test::kG;
using swell::test::kInf;
using swell::test::kNaN;
using swell::test::rel;

namespace sr = swell::reference;
using std::numbers::pi;

constexpr double kTau = sr::kSeaWaterTensionOverDensity;

// ω(k) written out from the definition, independently of the library.
double closed_form_omega(double k, double depth, double tau = 0.0, double g = kG) {
  const double tanh_kh = std::isinf(depth) ? 1.0 : std::tanh(k * depth);
  return std::sqrt((g * k + tau * k * k * k) * tanh_kh);
}

// dω/dk written out: [(g + 3τk²) tanh(kh) + (gk + τk³) h sech²(kh)] / (2ω).
double closed_form_group_velocity(double k, double depth, double tau = 0.0, double g = kG) {
  const double w = closed_form_omega(k, depth, tau, g);
  if (std::isinf(depth)) return (g + 3 * tau * k * k) / (2 * w);
  const double kh = k * depth;
  const double sech = kh > 350 ? 0.0 : 1.0 / std::cosh(kh);
  return ((g + 3 * tau * k * k) * std::tanh(kh) + (g * k + tau * k * k * k) * depth * sech * sech) /
         (2 * w);
}

std::vector<double> log_space(double lo, double hi, int n) {
  std::vector<double> v;
  for (int i = 0; i < n; ++i) v.push_back(lo * std::pow(hi / lo, double(i) / (n - 1)));
  return v;
}

const std::vector<double> kDepths = {0.5, 1.0, 10.0, 50.0, 1000.0, kInf};

sr::Dispersion make(double depth) {
  return std::isinf(depth) ? sr::Dispersion::deep() : sr::Dispersion::finite_depth(depth);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// ω(k) against the closed form.

TEST(Dispersion, DeepOmegaIsSqrtGk) {
  const auto d = sr::Dispersion::deep();
  EXPECT_TRUE(d.is_deep());
  EXPECT_EQ(d.gravity(), kG);
  for (double k : log_space(1e-4, 1e3, 57)) {
    // A product and a square root: a few ulps at most.
    EXPECT_LT(rel(d.omega(k), std::sqrt(kG * k)), 1e-15) << "k = " << k;
    EXPECT_LT(rel(d.omega_squared(k), kG * k), 1e-15) << "k = " << k;
  }
  EXPECT_EQ(d.omega(0.0), 0.0);
  EXPECT_EQ(d.omega_squared(0.0), 0.0);
}

TEST(Dispersion, OtherGravityIsUsed) {
  // The Moon: ω² = 1.62 k; checks gravity is a parameter and not the constant 9.81.
  const auto d = sr::Dispersion::finite_depth(7.0, 1.62);
  EXPECT_EQ(d.gravity(), 1.62);
  for (double k : {0.01, 0.3, 2.0}) {
    // A few ulps (tanh, product, sqrt).
    EXPECT_LT(rel(d.omega(k), closed_form_omega(k, 7.0, 0.0, 1.62)), 1e-14);
  }
}

TEST(Dispersion, FiniteDepthOmegaIsSqrtGkTanhKh) {
  for (double depth : kDepths) {
    const auto d = make(depth);
    EXPECT_EQ(d.depth(), depth);
    for (double k : log_space(1e-4, 1e3, 57)) {
      // tanh, product, sqrt: a few ulps.
      EXPECT_LT(rel(d.omega(k), closed_form_omega(k, depth)), 1e-14)
          << "k = " << k << ", h = " << depth;
    }
  }
}

TEST(Dispersion, FiniteDepthWithInfiniteDepthIsDeep) {
  const auto d = sr::Dispersion::finite_depth(sr::kInfiniteDepth);
  EXPECT_TRUE(d.is_deep());
  for (double k : {1e-3, 0.1, 10.0}) EXPECT_EQ(d.omega(k), sr::Dispersion::deep().omega(k));
  EXPECT_FALSE(sr::Dispersion::finite_depth(1000.0).is_deep());
}

TEST(Dispersion, CapillaryGravityOmegaMatchesClosedForm) {
  for (double depth : {kInf, 10.0, 0.5}) {
    const auto d = sr::Dispersion::capillary_gravity(kTau, depth);
    EXPECT_EQ(d.tension_over_density(), kTau);
    for (double k : log_space(1e-4, 1e3, 57)) {
      // A handful of roundings (k³, sum, tanh, sqrt): 1e-14 leaves room for a different order
      // of evaluation.
      EXPECT_LT(rel(d.omega(k), closed_form_omega(k, depth, kTau)), 1e-14)
          << "k = " << k << ", h = " << depth;
    }
  }
}

TEST(Dispersion, CapillaryGravityMinimumPhaseSpeed) {
  // Deep water: c² = g/k + τk is least at k_m = √(g/τ), where c_min = (4 g τ)^(1/4) — for sea
  // water about 0.23 m/s at λ ≈ 1.7 cm (Lamb, Hydrodynamics §267). Also c = c_g there.
  const auto d = sr::Dispersion::capillary_gravity(kTau);
  const double k_m = std::sqrt(kG / kTau);
  const double c_min = std::pow(4 * kG * kTau, 0.25);
  EXPECT_LT(rel(d.phase_velocity(k_m), c_min), 1e-14);  // a few roundings
  EXPECT_NEAR(c_min, 0.23, 0.005);                         // the published value, 2 digits
  EXPECT_NEAR(2 * pi / k_m, 0.017, 0.0005);                // λ_m ≈ 1.7 cm
  EXPECT_GT(d.phase_velocity(0.99 * k_m), d.phase_velocity(k_m));
  EXPECT_GT(d.phase_velocity(1.01 * k_m), d.phase_velocity(k_m));
  // At the minimum of c = ω/k, dω/dk = c (exact), up to rounding of the two routes.
  EXPECT_LT(rel(d.group_velocity(k_m), c_min), 1e-13);
}

TEST(Dispersion, PhaseVelocityIsOmegaOverK) {
  for (double depth : kDepths) {
    const auto d = make(depth);
    for (double k : {1e-3, 0.05, 1.0, 30.0}) {
      // One division on top of ω: a few ulps.
      EXPECT_LT(rel(d.phase_velocity(k), closed_form_omega(k, depth) / k), 1e-14);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// k(ω): round trip to 1e-12 across six decades of k and six depths.

TEST(Dispersion, WavenumberRoundTripAllDepths) {
  for (double depth : kDepths) {
    const auto d = make(depth);
    for (double k : log_space(1e-4, 1e3, 141)) {
      const double w = closed_form_omega(k, depth);
      // The header promises 1e-12 relative. Condition number of k(ω) is c/c_g ≤ 2 for gravity
      // waves, so the rounding of ω (≈1 ulp) costs at most a few ulps in k.
      EXPECT_LT(rel(d.wavenumber(w), k), 1e-12) << "k = " << k << ", h = " << depth;
      EXPECT_LT(rel(d.omega(d.wavenumber(w)), w), 1e-12) << "k = " << k << ", h = " << depth;
    }
    EXPECT_EQ(d.wavenumber(0.0), 0.0);
  }
}

TEST(Dispersion, WavenumberRoundTripCapillaryGravity) {
  for (double depth : {kInf, 50.0, 1.0}) {
    const auto d = sr::Dispersion::capillary_gravity(kTau, depth);
    for (double k : log_space(1e-4, 1e3, 141)) {
      const double w = closed_form_omega(k, depth, kTau);
      // Same 1e-12 promise; here c/c_g ∈ [2/3, 2], so the conditioning is as good.
      EXPECT_LT(rel(d.wavenumber(w), k), 1e-12) << "k = " << k << ", h = " << depth;
    }
  }
}

TEST(Dispersion, WavenumberKnownValues) {
  // Deep water k = ω²/g exactly; shallow water k → ω/√(gh).
  const auto deep = sr::Dispersion::deep();
  for (double w : {0.1, 0.7, 3.0, 25.0}) {
    EXPECT_LT(rel(deep.wavenumber(w), w * w / kG), 1e-14);  // a few ulps
  }
  const auto shallow = sr::Dispersion::finite_depth(2.0);
  const double w = 1e-6;  // kh ≈ 2e-7: the correction (kh)²/6 ≈ 7e-15 is below the tolerance.
  EXPECT_LT(rel(shallow.wavenumber(w), w / std::sqrt(kG * 2.0)), 1e-13);
}

// ---------------------------------------------------------------------------------------------
// Group velocity.

TEST(Dispersion, GroupVelocityMatchesFiniteDifferenceOfClosedForm) {
  struct Case {
    double depth, tau;
  };
  std::vector<Case> cases;
  for (double depth : kDepths) cases.push_back({depth, 0.0});
  cases.push_back({kInf, kTau});
  cases.push_back({10.0, kTau});
  for (const auto& c : cases) {
    const auto d = c.tau > 0 ? sr::Dispersion::capillary_gravity(c.tau, c.depth) : make(c.depth);
    for (double k : log_space(1e-4, 1e3, 29)) {
      // Fourth-order central difference of the test's own ω(k), step δ = 1e-3 k: truncation
      // ~δ⁴ ω⁽⁵⁾/30 ~ 1e-12·ω/k relative, rounding ~ε ω/δ ~ 1e-13 relative; 1e-9 is ample and
      // still catches any wrong factor or missing term.
      const double h = 1e-3 * k;
      auto w = [&](double x) { return closed_form_omega(x, c.depth, c.tau); };
      const double fd = (-w(k + 2 * h) + 8 * w(k + h) - 8 * w(k - h) + w(k - 2 * h)) / (12 * h);
      EXPECT_LT(rel(d.group_velocity(k), fd), 1e-9)
          << "k = " << k << ", h = " << c.depth << ", tau = " << c.tau;
      // And the analytic derivative written out here: a few roundings.
      EXPECT_LT(rel(d.group_velocity(k), closed_form_group_velocity(k, c.depth, c.tau)), 1e-13)
          << "k = " << k << ", h = " << c.depth << ", tau = " << c.tau;
    }
  }
}

TEST(Dispersion, GroupVelocityGravityTextbookForm) {
  // c_g = (c/2)(1 + 2kh / sinh 2kh) (e.g. Dean & Dalrymple eq. 4.70).
  for (double depth : {0.5, 1.0, 10.0, 50.0}) {
    const auto d = sr::Dispersion::finite_depth(depth);
    for (double k : {1e-3, 0.03, 0.2, 1.0, 5.0}) {
      const double kh = k * depth;
      const double c = closed_form_omega(k, depth) / k;
      const double cg = 0.5 * c * (1 + 2 * kh / std::sinh(2 * kh));
      EXPECT_LT(rel(d.group_velocity(k), cg), 1e-13);  // a few roundings, two routes
    }
  }
}

TEST(Dispersion, GroupVelocityDeepLimitIsHalfPhaseVelocity) {
  const auto d = sr::Dispersion::deep();
  for (double k : log_space(1e-4, 1e3, 29)) {
    // Deep water c_g = ω/(2k) exactly; a few roundings.
    EXPECT_LT(rel(d.group_velocity(k), std::sqrt(kG * k) / (2 * k)), 1e-14);
  }
  // Finite but deep: kh = 50 makes 2kh/sinh 2kh ≈ 1e-41, invisible in double.
  const auto h1000 = sr::Dispersion::finite_depth(1000.0);
  EXPECT_LT(rel(h1000.group_velocity(0.05), std::sqrt(kG * 0.05) / (2 * 0.05)), 1e-14);
  // At k = 0 in deep water c_g = √(g/k)/2 → ∞ (as the header states).
  EXPECT_EQ(d.group_velocity(0.0), kInf);
}

TEST(Dispersion, GroupVelocityShallowLimitIsSqrtGh) {
  for (double depth : {0.5, 1.0, 10.0, 50.0, 1000.0}) {
    const auto d = sr::Dispersion::finite_depth(depth);
    const double c0 = std::sqrt(kG * depth);
    // kh = 1e-7: c_g = √(gh)(1 − (kh)²/2 + …), a 5e-15 correction, below the 1e-13 used.
    const double k = 1e-7 / depth;
    EXPECT_LT(rel(d.group_velocity(k), c0), 1e-13) << "h = " << depth;
    EXPECT_LT(rel(d.phase_velocity(k), c0), 1e-13) << "h = " << depth;
    // The header defines c_g(0) = √(gh) in finite depth; one sqrt.
    EXPECT_LT(rel(d.group_velocity(0.0), c0), 1e-15) << "h = " << depth;
    // The limit is approached from below, c_g < c everywhere for gravity waves.
    EXPECT_LT(d.group_velocity(0.3 / depth), c0);
    EXPECT_LT(d.group_velocity(0.3 / depth), d.phase_velocity(0.3 / depth));
  }
}

// ---------------------------------------------------------------------------------------------
// Loop period.

TEST(Dispersion, QuantizeOmegaRoundsDownToMultiplesOfTwoPiOverT) {
  for (double T : {1.0, 7.5, 60.0}) {
    const double w0 = 2 * pi / T;
    for (double w : {0.013, 0.31, 1.0, 2.7, 9.99, 40.0}) {
      const double q = sr::quantize_omega(w, T);
      const double n = q / w0;
      // A multiple of ω0: n within rounding (1e-9 absolute on n ≤ 400) of an integer.
      EXPECT_NEAR(n, std::round(n), 1e-9) << "w = " << w << ", T = " << T;
      // Rounded down: q ≤ ω and ω − q < ω0 (rounding slack of a few ulps of ω).
      EXPECT_LE(q, w * (1 + 1e-15)) << "w = " << w << ", T = " << T;
      EXPECT_LT(w - q, w0 * (1 + 1e-12)) << "w = " << w << ", T = " << T;
      EXPECT_EQ(std::round(n), std::floor(w / w0 + 1e-12)) << "w = " << w << ", T = " << T;
    }
    // Below the first multiple everything freezes to ω = 0.
    EXPECT_EQ(sr::quantize_omega(0.5 * w0, T), 0.0);
    // Exactly k ω0 plus a little stays at k ω0.
    EXPECT_NEAR(sr::quantize_omega(3.5 * w0, T), 3 * w0, 1e-12 * w0);
  }
  // T = 0 leaves ω unchanged, bit for bit.
  for (double w : {0.0, 0.123, 5.0}) EXPECT_EQ(sr::quantize_omega(w, 0.0), w);
}

// ---------------------------------------------------------------------------------------------
// Invalid input.

TEST(Dispersion, InvalidParametersThrowInvalidInput) {
  EXPECT_THROW(sr::Dispersion::finite_depth(0.0), swell::InvalidInput);
  EXPECT_THROW(sr::Dispersion::finite_depth(-1.0), swell::InvalidInput);
  EXPECT_THROW(sr::Dispersion::finite_depth(kNaN), swell::InvalidInput);
  EXPECT_THROW(sr::Dispersion::finite_depth(10.0, 0.0), swell::InvalidInput);
  EXPECT_THROW(sr::Dispersion::finite_depth(10.0, -9.81), swell::InvalidInput);
  EXPECT_THROW(sr::Dispersion::finite_depth(10.0, kNaN), swell::InvalidInput);
  EXPECT_THROW(sr::Dispersion::deep(0.0), swell::InvalidInput);
  EXPECT_THROW(sr::Dispersion::deep(-1.0), swell::InvalidInput);
  EXPECT_THROW(sr::Dispersion::deep(kNaN), swell::InvalidInput);
  EXPECT_THROW(sr::Dispersion::capillary_gravity(kTau, 0.0), swell::InvalidInput);
  EXPECT_THROW(sr::Dispersion::capillary_gravity(kTau, -3.0), swell::InvalidInput);
  EXPECT_THROW(sr::Dispersion::capillary_gravity(kTau, 10.0, 0.0), swell::InvalidInput);
  EXPECT_THROW(sr::Dispersion::capillary_gravity(kNaN), swell::InvalidInput);
  // Negative τ/ρ would make ω² < 0 at large k.
  EXPECT_THROW(sr::Dispersion::capillary_gravity(-1e-5), swell::InvalidInput);
}

TEST(Dispersion, InvalidArgumentsThrowInvalidInput) {
  for (double depth : {10.0, kInf}) {
    const auto d = make(depth);
    EXPECT_THROW((void)d.omega(-1.0), swell::InvalidInput);
    EXPECT_THROW((void)d.omega(kNaN), swell::InvalidInput);
    EXPECT_THROW((void)d.omega_squared(-0.5), swell::InvalidInput);
    EXPECT_THROW((void)d.wavenumber(-1.0), swell::InvalidInput);
    EXPECT_THROW((void)d.wavenumber(kNaN), swell::InvalidInput);
    EXPECT_THROW((void)d.group_velocity(-1.0), swell::InvalidInput);
    EXPECT_THROW((void)d.group_velocity(kNaN), swell::InvalidInput);
  }
}

TEST(Dispersion, DescribeNamesTheRegime) {
  // The description is for humans; it must at least carry the depth it describes.
  EXPECT_NE(sr::Dispersion::finite_depth(10.0).describe().find("10"), std::string::npos);
  EXPECT_NE(sr::Dispersion::finite_depth(10.0).describe(), sr::Dispersion::deep().describe());
}
