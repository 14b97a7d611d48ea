// Horvath's (2015) spreading: normalization over the circle by the test's own tanh-sinh, its
// limits (uniform at b = 1, Hasselmann's cos-2s at ξ = 0, b = 0), values computed once from
// the paper's formulas in 30-digit arithmetic (Python mpmath), the wave age from U10 under
// deep and finite-depth dispersion, and bad input.
#include <gtest/gtest.h>

#include <boost/math/quadrature/tanh_sinh.hpp>
#include <cmath>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "quadrature_support.hpp"
#include "test_support.hpp"
#include "swell/reference/dispersion.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/model_factory.hpp"
#include "swell/reference/spreading.hpp"

namespace {

using swell::test::kG;
using swell::test::kInf;
using swell::test::kNaN;
using swell::test::rel;

namespace sr = swell::reference;
using std::numbers::pi;

constexpr double kWp = 0.8;

using swell::test::circle_integral;

sr::SpreadingPtr horvath(double wave_age, double swell, double blend) {
  sr::Horvath::Parameters p;
  p.wave_age = wave_age;
  p.swell = swell;
  p.spread_blend = blend;
  return sr::Horvath::create(kWp, p);
}

}  // namespace

TEST(SpreadingHorvath, IntegratesToOneOverTheCircle) {
  for (double swell : {0.0, 0.3, 1.0, 2.0}) {
    for (double blend : {0.0, 0.25, 0.9}) {
      for (double age : {0.83, 1.17, 3.0}) {
        const auto d = horvath(age, swell, blend);
        for (double r : {0.05, 0.3, 0.8, 1.0, 1.001, 1.04, 1.3, 2.5, 8.0}) {
          const double w = r * kWp;
          const double total = circle_integral([&](double th) { return (*d)(w, th); });
          // Exact G(s) and the test's tanh-sinh at 1e-14 a piece: ~1e-13; s + s_ξ reaches 70
          // (ξ = 2, ω ≪ ωp), where cos^(2s)(θ/2) is a narrow lobe that tanh-sinh resolves.
          EXPECT_NEAR(total, 1.0, 1e-12)
              << "swell " << swell << ", blend " << blend << ", age " << age << ", w/wp " << r;
        }
      }
    }
  }
}

TEST(SpreadingHorvath, FullBlendIsTheUniformSpread) {
  const auto d = horvath(1.17, 1.5, 1.0);
  for (double r : {0.1, 1.0, 3.0}) {
    for (double th : {-3.0, -0.5, 0.0, 1.0, pi}) {
      EXPECT_EQ((*d)(r * kWp, th), 0.5 / pi) << r << " " << th;  // exactly, not approximately
    }
  }
}

TEST(SpreadingHorvath, WithoutSwellOrBlendIsHasselmannCos2sAtThePapersBranch) {
  // ξ = 0, b = 0: D = G(s) cos^(2s)(θ/2) with Hasselmann's s. Cos2s::hasselmann switches laws
  // at 1.05 ωp (Hasselmann et al. 1980), Horvath at ωp: outside (ωp, 1.05 ωp] the two are the
  // same computation (equal to the last bit); inside, Horvath takes the upper law, which
  // Cos2s::constant with s = 9.77 r^μ reproduces, and the two models differ.
  for (double age : {0.83, 1.17, 2.5}) {
    const auto d = horvath(age, 0.0, 0.0);
    const auto hasselmann = sr::Cos2s::hasselmann(kWp, age);
    const double mu = -2.33 - 1.45 * (age - 1.17);
    for (double r : {0.1, 0.5, 0.9, 1.0, 1.06, 1.5, 3.0}) {
      for (double th : {-2.5, -0.4, 0.0, 0.7, 3.0}) {
        EXPECT_EQ((*d)(r * kWp, th), (*hasselmann)(r * kWp, th)) << r << " " << th;
      }
    }
    for (double r : {1.001, 1.02, 1.049}) {
      const double s = 9.77 * std::pow(r, mu);
      const auto upper = sr::Cos2s::constant(s);
      EXPECT_LT(rel(static_cast<const sr::Horvath&>(*d).s(r * kWp), s), 1e-14);
      for (double th : {-1.0, 0.0, 0.3}) {
        // r·ωp/ωp may differ from r by an ulp, and s with it: 1e-14.
        EXPECT_LT(rel((*d)(r * kWp, th), (*upper)(r * kWp, th)), 1e-14) << r << " " << th;
        EXPECT_NE((*d)(r * kWp, th), (*hasselmann)(r * kWp, th)) << r << " " << th;
      }
    }
  }
  // At ωp itself the paper takes the lower law: s = 6.97.
  EXPECT_EQ(static_cast<const sr::Horvath&>(*horvath(1.17, 0, 0)).s(kWp), 6.97);
}

TEST(SpreadingHorvath, ValuesFromThePapersFormulas) {
  // D(ω, θ) for ωp = 0.8 rad/s, in 30-digit mpmath from Horvath's formulas (s, s_ξ, the exact
  // G(s) = 2^(2s−1) Γ(s+1)² / (π Γ(2s+1)), the blend), with ω, θ and ωp the same doubles as
  // here. The library's G(s) goes through lgamma and exp of a sum up to ~300: 1e-13.
  struct Case {
    double omega, theta, wave_age, swell, blend, d;
  };
  const Case cases[] = {
      {0.5, 0.3, 1.17, 0.0, 0.0, 0.31501783792984065},     // below ωp, s = 1.034
      {0.8, -1.0, 1.17, 0.5, 0.0, 0.066080017354092106},   // at ωp: s = 6.97, s_ξ = 3.05
      {0.82, 0.7, 2.0, 0.0, 0.0, 0.27928966861672576},     // upper law within 1.05 ωp
      {1.6, 0.4, 0.9, 1.2, 0.3, 0.47338835027229985},      // swell and blend together
      {4.0, pi, 1.17, 0.8, 0.25, 0.039788735772973834},    // against the wind: b/(2π) only
      {0.2, -0.15, 1.17, 2.0, 0.6, 0.72628144454919155},   // s_ξ = 64: a narrow lobe
      {1.2, 0.05, 3.0, 0.3, 0.1, 0.4084822525240131},      // young sea (U10/cp = 3)
      {2.4, -2.2, 1.17, 0.0, 0.0, 0.086857063600661377},   // far above the peak, s = 0.755
  };
  for (const auto& c : cases) {
    const auto d = horvath(c.wave_age, c.swell, c.blend);
    EXPECT_LT(rel((*d)(c.omega, c.theta), c.d), 1e-13)
        << "w = " << c.omega << ", theta = " << c.theta << ", swell = " << c.swell
        << ", blend = " << c.blend;
  }
}

TEST(SpreadingHorvath, ExponentLaws) {
  sr::Horvath::Parameters p;
  p.wave_age = 1.9;
  p.swell = 0.7;
  const auto d = sr::Horvath::create(kWp, p);
  const double mu = -2.33 - 1.45 * (1.9 - 1.17);
  for (double r : {0.0, 0.2, 0.7, 1.0, 1.3, 4.0}) {
    const double w = r * kWp;
    const double s = r <= 1 ? 6.97 * std::pow(r, 4.06) : 9.77 * std::pow(r, mu);
    EXPECT_LT(rel(d->s(w), s), 1e-15) << r;  // one pow: ulps
    const double swell = r == 0 ? 16 * 0.49 : 16 * std::tanh(1 / r) * 0.49;
    EXPECT_LT(rel(d->swell_exponent(w), swell), 1e-15) << r;
  }
  // The swell term vanishes toward short waves (tanh(ωp/ω) → 0) and saturates at 16 ξ² for
  // long ones: it elongates the long crests only.
  EXPECT_LT(d->swell_exponent(100 * kWp), 16 * 0.49 * 0.0101);
  EXPECT_NEAR(d->swell_exponent(0.01 * kWp), 16 * 0.49, 1e-12);
}

TEST(SpreadingHorvath, WaveAgeFromTheWindUnderTheCasesDispersion) {
  // Deep water: cp = g/ωp, so U10/cp = U10 ωp/g (the paper's form).
  const double u10 = 14.0;
  EXPECT_LT(rel(sr::Horvath::wave_age(u10, kWp, sr::Dispersion::deep()), u10 * kWp / kG), 1e-15);
  // Finite depth: cp = ωp/kp with kp from ω² = g k tanh(kh), here by bisection (independent
  // of the library's Newton iteration, which is held to 1e-12).
  for (double h : {5.0, 20.0, 100.0}) {
    double lo = 0, hi = 10.0;
    for (int i = 0; i < 200; ++i) {
      const double mid = 0.5 * (lo + hi);
      (kG * mid * std::tanh(mid * h) < kWp * kWp ? lo : hi) = mid;
    }
    const double kp = 0.5 * (lo + hi);
    EXPECT_LT(rel(sr::Horvath::wave_age(u10, kWp, sr::Dispersion::finite_depth(h)), u10 * kp / kWp),
              1e-11)
        << "h = " << h;
    // Shallower water, slower waves: a larger wave age for the same wind.
    EXPECT_GT(sr::Horvath::wave_age(u10, kWp, sr::Dispersion::finite_depth(h)), u10 * kWp / kG);
  }
  EXPECT_THROW((void)sr::Horvath::wave_age(0.0, kWp, sr::Dispersion::deep()), swell::InvalidInput);
  EXPECT_THROW((void)sr::Horvath::wave_age(10.0, -1.0, sr::Dispersion::deep()),
               swell::InvalidInput);
}

TEST(SpreadingHorvath, InvalidArgumentsNameTheParameter) {
  auto message = [](double omega_p, double age, double swell, double blend) {
    sr::Horvath::Parameters p;
    p.wave_age = age;
    p.swell = swell;
    p.spread_blend = blend;
    try {
      (void)sr::Horvath::create(omega_p, p);
    } catch (const swell::InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  EXPECT_NE(message(0.0, 1.17, 0, 0).find("omega_p"), std::string::npos);
  EXPECT_NE(message(kWp, 0.0, 0, 0).find("wave_age"), std::string::npos);
  EXPECT_NE(message(kWp, 1.17, -0.1, 0).find("swell"), std::string::npos);
  EXPECT_NE(message(kWp, 1.17, kNaN, 0).find("swell"), std::string::npos);
  EXPECT_NE(message(kWp, 1.17, 0, -0.01).find("spread_blend"), std::string::npos);
  EXPECT_NE(message(kWp, 1.17, 0, 1.01).find("spread_blend"), std::string::npos);
  EXPECT_NE(message(kWp, 1.17, 0, kNaN).find("spread_blend"), std::string::npos);
  EXPECT_NO_THROW((void)horvath(1.17, 0, 1));
}

TEST(ModelFactory, HorvathFromNamedParameters) {
  const auto d = sr::make_spreading(
      {"horvath", {{"wave_age", 1.5}, {"swell", 0.6}, {"spread_blend", 0.2}}, {}}, kWp);
  const auto direct = horvath(1.5, 0.6, 0.2);
  EXPECT_EQ(d->name(), "horvath");
  for (double w : {0.3, 0.8, 2.0}) {
    for (double th : {-2.0, 0.0, 0.9}) EXPECT_EQ((*d)(w, th), (*direct)(w, th));
  }
  // Defaults: wave age 1.17, no swell, no blend.
  const auto plain = sr::make_spreading({"horvath", {}, {}}, kWp);
  EXPECT_EQ((*plain)(0.5, 0.3), (*horvath(1.17, 0, 0))(0.5, 0.3));
  try {
    (void)sr::make_spreading({"horvath", {{"spread_blend", 2.0}}, {}}, kWp);
    ADD_FAILURE() << "spread_blend = 2 must throw";
  } catch (const swell::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("spread_blend"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)sr::make_spreading({"horvath", {{"swell", -1.0}}, {}}, kWp),
               swell::InvalidInput);
  EXPECT_THROW((void)sr::make_spreading({"horvath", {{"s", 3.0}}, {}}, kWp), swell::InvalidInput);
}
