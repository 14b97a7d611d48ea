// The JONSWAP fit (validation/jonswap_fit.hpp, docs/fit.md): its model against the reference
// spectra, recovery and the 1/√R shrinking of its standard errors, its Fisher covariance
// against the spread of estimates over seeds, and the coverage of its 95 % Wald intervals —
// on periodograms drawn directly as μ·Exp(1) (the exact law of a Gaussian surface's
// periodogram; fast) and on surfaces from the synthesizer (the calibration test).
#include "swell/validation/jonswap_fit.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "swell/impls/synthesizer.hpp"
#include "swell/reference/errors.hpp"
#include "swell/validation/periodogram.hpp"

namespace {

using swell::InvalidInput;
using swell::reference::Field;
using swell::reference::FrameSequence;
using swell::reference::Grid;
using swell::reference::OceanCase;
using swell::validation::Estimate;
using swell::validation::JonswapFit;
using swell::validation::JonswapFitOptions;

// JONSWAP Hs 3 m, Tp 8 s, γ 3.3, deep water, cos-2s s = 10 toward 30°. λp = g Tp²/2π = 99.9 m;
// the 800 m patch puts the peak at |k| = 8 Δk and the grid's axes reach k = 16 kp, ω = 4 ωp.
OceanCase coverage_case(int n = 256, double length = 800) {
  OceanCase c;
  c.grid = Grid::create(n, n, length, length);
  c.spectrum = {"jonswap", {{"hs", 3.0}, {"tp", 8.0}, {"gamma", 3.3}}, {}};
  c.spreading = {"cos2s", {{"s", 10.0}}, {}};
  c.wind_dir_deg = 30;
  return c;
}

// Exp(1) by inverting the CDF of a 53-bit uniform from mt19937_64, whose output is fixed by
// the standard (std::exponential_distribution's algorithm is not).
double exponential(std::mt19937_64& rng) {
  const double u = double(rng() >> 11) * 0x1p-53;  // [0, 1)
  return -std::log1p(-u);
}

// I(k) = μ(k) E(k) over the half plane, mirrored to −k: exactly the law of the periodogram of
// one Gaussian surface (independent exponentials over a half plane, I(−k) = I(k)).
std::vector<double> exponential_periodogram(const std::vector<double>& mu, const Grid& grid,
                                            std::mt19937_64& rng) {
  std::vector<double> periodogram(mu.size(), 0.0);
  for (int j = 0; j < grid.ny; ++j) {
    const int m = Grid::signed_index(j, grid.ny);
    for (int i = 0; i < grid.nx; ++i) {
      const int n = Grid::signed_index(i, grid.nx);
      if (!grid.carries_energy(n, m) || !swell::validation::in_half_plane(n, m)) continue;
      const std::size_t k = std::size_t(j) * grid.nx + i;
      const std::size_t minus =
          std::size_t((grid.ny - j) % grid.ny) * grid.nx + (grid.nx - i) % grid.nx;
      periodogram[k] = periodogram[minus] = mu[k] * exponential(rng);
    }
  }
  return periodogram;
}

std::vector<double> true_mu(const OceanCase& c) {
  return swell::validation::expected_periodogram(*c.directional_spectrum(), c.grid);
}

// Estimates of one parameter over many fits: bias, spread, mean Fisher variance and coverage.
struct Tally {
  std::string name;
  double truth = 0;
  int trials = 0, covered = 0;
  double sum = 0, sum2 = 0, fisher_variance = 0;

  void add(const Estimate& e) {
    ++trials;
    covered += e.ci95_low <= truth && truth <= e.ci95_high;
    sum += e.value;
    sum2 += e.value * e.value;
    fisher_variance += e.standard_error * e.standard_error;
  }
  double mean() const { return sum / trials; }
  double variance() const { return (sum2 - sum * sum / trials) / (trials - 1); }
  double spread() const { return std::sqrt(variance()); }
  double mean_se() const { return std::sqrt(fisher_variance / trials); }
  double coverage() const { return double(covered) / trials; }
  void print() const {
    std::printf(
        "  %-6s truth %-7.4g coverage %5.1f %% (%d/%d)  bias %+.4g (%+.2f se)  "
        "spread %.4g  Fisher se %.4g  spread/se %.3f\n",
        name.c_str(), truth, 100 * coverage(), covered, trials, mean() - truth,
        (mean() - truth) / mean_se(), spread(), mean_se(), spread() / mean_se());
  }
};

struct Tallies {
  Tally hs{"hs", 3.0}, tp{"tp", 8.0}, gamma{"gamma", 3.3};
  int converged = 0;
  void add(const JonswapFit& fit) {
    hs.add(fit.hs);
    tp.add(fit.tp);
    gamma.add(fit.gamma);
    converged += fit.converged;
  }
  void print(const char* title) const {
    std::printf("%s\n", title);
    for (const auto* t : {&hs, &tp, &gamma}) t->print();
  }
};

// The coverage criterion of the issue: 95 ± 4.5 %. With 200 trials and a true coverage of 95 %,
// the count of covering intervals is Binomial(200, 0.95); it falls outside [181, 199] (90.5 %
// to 99.5 %) with probability 0.27 % (P(X ≤ 180) = 0.26 %, P(X = 200) = 0.95²⁰⁰ = 0.004 %),
// so the test's false-alarm probability for one parameter is 0.27 % and for the three at most
// 0.81 % (union bound; 1 − 0.9973³ if they were independent). Measured over 6000 trials, the
// Tp intervals cover 94.4 ± 0.3 % (docs/fit.md §6), for which P(X ≤ 180) is 0.9 %.
void expect_calibrated(const Tally& t) {
  EXPECT_GE(t.coverage(), 0.905) << t.name << ": the 95 % intervals cover too rarely";
  EXPECT_LE(t.coverage(), 0.995) << t.name << ": the 95 % intervals cover too often";
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// ---------------------------------------------------------------- the model

// The fit's μ(k; θ) at the truth is the reference's ½ (Ψ(k) + Ψ(−k)) Δk²: the exact
// normalization, the spreading, the dispersion and the TMA factor all agree with reference/.
TEST(JonswapFitModel, MatchesTheReferenceExpectedPeriodogram) {
  std::vector<OceanCase> cases;
  cases.push_back(coverage_case(64, 400));
  auto tma = coverage_case(64, 400);
  tma.spectrum = {"tma", {{"hs", 2.0}, {"tp", 9.0}, {"gamma", 2.0}, {"sigma_a", 0.06}}, {}};
  tma.depth = 12;
  cases.push_back(tma);
  auto tv = tma;
  tv.spectrum.choices["depth_factor"] = "thompson-vincent";
  cases.push_back(tv);
  auto mitsuyasu = coverage_case(64, 400);
  mitsuyasu.spreading = {"mitsuyasu", {{"s_max", 25.0}}, {}};
  cases.push_back(mitsuyasu);
  auto bretschneider = coverage_case(64, 400);
  bretschneider.spectrum = {"bretschneider", {{"hs", 1.5}, {"tp", 7.0}}, {}};
  bretschneider.spreading = {"donelan-banner", {}, {}};
  cases.push_back(bretschneider);
  auto wind = coverage_case(64, 400);
  wind.spectrum = {"jonswap", {{"u10", 15.0}, {"fetch", 50e3}, {"gamma", 5.0}}, {}};
  cases.push_back(wind);
  auto dnv = coverage_case(64, 400);
  dnv.spectrum.choices["normalization"] = "dnv";
  cases.push_back(dnv);

  for (const auto& c : cases) {
    const auto truth = swell::validation::case_jonswap_parameters(c);
    const auto model = swell::validation::jonswap_model_periodogram(c, truth);
    const auto reference = true_mu(c);
    ASSERT_EQ(model.size(), reference.size());
    double largest = 0, worst = 0;
    for (double mu : reference) largest = std::max(largest, mu);
    for (std::size_t k = 0; k < model.size(); ++k) {
      if (reference[k] < 1e-12 * largest) continue;
      worst = std::max(worst, std::abs(model[k] - reference[k]) / reference[k]);
    }
    // The reference normalizes by a moment to 1e-9; the fit's F is exact to ~1e-12.
    EXPECT_LT(worst, 1e-8) << c.describe();
  }
}

TEST(JonswapFitModel, CaseParametersOfEachForm) {
  auto c = coverage_case(64, 400);
  auto p = swell::validation::case_jonswap_parameters(c);
  EXPECT_EQ(p.hs, 3.0);
  EXPECT_EQ(p.tp, 8.0);
  EXPECT_EQ(p.gamma, 3.3);
  EXPECT_EQ(p.sigma_a, 0.07);
  c.spectrum = {"bretschneider", {{"hs", 1.5}, {"tp", 7.0}}, {}};
  p = swell::validation::case_jonswap_parameters(c);
  EXPECT_EQ(p.gamma, 1.0);
  EXPECT_EQ(p.hs, 1.5);
  c.spectrum = {"jonswap", {{"alpha", 0.0081}, {"tp", 10.0}, {"gamma", 1.0}}, {}};
  p = swell::validation::case_jonswap_parameters(c);
  // α = 0.0081 with γ = 1 is Pierson–Moskowitz: Hs = 4 √(α g²/(4 · 1.25 ωp⁴)).
  const double omega_p = 2 * M_PI / 10.0;
  EXPECT_NEAR(p.hs, 4 * std::sqrt(0.0081 * 9.81 * 9.81 / (5 * std::pow(omega_p, 4))), 1e-8);
  c.spectrum = {"phillips", {{"amplitude", 1e-3}, {"wind_speed", 10.0}}, {}};
  c.spreading = {};
  EXPECT_THROW(swell::validation::case_jonswap_parameters(c), InvalidInput);
}

// ---------------------------------------------------------------- recovery

// 16 and 64 realizations at 256² recover Hs, Tp and γ within 4 standard errors, and the
// standard errors shrink as 1/√R: from 16 to 64 realizations by 2, up to the change of the
// estimates at which the Fisher information is evaluated (they scatter by 1/4 of a one-
// realization standard error; allow 6 %); on R copies of one periodogram, which have the same
// estimate (to the optimizer's tolerance, 1e-5 standard errors), by exactly √R.
TEST(JonswapFit, RecoversTheParametersAndErrorsShrinkAsOneOverRootR) {
  const auto c = coverage_case();
  const auto mu = true_mu(c);
  std::mt19937_64 rng(20240601);
  std::vector<std::vector<double>> periodograms;
  for (int r = 0; r < 64; ++r) periodograms.push_back(exponential_periodogram(mu, c.grid, rng));
  const auto start = std::chrono::steady_clock::now();
  const auto many = swell::validation::fit_jonswap_periodograms(
      c, {periodograms.begin(), periodograms.begin() + 16});
  std::printf("16 realizations: %d wave vectors each, %d iterations, %.3f s\n  %s\n",
              many.wave_vectors, many.iterations, seconds_since(start), many.report.c_str());
  const auto sixty_four = swell::validation::fit_jonswap_periodograms(c, periodograms);
  const auto one = swell::validation::fit_jonswap_periodograms(c, {periodograms.front()});
  const auto copies = swell::validation::fit_jonswap_periodograms(
      c, std::vector<std::vector<double>>(9, periodograms.front()));
  for (const auto* fit : {&many, &sixty_four, &one, &copies}) {
    EXPECT_TRUE(fit->converged) << fit->report;
    EXPECT_EQ(fit->wave_vectors, many.wave_vectors);
  }
  EXPECT_EQ(many.realizations, 16);
  EXPECT_EQ(copies.realizations, 9);
  EXPECT_FALSE(many.sigma_a.has_value());
  const double truth[] = {3.0, 8.0, 3.3};
  const char* names[] = {"hs", "tp", "gamma"};
  auto pick = [](const JonswapFit& f, int i) { return i == 0 ? f.hs : i == 1 ? f.tp : f.gamma; };
  for (int i = 0; i < 3; ++i) {
    const Estimate m = pick(many, i), r64 = pick(sixty_four, i), r1 = pick(one, i),
                   r9 = pick(copies, i);
    std::printf("  %-5s R=16: %.5g ± %.3g   R=64: %.5g ± %.3g   se(16)/se(64) %.3f\n", names[i],
                m.value, m.standard_error, r64.value, r64.standard_error,
                m.standard_error / r64.standard_error);
    EXPECT_NEAR(m.value, truth[i], 4 * m.standard_error) << names[i];
    EXPECT_NEAR(r64.value, truth[i], 4 * r64.standard_error) << names[i];
    EXPECT_NEAR(m.standard_error / r64.standard_error, 2.0, 2.0 * 0.06) << names[i];
    EXPECT_NEAR(r9.value, r1.value, 1e-4 * r1.standard_error) << names[i];
    EXPECT_NEAR(r1.standard_error / r9.standard_error, 3.0, 1e-4) << names[i];
    // The Wald interval: estimate ± 1.959964 se.
    EXPECT_NEAR(m.ci95_high - m.value, 1.959964 * m.standard_error, 1e-6 * m.standard_error);
    EXPECT_NEAR(m.value - m.ci95_low, 1.959964 * m.standard_error, 1e-6 * m.standard_error);
  }
}

// With σa and σb free as well (5 parameters), on 64 realizations.
TEST(JonswapFit, RecoversThePeakWidthsWhenAskedTo) {
  const auto c = coverage_case();
  const auto mu = true_mu(c);
  std::mt19937_64 rng(7);
  std::vector<std::vector<double>> periodograms;
  for (int r = 0; r < 64; ++r) periodograms.push_back(exponential_periodogram(mu, c.grid, rng));
  JonswapFitOptions options;
  options.fit_sigma = true;
  const auto fit = swell::validation::fit_jonswap_periodograms(c, periodograms, options);
  ASSERT_TRUE(fit.sigma_a.has_value());
  ASSERT_TRUE(fit.sigma_b.has_value());
  EXPECT_TRUE(fit.converged) << fit.report;
  const std::pair<Estimate, double> rows[] = {
      {fit.hs, 3.0}, {fit.tp, 8.0}, {fit.gamma, 3.3}, {*fit.sigma_a, 0.07}, {*fit.sigma_b, 0.09}};
  for (const auto& [e, truth] : rows) {
    std::printf("  %.5g ± %.3g (truth %g)\n", e.value, e.standard_error, truth);
    EXPECT_NEAR(e.value, truth, 4 * e.standard_error);
  }
}

// TMA in 12 m of water: the JONSWAP part's Hs (larger than the TMA spectrum's own) is what is
// estimated, with the case's depth factor held fixed.
TEST(JonswapFit, RecoversTheJonswapPartOfATmaSpectrum) {
  auto c = coverage_case();
  c.spectrum = {"tma", {{"hs", 2.0}, {"tp", 9.0}, {"gamma", 3.3}}, {}};
  c.depth = 12;
  const auto mu = true_mu(c);
  std::mt19937_64 rng(11);
  std::vector<std::vector<double>> periodograms;
  for (int r = 0; r < 8; ++r) periodograms.push_back(exponential_periodogram(mu, c.grid, rng));
  const auto fit = swell::validation::fit_jonswap_periodograms(c, periodograms);
  EXPECT_TRUE(fit.converged) << fit.report;
  EXPECT_NEAR(fit.hs.value, 2.0, 4 * fit.hs.standard_error);
  EXPECT_NEAR(fit.tp.value, 9.0, 4 * fit.tp.standard_error);
  EXPECT_NEAR(fit.gamma.value, 3.3, 4 * fit.gamma.standard_error);
}

// ---------------------------------------------------------------- calibration

// The Fisher covariance is the covariance of the estimates: over 300 seeds of one realization
// each, the empirical variance of each estimate matches the mean Fisher variance. The sample
// variance of n estimates scatters by √(2/(n−1)) = 8.2 % relative; allow 3.5 of those (29 %).
// The mean is within 3.5 standard errors of the mean (3.5 spread/√n) plus 0.1 of a standard
// error, the MLE's own bias being O(1/√(information)) of one (measured over 5000 seeds:
// Tp −0.11 se, Hs and γ below 0.05 se).
TEST(JonswapFit, FisherCovarianceMatchesTheSpreadOverSeeds) {
  const auto c = coverage_case();
  const auto mu = true_mu(c);
  std::mt19937_64 rng(99);
  Tallies t;
  constexpr int kSeeds = 300;
  const auto start = std::chrono::steady_clock::now();
  for (int s = 0; s < kSeeds; ++s) {
    t.add(
        swell::validation::fit_jonswap_periodograms(c, {exponential_periodogram(mu, c.grid, rng)}));
  }
  std::printf("%d fits in %.1f s\n", kSeeds, seconds_since(start));
  t.print(
      "Fisher variance against the spread over seeds (exponential periodograms, 256² over 800 m):");
  EXPECT_EQ(t.converged, kSeeds);
  for (const auto* x : {&t.hs, &t.tp, &t.gamma}) {
    EXPECT_NEAR(x->variance() / (x->mean_se() * x->mean_se()), 1.0,
                3.5 * std::sqrt(2.0 / (kSeeds - 1)))
        << x->name;
    EXPECT_NEAR(x->mean(), x->truth, 3.5 * x->spread() / std::sqrt(kSeeds) + 0.1 * x->mean_se())
        << x->name;
  }
}

// The fast version of the coverage test: the same case, periodograms drawn as μ·Exp(1).
TEST(JonswapFit, WaldIntervalsAreCalibratedOnExponentialPeriodograms) {
  const auto c = coverage_case();
  const auto mu = true_mu(c);
  std::mt19937_64 rng(2024);
  Tallies t;
  constexpr int kSeeds = 200;
  const auto start = std::chrono::steady_clock::now();
  for (int s = 0; s < kSeeds; ++s) {
    t.add(
        swell::validation::fit_jonswap_periodograms(c, {exponential_periodogram(mu, c.grid, rng)}));
  }
  std::printf("%d fits in %.1f s\n", kSeeds, seconds_since(start));
  t.print("95 % Wald intervals, exponential periodograms (256² over 800 m):");
  EXPECT_EQ(t.converged, kSeeds);
  for (const auto* x : {&t.hs, &t.tp, &t.gamma}) expect_calibrated(*x);
}

// The requirement: over 200 seeds, surfaces synthesized by the fftw backend in fp64,
// the 95 % intervals cover the true Hs, Tp and γ each in 95 ± 4.5 % of the trials (see
// expect_calibrated for the false-alarm probability).
TEST(JonswapFit, CoverageOfWaldIntervalsOnSynthesizedSurfaces) {
  auto c = coverage_case();
  swell::impls::SynthesizerOptions options;
  options.backend = "fftw";
  options.precision = swell::impls::Precision::f64;
  Tallies t;
  constexpr int kSeeds = 200;
  const auto start = std::chrono::steady_clock::now();
  for (int s = 0; s < kSeeds; ++s) {
    c.seed = 1000 + s;
    const swell::impls::Synthesizer synthesizer(c, options);
    t.add(swell::validation::fit_jonswap(c, {synthesizer.frames()}));
  }
  std::printf("%d syntheses and fits in %.1f s\n", kSeeds, seconds_since(start));
  t.print("95 % Wald intervals, synthesized surfaces (fftw, fp64, 256² over 800 m):");
  EXPECT_EQ(t.converged, kSeeds);
  for (const auto* x : {&t.hs, &t.tp, &t.gamma}) expect_calibrated(*x);
}

// ---------------------------------------------------------------- bad input

FrameSequence frames_of(const OceanCase& c) {
  swell::impls::SynthesizerOptions options;
  options.precision = swell::impls::Precision::f64;
  return swell::impls::Synthesizer(c, options).frames();
}

TEST(JonswapFitInput, PhillipsIsNotInTheFamily) {
  auto c = coverage_case(64, 400);
  const auto frames = frames_of(c);
  c.spectrum = {"phillips", {{"amplitude", 1e-3}, {"wind_speed", 10.0}}, {}};
  c.spreading = {};
  EXPECT_THROW(swell::validation::fit_jonswap(c, {frames}), InvalidInput);
  EXPECT_THROW(swell::validation::fit_jonswap_periodograms(c, {std::vector<double>(64 * 64, 1.0)}),
               InvalidInput);
}

TEST(JonswapFitInput, FramesWithoutHeight) {
  const auto c = coverage_case(64, 400);
  auto frames = frames_of(c);
  for (auto& frame : frames.frames) frame.fields.erase(Field::height);
  EXPECT_THROW(swell::validation::fit_jonswap(c, {frames}), InvalidInput);
}

TEST(JonswapFitInput, MismatchedGrids) {
  const auto c = coverage_case(64, 400);
  const auto frames = frames_of(c);
  auto other = frames_of(coverage_case(64, 500));  // same sizes, another patch
  EXPECT_THROW(swell::validation::fit_jonswap(c, {frames, other}), InvalidInput);
  EXPECT_THROW(swell::validation::fit_jonswap(c, {frames_of(coverage_case(32, 400))}),
               InvalidInput);
  EXPECT_THROW(swell::validation::fit_jonswap_periodograms(c, {std::vector<double>(32 * 32, 1.0)}),
               InvalidInput);
}

TEST(JonswapFitInput, NoRealizationsFlatFramesAndAMissingFrame) {
  const auto c = coverage_case(64, 400);
  EXPECT_THROW(swell::validation::fit_jonswap(c, {}), InvalidInput);
  auto frames = frames_of(c);
  JonswapFitOptions options;
  options.frame = 1;  // the case has one frame
  EXPECT_THROW(swell::validation::fit_jonswap(c, {frames}, options), InvalidInput);
  for (auto& value : frames.frames[0].fields[Field::height]) value = 0;
  EXPECT_THROW(swell::validation::fit_jonswap(c, {frames}), InvalidInput);
  std::vector<double> negative(64 * 64, 1.0);
  negative[5] = -1;
  EXPECT_THROW(swell::validation::fit_jonswap_periodograms(c, {negative}), InvalidInput);
}

// σa and σb of a sea without peak enhancement are not identifiable: a singular Fisher matrix is
// a numerical error, not an interval.
TEST(JonswapFitInput, UnidentifiablePeakWidthsAreANumericalError) {
  auto c = coverage_case(64, 400);
  c.spectrum = {"jonswap", {{"hs", 3.0}, {"tp", 8.0}, {"gamma", 1.0}}, {}};
  JonswapFitOptions options;
  options.fit_sigma = true;
  // Data exactly at their mean: the estimate is γ = 1 where ∂μ/∂σ = 0.
  EXPECT_THROW(swell::validation::fit_jonswap_periodograms(c, {true_mu(c)}, options),
               swell::NumericalError);
}

}  // namespace
