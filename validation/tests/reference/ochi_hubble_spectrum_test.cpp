// The Ochi–Hubble six-parameter spectrum against WAFO's published example, the Bretschneider
// spectrum it reduces to at λ = 1, the closed-form moments of each component (Γ functions),
// the test's own quadrature, and where its peaks lie.
#include <gtest/gtest.h>

#include <algorithm>
#include <boost/math/special_functions/gamma.hpp>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "quadrature_support.hpp"
#include "test_support.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/frequency_spectrum.hpp"
#include "swell/reference/model_factory.hpp"
#include "swell/reference/moments.hpp"

namespace {

using swell::test::kInf;
using swell::test::kNaN;
using swell::test::rel;

namespace sr = swell::reference;
using std::numbers::pi;

// The most-probable-like member 2 of Ochi & Hubble's family for Hm0 = 7 m, as WAFO builds it
// (pywafo wafo/spectrum/models.py, OchiHubble(Hm0=7, par=2)): Hs_j = (0.84, 0.54) Hm0,
// ωp_j = (0.41 e^(−0.016 Hm0), 0.88 e^(−0.026 Hm0)), λ = (2.55, 1.82 e^(−0.089 Hm0)).
sr::OchiHubbleComponent wafo_component(int j) {
  const double hm0 = 7.0;
  const double share[] = {0.84, 0.54}, a[] = {0.41, 0.88}, b[] = {0.016, 0.026};
  const double lambda = j == 0 ? 2.55 : 1.82 * std::exp(-0.089 * hm0);
  return {share[j] * hm0, 2 * pi * std::exp(b[j] * hm0) / a[j], lambda};
}

// m_n of one component: substituting u = ((4λ + 1)/4)(ωp/ω)⁴ turns ∫ ωⁿ S_j dω into a Γ
// integral, m_n = (Hs²/16) ωp^n ((4λ + 1)/4)^(n/4) Γ(λ − n/4)/Γ(λ), finite for n < 4λ.
double component_moment(const sr::OchiHubbleComponent& c, int n) {
  const double wp = 2 * pi / c.tp, c4 = (4 * c.lambda + 1) / 4;
  return c.hs * c.hs / 16 * std::pow(wp, n) * std::pow(c4, n / 4.0) *
         boost::math::tgamma_ratio(c.lambda - n / 4.0, c.lambda);
}

// Bretschneider written out: (5/16) Hs² ωp⁴ ω⁻⁵ exp(−(5/4)(ωp/ω)⁴).
double bretschneider(double w, double hs, double tp) {
  const double wp = 2 * pi / tp;
  return 5.0 / 16 * hs * hs * std::pow(wp, 4) * std::pow(w, -5.0) *
         std::exp(-1.25 * std::pow(wp / w, 4));
}

const std::vector<std::pair<sr::OchiHubbleComponent, sr::OchiHubbleComponent>> kPairs = {
    {{3.0, 14.0, 3.0}, {2.0, 7.0, 1.5}},    // swell and wind sea, clearly apart
    {{1.0, 9.0, 1.0}, {1.5, 8.0, 1.0}},     // two Bretschneiders nearly on top of each other
    {{2.5, 11.0, 6.4}, {1.2, 5.5, 0.7}},    // a narrow swell and a broad wind sea
    {wafo_component(0), wafo_component(1)},  // λ2 = 0.98: a ω^−4.9 tail
    {{1.0, 10.0, 2.0}, {0.8, 5.0, 0.3}},    // λ2 = 0.3, an ω^−2.2 tail: m1 converges slowly
};

}  // namespace

TEST(SpectrumOchiHubble, WafoPublishedExample) {
  // pywafo's doctest: OchiHubble(par=2)(range(4)) → [0, 0.90155636, 0.04185445, 0.00583207]
  // (printed to 8 decimals: ±5e-9 absolute). The same from Ochi & Hubble's formula in 30-digit
  // mpmath: 0.90155636423648363, 0.041854450317364365, 0.0058320665070944385 (1e-13 relative:
  // the prefactor [((4λ+1)/4) ωp⁴]^λ / Γ(λ) and the ω^−(4λ+1) power cost a few roundings).
  const auto s = sr::OchiHubble::create(wafo_component(0), wafo_component(1));
  EXPECT_NEAR((*s)(1.0), 0.90155636, 5e-9);
  EXPECT_NEAR((*s)(2.0), 0.04185445, 5e-9);
  EXPECT_NEAR((*s)(3.0), 0.00583207, 5e-9);
  EXPECT_LT(rel((*s)(1.0), 0.90155636423648363), 1e-13);
  EXPECT_LT(rel((*s)(2.0), 0.041854450317364365), 1e-13);
  EXPECT_LT(rel((*s)(3.0), 0.0058320665070944385), 1e-13);
  EXPECT_EQ((*s)(0.0), 0.0);
}

TEST(SpectrumOchiHubble, LambdaOneIsBretschneiderExactly) {
  // λ = 1: (1/4)((5/4) ωp⁴)/Γ(1) Hs² ω⁻⁵ exp(−(5/4)(ωp/ω)⁴) = (5/16) Hs² ωp⁴ ω⁻⁵ … — the
  // Bretschneider spectrum term for term. Two arithmetic routes (one exponential of a sum of
  // logarithms in the library, powers here and in PiersonMoskowitz) differ by the rounding of
  // exp's argument: a few ulps of |(5/4)(ωp/ω)⁴| + |5 ln ω| + 10, relative.
  const auto s = sr::OchiHubble::create({2.0, 9.0, 1.0}, {1.2, 5.0, 1.0});
  const auto pm1 = sr::PiersonMoskowitz::bretschneider(2.0, 9.0);
  const auto pm2 = sr::PiersonMoskowitz::bretschneider(1.2, 5.0);
  for (double w = 0.2; w < 6.0; w *= 1.03) {
    auto budget = [&](double tp) {
      return 4e-16 * (1.25 * std::pow(2 * pi / tp / w, 4) + 5 * std::abs(std::log(w)) + 10);
    };
    EXPECT_LT(rel(s->component(0, w), (*pm1)(w)), budget(9.0)) << "w = " << w;
    EXPECT_LT(rel(s->component(1, w), bretschneider(w, 1.2, 5.0)), budget(5.0)) << "w = " << w;
    EXPECT_LT(rel((*s)(w), (*pm1)(w) + (*pm2)(w)), budget(5.0)) << "w = " << w;
  }
}

TEST(SpectrumOchiHubble, ZerothMomentIsTheSumOfSquaresOverSixteen) {
  for (const auto& [a, b] : kPairs) {
    const auto s = sr::OchiHubble::create(a, b);
    const double want = (a.hs * a.hs + b.hs * b.hs) / 16;
    // The library's quadrature is held to 1e-9 (kMomentRelativeTolerance).
    EXPECT_LT(rel(sr::spectral_moment(*s, 0), want), 1e-9) << a.lambda << " " << b.lambda;
    // The test's own tanh-sinh/exp-sinh, split at both peaks and their neighbourhoods: 1e-13 a
    // piece; the ω^−(4λ+1) tail beyond the exp-sinh cut holds < 1e-12 · 4λ of m0. 1e-10.
    const double w1 = 2 * pi / a.tp, w2 = 2 * pi / b.tp;
    const double lo = std::min(w1, w2), hi = std::max(w1, w2);
    const double own = swell::test::integrate_pieces(
        [&](double w) { return (*s)(w); }, {0.0, 0.5 * lo, lo, hi, 2 * hi});
    EXPECT_LT(rel(own, want), 1e-10) << a.lambda << " " << b.lambda;
  }
}

TEST(SpectrumOchiHubble, MomentsAreTheGammaFunctionClosedForms) {
  for (const auto& [a, b] : kPairs) {
    const auto s = sr::OchiHubble::create(a, b);
    for (int n : {-1, 0, 1, 2}) {
      if (n >= s->tail_exponent() - 1) {
        EXPECT_EQ(sr::spectral_moment(*s, n), kInf) << n;
        continue;
      }
      const double want = component_moment(a, n) + component_moment(b, n);
      // Quadrature to 1e-9 against Γ ratios good to ~1e-15.
      EXPECT_LT(rel(sr::spectral_moment(*s, n), want), 1e-9)
          << "n = " << n << ", lambdas " << a.lambda << ", " << b.lambda;
    }
  }
  // The closed form itself against 30-digit mpmath quadrature of one component
  // (Hs = 3, Tp = 10, λ = 2.5): m−1, m0, m1, m2 = 0.84111696534085243, 0.5625,
  // 0.38790954454706021, 0.277020820126831. Γ ratios and powers: 1e-14.
  const sr::OchiHubbleComponent one{3.0, 10.0, 2.5};
  EXPECT_LT(rel(component_moment(one, -1), 0.84111696534085243), 1e-14);
  EXPECT_LT(rel(component_moment(one, 0), 0.5625), 1e-14);
  EXPECT_LT(rel(component_moment(one, 1), 0.38790954454706021), 1e-14);
  EXPECT_LT(rel(component_moment(one, 2), 0.277020820126831), 1e-14);
}

TEST(SpectrumOchiHubble, EachComponentPeaksAtItsOwnPeakFrequency) {
  // dS_j/dω = 0 ⇔ (4λ + 1)/ω = 4 ((4λ + 1)/4) ωp⁴/ω⁵ ⇔ ω = ωp. Golden section locates a flat
  // maximum to ~√ε: 1e-7.
  for (const auto& [a, b] : kPairs) {
    const auto s = sr::OchiHubble::create(a, b);
    for (int j : {0, 1}) {
      const double wp = 2 * pi / (j == 0 ? a.tp : b.tp);
      const double found = swell::test::golden_section_maximum(
          [&](double w) { return s->component(j, w); }, 0.5 * wp, 2 * wp);
      EXPECT_LT(rel(found, wp), 1e-7) << "component " << j;
    }
  }
}

TEST(SpectrumOchiHubble, PeakIsTheGlobalMaximumAndBothPeaksAreBreakpoints) {
  for (const auto& [a, b] : kPairs) {
    const auto s = sr::OchiHubble::create(a, b);
    const double w1 = 2 * pi / a.tp, w2 = 2 * pi / b.tp;
    // A dense scan (independent of the library's scan + Brent) finds the largest value; the
    // library's peak is at least as high, and where the scan's best point is.
    double best = 0, best_w = 0;
    for (double w = 0.2 * std::min(w1, w2); w < 3 * std::max(w1, w2); w *= 1.0005) {
      if ((*s)(w) > best) best = (*s)(w), best_w = w;
    }
    EXPECT_GE((*s)(s->peak_omega()), best * (1 - 1e-12));
    EXPECT_LT(rel(s->peak_omega(), best_w), 1e-3);  // the scan's step is 5e-4
    const auto points = s->breakpoints();
    for (double w : {w1, w2, s->peak_omega()}) {
      EXPECT_NE(std::find(points.begin(), points.end(), w), points.end()) << w;
    }
    EXPECT_TRUE(std::is_sorted(points.begin(), points.end()));
  }
  // Equal peak frequencies: the peak is that ωp exactly.
  const auto same = sr::OchiHubble::create({1.0, 9.0, 2.0}, {1.0, 9.0, 0.8});
  EXPECT_EQ(same->peak_omega(), 2 * pi / 9.0);
}

TEST(SpectrumOchiHubble, TailIsSetByTheSmallerLambda) {
  const auto s = sr::OchiHubble::create({1.0, 12.0, 3.0}, {1.0, 6.0, 0.4});
  EXPECT_DOUBLE_EQ(s->tail_exponent(), 4 * 0.4 + 1);
  // ω^(4λ+1) S → (1/4)((4λ+1)/4 ωp⁴)^λ Hs²/Γ(λ) of the λ = 0.4 component as ω → ∞.
  const double wp = 2 * pi / 6.0, c4 = (4 * 0.4 + 1) / 4;
  const double limit = 0.25 * std::pow(c4 * std::pow(wp, 4), 0.4) / std::tgamma(0.4);
  EXPECT_LT(rel((*s)(1e4) * std::pow(1e4, 2.6), limit), 1e-6);  // the other term: 1e-8 of it
  EXPECT_EQ(sr::spectral_moment(*s, 2), kInf);                  // 2 ≥ 4·0.4: diverges
  // With m2 and m4 both infinite the periods take their limits: Tm02 = 2π √(m0/m2) → 0,
  // ν → ∞, and ε4 → 1 (m2²/m4 → 0 over a widening band), never ∞/∞ = NaN.
  const auto state = sr::sea_state(*s);
  EXPECT_EQ(state.tm02, 0.0);
  EXPECT_EQ(state.nu, kInf);
  EXPECT_EQ(state.epsilon4, 1.0);
  EXPECT_LT(rel(state.hs, std::sqrt(2.0)), 1e-9);
  for (double w : {1e-300, 1e-10, 1e10, 1e100, 1e300}) {
    EXPECT_TRUE(std::isfinite((*s)(w))) << w;
    EXPECT_GE((*s)(w), 0.0) << w;
  }
}

TEST(SpectrumOchiHubble, InvalidArgumentsNameTheParameter) {
  auto message = [](sr::OchiHubbleComponent a, sr::OchiHubbleComponent b) {
    try {
      (void)sr::OchiHubble::create(a, b);
    } catch (const swell::InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  EXPECT_NE(message({0.0, 10, 2}, {1, 6, 1}).find("hs1"), std::string::npos);
  EXPECT_NE(message({1.0, 10, 2}, {-1, 6, 1}).find("hs2"), std::string::npos);
  EXPECT_NE(message({1.0, 0.0, 2}, {1, 6, 1}).find("tp1"), std::string::npos);
  EXPECT_NE(message({1.0, 10, 2}, {1, kNaN, 1}).find("tp2"), std::string::npos);
  EXPECT_NE(message({1.0, 10, 0.0}, {1, 6, 1}).find("lambda1"), std::string::npos);
  EXPECT_NE(message({1.0, 10, 2}, {1, 6, -1}).find("lambda2"), std::string::npos);
}

TEST(ModelFactory, OchiHubbleFromNamedParameters) {
  const sr::ModelSpec spec{"ochi-hubble",
                           {{"hs1", 3.0}, {"tp1", 14.0}, {"lambda1", 3.0},
                            {"hs2", 2.0}, {"tp2", 7.0}, {"lambda2", 1.5}},
                           {}};
  const auto s = sr::make_frequency_spectrum(spec);
  const auto direct = sr::OchiHubble::create({3.0, 14.0, 3.0}, {2.0, 7.0, 1.5});
  EXPECT_EQ(s->name(), "ochi-hubble");
  for (double w = 0.1; w < 3; w *= 1.1) EXPECT_EQ((*s)(w), (*direct)(w));
  EXPECT_EQ(s->peak_omega(), direct->peak_omega());
  for (const char* missing : {"hs1", "tp1", "lambda1", "hs2", "tp2", "lambda2"}) {
    auto partial = spec;
    partial.numbers.erase(missing);
    try {
      (void)sr::make_frequency_spectrum(partial);
      ADD_FAILURE() << "missing " << missing << " must throw";
    } catch (const swell::InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
    }
  }
  auto negative = spec;
  negative.numbers["lambda2"] = -1;
  EXPECT_THROW((void)sr::make_frequency_spectrum(negative), swell::InvalidInput);
}
