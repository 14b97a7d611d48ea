// Composite seas (docs/case_files.md §Composite seas): the sea's Ψ is the sum of its components'
// Ψ, its moments the sums of theirs, against closed forms (Bretschneider's moments); the energy
// factor scales Ψ and every moment; the short-wave fade's omnidirectional spectrum is what the
// faded Ψ integrates to, by the test's own quadrature over the wave-number plane.
#include <gtest/gtest.h>

#include <boost/math/quadrature/exp_sinh.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>
#include <boost/math/special_functions/gamma.hpp>
#include <cmath>
#include <functional>
#include <numbers>

#include "test_support.hpp"
#include "swell/reference/composite_spectrum.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/moments.hpp"
#include "swell/reference/ocean_case.hpp"

namespace {

namespace sr = swell::reference;
using std::numbers::pi;
using swell::test::kG;
using swell::test::rel;

// Bretschneider's moments in closed form: m_n = (Hs²/16) ωp^n (5/4)^(n/4) Γ(1 − n/4), n < 4.
double pm_moment(double hs, double tp, int n) {
  const double wp = 2 * pi / tp;
  return hs * hs / 16 * std::pow(wp, n) * std::pow(1.25, n / 4.0) * boost::math::tgamma(1 - n / 4.0);
}

sr::SeaComponent bretschneider(double hs, double tp, double s, double toward_deg) {
  sr::SeaComponent c;
  c.spectrum = {"bretschneider", {{"hs", hs}, {"tp", tp}}, {}};
  c.spreading = {"cos2s", {{"s", s}}, {}};
  c.wind_dir_deg = toward_deg;
  return c;
}

// Wind sea (Hs 2.5 m, Tp 7 s, s = 10, toward 30°) and swell (Hs 1.5 m, Tp 14 s, s = 40, toward 75°).
sr::OceanCase wind_sea_and_swell() {
  sr::OceanCase c;
  c.grid = sr::Grid::create(64, 64, 200, 200);
  c.set_components({bretschneider(2.5, 7, 10, 30), bretschneider(1.5, 14, 40, 75)});
  return c;
}

// ∫∫ Ψ dk over the plane in polar coordinates (deep water), by tanh-sinh in θ (split at every
// quarter turn) and exp-sinh in k from k(ω_lo), below which the spectra here carry < e⁻³⁰⁰.
double plane_integral(const sr::DirectionalSpectrum& psi, double omega_lo) {
  static boost::math::quadrature::tanh_sinh<double> angular;
  static boost::math::quadrature::exp_sinh<double> radial;
  auto ring = [&](double k) {
    auto f = [&](double th) { return psi.psi(k * std::cos(th), k * std::sin(th)); };
    double sum = 0, error = 0, l1 = 0;
    for (int q = 0; q < 4; ++q) sum += angular.integrate(f, q * pi / 2 - pi, (q + 1) * pi / 2 - pi, 1e-12, &error, &l1);
    return k * sum;
  };
  double error = 0, l1 = 0;
  return radial.integrate(ring, omega_lo * omega_lo / kG, std::numeric_limits<double>::infinity(),
                          1e-10, &error, &l1);
}

}  // namespace

TEST(CompositeSea, PsiIsTheSumOfTheComponentsPsi) {
  const auto sea = wind_sea_and_swell();
  const auto psi = sea.sea_spectrum();
  const auto parts = sea.components();
  const auto wind = sea.component_spectrum(parts[0]), swell = sea.component_spectrum(parts[1]);
  for (double k : {0.01, 0.03, 0.08, 0.2, 0.5}) {
    for (double th = -pi; th < pi; th += pi / 7) {
      const double kx = k * std::cos(th), ky = k * std::sin(th);
      // A sum of two doubles: exact to its rounding.
      EXPECT_DOUBLE_EQ(psi->psi(kx, ky), wind->psi(kx, ky) + swell->psi(kx, ky)) << k << " " << th;
    }
  }
}

TEST(CompositeSea, MomentsAreTheSumsOfTheComponentsClosedForms) {
  const auto psi = wind_sea_and_swell().sea_spectrum();
  for (int n : {-1, 0, 1, 2}) {
    const double expected = pm_moment(2.5, 7, n) + pm_moment(1.5, 14, n);
    // The library's moments promise kMomentRelativeTolerance = 1e-9.
    EXPECT_LT(rel(sr::spectral_moment(psi->omnidirectional(), n), expected), 2e-9) << "n = " << n;
  }
  // Hs of the sea: 4 √(Σ Hs_i²/16) = √(2.5² + 1.5²).
  const auto state = sr::sea_state(psi->omnidirectional());
  EXPECT_LT(rel(state.hs, std::hypot(2.5, 1.5)), 1e-9);
  // The peak of the sum, against the test's own scan of Bretschneider's closed form
  // S(ω) = (5/16) Hs² ωp⁴ ω⁻⁵ e^(−(5/4)(ωp/ω)⁴) summed over both seas, every 1e-6 rad/s: the
  // wind sea's (its S(ωp) = (5/16) e^(−5/4) Hs²/ωp is 0.62 m²s against the swell's 0.45), moved
  // 1.8 % by the swell's tail under it.
  auto pm = [](double hs, double tp, double w) {
    const double wp = 2 * pi / tp;
    return 5.0 / 16 * hs * hs * std::pow(wp, 4) * std::pow(w, -5) * std::exp(-1.25 * std::pow(wp / w, 4));
  };
  double best = 0, best_s = 0;
  for (double w = 0.5; w < 1.5; w += 1e-6) {
    const double s = pm(2.5, 7, w) + pm(1.5, 14, w);
    if (s > best_s) best_s = s, best = w;
  }
  EXPECT_NEAR(state.omega_p, best, 2e-6);
  EXPECT_GT(rel(best, 2 * pi / 7), 0.01);  // the shift is real: not the wind sea's own peak
  // ∫∫ Ψ dk = m0 by the test's own quadrature over the plane.
  EXPECT_LT(rel(plane_integral(*psi, 0.1), pm_moment(2.5, 7, 0) + pm_moment(1.5, 14, 0)), 1e-7);
}

TEST(CompositeSea, EnergyFactorMultipliesPsiAndEveryMoment) {
  auto sea = wind_sea_and_swell();
  const auto plain = sea.sea_spectrum();
  auto parts = sea.components();
  for (auto& p : parts) p.energy_factor = 8;
  sea.set_components(parts);
  const auto scaled = sea.sea_spectrum();
  for (double k : {0.02, 0.1, 0.4}) {
    EXPECT_LT(rel(scaled->psi(k, 0.3 * k), 8 * plain->psi(k, 0.3 * k)), 1e-15);
  }
  for (int n : {0, 1, 2}) {
    EXPECT_LT(rel(sr::spectral_moment(scaled->omnidirectional(), n),
                  8 * (pm_moment(2.5, 7, n) + pm_moment(1.5, 14, n))), 2e-9);
  }
}

TEST(CompositeSea, ShortWaveFadeIsWhatTheFadedPsiIntegratesTo) {
  for (double l : {0.0, 0.2, 1.0, 3.0}) {
    sr::OceanCase c;
    c.grid = sr::Grid::create(64, 64, 200, 200);
    auto part = bretschneider(2.5, 7, 10, 30);
    part.short_wave_fade = l;
    c.set_components({part});
    const auto psi = c.sea_spectrum();
    // Ψ e^(−k²l²) at every k.
    const auto bare = c.component_spectrum(bretschneider(2.5, 7, 10, 30));
    for (double k : {0.05, 0.3, 1.0}) {
      EXPECT_LT(rel(psi->psi(k, 0), bare->psi(k, 0) * std::exp(-k * k * l * l)), 1e-14);
    }
    // The omnidirectional S'(ω) = S(ω) e^(−k(ω)²l²) carries what the faded Ψ carries.
    const double m0 = sr::spectral_moment(psi->omnidirectional(), 0);
    EXPECT_LT(rel(plane_integral(*psi, 0.2), m0), 1e-7) << "l = " << l;
    if (l == 0) {
      EXPECT_LT(rel(m0, pm_moment(2.5, 7, 0)), 1e-9);
    } else {
      EXPECT_LT(m0, pm_moment(2.5, 7, 0));
    }
  }
}

TEST(CompositeSea, BadFactorsAreRefusedByName) {
  sr::OceanCase c;
  c.grid = sr::Grid::create(16, 16, 100, 100);
  auto part = bretschneider(2, 8, 10, 0);
  part.energy_factor = 0;
  c.set_components({part, bretschneider(1, 12, 20, 0)});
  try {
    c.validate();
    FAIL() << "energy_factor 0 accepted";
  } catch (const swell::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("energy_factor"), std::string::npos) << e.what();
  }
  part.energy_factor = 1;
  part.short_wave_fade = -1;
  c.set_components({bretschneider(1, 12, 20, 0), part});
  EXPECT_THROW(c.validate(), swell::InvalidInput);
}
