// Frequency spectra S(ω) (Pierson–Moskowitz/Bretschneider, JONSWAP, TMA) and the ModelSpec
// factory, against formulas written out here, an independent quadrature (Boost tanh_sinh /
// exp_sinh, where the library uses Gauss–Kronrod), and a finite-depth group velocity computed
// here from ω² = g k tanh(kh).
#include <gtest/gtest.h>

#include <algorithm>
#include <boost/math/quadrature/exp_sinh.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "quadrature_support.hpp"
#include "test_support.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/frequency_spectrum.hpp"
#include "swell/reference/model_factory.hpp"
#include "swell/reference/spreading.hpp"

namespace {

using swell::test::kG;
using swell::test::kInf;
using swell::test::kNaN;
using swell::test::rel;

namespace sr = swell::reference;
using std::numbers::pi;

// ∫_a^b f by tanh-sinh (b finite) or exp-sinh (b = ∞), requested to 1e-13. exp-sinh samples
// out to ω ~ 1e300; beyond 1e8 a the ω⁻⁵ tails here hold < (1e-8)² of any moment up to m2,
// so the integrand is cut there (extreme arguments are tested on their own, below).
template <class F>
double integrate(F f, double a, double b) {
  static boost::math::quadrature::tanh_sinh<double> ts;
  static boost::math::quadrature::exp_sinh<double> es;
  double error = 0, l1 = 0;
  if (std::isinf(b)) {
    auto cut = [&](double x) { return x > 1e8 * a ? 0.0 : f(x); };
    return es.integrate(cut, a, b, 1e-13, &error, &l1);
  }
  return ts.integrate(f, a, b, 1e-13, &error, &l1);
}

// m_n = ∫ ω^n S dω by the test's own quadrature, split around the peak ωp. Below 0.25 ωp every
// spectrum here carries less than exp(−(5/4)·4⁴) = e^−320 of its energy, so the integral
// starts there (and never asks S for ω → 0).
double test_moment(const sr::FrequencySpectrum& s, int n, double wp) {
  auto f = [&](double w) { return std::pow(w, n) * s(w); };
  const std::vector<double> cuts = {0.25 * wp, 0.8 * wp, 0.95 * wp, wp, 1.05 * wp,
                                    1.3 * wp,  2.0 * wp, 4.0 * wp};
  double sum = 0;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) sum += integrate(f, cuts[i], cuts[i + 1]);
  return sum + integrate(f, cuts.back(), kInf);
}

// Pierson–Moskowitz family written out: a ω⁻⁵ exp(−b ω⁻⁴).
double pm_formula(double w, double a, double b) {
  return a * std::pow(w, -5.0) * std::exp(-b * std::pow(w, -4.0));
}

// Bretschneider: a = (5/16) Hs² ωp⁴, b = (5/4) ωp⁴.
double bretschneider_formula(double w, double hs, double tp) {
  const double wp = 2 * pi / tp;
  return pm_formula(w, 5.0 / 16.0 * hs * hs * std::pow(wp, 4), 1.25 * std::pow(wp, 4));
}

// JONSWAP written out (Hasselmann et al. 1973, eq. 2.12 in ω).
double jonswap_formula(double w, double alpha, double wp, double gamma, double sa, double sb,
                       double g = kG) {
  const double sigma = w <= wp ? sa : sb;
  const double r = std::exp(-(w - wp) * (w - wp) / (2 * sigma * sigma * wp * wp));
  return alpha * g * g * std::pow(w, -5.0) * std::exp(-1.25 * std::pow(wp / w, 4)) *
         std::pow(gamma, r);
}

// k(ω, h) by bisection of g k tanh(kh) − ω² (monotone in k): independent of the library's
// Newton iteration, converged to adjacent doubles.
double test_wavenumber(double w, double h, double g = kG) {
  double lo = 0, hi = std::max(w * w / g, w / std::sqrt(g * h)) * 4 + 1e-300;
  while (g * hi * std::tanh(hi * h) < w * w) hi *= 2;
  for (int i = 0; i < 2000 && hi - lo > 0; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    (g * mid * std::tanh(mid * h) < w * w ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// The finite-depth group velocity from ω² = g k tanh(kh): c_g = (g tanh kh + g k h sech² kh)/(2ω).
double test_group_velocity(double k, double h, double g = kG) {
  const double kh = k * h;
  const double sech = kh > 350 ? 0.0 : 1.0 / std::cosh(kh);
  return (g * std::tanh(kh) + g * k * h * sech * sech) / (2 * std::sqrt(g * k * std::tanh(kh)));
}

std::vector<double> omegas_around(double wp) {
  std::vector<double> v;
  for (double x = 0.3; x <= 6.0; x += 0.037) v.push_back(x * wp);
  v.push_back(wp);
  return v;
}

}  // namespace

// =============================================================================================
// Pierson–Moskowitz

TEST(PiersonMoskowitz, WindFormPeakIsFourBetaOverFiveToTheQuarterGOverU) {
  for (double u : {5.0, 12.0, 25.0}) {
    const auto pm = sr::PiersonMoskowitz::from_wind(u);
    // dS/dω = 0 ⇔ ωp⁴ = (4/5) b, b = β (g/U)⁴: ωp = (4β/5)^(1/4) g/U exactly. A pow and a
    // division: a few ulps.
    const double wp = std::pow(4 * 0.74 / 5, 0.25) * kG / u;
    EXPECT_LT(rel(pm->peak_omega(), wp), 1e-14) << "U = " << u;
    // The published rounding, 0.877 g/U19.5 (e.g. Holthuijsen 2007 §6.3.3), to its 3 digits.
    EXPECT_NEAR(pm->peak_omega() * u / kG, 0.877, 0.0005);
    // And it is the maximum of S: a golden-section search finds the same ω to ~√ε (1e-7
    // leaves room for the flatness of a maximum).
    EXPECT_LT(rel(swell::test::golden_section_maximum([&](double w) { return (*pm)(w); }, 0.3 * wp, 3 * wp), wp), 1e-7);
  }
}

TEST(PiersonMoskowitz, WindFormCoefficientsAreAlphaGSquaredAndBeta) {
  const double u = 15.0;
  const auto pm = sr::PiersonMoskowitz::from_wind(u);
  const double a = 8.1e-3 * kG * kG, b = 0.74 * std::pow(kG / u, 4);
  for (double w : {0.2, 0.45, 0.7, 1.0, 2.0, 5.0}) {
    // S ω⁵ exp(b ω⁻⁴) is the constant α g²; a few roundings in pow/exp.
    EXPECT_LT(rel((*pm)(w)*std::pow(w, 5) * std::exp(b * std::pow(w, -4)), a), 1e-13)
        << "w = " << w;
    EXPECT_LT(rel((*pm)(w), pm_formula(w, a, b)), 1e-13) << "w = " << w;
  }
  // Hs = 4√m0 = 4 √(a/(4b)) = 2 √(α/β) U²/g: by the test's own quadrature (1e-10: tanh-sinh
  // at 1e-13 per piece, summed over 8 pieces, with margin), and the classic rounded
  // "Hs ≈ 0.21 U19.5²/g" to its two digits.
  const double m0 = test_moment(*pm, 0, pm->peak_omega());
  const double hs = 2 * std::sqrt(8.1e-3 / 0.74) * u * u / kG;
  EXPECT_LT(rel(4 * std::sqrt(m0), hs), 1e-10);
  EXPECT_NEAR(4 * std::sqrt(m0) * kG / (u * u), 0.21, 0.005);
}

TEST(PiersonMoskowitz, WindFormUsesGivenGravity) {
  const auto pm = sr::PiersonMoskowitz::from_wind(10.0, 9.7);
  EXPECT_LT(rel(pm->peak_omega(), std::pow(4 * 0.74 / 5, 0.25) * 9.7 / 10.0), 1e-14);
  EXPECT_LT(rel((*pm)(1.0), pm_formula(1.0, 8.1e-3 * 9.7 * 9.7, 0.74 * std::pow(0.97, 4))),
            1e-13);  // a few roundings
}

TEST(PiersonMoskowitz, BretschneiderMatchesFormulaAndNormalization) {
  for (auto [hs, tp] : {std::pair{1.0, 6.0}, std::pair{3.5, 10.0}, std::pair{8.0, 15.0}}) {
    const auto s = sr::PiersonMoskowitz::bretschneider(hs, tp);
    const double wp = 2 * pi / tp;
    EXPECT_LT(rel(s->peak_omega(), wp), 1e-14);  // (4b/5)^(1/4) = ωp: a few roundings
    for (double w : omegas_around(wp)) {
      EXPECT_LT(rel((*s)(w), bretschneider_formula(w, hs, tp)), 1e-13) << "w = " << w;
    }
    // m0 = Hs²/16 in closed form; test quadrature at 1e-13 per piece → 1e-10 with margin.
    EXPECT_LT(rel(test_moment(*s, 0, wp), hs * hs / 16), 1e-10);
    EXPECT_EQ(s->tail_exponent(), 5.0);
  }
}

TEST(PiersonMoskowitz, ZeroAtAndBelowZeroAndFiniteNearZero) {
  const auto s = sr::PiersonMoskowitz::bretschneider(2.0, 8.0);
  EXPECT_EQ((*s)(0.0), 0.0);
  EXPECT_EQ((*s)(-1.0), 0.0);
  // ω⁻⁵ overflows for tiny ω while exp(−bω⁻⁴) underflows: inf × 0 must not leak out as NaN.
  for (double w : {1e-300, 1e-100, 1e-10, 1e-3, 0.05}) {
    EXPECT_TRUE(std::isfinite((*s)(w))) << "w = " << w;
    EXPECT_GE((*s)(w), 0.0) << "w = " << w;
  }
  EXPECT_TRUE(std::isfinite((*s)(1e6)));
}

TEST(PiersonMoskowitz, InvalidArgumentsThrow) {
  EXPECT_THROW(sr::PiersonMoskowitz::from_wind(0.0), swell::InvalidInput);
  EXPECT_THROW(sr::PiersonMoskowitz::from_wind(-3.0), swell::InvalidInput);
  EXPECT_THROW(sr::PiersonMoskowitz::from_wind(kNaN), swell::InvalidInput);
  EXPECT_THROW(sr::PiersonMoskowitz::bretschneider(0.0, 8.0), swell::InvalidInput);
  EXPECT_THROW(sr::PiersonMoskowitz::bretschneider(-1.0, 8.0), swell::InvalidInput);
  EXPECT_THROW(sr::PiersonMoskowitz::bretschneider(2.0, 0.0), swell::InvalidInput);
  EXPECT_THROW(sr::PiersonMoskowitz::bretschneider(2.0, kNaN), swell::InvalidInput);
}

// =============================================================================================
// JONSWAP

TEST(Jonswap, DefaultShapeIsHasselmann1973MeanValues) {
  const sr::Jonswap::Shape shape;
  EXPECT_EQ(shape.gamma, 3.3);
  EXPECT_EQ(shape.sigma_a, 0.07);
  EXPECT_EQ(shape.sigma_b, 0.09);
}

TEST(Jonswap, FromAlphaMatchesFormula) {
  const double alpha = 0.0123, wp = 0.9;
  for (sr::Jonswap::Shape shape : {sr::Jonswap::Shape{}, sr::Jonswap::Shape{1.0, 0.07, 0.09},
                                   sr::Jonswap::Shape{6.0, 0.05, 0.12}}) {
    const auto j = sr::Jonswap::from_alpha(alpha, wp, shape);
    EXPECT_EQ(j->peak_omega(), wp);
    EXPECT_EQ(j->alpha(), alpha);
    for (double w : omegas_around(wp)) {
      // pow/exp chain: a few roundings, 1e-13.
      EXPECT_LT(rel((*j)(w), jonswap_formula(w, alpha, wp, shape.gamma, shape.sigma_a,
                                             shape.sigma_b)),
                1e-13)
          << "w = " << w << ", gamma = " << shape.gamma;
    }
  }
}

// The spectrum's constants (α g², 1.25 ωp⁴, log γ) are made once and exponentials that
// underflow are not computed: the values are bit for bit the definition's evaluation, from far
// below the peak (where e^(−1.25 (ωp/ω)⁴) underflows) to far above it (where the peak's
// e^(−d²/2) does).
TEST(Jonswap, ValuesAreTheDefinitionEvaluatedBitForBit) {
  const double alpha = 0.0123, wp = 0.9;
  for (sr::Jonswap::Shape shape : {sr::Jonswap::Shape{}, sr::Jonswap::Shape{6.0, 0.05, 0.12}}) {
    const auto j = sr::Jonswap::from_alpha(alpha, wp, shape, 9.81);
    for (double w = 0.02; w < 60; w *= 1.0137) {
      const double a = alpha * 9.81 * 9.81, b = 1.25 * std::pow(wp, 4);
      const double x = b / (w * w * w * w);
      const double pm = x > 700 ? a * std::exp(-x - 5.0 * std::log(w)) : a * std::exp(-x) / (w * w * w * w * w);
      const double sigma = w <= wp ? shape.sigma_a : shape.sigma_b;
      const double d = (w - wp) / (sigma * wp);
      const double want = pm * std::exp(std::exp(-0.5 * d * d) * std::log(shape.gamma));
      const double got = (*j)(w);
      EXPECT_TRUE(got == want) << "w = " << w << ": " << got << " against " << want;
    }
  }
}

TEST(Jonswap, GammaOneFromAlphaIsPiersonMoskowitz) {
  // With γ = 1 and α = (5/16) Hs² ωp⁴ / g², JONSWAP is the Bretschneider spectrum pointwise.
  const double hs = 2.5, tp = 9.0, wp = 2 * pi / tp;
  const double alpha = 5.0 / 16.0 * hs * hs * std::pow(wp, 4) / (kG * kG);
  const auto j = sr::Jonswap::from_alpha(alpha, wp, {1.0, 0.07, 0.09});
  const auto pm = sr::PiersonMoskowitz::bretschneider(hs, tp);
  for (double w : omegas_around(wp)) {
    EXPECT_LT(rel((*j)(w), (*pm)(w)), 1e-13) << "w = " << w;  // two formula routes, roundings
  }
}

TEST(Jonswap, GammaOneFromHsTpIsPiersonMoskowitz) {
  for (auto [hs, tp] : {std::pair{1.0, 5.0}, std::pair{4.0, 12.0}}) {
    const auto j = sr::Jonswap::from_hs_tp(hs, tp, {1.0, 0.07, 0.09});
    const auto pm = sr::PiersonMoskowitz::bretschneider(hs, tp);
    const double wp = 2 * pi / tp;
    EXPECT_LT(rel(j->peak_omega(), wp), 1e-15);
    // α comes from a quadrature held to kMomentRelativeTolerance = 1e-9; 2e-9 allows that
    // plus rounding. The closed form is α = (5/16) Hs² ωp⁴ / g².
    EXPECT_LT(rel(j->alpha(), 5.0 / 16.0 * hs * hs * std::pow(wp, 4) / (kG * kG)), 2e-9);
    for (double w : omegas_around(wp)) {
      EXPECT_LT(rel((*j)(w), (*pm)(w)), 2e-9) << "w = " << w;  // same budget as α
    }
  }
}

TEST(Jonswap, ExactNormalizationGivesBackHs) {
  for (double gamma : {1.0, 1.5, 2.0, 3.3, 5.0, 7.0}) {
    for (auto [hs, tp] : {std::pair{1.5, 7.0}, std::pair{6.0, 14.0}}) {
      const auto j = sr::Jonswap::from_hs_tp(hs, tp, {gamma, 0.07, 0.09});
      // m0 by the test's own tanh-sinh quadrature (not the library's Gauss–Kronrod).
      // The normalization is held to 1e-9 in m0, i.e. 5e-10 in Hs; 1e-8 is 20× that and
      // 100× tighter than the 1e-6 the issue asks for.
      const double m0 = test_moment(*j, 0, j->peak_omega());
      EXPECT_LT(rel(4 * std::sqrt(m0), hs), 1e-8) << "gamma = " << gamma << ", hs = " << hs;
    }
  }
  // Non-default widths too: normalization must integrate the actual shape.
  const auto j = sr::Jonswap::from_hs_tp(2.0, 10.0, {4.0, 0.12, 0.05});
  EXPECT_LT(rel(4 * std::sqrt(test_moment(*j, 0, j->peak_omega())), 2.0), 1e-8);
  // And the shape is the JONSWAP shape with the α it reports.
  for (double w : omegas_around(j->peak_omega())) {
    EXPECT_LT(rel((*j)(w), jonswap_formula(w, j->alpha(), 2 * pi / 10.0, 4.0, 0.12, 0.05)),
              1e-13);
  }
}

TEST(Jonswap, DnvNormalizationIsTheDnvFormula) {
  // DNV-RP-C205 §3.5.5: S_J = (1 − 0.287 ln γ) S_PM(ω) γ^r, S_PM the Bretschneider spectrum.
  const double hs = 3.0, tp = 10.0, wp = 2 * pi / tp;
  for (double gamma : {1.0, 1.5, 2.0, 3.3, 5.0}) {
    const auto j =
        sr::Jonswap::from_hs_tp(hs, tp, {gamma, 0.07, 0.09}, sr::JonswapNormalization::dnv);
    for (double w : omegas_around(wp)) {
      const double sigma = w <= wp ? 0.07 : 0.09;
      const double r = std::exp(-(w - wp) * (w - wp) / (2 * sigma * sigma * wp * wp));
      const double want =
          (1 - 0.287 * std::log(gamma)) * bretschneider_formula(w, hs, tp) * std::pow(gamma, r);
      EXPECT_LT(rel((*j)(w), want), 1e-13) << "w = " << w << ", gamma = " << gamma;
    }
  }
}

TEST(Jonswap, DnvNormalizationHsErrorBound) {
  // The DNV factor is an approximation, quoted as good to −0.5 % … +0.2 % for γ ∈ [1.5, 5]
  // (σa = 0.07, σb = 0.09). That holds for Hs. On m0 it does not: scanned independently
  // (composite Simpson of the DNV formula, step 0.05 in γ), the m0 error runs from −0.328 %
  // (γ = 1.5) to +0.292 % (γ ≈ 3.8), so Hs is off by −0.16 % … +0.15 %. The bound catches a
  // wrong factor (0.287 → 0.28 moves γ = 5 by +1 % in Hs) or a missing one (γ = 5: +36 %).
  const double hs = 2.0, tp = 8.0;
  double lo_m0 = 1, hi_m0 = -1;
  for (double gamma = 1.5; gamma <= 5.0 + 1e-12; gamma += 0.25) {
    const auto j =
        sr::Jonswap::from_hs_tp(hs, tp, {gamma, 0.07, 0.09}, sr::JonswapNormalization::dnv);
    const double m0_error = test_moment(*j, 0, j->peak_omega()) / (hs * hs / 16) - 1;
    const double hs_error = std::sqrt(1 + m0_error) - 1;
    EXPECT_GE(hs_error, -0.005) << "gamma = " << gamma;
    EXPECT_LE(hs_error, 0.002) << "gamma = " << gamma;
    lo_m0 = std::min(lo_m0, m0_error), hi_m0 = std::max(hi_m0, m0_error);
  }
  // The scan sees both signs, and the m0 error really exceeds +0.2 % (what the notes claim).
  EXPECT_LT(lo_m0, -0.002);
  EXPECT_GT(hi_m0, 0.002);
}

TEST(Jonswap, FiniteAndPositiveBelowThePeak) {
  // Blender's ocean modifier returned NaN below the peak. Every ω in (0, ωp] must give a
  // finite value, positive where the exponential has not underflowed.
  for (double gamma : {1.0, 3.3, 7.0}) {
    const auto j = sr::Jonswap::from_hs_tp(2.0, 8.0, {gamma, 0.07, 0.09});
    const double wp = j->peak_omega();
    for (double x = 0.3; x <= 1.0; x += 0.01) {
      const double v = (*j)(x * wp);
      EXPECT_TRUE(std::isfinite(v)) << "w/wp = " << x;
      EXPECT_GT(v, 0.0) << "w/wp = " << x;
    }
    for (double w : {1e-300, 1e-20, 1e-3, 0.05 * wp}) {
      EXPECT_TRUE(std::isfinite((*j)(w))) << "w = " << w;
      EXPECT_GE((*j)(w), 0.0) << "w = " << w;
    }
    EXPECT_EQ((*j)(0.0), 0.0);
    EXPECT_EQ((*j)(-2.0), 0.0);
  }
}

TEST(Jonswap, SigmaAActsBelowPeakSigmaBAbove) {
  const double alpha = 0.01, wp = 1.1;
  const auto base = sr::Jonswap::from_alpha(alpha, wp, {3.3, 0.07, 0.09});
  const auto wide_a = sr::Jonswap::from_alpha(alpha, wp, {3.3, 0.20, 0.09});
  const auto wide_b = sr::Jonswap::from_alpha(alpha, wp, {3.3, 0.07, 0.20});
  for (double x = 0.6; x <= 1.6; x += 0.01) {
    const double w = x * wp;
    if (w < wp * (1 - 1e-6)) {
      EXPECT_NE((*wide_a)(w), (*base)(w)) << "w/wp = " << x;  // σa changes the low side
      EXPECT_EQ((*wide_b)(w), (*base)(w)) << "w/wp = " << x;  // σb does not
    } else if (w > wp * (1 + 1e-6)) {
      EXPECT_EQ((*wide_a)(w), (*base)(w)) << "w/wp = " << x;  // σa does not touch the high side
      EXPECT_NE((*wide_b)(w), (*base)(w)) << "w/wp = " << x;  // σb does
    }
  }
  // At ωp itself r = 1 whatever σ.
  EXPECT_EQ((*wide_a)(wp), (*base)(wp));
  EXPECT_EQ((*wide_b)(wp), (*base)(wp));
  // A wider σ raises the enhancement off the peak (γ^r with r closer to 1).
  EXPECT_GT((*wide_a)(0.9 * wp), (*base)(0.9 * wp));
  EXPECT_GT((*wide_b)(1.1 * wp), (*base)(1.1 * wp));
}

TEST(Jonswap, FromWindFetchIsHasselmann1973) {
  for (auto [u10, fetch] : {std::pair{10.0, 50e3}, std::pair{20.0, 300e3}, std::pair{7.0, 8e3}}) {
    const auto j = sr::Jonswap::from_wind_fetch(u10, fetch);
    // Hasselmann et al. (1973): α = 0.076 (U10²/(F g))^0.22, ωp = 22 (g²/(U10 F))^(1/3).
    const double alpha = 0.076 * std::pow(u10 * u10 / (fetch * kG), 0.22);
    const double wp = 22 * std::cbrt(kG * kG / (u10 * fetch));
    EXPECT_LT(rel(j->alpha(), alpha), 1e-14) << "U10 = " << u10;   // one pow: a few ulps
    EXPECT_LT(rel(j->peak_omega(), wp), 1e-14) << "U10 = " << u10;  // one cbrt
    for (double w : omegas_around(wp)) {
      EXPECT_LT(rel((*j)(w), jonswap_formula(w, alpha, wp, 3.3, 0.07, 0.09)), 1e-13);
    }
  }
  // The same law in Hasselmann et al.'s frequency form, fp = 3.5 (g/U10) (g F/U10²)^−0.33:
  // 2π·3.5 = 21.99 ≈ 22 and −0.33 ≈ −1/3, so the two differ by (gF/U²)^(1/3 − 0.33), 3.0 % at
  // U10 = 10 m/s over 100 km (Tp ≈ 6.2 s vs 6.05 s). Tolerance 3.5 %.
  const auto j = sr::Jonswap::from_wind_fetch(10.0, 100e3);
  const double fp = 3.5 * (kG / 10.0) * std::pow(kG * 100e3 / 100.0, -0.33);
  EXPECT_NEAR(j->peak_omega() / (2 * pi * fp), 1.0, 0.035);
}

TEST(Jonswap, PeakEnhancementIsGamma) {
  // For equal α and ωp, S_J(ωp)/S_PM(ωp) = γ exactly (r = 1 at the peak). S_PM is built
  // independently as the Bretschneider spectrum with the same a = α g².
  const double alpha = 0.0081, wp = 0.8;
  const double hs = std::sqrt(16 * alpha * kG * kG / (5 * std::pow(wp, 4)));
  const auto pm = sr::PiersonMoskowitz::bretschneider(hs, 2 * pi / wp);
  for (double gamma : {1.0, 2.0, 3.3, 5.0, 7.0}) {
    const auto j = sr::Jonswap::from_alpha(alpha, wp, {gamma, 0.07, 0.09});
    EXPECT_LT(rel((*j)(wp) / (*pm)(wp), gamma), 1e-13) << "gamma = " << gamma;  // roundings
    EXPECT_EQ(j->peak_omega(), wp);
  }
}

TEST(Jonswap, InvalidArgumentsThrow) {
  EXPECT_THROW(sr::Jonswap::from_hs_tp(0.0, 8.0), swell::InvalidInput);
  EXPECT_THROW(sr::Jonswap::from_hs_tp(-2.0, 8.0), swell::InvalidInput);
  EXPECT_THROW(sr::Jonswap::from_hs_tp(2.0, 0.0), swell::InvalidInput);
  EXPECT_THROW(sr::Jonswap::from_hs_tp(2.0, kNaN), swell::InvalidInput);
  EXPECT_THROW(sr::Jonswap::from_hs_tp(2.0, 8.0, {0.99, 0.07, 0.09}), swell::InvalidInput);
  EXPECT_THROW(sr::Jonswap::from_hs_tp(2.0, 8.0, {3.3, 0.0, 0.09}), swell::InvalidInput);
  EXPECT_THROW(sr::Jonswap::from_hs_tp(2.0, 8.0, {3.3, 0.07, -0.09}), swell::InvalidInput);
  EXPECT_THROW(sr::Jonswap::from_alpha(0.0, 1.0), swell::InvalidInput);
  EXPECT_THROW(sr::Jonswap::from_alpha(0.01, 0.0), swell::InvalidInput);
  EXPECT_THROW(sr::Jonswap::from_alpha(0.01, -1.0), swell::InvalidInput);
  EXPECT_THROW(sr::Jonswap::from_wind_fetch(0.0, 1e4), swell::InvalidInput);
  EXPECT_THROW(sr::Jonswap::from_wind_fetch(10.0, 0.0), swell::InvalidInput);
  EXPECT_THROW(sr::Jonswap::from_wind_fetch(10.0, kNaN), swell::InvalidInput);
}

// =============================================================================================
// TMA and the Kitaigorodskii depth factor

TEST(Tma, TendsToJonswapInDeepWater) {
  const auto j = sr::Jonswap::from_hs_tp(2.0, 9.0);
  for (auto factor : {sr::TmaFactor::exact, sr::TmaFactor::thompson_vincent}) {
    const auto tma = sr::Tma::create(j, 1e4, factor);
    for (double x = 0.5; x <= 3.0; x += 0.05) {
      const double w = x * j->peak_omega();
      // kh ≥ (0.5 ωp)² h/g ≈ 124: tanh kh = 1 and 2kh/sinh 2kh ≈ 1e-105, both invisible in
      // double; the issue asks 1e-12.
      EXPECT_LT(rel((*tma)(w), (*j)(w)), 1e-12) << "w = " << w;
    }
    EXPECT_LT(rel(tma->peak_omega(), j->peak_omega()), 1e-6);  // a numerical peak search
  }
  // Infinite depth: Φ = 1 exactly for both forms.
  for (double w : {0.1, 1.0, 10.0}) {
    EXPECT_EQ(sr::kitaigorodskii_exact(w, sr::kInfiniteDepth), 1.0);
    EXPECT_EQ(sr::kitaigorodskii_thompson_vincent(w, sr::kInfiniteDepth), 1.0);
  }
}

TEST(Tma, ExactFactorIsKitaigorodskiiDefinition) {
  // Kitaigorodskii et al. (1975): Φ = [k⁻³ dk/dω]_h / [k⁻³ dk/dω]_∞ = ω⁵ / (2 g² k³ c_g),
  // with k = k(ω, h) and c_g the finite-depth group velocity, both computed here (bisection
  // and the derivative of ω² = g k tanh kh), not by the library.
  for (double h : {1.0, 5.0, 20.0, 100.0}) {
    for (double w = 0.05; w <= 5.0; w *= 1.15) {
      const double k = test_wavenumber(w, h);
      const double phi = std::pow(w, 5) / (2 * kG * kG * k * k * k * test_group_velocity(k, h));
      // The library's k(ω) is promised to 1e-12; Φ ∝ (kh)² in shallow water doubles that;
      // with the roundings of either route, 1e-11.
      EXPECT_LT(rel(sr::kitaigorodskii_exact(w, h), phi), 1e-11) << "w = " << w << ", h = " << h;
    }
  }
  // Shallow limit Φ → ωh²/2 (ωh = ω √(h/g)): ω = 1e-4 at h = 1 makes ωh ≈ 3e-5 and the
  // next term relative (2/3)(kh)² ≈ 7e-10; tolerance 1e-9.
  const double wh = 1e-4 * std::sqrt(1.0 / kG);
  EXPECT_LT(rel(sr::kitaigorodskii_exact(1e-4, 1.0), 0.5 * wh * wh), 1e-9);
}

TEST(Tma, SpectrumIsJonswapTimesPhi) {
  const auto j = sr::Jonswap::from_hs_tp(1.5, 8.0, {2.5, 0.07, 0.09});
  for (double h : {3.0, 15.0}) {
    const auto exact = sr::Tma::create(j, h, sr::TmaFactor::exact);
    const auto tv = sr::Tma::create(j, h, sr::TmaFactor::thompson_vincent);
    for (double x = 0.4; x <= 4.0; x += 0.05) {
      const double w = x * j->peak_omega();
      // One product on top of two library values: a couple of ulps.
      EXPECT_LT(rel((*exact)(w), (*j)(w)*sr::kitaigorodskii_exact(w, h)), 1e-14);
      EXPECT_LT(rel((*tv)(w), (*j)(w)*sr::kitaigorodskii_thompson_vincent(w, h)), 1e-14);
      EXPECT_EQ(exact->depth_factor(w), sr::kitaigorodskii_exact(w, h));
      EXPECT_EQ(tv->depth_factor(w), sr::kitaigorodskii_thompson_vincent(w, h));
    }
    // Φ < 1 everywhere in finite depth: the TMA sea is smaller than its JONSWAP.
    EXPECT_LT(test_moment(*exact, 0, j->peak_omega()), test_moment(*j, 0, j->peak_omega()));
  }
}

TEST(Tma, PeakIsTheMaximumOfS) {
  const auto j = sr::Jonswap::from_hs_tp(2.0, 12.0, {1.5, 0.07, 0.09});
  // h = 3 m: Φ rises steeply through the peak, so the TMA peak moves off the JONSWAP one.
  const auto tma = sr::Tma::create(j, 3.0);
  const double found = swell::test::golden_section_maximum([&](double w) { return (*tma)(w); }, 0.5 * j->peak_omega(),
                                  2.0 * j->peak_omega());
  // Both sides locate a flat maximum to ~√ε; 1e-6 relative.
  EXPECT_LT(rel(tma->peak_omega(), found), 1e-6);
  EXPECT_GT(tma->peak_omega(), j->peak_omega());
}

TEST(Tma, ThompsonVincentBranches) {
  const double h = 10.0;
  auto at = [&](double wh) { return sr::kitaigorodskii_thompson_vincent(wh * std::sqrt(kG / h), h); };
  // Each branch at interior points (ωh = ω √(h/g)); ωh passes through one sqrt and a
  // product, so 1e-14 absolute.
  for (double wh : {0.1, 0.4, 0.75, 0.99}) EXPECT_NEAR(at(wh), 0.5 * wh * wh, 1e-14) << wh;
  for (double wh : {1.01, 1.3, 1.5, 1.8, 1.99}) {
    EXPECT_NEAR(at(wh), 1 - 0.5 * (2 - wh) * (2 - wh), 1e-14) << wh;
  }
  for (double wh : {2.01, 2.5, 4.0, 30.0}) EXPECT_NEAR(at(wh), 1.0, 1e-14) << wh;
  // Continuity at ωh = 1 (½ from both sides) and ωh = 2 (1 from both sides): the slope is at
  // most 1 in ωh, so a 1e-9 step moves Φ by ≤ 1e-9.
  for (double edge : {1.0, 2.0}) {
    EXPECT_NEAR(at(edge * (1 - 1e-9)), at(edge * (1 + 1e-9)), 3e-9) << edge;
  }
  EXPECT_NEAR(at(1.0), 0.5, 1e-14);
  EXPECT_NEAR(at(2.0), 1.0, 1e-14);
  // It depends on ω and h only through ωh.
  EXPECT_NEAR(sr::kitaigorodskii_thompson_vincent(1.3 * std::sqrt(kG / 40.0), 40.0), at(1.3),
              1e-14);
}

TEST(Tma, ThompsonVincentWithinFourPercentOfExact) {
  // Φ depends on ω and h only through ωh. Scanned independently (bisection for k, ωh from
  // 0.0025 to 5), the Thompson–Vincent fit differs from the exact Φ by at most 4.09 %
  // relative (at ωh ≈ 1.065) and 0.0228 absolute (at ωh ≈ 1.10). Asserted: 4.2 % and 0.0235.
  double worst_rel = 0, worst_abs = 0;
  for (double h : {2.0, 30.0}) {
    for (double wh = 0.01; wh <= 5.0; wh += 0.005) {
      const double w = wh * std::sqrt(kG / h);
      const double exact = sr::kitaigorodskii_exact(w, h);
      const double tv = sr::kitaigorodskii_thompson_vincent(w, h);
      worst_rel = std::max(worst_rel, std::abs(tv / exact - 1));
      worst_abs = std::max(worst_abs, std::abs(tv - exact));
    }
  }
  EXPECT_LE(worst_rel, 0.042);
  EXPECT_LE(worst_abs, 0.0235);
  EXPECT_GT(worst_rel, 0.03);  // the two really are different functions
}

TEST(Tma, InvalidArgumentsThrow) {
  const auto j = sr::Jonswap::from_hs_tp(2.0, 8.0);
  EXPECT_THROW(sr::Tma::create(j, 0.0), swell::InvalidInput);
  EXPECT_THROW(sr::Tma::create(j, -4.0), swell::InvalidInput);
  EXPECT_THROW(sr::Tma::create(j, kNaN), swell::InvalidInput);
  EXPECT_THROW((void)sr::kitaigorodskii_exact(1.0, -1.0), swell::InvalidInput);
  EXPECT_THROW((void)sr::kitaigorodskii_thompson_vincent(1.0, 0.0), swell::InvalidInput);
}

TEST(FrequencySpectra, FiniteAtExtremeFrequencies) {
  // Quadrature on [a, ∞) (Boost's Gauss–Kronrod mapping, exp-sinh) samples ω out to ~1e300, so
  // S must stay a number there: ω⁻⁵ → 0, exp(−bω⁻⁴) → 1, Φ → 1. A NaN poisons any moment.
  const auto j = sr::Jonswap::from_hs_tp(2.0, 9.0);
  const std::vector<std::pair<std::string, sr::FrequencySpectrumPtr>> spectra = {
      {"bretschneider", sr::PiersonMoskowitz::bretschneider(2.0, 9.0)},
      {"jonswap", j},
      {"tma exact h=8", sr::Tma::create(j, 8.0)},
      {"tma thompson-vincent h=8", sr::Tma::create(j, 8.0, sr::TmaFactor::thompson_vincent)}};
  for (const auto& [label, s] : spectra) {
    for (double w : {1e3, 1e10, 1e50, 1e100, 1e155, 1e200, 1e300}) {
      EXPECT_TRUE(std::isfinite((*s)(w))) << label << ", w = " << w;
      EXPECT_GE((*s)(w), 0.0) << label << ", w = " << w;
    }
  }
  for (double w : {1e10, 1e100, 1e155, 1e200, 1e300}) {
    EXPECT_NEAR(sr::kitaigorodskii_exact(w, 8.0), 1.0, 1e-15) << "w = " << w;  // deep limit
  }
}

TEST(FindPeakOmega, FindsTheClosedFormPeak) {
  const auto pm = sr::PiersonMoskowitz::bretschneider(2.0, 7.0);
  // Brent on a smooth maximum locates it to ~√ε relative; 1e-7.
  EXPECT_LT(rel(sr::find_peak_omega(*pm, 0.1, 10.0), 2 * pi / 7.0), 1e-7);
  // Peak outside the interval: the maximum on [lo, hi] is at the edge nearest the peak.
  EXPECT_LT(rel(sr::find_peak_omega(*pm, 2.0, 5.0), 2.0), 1e-7);
}

// =============================================================================================
// ModelSpec factory

namespace {

// Runs f, expects swell::InvalidInput, and returns its message.
template <class F>
std::string invalid_input_message(F f) {
  try {
    f();
  } catch (const swell::InvalidInput& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "threw something other than swell::InvalidInput: " << e.what();
    return "";
  }
  ADD_FAILURE() << "did not throw";
  return "";
}

bool mentions(const std::string& message, const std::string& word) {
  return message.find(word) != std::string::npos;
}

}  // namespace

TEST(ModelFactory, NamesTheKnownModels) {
  const auto names = sr::frequency_model_names();
  for (const char* m : {"phillips", "pierson-moskowitz", "bretschneider", "jonswap", "tma"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), m), names.end()) << m;
  }
  const auto spreads = sr::spreading_model_names();
  for (const char* m : {"cos2s", "mitsuyasu", "hasselmann", "donelan-banner", "cos-power"}) {
    EXPECT_NE(std::find(spreads.begin(), spreads.end(), m), spreads.end()) << m;
  }
}

TEST(ModelFactory, UnknownModelIsNamed) {
  const auto msg = invalid_input_message([] {
    sr::make_frequency_spectrum({"jonswapp", {{"hs", 2.0}, {"tp", 8.0}}, {}});
  });
  EXPECT_TRUE(mentions(msg, "jonswapp")) << msg;
  const auto msg2 = invalid_input_message([] { sr::make_spreading({"cos3s", {}, {}}, 1.0); });
  EXPECT_TRUE(mentions(msg2, "cos3s")) << msg2;
}

TEST(ModelFactory, UnknownParameterIsNamed) {
  const auto msg = invalid_input_message([] {
    sr::make_frequency_spectrum({"jonswap", {{"hs", 2.0}, {"tp", 8.0}, {"gamme", 3.0}}, {}});
  });
  EXPECT_TRUE(mentions(msg, "gamme")) << msg;
}

TEST(ModelFactory, MissingRequiredParameterIsNamed) {
  const auto msg = invalid_input_message(
      [] { sr::make_frequency_spectrum({"jonswap", {{"hs", 2.0}, {"gamma", 3.0}}, {}}); });
  EXPECT_TRUE(mentions(msg, "tp")) << msg;
  const auto msg2 = invalid_input_message(
      [] { sr::make_frequency_spectrum({"tma", {{"hs", 2.0}, {"tp", 8.0}}, {}}); });
  EXPECT_TRUE(mentions(msg2, "depth")) << msg2;
  const auto msg3 = invalid_input_message(
      [] { sr::make_frequency_spectrum({"bretschneider", {{"tp", 8.0}}, {}}); });
  EXPECT_TRUE(mentions(msg3, "hs")) << msg3;
}

TEST(ModelFactory, NonPhysicalValuesAreNamed) {
  for (double hs : {0.0, -1.0}) {
    const auto msg = invalid_input_message(
        [&] { sr::make_frequency_spectrum({"jonswap", {{"hs", hs}, {"tp", 8.0}}, {}}); });
    EXPECT_TRUE(mentions(msg, "hs")) << msg;
  }
  const auto msg = invalid_input_message([] {
    sr::make_frequency_spectrum({"jonswap", {{"hs", 2.0}, {"tp", 8.0}, {"gamma", 0.5}}, {}});
  });
  EXPECT_TRUE(mentions(msg, "gamma") || mentions(msg, "γ")) << msg;
  for (double depth : {0.0, -5.0}) {
    const auto msg2 = invalid_input_message([&] {
      sr::make_frequency_spectrum({"tma", {{"hs", 2.0}, {"tp", 8.0}, {"depth", depth}}, {}});
    });
    EXPECT_TRUE(mentions(msg2, "depth")) << msg2;
  }
}

// Each value in its own range, yet the whole far outside any sea: the normalization or a
// moment cannot be computed (tp = 4e65 s puts the peak at 1.6e-65 rad/s; hs = 1e300 m
// overflows m0 = hs²/16; hs = 1e-300 m underflows it). Bad input naming the model and the
// values, never a NumericalError (which the CLI reports as exit 1, a failure of swell's).
TEST(ModelFactory, ParametersOutsideAnySeaAreBadInput) {
  const std::vector<sr::ModelSpec> absurd = {
      {"tma", {{"hs", 3.0}, {"tp", 4e65}, {"depth", 10.0}}, {}},
      {"jonswap", {{"hs", 1e300}, {"tp", 8.0}}, {}},
      {"jonswap", {{"hs", 1e-300}, {"tp", 8.0}}, {}},
      {"jonswap", {{"hs", 3.0}, {"tp", 1e-300}}, {}},
  };
  for (const auto& spec : absurd) {
    const auto msg = invalid_input_message([&] { (void)sr::make_frequency_spectrum(spec); });
    SCOPED_TRACE(msg);
    EXPECT_TRUE(mentions(msg, "spectrum model '" + spec.model + "' cannot be evaluated"));
    EXPECT_TRUE(mentions(msg, "tp = "));
  }
}

TEST(ModelFactory, ValidSpecsMatchDirectFactories) {
  const auto j = sr::make_frequency_spectrum({"jonswap", {{"hs", 3.0}, {"tp", 9.0}, {"gamma", 2.5}}, {}});
  const auto j_direct = sr::Jonswap::from_hs_tp(3.0, 9.0, {2.5, 0.07, 0.09});
  const auto t = sr::make_frequency_spectrum(
      {"tma", {{"hs", 3.0}, {"tp", 9.0}, {"gamma", 2.5}, {"depth", 12.0}}, {}});
  const auto t_direct = sr::Tma::create(j_direct, 12.0);
  const auto b = sr::make_frequency_spectrum({"bretschneider", {{"hs", 1.2}, {"tp", 6.0}}, {}});
  const auto b_direct = sr::PiersonMoskowitz::bretschneider(1.2, 6.0);
  for (double w = 0.2; w < 5.0; w *= 1.07) {
    // Same inputs through two routes: identical up to the normalization quadrature being run
    // twice (deterministic, so this is rounding at most).
    EXPECT_LT(rel((*j)(w), (*j_direct)(w)), 1e-12) << "w = " << w;
    EXPECT_LT(rel((*t)(w), (*t_direct)(w)), 1e-12) << "w = " << w;
    EXPECT_LT(rel((*b)(w), (*b_direct)(w)), 1e-12) << "w = " << w;
  }
  EXPECT_EQ(j->name(), "jonswap");
  EXPECT_EQ(t->name(), "tma");

  const auto db = sr::make_spreading({"donelan-banner", {}, {}}, 0.7);
  const auto db_direct = sr::DonelanBanner::create(0.7);
  const auto c = sr::make_spreading({"cos2s", {{"s", 7.0}}, {}}, 0.7);
  const auto c_direct = sr::Cos2s::constant(7.0);
  for (double w : {0.4, 0.7, 1.5}) {
    for (double th : {-2.0, -0.3, 0.0, 0.9}) {
      EXPECT_EQ((*db)(w, th), (*db_direct)(w, th));
      EXPECT_EQ((*c)(w, th), (*c_direct)(w, th));
    }
  }
  const auto d = sr::make_dispersion({"tma", {{"depth", 12.0}}, {}});
  EXPECT_EQ(d.depth(), 12.0);
  EXPECT_TRUE(sr::make_dispersion({"jonswap", {}, {}}).is_deep());
}
