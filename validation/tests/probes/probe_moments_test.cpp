// series.skewness and series.kurtosis (checks/probes/series_moments.hpp).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <numeric>

#include "checks/probes/series_moments.hpp"
#include "swell/impls/probe_synthesis.hpp"
#include "swell/reference/errors.hpp"

namespace {

namespace sr = swell::reference;
namespace sv = swell::validation;
using std::numbers::pi;

sr::ProbeCase jonswap(double gamma, double dt, std::size_t samples, double repeat_period, double omega_high,
                      sr::ProbeAmplitudes amplitudes = sr::ProbeAmplitudes::rayleigh,
                      sr::ProbeDirections directions = sr::ProbeDirections::long_crested, int n_directions = 1) {
  sr::ProbeCase c;
  c.sea.spectrum = {"jonswap", {{"hs", 3.0}, {"tp", 10.0}, {"gamma", gamma}}, {}};
  c.sea.spreading = {"cos2s", {{"s", 10.0}}, {}};
  c.sea.wind_dir_deg = 30;
  c.sea.depth = 30;
  c.layout.positions = {{0.0, 0.0}, {25.0, 0.0}, {0.0, 25.0}};
  c.layout.dt = dt;
  c.layout.samples = samples;
  c.synthesis.amplitudes = amplitudes;
  c.synthesis.frequencies = sr::ProbeFrequencies::uniform;
  c.synthesis.repeat_period = repeat_period;
  c.synthesis.omega_low = 0;
  c.synthesis.omega_high = omega_high;
  c.synthesis.directions = directions;
  c.synthesis.n_directions = n_directions;
  c.validate();
  return c;
}

struct Summary {
  double mean = 0, sd = 0, skew = 0, kurt = 0;
};
Summary summarize(const std::vector<double>& x) {
  Summary s;
  const double n = double(x.size());
  for (double v : x) s.mean += v;
  s.mean /= n;
  double m2 = 0, m3 = 0, m4 = 0;
  for (double v : x) {
    const double d = v - s.mean;
    m2 += d * d, m3 += d * d * d, m4 += d * d * d * d;
  }
  m2 /= n, m3 /= n, m4 /= n;
  s.sd = std::sqrt(m2 * n / (n - 1));
  s.skew = m3 / std::pow(m2, 1.5);
  s.kurt = m4 / (m2 * m2) - 3;
  return s;
}

// The one-point series of `c` at probe `probe` for `seed`, from swell's generator.
std::vector<double> generated(const sr::ProbeCase& c, std::uint64_t seed, std::size_t probe = 0) {
  return swell::impls::synthesize_probe_series(c, sr::probe_wave_lines(c, seed))[probe];
}

struct SeriesMoments {
  double g1 = 0, g2 = 0;
};
SeriesMoments moments_of(const std::vector<double>& x) {
  const auto s = summarize(x);
  return {s.skew, s.kurt};
}

// The lean null (one complex amplitude per frequency at one point) against the law of swell's
// own generator's series at a probe off the origin: 400 seeds against 2000 replicas. The mean of
// g2 and the sd of g1 and g2 must agree (double summation's phasors: ProbeMomentsCalibration) within 4 standard errors of their difference (the sd's
// standard error √((κ + 2)/(4n)) of its value, κ the law's excess kurtosis).
TEST(ProbeMoments, TheSimulatedNullIsTheGeneratorsLaw) {
  const sr::ProbeCase cases[] = {
      jonswap(3.3, 0.5, 1024, 512, 4),
      jonswap(3.3, 0.5, 1024, 512, 4, sr::ProbeAmplitudes::deterministic)};
  for (const auto& c : cases) {
    std::vector<double> g1, g2;
    for (int seed = 0; seed < 400; ++seed) {
      const auto m = moments_of(generated(c, std::uint64_t(5000 + seed), 1));
      g1.push_back(m.g1), g2.push_back(m.g2);
    }
    const auto null = sv::simulate_moment_null(c, 2000);
    const auto a1 = summarize(g1), a2 = summarize(g2), b1 = summarize(null.skewness), b2 = summarize(null.kurtosis);
    std::printf("[ measure  ] %s: generator g1 sd %.4f, g2 %.4f ± %.4f; null g1 sd %.4f, g2 %.4f ± %.4f\n",
                sr::to_string(c.synthesis.amplitudes), a1.sd, a2.mean, a2.sd, b1.sd, b2.mean, b2.sd);
    EXPECT_NEAR(a2.mean, b2.mean, 4 * b2.sd * std::sqrt(1.0 / 400 + 1.0 / 2000));
    const auto sd_se = [](const Summary& s, double n) { return s.sd * std::sqrt((s.kurt + 2) / (4 * n)); };
    EXPECT_NEAR(a1.sd, b1.sd, 4 * std::hypot(sd_se(b1, 400), sd_se(b1, 2000)));
    EXPECT_NEAR(a2.sd, b2.sd, 4 * std::hypot(sd_se(b2, 400), sd_se(b2, 2000)));
  }
}

// For Rayleigh amplitudes the series is a Gaussian process, and Lomnicki (1961) gives
// Var g1 ≈ (6/N) Σ_τ ρ(τ)³, Var g2 ≈ (24/N) Σ_τ ρ(τ)⁴ to O(1/N): over one repeat period
// (N = M) ρ is the circular autocorrelation Σ_i S_i Δω cos(2π q_i τ/M) / Σ_i S_i Δω, summed here
// by the test itself over the lines. 2000 replicas estimate an sd to √((κ + 2)/8000) ≈ 1.7 %
// and 12 000 samples hold ~600 peak periods (the O(1/N_eff) terms a few %): the simulated sd
// must be within 8 % of Lomnicki's. Kurtosis's spread is far above white noise's √(24/N) in a
// narrow and a broad sea alike (ρ⁴ ≥ 0 sums the oscillation's lobes); skewness's is not
// (ρ³ cancels between the lobes), and the test says so by measuring it.
TEST(ProbeMoments, TheSimulatedSpreadIsLomnickis) {
  for (const double gamma : {7.0, 1.0}) {
    const auto c = jonswap(gamma, 0.5, 12000, 6000, 3);
    const auto null = sv::simulate_moment_null(c, 2000);
    const auto spectrum = c.spectrum();
    const std::size_t m = c.layout.samples;
    std::vector<double> rho(m, 0.0);
    double total = 0;
    for (const auto& line : sr::probe_frequency_lines(c)) {
      const double variance = spectrum->omnidirectional()(line.omega) * line.band_width;
      const auto q = std::size_t(std::llround(line.omega / line.band_width));
      total += variance;
      for (std::size_t tau = 0; tau < m; ++tau) rho[tau] += variance * std::cos(2 * pi * double((q * tau) % m) / double(m));
    }
    double sum3 = 0, sum4 = 0;
    for (double r : rho) sum3 += std::pow(r / total, 3), sum4 += std::pow(r / total, 4);
    const double n = double(m);
    const double lomnicki1 = std::sqrt(6 / n * sum3), lomnicki2 = std::sqrt(24 / n * sum4);
    const auto g1 = summarize(null.skewness), g2 = summarize(null.kurtosis);
    std::printf("[ measure  ] γ = %g: sd g1 %.4f (Lomnicki %.4f, white %.4f), sd g2 %.4f (Lomnicki %.4f, white %.4f)\n",
                gamma, g1.sd, lomnicki1, std::sqrt(6 / n), g2.sd, lomnicki2, std::sqrt(24 / n));
    EXPECT_NEAR(g1.sd / lomnicki1, 1, 0.08);
    EXPECT_NEAR(g2.sd / lomnicki2, 1, 0.08);
    EXPECT_GT(g2.sd, 2 * std::sqrt(24 / n));
  }
}

}  // namespace
