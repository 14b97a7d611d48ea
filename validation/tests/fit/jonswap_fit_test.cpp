// The JONSWAP fit (validation/jonswap_fit.hpp, docs/fit.md): its model against the reference
// spectra, recovery and the 1/√R shrinking of its standard errors, its Fisher covariance
// against the spread of estimates over seeds, its profile-likelihood intervals against a brute-
// force profile, the optimizer kept inside the valid region, and (label calibration) the
// coverage of its 95 % intervals over grids of 1 to 20 peak wavelengths — on periodograms drawn
// directly as μ·Exp(1) (the exact law of a Gaussian surface's periodogram; fast) and on
// surfaces from the synthesizer.
#include "swell/validation/fit/jonswap_fit.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <utility>
#include <random>
#include <string>
#include <vector>

#include "swell/impls/synthesizer.hpp"
#include "swell/reference/errors.hpp"
#include "swell/validation/stats/periodogram.hpp"

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
  JonswapFitOptions wald_options;
  wald_options.interval = swell::validation::IntervalMethod::wald;
  const auto wald16 = swell::validation::fit_jonswap_periodograms(
      c, {periodograms.begin(), periodograms.begin() + 16}, wald_options);
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
    // The default interval is the profile-likelihood one, calibrated on this resolved grid (8
    // peak wavelengths); with 16 realizations the likelihood is close to quadratic, so its ends
    // lie within 0.1 se of the Wald ends (measured: 0.03–0.08 se outward).
    EXPECT_EQ(m.method, "profile-likelihood");
    EXPECT_TRUE(m.calibrated) << m.reason;
    EXPECT_LT(m.ci95_low, m.value);
    EXPECT_GT(m.ci95_high, m.value);
    EXPECT_NEAR(m.ci95_high - m.value, 1.959964 * m.standard_error, 0.1 * m.standard_error);
    EXPECT_NEAR(m.value - m.ci95_low, 1.959964 * m.standard_error, 0.1 * m.standard_error);
    std::printf("        profile ends − Wald ends: %+.4f se, %+.4f se\n",
                (m.ci95_low - (m.value - 1.959964 * m.standard_error)) / m.standard_error,
                (m.ci95_high - (m.value + 1.959964 * m.standard_error)) / m.standard_error);
    // Wald on request: estimate ± 1.959964 se, the same estimate and standard error.
    const Estimate w = pick(wald16, i);
    EXPECT_EQ(w.method, "wald");
    EXPECT_EQ(w.value, m.value);
    EXPECT_EQ(w.standard_error, m.standard_error);
    EXPECT_NEAR(w.ci95_high - w.value, 1.959964 * w.standard_error, 1e-6 * w.standard_error);
    EXPECT_NEAR(w.value - w.ci95_low, 1.959964 * w.standard_error, 1e-6 * w.standard_error);
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
  JonswapFitOptions wald;  // only the standard errors are tested: skip the profiles
  wald.interval = swell::validation::IntervalMethod::wald;
  const auto start = std::chrono::steady_clock::now();
  for (int s = 0; s < kSeeds; ++s) {
    t.add(swell::validation::fit_jonswap_periodograms(
        c, {exponential_periodogram(mu, c.grid, rng)}, wald));
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

// ---------------------------------------------------------------- profile intervals

// −log L of the fit's own ordinates (JonswapFit::wave_vector_index) at θ, for one periodogram,
// from the public model μ(k; θ) (itself checked against the reference library above).
double whittle_nll(const OceanCase& c, const std::vector<double>& periodogram,
                   const std::vector<std::size_t>& index, double hs, double tp, double gamma) {
  swell::validation::JonswapParameters p;
  p.hs = hs, p.tp = tp, p.gamma = gamma;
  const auto mu = swell::validation::jonswap_model_periodogram(c, p);
  double total = 0;
  for (auto k : index) total += std::log(mu[k]) + periodogram[k] / mu[k];
  return total;
}

// min over Hs of −log L at (Tp, γ), in closed form: μ_k = Hs² g_k (g = μ at Hs = 1) gives
// ∂/∂(Hs²) = 0 at Hs² = (1/K) Σ I_k/g_k, where −log L = Σ log g_k + K log Hs² + K.
double nll_min_over_hs(const OceanCase& c, const std::vector<double>& periodogram,
                       const std::vector<std::size_t>& index, double tp, double gamma) {
  swell::validation::JonswapParameters p;
  p.hs = 1, p.tp = tp, p.gamma = gamma;
  const auto g = swell::validation::jonswap_model_periodogram(c, p);
  double log_g = 0, ratio = 0;
  for (auto k : index) log_g += std::log(g[k]), ratio += periodogram[k] / g[k];
  const double K = double(index.size());
  return log_g + K * std::log(ratio / K) + K;
}

// Golden-section minimum of f on [lo, hi] (unimodal there), to 1e-9 of the bracket.
template <typename F>
double golden_minimum(F&& f, double lo, double hi) {
  const double r = (std::sqrt(5.0) - 1) / 2;
  double x1 = hi - r * (hi - lo), x2 = lo + r * (hi - lo), f1 = f(x1), f2 = f(x2);
  while (hi - lo > 1e-9 * (std::abs(lo) + std::abs(hi))) {
    if (f1 < f2) {
      hi = x2, x2 = x1, f2 = f1, x1 = hi - r * (hi - lo), f1 = f(x1);
    } else {
      lo = x1, x1 = x2, f1 = f2, x2 = lo + r * (hi - lo), f2 = f(x2);
    }
  }
  return std::min(f1, f2);
}

// The profile −log L at θ_fixed = value (0 Hs, 1 Tp, 2 γ), minimized over the other two by a
// route independent of the fit's: Hs in closed form (above) and the remaining one by golden
// section over ±6 standard errors (γ ≥ 1, as in the fit); for the Hs profile, a 11 × 11 scan
// of (Tp, γ) re-centred on its best point and shrunk by 4, seven times (to 6·4⁻⁶ ≈ 1.5e-3 se,
// where −log L is within ~1e-6 of its minimum, far below the 0.01 asserted).
double brute_force_profile(const OceanCase& c, const std::vector<double>& periodogram,
                           const JonswapFit& fit, int fixed, double value) {
  const auto& index = fit.wave_vector_index;
  const double tp_se = fit.tp.standard_error, gamma_se = fit.gamma.standard_error;
  if (fixed == 1) {
    return golden_minimum([&](double g) { return nll_min_over_hs(c, periodogram, index, value, g); },
                          std::max(1.0, fit.gamma.value - 6 * gamma_se),
                          fit.gamma.value + 6 * gamma_se);
  }
  if (fixed == 2) {
    return golden_minimum([&](double t) { return nll_min_over_hs(c, periodogram, index, t, value); },
                          fit.tp.value - 6 * tp_se, fit.tp.value + 6 * tp_se);
  }
  double ct = fit.tp.value, cg = fit.gamma.value, ht = 6 * tp_se, hg = 6 * gamma_se,
         best = HUGE_VAL;
  for (int zoom = 0; zoom < 7; ++zoom) {
    double best_t = ct, best_g = cg;
    for (int i = -5; i <= 5; ++i) {
      for (int j = -5; j <= 5; ++j) {
        const double tp = ct + ht * i / 5.0, gamma = cg + hg * j / 5.0;
        if (gamma < 1) continue;
        const double v = whittle_nll(c, periodogram, index, value, tp, gamma);
        if (v < best) best = v, best_t = tp, best_g = gamma;
      }
    }
    ct = best_t, cg = best_g, ht /= 4, hg /= 4;
  }
  return best;
}

// The profile-likelihood interval against an independent computation: on one exponential
// periodogram of a coarse grid (64² over 400 m: 4 peak wavelengths, where the likelihood is
// visibly not quadratic), the brute-force profile deviance 2(min −log L at θ_i − −log L(θ̂)) at
// each reported end is χ²₁(0.95) = 3.8415 within 0.01 (0.003 se in the end's position; the
// fit's root finding stops at 1e-4 of √3.84), and the MLE itself is not beaten by the scan. At
// the Wald ends the same deviance is printed: it is off by far more than 0.01 (else the test
// would not tell the two apart).
TEST(JonswapFit, ProfileIntervalEndsMatchABruteForceProfile) {
  const auto c = coverage_case(64, 400);
  std::mt19937_64 rng(31337);
  const auto periodogram = exponential_periodogram(true_mu(c), c.grid, rng);
  const auto fit = swell::validation::fit_jonswap_periodograms(c, {periodogram});
  ASSERT_TRUE(fit.converged) << fit.report;
  const double nll_hat =
      whittle_nll(c, periodogram, fit.wave_vector_index, fit.hs.value, fit.tp.value,
                  fit.gamma.value);
  const Estimate e[3] = {fit.hs, fit.tp, fit.gamma};
  const char* names[] = {"hs", "tp", "gamma"};
  bool any_asymmetric = false;
  for (int i = 0; i < 3; ++i) {
    SCOPED_TRACE(names[i]);
    ASSERT_EQ(e[i].method, "profile-likelihood");
    ASSERT_TRUE(e[i].calibrated) << e[i].reason;
    EXPECT_GE(brute_force_profile(c, periodogram, fit, i, e[i].value), nll_hat - 1e-6);
    for (const double end : {e[i].ci95_low, e[i].ci95_high}) {
      const double d = 2 * (brute_force_profile(c, periodogram, fit, i, end) - nll_hat);
      EXPECT_NEAR(d, 3.841458820694124, 0.01) << "at " << end;
    }
    double wald_d[2];
    for (int side = 0; side < 2; ++side) {
      const double end = e[i].value + (side ? 1 : -1) * 1.959964 * e[i].standard_error;
      wald_d[side] = 2 * (brute_force_profile(c, periodogram, fit, i, end) - nll_hat);
      any_asymmetric |= std::abs(wald_d[side] - 3.8415) > 0.05;
    }
    std::printf("  %-5s %.5g, profile [%.5g, %.5g], Wald [%.5g, %.5g] (deviance %.3f, %.3f)\n",
                names[i], e[i].value, e[i].ci95_low, e[i].ci95_high,
                e[i].value - 1.959964 * e[i].standard_error,
                e[i].value + 1.959964 * e[i].standard_error, wald_d[0], wald_d[1]);
  }
  EXPECT_TRUE(any_asymmetric) << "the case does not tell profile from Wald intervals";
}

// An estimate beyond the usual search range: a sea without enhancement (γ = 1) on 64² over
// 200 m; draw 91 of this generator (found by scanning 1000 draws: 4 behave so) fits γ ≈ 1.9e4,
// a spike between the wave vectors. The upward search for γ's profile end once stopped at a
// fixed 1e4, below the estimate, and called the profile open ("cannot"); it now starts from the
// estimate, and the profile closes: γ ∈ [1, ~4e4], which contains the truth — honest and wide.
// Hs and Tp keep their calibrated profile intervals.
TEST(JonswapFit, ProfileEndsAreSearchedBeyondAnEstimateAboveTheUsualRange) {
  auto c = coverage_case(64, 200);
  c.spectrum.numbers["gamma"] = 1.0;
  const auto mu = true_mu(c);
  std::mt19937_64 rng(4242);
  std::vector<double> periodogram;
  for (int i = 0; i <= 91; ++i) periodogram = exponential_periodogram(mu, c.grid, rng);
  const auto fit = swell::validation::fit_jonswap_periodograms(c, {periodogram});
  std::printf("  γ %.6g [%g, %g] %s\n", fit.gamma.value, fit.gamma.ci95_low, fit.gamma.ci95_high,
              fit.gamma.reason.c_str());
  EXPECT_GT(fit.gamma.value, 1e4);
  EXPECT_EQ(fit.gamma.method, "profile-likelihood");
  EXPECT_TRUE(fit.gamma.calibrated) << fit.gamma.reason;
  EXPECT_EQ(fit.gamma.ci95_low, 1.0);  // the profile at γ = 1 is within 1.92 of the maximum
  EXPECT_GT(fit.gamma.ci95_high, fit.gamma.value);
  EXPECT_TRUE(std::isfinite(fit.gamma.ci95_high));
  for (const Estimate* e : {&fit.hs, &fit.tp}) {
    EXPECT_TRUE(e->calibrated) << e->reason;
    EXPECT_LT(e->ci95_low, e->value);
    EXPECT_GT(e->ci95_high, e->value);
  }
}

// The optimizer stays inside the valid region: these seeds of 64² over 200 m, Tp 10 s (fp32
// surfaces, the default) drove the previous log-γ parametrization to γ ≈ 1e-310 and a
// NumericalError ("normalization: ∂F/∂γ … reached only nan"; found by searching seeds 0–399
// with the previous code: 13 of 400). Now each fit ends cleanly with γ ≥ 1, and since the patch
// holds only 1.28 peak wavelengths (λp = 156 m), every interval says why it is not calibrated.
TEST(JonswapFit, StaysInsideTheValidRegionOnACoarseGrid) {
  auto c = coverage_case(64, 200);
  c.spectrum = {"jonswap", {{"hs", 3.0}, {"tp", 10.0}, {"gamma", 3.3}}, {}};
  for (const int seed : {39, 62, 76, 97, 130, 154, 199, 209, 218, 280, 363, 372, 382}) {
    SCOPED_TRACE(seed);
    c.seed = seed;
    JonswapFit fit;
    ASSERT_NO_THROW(fit = swell::validation::fit_jonswap(c, {swell::impls::Synthesizer(c).frames()}));
    EXPECT_GE(fit.gamma.value, 1.0);
    EXPECT_GT(fit.hs.value, 0);
    EXPECT_GT(fit.tp.value, 0);
    EXPECT_NEAR(fit.peak_wavelengths, 200 / (9.81 * 100 / (2 * M_PI)), 1e-9);
    for (const Estimate* e : {&fit.hs, &fit.tp, &fit.gamma}) {
      EXPECT_TRUE(std::isfinite(e->value));
      EXPECT_FALSE(e->calibrated);
      EXPECT_NE(e->reason.find("1.28 peak wavelengths"), std::string::npos) << e->reason;
    }
  }
}

// ---------------------------------------------------------------- coverage across grids

// Binomial(n, p) CDF P(X ≤ k), by summing the pmf in log space (lgamma): exact to rounding for
// the n ≤ a few thousand used here.
double binomial_cdf(int k, int n, double p) {
  double total = 0;
  for (int i = 0; i <= k; ++i) {
    total += std::exp(std::lgamma(n + 1.0) - std::lgamma(i + 1.0) - std::lgamma(n - i + 1.0) +
                      i * std::log(p) + (n - i) * std::log1p(-p));
  }
  return std::min(1.0, total);
}

// The two-sided acceptance region [lo, hi] for the count of misses of n intervals of true
// coverage 95 %: P(X < lo) ≤ α/2 and P(X > hi) ≤ α/2, X ~ Binomial(n, 0.05).
std::pair<int, int> miss_bounds(int n, double alpha) {
  int lo = 0;
  while (lo < n && binomial_cdf(lo, n, 0.05) <= alpha / 2) ++lo;  // P(X ≤ lo) > α/2: X < lo rare
  int hi = 0;
  while (hi < n && 1.0 - binomial_cdf(hi, n, 0.05) > alpha / 2) ++hi;
  return {lo, hi};
}

// One grid of the calibration: a case, how its periodograms are made, how many seeds.
struct CalibrationGrid {
  int n;
  double length;  // m
  double s;       // cos-2s spreading
  bool synthesized;
  bool cannot = false;  // the resolution rule must refuse every interval on this grid
  int seeds = 200;
};

// What the calibration measured on one grid for one parameter.
struct Coverage {
  Coverage(std::string n, double t) : name(std::move(n)), truth(t) {}
  std::string name;
  double truth;
  int fits = 0, calibrated = 0, covered = 0;
  double sum = 0, sum2 = 0, se2 = 0, n_eff = 0;
  std::string reason;
  // Spread and standard errors over the fits whose interval is called calibrated: the others
  // may carry no finite standard error (a singular Fisher information).
  void add(const Estimate& e) {
    ++fits;
    n_eff += e.effective_ordinates;
    if (!e.calibrated) {
      if (reason.empty()) reason = e.reason;
      return;
    }
    sum += e.value, sum2 += e.value * e.value, se2 += e.standard_error * e.standard_error;
    ++calibrated;
    covered += e.ci95_low <= truth && truth <= e.ci95_high;
  }
  int misses() const { return calibrated - covered; }
  // The spread of the estimates over seeds against the root mean reported standard error.
  double spread_over_se() const {
    if (calibrated < 2) return NAN;
    const double variance = (sum2 - sum * sum / calibrated) / (calibrated - 1);
    return std::sqrt(variance / (se2 / calibrated));
  }
};

// The family-wise false-alarm rate of the calibration tests: 1 % over every statistical
// assertion, split evenly (Bonferroni) over kCalibrationTests = 3 parameters × 11 resolved grids
// × 2 (the coverage, and the spread over the standard error).
constexpr double kFamilyAlpha = 0.01;
constexpr int kCalibrationTests = 3 * 11 * 2;

// Fits `grid.seeds` independent realizations of the coverage case on `grid` (one frame each),
// prints one table row per parameter and asserts, per parameter: on a resolved grid every
// interval is called calibrated, and their misses lie in the two-sided binomial acceptance
// region at α = kFamilyAlpha / kCalibrationTests; on a grid marked `cannot` every interval must
// say "cannot" with a reason (and none is counted).
void calibrate(const CalibrationGrid& grid, std::uint64_t seed0) {
  auto c = coverage_case(grid.n, grid.length);
  c.spreading = {"cos2s", {{"s", grid.s}}, {}};
  const auto mu = true_mu(c);
  std::mt19937_64 rng(seed0);
  std::vector<Coverage> t = {{"Hs", 3.0}, {"Tp", 8.0}, {"γ", 3.3}};
  int converged = 0;
  const auto start = std::chrono::steady_clock::now();
  for (int s = 0; s < grid.seeds; ++s) {
    JonswapFit fit;
    if (grid.synthesized) {
      c.seed = seed0 + s;
      swell::impls::SynthesizerOptions options;
      options.precision = swell::impls::Precision::f64;
      fit = swell::validation::fit_jonswap(c, {swell::impls::Synthesizer(c, options).frames()});
    } else {
      fit = swell::validation::fit_jonswap_periodograms(c,
                                                        {exponential_periodogram(mu, c.grid, rng)});
    }
    converged += fit.converged;
    t[0].add(fit.hs), t[1].add(fit.tp), t[2].add(fit.gamma);
    // An unresolved peak keeps the Wald interval for diagnosis (no profiles).
    EXPECT_EQ(fit.hs.method, grid.cannot ? "wald" : "profile-likelihood");
  }
  const double lambda_p = 9.81 * 8.0 * 8.0 / (2 * M_PI);
  const double alpha = kFamilyAlpha / kCalibrationTests;
  for (const auto& x : t) {
    const auto [lo, hi] = miss_bounds(x.calibrated, alpha);
    std::printf(
        "| %4d² | %6.0f m | %5.1f | %4.0f | %-11s | %3d | %2s | %3d/%3d | %5.1f %% | %3d | [%d, %d] "
        "| %5.3f | %7.1f |\n",
        grid.n, grid.length, grid.length / lambda_p, grid.s,
        grid.synthesized ? "synthesized" : "μ·Exp(1)", grid.seeds, x.name.c_str(), x.calibrated,
        x.fits, x.calibrated ? 100.0 * x.covered / x.calibrated : 0.0, x.misses(), lo, hi,
        x.spread_over_se(), x.n_eff / x.fits);
    if (!x.reason.empty()) std::printf("|   cannot (%d seeds): %s\n", x.fits - x.calibrated, x.reason.c_str());
    if (grid.cannot) {
      EXPECT_EQ(x.calibrated, 0) << x.name << " on " << c.describe() << ": must say cannot";
      EXPECT_FALSE(x.reason.empty());
    } else {
      EXPECT_EQ(x.calibrated, x.fits) << x.name << " on " << c.describe() << ": " << x.reason;
    }
    // The spread of n estimates against the mean standard error: the sample standard deviation
    // of n near-normal values scatters by 1/√(2(n − 1)) relative (5 % at n = 200); two-sided at
    // α, z = 3.79. Asserted from 4 peak wavelengths up: at 2 the Fisher standard error
    // overstates the spread of Hs and γ by 9–17 % (measured, docs/fit.md §6) — the
    // asymptotics behind a standard error are not reached there, which is why the intervals
    // are profile-likelihood ones (their coverage is asserted on every grid).
    if (x.calibrated > 1 && grid.length / lambda_p >= 4) {
      const double z = 3.79;
      EXPECT_NEAR(x.spread_over_se(), 1.0, z / std::sqrt(2.0 * (x.calibrated - 1)))
          << x.name << " on " << c.describe();
    }
    if (x.calibrated > 0) {
      EXPECT_GE(x.misses(), lo) << x.name << " on " << c.describe() << ": too few misses";
      EXPECT_LE(x.misses(), hi) << x.name << " on " << c.describe() << ": too many misses";
    }
  }
  std::printf("|   %d/%d converged, %.1f s\n", converged, grid.seeds, seconds_since(start));
  std::fflush(stdout);
  // On a grid that must say "cannot" the optimizer may stop short (a flat likelihood along
  // Hs, Tp beyond the patch); the fit still ends without an error, which is what is asserted.
  if (!grid.cannot) {
    EXPECT_EQ(converged, grid.seeds);
  }
}

void print_header() {
  std::printf(
      "| grid | L | L/λp | s | periodograms | N | parameter | calibrated/N | coverage | misses "
      "| bound | spread/se | n_eff |\n");
}

// The calibration (label "calibration"): 12 grids from 1 to 20 peak wavelengths, s = 2 to 20,
// 64² and 256², μ·Exp(1) periodograms (the exact law of a Gaussian surface's periodogram) and,
// for the grid of the original report (256² over 400 m), synthesized surfaces; 200 seeds each.
// The nine 64² grids and the synthesized one run in every test run; the two 256² grids of
// μ·Exp(1) periodograms (half a minute) in the soak tier (JonswapFitSoak).
TEST(JonswapFit, CoverageOnSmallGrids) {
  print_header();
  int i = 0;
  for (const CalibrationGrid g : {CalibrationGrid{64, 100, 10, false, true},
                                  CalibrationGrid{64, 200, 2, false}, {64, 200, 20, false},
                                  {64, 400, 2, false}, {64, 400, 20, false},
                                  {64, 1000, 2, false}, {64, 1000, 20, false},
                                  {64, 2000, 2, false}, {64, 2000, 20, false}}) {
    calibrate(g, 5000 + 1000 * i++);
  }
}

TEST(JonswapFit, CoverageOnSynthesizedSurfaces) {
  print_header();
  calibrate({256, 400, 10, true}, 1000);
}

TEST(JonswapFitSoak, CoverageOnLargeGrids) {
  print_header();
  calibrate({256, 800, 2, false}, 30000);
  calibrate({256, 2000, 20, false}, 40000);
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

TEST(JonswapFitInput, CompositeSeasAndDeclaredFactorsAreRefusedByName) {
  const auto c = coverage_case(64, 400);
  const auto frames = frames_of(c);
  auto refusal = [&](const OceanCase& sea) {
    try {
      (void)swell::validation::case_jonswap_parameters(sea);
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  auto composite = c;
  auto swell_part = c.components().front();
  swell_part.wind_dir_deg += 45;
  composite.more_components = {swell_part};
  EXPECT_NE(refusal(composite).find("composite sea of 2 components"), std::string::npos)
      << refusal(composite);
  EXPECT_THROW(swell::validation::fit_jonswap(composite, {frames}), InvalidInput);
  auto factor = c;
  factor.energy_factor = 8;
  EXPECT_NE(refusal(factor).find("energy_factor = 8"), std::string::npos) << refusal(factor);
  auto fade = c;
  fade.short_wave_fade = 0.1;
  EXPECT_NE(refusal(fade).find("short_wave_fade"), std::string::npos) << refusal(fade);
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
