// Probe seas (reference/probe_sea.hpp, impls/probe_synthesis.hpp): each scheme's lines against
// what it promises — the periodogram over one repeat period equal to S Δω (deterministic
// amplitudes), E a² = 2 S Δω (Rayleigh), equal shares of the band's m0 at its energy quantiles,
// direction sectors whose first circular moment is the spreading's s/(s + 1) — checked by the
// test's own DFT and quadrature; and the fast series against the direct sum.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <numeric>

#include "quadrature_support.hpp"
#include "swell/impls/probe_synthesis.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/moments.hpp"
#include "swell/reference/probe_sea.hpp"

namespace {

namespace sr = swell::reference;
using std::numbers::pi;

// JONSWAP Hs 3 m, Tp 10 s, γ 3.3 in 30 m of water, cos-2s s = 10 toward 30°: the sea of the
// issue's OpenFAST run, sampled every 0.25 s at three probes.
sr::ProbeCase jonswap_case() {
  sr::ProbeCase c;
  c.sea.spectrum = {"jonswap", {{"hs", 3.0}, {"tp", 10.0}, {"gamma", 3.3}}, {}};
  c.sea.spreading = {"cos2s", {{"s", 10.0}}, {}};
  c.sea.wind_dir_deg = 30;
  c.sea.depth = 30;
  c.layout.positions = {{0.0, 0.0}, {10.0, 0.0}, {0.0, 10.0}};
  c.layout.t0 = 0;
  c.layout.dt = 0.25;
  c.layout.samples = 4096;
  c.synthesis.amplitudes = sr::ProbeAmplitudes::deterministic;
  c.synthesis.frequencies = sr::ProbeFrequencies::uniform;
  c.synthesis.repeat_period = 1024;  // 4096 samples: one repeat period
  c.synthesis.omega_low = 0;
  c.synthesis.omega_high = 6;
  c.synthesis.directions = sr::ProbeDirections::long_crested;
  return c;
}

// X_q = (1/N) Σ η_n e^(+2πi q n/N) at one bin, by the test's own sum.
std::complex<double> dft_bin(const std::vector<double>& series, std::size_t q) {
  std::complex<long double> sum = 0;
  const std::size_t n = series.size();
  for (std::size_t i = 0; i < n; ++i) {
    const long double angle = 2 * std::numbers::pi_v<long double> * (long double)((q * i) % n) / n;
    sum += std::complex<long double>(series[i] * std::cos(angle), series[i] * std::sin(angle));
  }
  return {double(sum.real() / n), double(sum.imag() / n)};
}

TEST(ProbeSea, DeterministicUniformLinesGiveThePeriodogramSOverOneRepeatPeriod) {
  const auto c = jonswap_case();
  c.validate();
  const auto lines = sr::probe_wave_lines(c, 7);
  const auto spectrum = c.sea.sea_spectrum();
  const auto series = sr::probe_series_direct(lines, 10.0, 0.0, c.layout);
  // A long-crested line i contributes a cos(…) to bin q_i = i: 2|X_q|² = a²/2 = S(ω_q) Δω.
  const double step = 2 * pi / c.synthesis.repeat_period;
  double worst = 0;
  for (std::size_t q : {64, 80, 100, 150, 200, 500, 900}) {
    const double expected = spectrum->omnidirectional()(q * step) * step;
    const double measured = 2 * std::norm(dft_bin(series, q));
    worst = std::max(worst, std::abs(measured / expected - 1));
  }
  EXPECT_LT(worst, 1e-9);
  // Every line carries S Δω and the band's lines, summed, m0 over the band to the rectangle
  // rule's error (Δω = 0.006 rad/s against a peak of width ~0.05 rad/s).
  double energy = 0;
  for (const auto& line : lines) energy += line.amplitude * line.amplitude / 2;
  const double m0 = sr::spectral_moment(spectrum->omnidirectional(), 0, sr::Band{0, 6});
  EXPECT_NEAR(energy, m0, 1e-6 * m0);
}

TEST(ProbeSea, RayleighAmplitudesHaveMeanSquareTwoSDeltaOmega) {
  auto c = jonswap_case();
  c.synthesis.amplitudes = sr::ProbeAmplitudes::rayleigh;
  c.synthesis.repeat_period = 10800;
  const auto lines = sr::probe_wave_lines(c, 11);
  const auto spectrum = c.sea.sea_spectrum();
  // u = a²/(2 S Δω) ~ Exp(1) independent: mean 1 ± 1/√n; over n = 10313 lines 4σ is 0.039 (a
  // fixed seed, so this either always holds or never; 4σ: the CLT's 6e-5 two-sided).
  double sum = 0, squares = 0;
  int n = 0;
  for (const auto& line : lines) {
    const double s = spectrum->omnidirectional()(line.omega) * line.band_width;
    if (!(s > 1e-12)) continue;
    const double u = line.amplitude * line.amplitude / (2 * s);
    sum += u, squares += u * u, ++n;
  }
  ASSERT_GT(n, 5000);
  EXPECT_LT(std::abs(sum / n - 1), 4 / std::sqrt(double(n)));
  // Exp(1) has E u² = 2: a half-normal or uniform law would not.
  EXPECT_LT(std::abs(squares / n - 2), 4 * std::sqrt(20.0 / n));
}

TEST(ProbeSea, EqualEnergyLinesShareTheBandsM0AtItsQuantiles) {
  auto c = jonswap_case();
  c.synthesis.frequencies = sr::ProbeFrequencies::equal_energy;
  c.synthesis.repeat_period = 0;
  c.synthesis.n_frequencies = 50;
  c.synthesis.omega_low = 0.3;
  c.synthesis.omega_high = 3;
  c.validate();
  const auto lines = sr::probe_wave_lines(c, 3);
  ASSERT_EQ(lines.size(), 50u);
  const auto sea = c.sea.sea_spectrum();
  const auto& s = sea->omnidirectional();
  const double m0 = sr::spectral_moment(s, 0, sr::Band{0.3, 3});
  for (std::size_t i = 0; i < lines.size(); ++i) {
    EXPECT_NEAR(lines[i].amplitude * lines[i].amplitude / 2, m0 / 50, 1e-6 * m0 / 50);
    // Line i sits where the test's own quadrature of S reaches (i + ½)/50 of the band's m0.
    const double below = swell::test::integrate([&](double w) { return s(w); }, 0.3, lines[i].omega, 1e-12);
    EXPECT_NEAR(below / m0, (i + 0.5) / 50, 2e-6) << "line " << i;
  }
}

TEST(ProbeSea, DirectionSectorsCarryTheSpreadingsFirstCircularMoment) {
  auto c = jonswap_case();
  c.synthesis.directions = sr::ProbeDirections::double_summation;
  c.synthesis.n_directions = 360;
  c.synthesis.repeat_period = 256;
  c.synthesis.omega_low = 0.5;
  c.synthesis.omega_high = 0.6;
  c.validate();
  const auto lines = sr::probe_wave_lines(c, 5);
  // cos-2s: E cos(θ − θw) = s/(s + 1) = 10/11, E sin(θ − θw) = 0. Medians of 360 equal-probability
  // sectors reproduce it to the 0.1° cells' and the midpoint rule's error.
  for (int frequency = 0; frequency < int(lines.size() / 360); ++frequency) {
    std::complex<double> resultant = 0;
    for (int j = 0; j < 360; ++j) {
      const auto& line = lines[std::size_t(frequency * 360 + j)];
      ASSERT_EQ(line.frequency, frequency);
      resultant += std::polar(1.0, line.theta - 30 * pi / 180) / 360.0;
    }
    EXPECT_NEAR(resultant.real(), 10.0 / 11, 2e-4);
    EXPECT_NEAR(resultant.imag(), 0, 1e-6);
    // sector_directions gives the gate the same directions, bit for bit.
    const auto sectors = sr::sector_directions(*c.spectrum(), lines[std::size_t(frequency * 360)].omega, 360);
    for (int j = 0; j < 360; ++j) ASSERT_EQ(sectors[std::size_t(j)], lines[std::size_t(frequency * 360 + j)].theta);
  }
}

TEST(ProbeSea, TheFastSeriesIsTheDirectSum) {
  for (auto frequencies : {sr::ProbeFrequencies::uniform, sr::ProbeFrequencies::random}) {
    auto c = jonswap_case();
    c.synthesis.amplitudes = sr::ProbeAmplitudes::rayleigh;
    c.synthesis.directions = sr::ProbeDirections::double_summation;
    c.synthesis.n_directions = 5;
    c.synthesis.frequencies = frequencies;
    c.synthesis.repeat_period = frequencies == sr::ProbeFrequencies::uniform ? 256 : 0;
    c.synthesis.n_frequencies = 300;
    c.layout.t0 = 1234.5;
    c.layout.samples = 2500;  // beyond one repeat period (1024 samples) for the uniform lines
    c.validate();
    EXPECT_EQ(swell::impls::probe_series_is_periodic(c), frequencies == sr::ProbeFrequencies::uniform);
    const auto lines = sr::probe_wave_lines(c, 9);
    const auto fast = swell::impls::synthesize_probe_series(c, lines, 2);
    ASSERT_EQ(fast.size(), 3u);
    for (std::size_t p = 0; p < 3; ++p) {
      const auto direct = sr::probe_series_direct(lines, c.layout.positions[p][0], c.layout.positions[p][1], c.layout);
      double error = 0, norm = 0;
      for (std::size_t n = 0; n < direct.size(); ++n) {
        error = std::max(error, std::abs(fast[p][n] - direct[n]));
        norm += direct[n] * direct[n];
      }
      EXPECT_LT(error, 1e-11 * std::sqrt(norm / double(direct.size()))) << sr::to_string(frequencies) << " probe " << p;
    }
  }
}

TEST(ProbeSea, BadSchemesAreRefusedNamingTheKey) {
  auto refusal = [](const sr::ProbeCase& c) {
    try {
      c.validate();
    } catch (const swell::InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  auto c = jonswap_case();
  c.synthesis.omega_high = 20;  // π/0.25 = 12.6 rad/s
  EXPECT_NE(refusal(c).find("Nyquist"), std::string::npos) << refusal(c);
  c = jonswap_case();
  c.synthesis.repeat_period = 0;
  EXPECT_NE(refusal(c).find("repeat_period"), std::string::npos) << refusal(c);
  c = jonswap_case();
  c.synthesis.n_directions = 4;
  EXPECT_NE(refusal(c).find("n_directions"), std::string::npos) << refusal(c);
  c = jonswap_case();
  c.layout.positions.push_back({NAN, 0.0});
  EXPECT_NE(refusal(c).find("probe 3"), std::string::npos) << refusal(c);
  c = jonswap_case();
  c.synthesis.frequencies = sr::ProbeFrequencies::random;
  c.synthesis.n_frequencies = 0;
  c.synthesis.repeat_period = 0;
  EXPECT_NE(refusal(c).find("n_frequencies"), std::string::npos) << refusal(c);
  EXPECT_THROW(sr::probe_amplitudes_from_string("gaussian"), swell::InvalidInput);
}

}  // namespace
