// The Gaussian swell spectrum (DNV-RP-C205): its values against the formula and against values
// computed once in 30-digit arithmetic (Python mpmath), its moments against the closed forms
// of a Gaussian truncated at ω = 0, and bad input.
#include <gtest/gtest.h>

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

struct GaussianCase {
  double hs, tp, sigma;
};

// Three widths: σ ≪ ωp (ωp/σ = 5.2, the cut-off part 8e-8), σ = 0.32 ωp (8e-4), and a swell so
// broad that 5.8 % of the Gaussian lies below ω = 0 (ωp/σ = 1.57).
const std::vector<GaussianCase> kCases = {{2.0, 12.0, 0.1}, {3.0, 10.0, 0.2}, {1.0, 8.0, 0.5}};

// Closed forms of a normal density N(ωp, σ²) scaled to Hs²/16 and cut at ω = 0, with
// a = ωp/σ, Φ and φ the standard normal CDF and density:
//   m0 = (Hs²/16) Φ(a),   m1 = (Hs²/16)(ωp Φ(a) + σ φ(a)),
//   m2 = (Hs²/16)((ωp² + σ²) Φ(a) + ωp σ φ(a)).
double truncated_moment(const GaussianCase& c, int n) {
  const double wp = 2 * pi / c.tp, a = wp / c.sigma;
  const double cdf = 0.5 * std::erfc(-a / std::sqrt(2.0));
  const double pdf = std::exp(-0.5 * a * a) / std::sqrt(2 * pi);
  const double scale = c.hs * c.hs / 16;
  if (n == 0) return scale * cdf;
  if (n == 1) return scale * (wp * cdf + c.sigma * pdf);
  return scale * ((wp * wp + c.sigma * c.sigma) * cdf + wp * c.sigma * pdf);
}

}  // namespace

TEST(SpectrumGaussian, ValueIsTheDnvFormula) {
  for (const auto& c : kCases) {
    const auto s = sr::GaussianSwell::create(c.hs, c.tp, c.sigma);
    const double wp = 2 * pi / c.tp;
    EXPECT_EQ(s->peak_omega(), wp);
    for (double x = 0.05; x < 4.0; x += 0.0173) {
      const double w = x * wp;
      const double want = c.hs * c.hs / 16 / (c.sigma * std::sqrt(2 * pi)) *
                          std::exp(-(w - wp) * (w - wp) / (2 * c.sigma * c.sigma));
      // One exp and a few products on either side: ulps; 1e-13 allows exp(−z²/2) at z ≈ 30.
      EXPECT_LT(rel((*s)(w), want), 1e-13) << "w = " << w << ", sigma = " << c.sigma;
    }
  }
  // 30-digit values (mpmath) at ωp, ωp/2, 3ωp/2 — both sides equal by symmetry:
  // Hs = 2, Tp = 12, σ = 0.1 and Hs = 1, Tp = 8, σ = 0.5. Double arithmetic: 1e-14.
  const auto narrow = sr::GaussianSwell::create(2.0, 12.0, 0.1);
  const double wn = 2 * pi / 12.0;
  EXPECT_LT(rel((*narrow)(wn), 0.99735570100358164), 1e-14);
  EXPECT_LT(rel((*narrow)(0.5 * wn), 0.032400099865146707), 1e-14);
  EXPECT_LT(rel((*narrow)(1.5 * wn), 0.032400099865146707), 1e-14);
  const auto broad = sr::GaussianSwell::create(1.0, 8.0, 0.5);
  const double wb = 2 * pi / 8.0;
  EXPECT_LT(rel((*broad)(wb), 0.049867785050179085), 1e-14);
  EXPECT_LT(rel((*broad)(0.5 * wb), 0.03663302172500896), 1e-14);
}

TEST(SpectrumGaussian, ZeroAtAndBelowZeroFiniteEverywhereElse) {
  const auto s = sr::GaussianSwell::create(1.0, 8.0, 0.5);
  EXPECT_EQ((*s)(0.0), 0.0);
  EXPECT_EQ((*s)(-0.3), 0.0);
  EXPECT_EQ((*s)(kNaN), 0.0);
  // Just above 0 the cut Gaussian is still there: S(0⁺) = (Hs²/16) φ(ωp/σ)/σ > 0.
  const double wp = 2 * pi / 8.0;
  const double at_zero = 1.0 / 16 / (0.5 * std::sqrt(2 * pi)) * std::exp(-0.5 * wp * wp / 0.25);
  EXPECT_LT(rel((*s)(1e-300), at_zero), 1e-14);
  for (double w : {1e3, 1e100, 1e300}) EXPECT_EQ((*s)(w), 0.0) << w;  // exp underflows to 0
  EXPECT_EQ(s->tail_exponent(), kInf);
  EXPECT_EQ(s->low_frequency_exponent(), 0.0);
}

TEST(SpectrumGaussian, MomentsAreTheTruncatedGaussianClosedForms) {
  for (const auto& c : kCases) {
    const auto s = sr::GaussianSwell::create(c.hs, c.tp, c.sigma);
    for (int n : {0, 1, 2}) {
      // The library's Gauss–Kronrod is held to kMomentRelativeTolerance = 1e-9; the closed
      // forms here are good to a few ulps.
      EXPECT_LT(rel(sr::spectral_moment(*s, n), truncated_moment(c, n)), 1e-9)
          << "n = " << n << ", sigma = " << c.sigma;
      // The test's own tanh-sinh, split at ωp: 1e-13 per piece, 1e-11 with margin.
      const double wp = 2 * pi / c.tp;
      const double own = swell::test::integrate_pieces(
          [&](double w) { return std::pow(w, n) * (*s)(w); }, {0.0, wp});
      EXPECT_LT(rel(own, truncated_moment(c, n)), 1e-11) << "n = " << n << ", sigma = " << c.sigma;
    }
  }
  // The closed forms themselves against 30-digit mpmath quadrature of the three cases (the
  // quadrature and mpmath's closed forms agree to all 17 digits printed). erfc and exp: 1e-14.
  EXPECT_LT(rel(truncated_moment(kCases[0], 0), 0.24999997948689599), 1e-14);
  EXPECT_LT(rel(truncated_moment(kCases[0], 1), 0.13089969426692069), 1e-14);
  EXPECT_LT(rel(truncated_moment(kCases[0], 2), 0.071038919439220296), 1e-14);
  EXPECT_LT(rel(truncated_moment(kCases[1], 0), 0.56202741103035185), 1e-14);
  EXPECT_LT(rel(truncated_moment(kCases[1], 1), 0.35345501608577378), 1e-14);
  EXPECT_LT(rel(truncated_moment(kCases[1], 2), 0.2445634328231199), 1e-14);
  EXPECT_LT(rel(truncated_moment(kCases[2], 0), 0.058867813576036906), 1e-14);
  EXPECT_LT(rel(truncated_moment(kCases[2], 1), 0.049865208655179998), 1e-14);
  EXPECT_LT(rel(truncated_moment(kCases[2], 2), 0.05388099668921814), 1e-14);
}

TEST(SpectrumGaussian, EnergyBelowZeroIsCutOffNotRenormalized) {
  // m0 = (Hs²/16) Φ(ωp/σ): Φ from mpmath, 0.99999991794758398, 0.99915984183173662,
  // 0.9418850172165905 for the three cases; the cut-off share 1 − Φ is 8.2e-8, 8.4e-4, 5.8 %.
  const double phi[] = {0.99999991794758398, 0.99915984183173662, 0.9418850172165905};
  for (std::size_t i = 0; i < kCases.size(); ++i) {
    const auto& c = kCases[i];
    const auto s = sr::GaussianSwell::create(c.hs, c.tp, c.sigma);
    EXPECT_LT(rel(s->energy_fraction(), phi[i]), 1e-15) << i;  // erfc: ulps
    EXPECT_LT(rel(sr::sea_state(*s).hs, c.hs * std::sqrt(phi[i])), 1e-9) << i;
    EXPECT_LT(sr::spectral_moment(*s, 0), c.hs * c.hs / 16) << i;
  }
}

TEST(SpectrumGaussian, MinusFirstMomentDivergesTheOthersDoNot) {
  // S(0⁺) > 0, so ∫ S/ω dω diverges at 0 (logarithmically): m−1 and Te are +∞, by contract
  // (docs/conventions.md §6), not a quadrature that failed or a finite guess.
  const auto s = sr::GaussianSwell::create(3.0, 10.0, 0.2);
  EXPECT_EQ(sr::spectral_moment(*s, -1), kInf);
  const auto state = sr::sea_state(*s);
  EXPECT_EQ(state.te, kInf);
  EXPECT_TRUE(std::isfinite(state.moments.m4));  // a Gaussian tail: every m_n ≥ 0 is finite
  EXPECT_LT(state.epsilon4, 1.0);
  // A band above 0 has a finite m−1.
  EXPECT_TRUE(std::isfinite(sr::spectral_moment(*s, -1, {0.1, kInf})));
}

TEST(SpectrumGaussian, InvalidArgumentsNameTheParameter) {
  auto message = [](double hs, double tp, double sigma) {
    try {
      (void)sr::GaussianSwell::create(hs, tp, sigma);
    } catch (const swell::InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  EXPECT_NE(message(0.0, 10, 0.1).find("hs"), std::string::npos);
  EXPECT_NE(message(-1.0, 10, 0.1).find("hs"), std::string::npos);
  EXPECT_NE(message(1.0, 0.0, 0.1).find("tp"), std::string::npos);
  EXPECT_NE(message(1.0, kNaN, 0.1).find("tp"), std::string::npos);
  EXPECT_NE(message(1.0, 10, 0.0).find("sigma"), std::string::npos);
  EXPECT_NE(message(1.0, 10, -0.1).find("sigma"), std::string::npos);
  EXPECT_NE(message(1.0, 10, kInf).find("sigma"), std::string::npos);
}

TEST(ModelFactory, GaussianFromNamedParameters) {
  const auto s =
      sr::make_frequency_spectrum({"gaussian", {{"hs", 3.0}, {"tp", 10.0}, {"sigma", 0.2}}, {}});
  const auto direct = sr::GaussianSwell::create(3.0, 10.0, 0.2);
  EXPECT_EQ(s->name(), "gaussian");
  for (double w = 0.1; w < 2; w *= 1.1) EXPECT_EQ((*s)(w), (*direct)(w));
  try {
    (void)sr::make_frequency_spectrum({"gaussian", {{"hs", 3.0}, {"tp", 10.0}}, {}});
    ADD_FAILURE() << "a missing sigma must throw";
  } catch (const swell::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("sigma"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)sr::make_frequency_spectrum(
                   {"gaussian", {{"hs", 3.0}, {"tp", 10.0}, {"sigma", -1.0}}, {}}),
               swell::InvalidInput);
  EXPECT_THROW((void)sr::make_frequency_spectrum(
                   {"gaussian", {{"hs", 3.0}, {"tp", 10.0}, {"sigma", 0.2}, {"gamma", 2.0}}, {}}),
               swell::InvalidInput);
}
