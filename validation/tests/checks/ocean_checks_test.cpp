// The ocean checks: the sampling laws behind them against exact values and simulation, right
// surfaces pass on every built-in case, every check fails on a surface made wrong for it and
// names the fault, and (label "calibration") each statistical check's false-alarm rate over
// 200 seeds is within the binomial bound of its α.
#include <gtest/gtest.h>

#include <algorithm>

#include <boost/math/distributions/binomial.hpp>
#include <boost/math/distributions/gamma.hpp>
#include <cmath>
#include <fstream>
#include <map>
#include <random>
#include <set>

#include "swell/impls/synthesizer.hpp"
#include "swell/reference/lattice.hpp"
#include "swell/reference/errors.hpp"
#include "swell/validation/checks/ocean_check_table.hpp"
#include "swell/validation/checks/ocean_checks.hpp"
#include "swell/validation/checks/ocean_matrix.hpp"
#include "swell/validation/io/case_file.hpp"
#include "swell/validation/stats/statistics.hpp"
#include "test_engine.hpp"

namespace {

namespace stats = swell::validation::stats;
using swell::reference::Grid;
using swell::reference::OceanCase;
using swell::test::EngineBug;
using swell::validation::CheckResult;
using swell::validation::OceanCheckOptions;
using swell::validation::OceanCheckReport;
using swell::validation::run_ocean_checks;

// ------------------------------------------------------------------ sampling laws

// Equal weights make the sum Gamma(n, w): the saddlepoint tails against the exact ones.
TEST(SamplingLaws, SaddlepointMatchesGammaForEqualWeights) {
  for (int n : {1, 3, 30, 400}) {
    const double w = 0.37;
    const stats::WeightedExponentialSum law(std::vector<double>(n, w));
    const boost::math::gamma_distribution<double> exact(n, w);
    EXPECT_NEAR(law.mean(), n * w, 1e-12 * n);
    EXPECT_NEAR(law.variance(), n * w * w, 1e-12 * n);
    for (double p : {1e-4, 1e-3, 0.05, 0.3, 0.7, 0.95, 0.999, 0.9999}) {
      const double x = boost::math::quantile(exact, p);
      // Lugannani–Rice for a Gamma is accurate to O(1/n) relative in each tail (Daniels 1987):
      // 7 % in the far lower tail of a single exponential, 1.1 % at n = 3, less beyond.
      const double tolerance = n == 1 ? 0.08 : n == 3 ? 0.015 : 0.01;
      if (p < 0.5) {
        EXPECT_NEAR(law.cdf(x) / p, 1.0, tolerance) << "n=" << n << " p=" << p;
      } else {
        EXPECT_NEAR(law.survival(x) / (1 - p), 1.0, tolerance) << "n=" << n << " p=" << p;
      }
    }
    EXPECT_NEAR(law.quantile(0.999) / boost::math::quantile(exact, 0.999), 1.0, 0.01);
  }
}

// Near the mean the formula is 0/0; every x there, however close, gives a finite, continuous
// answer (a recursion at the guard's edge once overflowed the stack).
TEST(SamplingLaws, SaddlepointIsContinuousThroughTheMean) {
  std::vector<double> weights;
  for (int i = 1; i <= 300; ++i) weights.push_back(1.0 / (1 + 0.01 * i * i));
  const stats::WeightedExponentialSum law(weights);
  const double sd = std::sqrt(law.variance());
  double previous = 0;
  for (int step = -2000; step <= 2000; ++step) {
    const double x = law.mean() + step * 1e-6 * sd;
    const double f = law.cdf(x);
    ASSERT_TRUE(std::isfinite(f)) << step;
    EXPECT_GE(f, previous - 1e-9) << step;
    EXPECT_NEAR(f + law.survival(x), 1.0, 1e-6) << step;
    previous = f;
  }
  EXPECT_NEAR(law.two_sided_p(law.quantile(0.5)), 1.0, 1e-6);  // the median, not the mean
}

// The quantile inverts the tails it is solved from, for the weights the gate meets: equal ones,
// one dominant wave among many small ones, weights over twelve decades, and 10⁵ weights of a
// spectrum-like decay — at the gate's p (α/48 and α/B per bin, down to 3e-7) and the body. The
// root is found to ~5e-10 relative in x (eps_tolerance(32)); in p that is below 1e-7 relative
// even 15 scales into a tail, so 1e-6 fails a quantile solved to the wrong point or bracket.
TEST(SamplingLaws, QuantileInvertsTheTailsForEveryKindOfWeights) {
  std::vector<std::pair<std::string, std::vector<double>>> sets;
  sets.push_back({"one", {0.37}});
  sets.push_back({"equal", std::vector<double>(1000, 2.5)});
  std::vector<double> dominant(5000, 1e-4);
  dominant.push_back(3.0);
  sets.push_back({"dominant", dominant});
  std::vector<double> decades;
  for (int i = 0; i < 400; ++i) decades.push_back(std::pow(10.0, -12.0 * i / 399));
  sets.push_back({"decades", decades});
  std::vector<double> spectrum;
  for (int i = 1; i <= 100000; ++i) {
    const double k = 0.01 * i;
    spectrum.push_back(std::pow(k, -3.5) * std::exp(-1.25 / (k * k)) * (1 + 0.3 * std::sin(i)));
  }
  sets.push_back({"spectrum", spectrum});
  for (const auto& [name, weights] : sets) {
    const stats::WeightedExponentialSum law(weights);
    double previous = 0;
    for (double p : {3e-7, 1e-4, 0.02, 0.5, 0.98, 1 - 1e-4, 1 - 3e-7}) {
      const double x = law.quantile(p);
      ASSERT_TRUE(std::isfinite(x) && x > 0) << name << " p=" << p;
      EXPECT_GT(x, previous) << name << " p=" << p;  // increasing in p
      previous = x;
      if (p <= 0.5) {
        EXPECT_NEAR(law.cdf(x) / p, 1.0, 1e-6) << name << " p=" << p;
      } else {
        EXPECT_NEAR(law.survival(x) / (1 - p), 1.0, 1e-6) << name << " p=" << p;
      }
    }
    // Beyond what the tails resolve (the gamma guess underflows or the bracket cannot close):
    // the bisection's answer, finite, not an exception from boost.
    for (double p : {1e-300, 1 - 1e-16}) {
      double x = -1;
      EXPECT_NO_THROW(x = law.quantile(p)) << name << " p=" << p;
      EXPECT_TRUE(std::isfinite(x) && x >= 0) << name << " p=" << p << " x=" << x;
    }
  }
}

// Unequal weights, the case of a real spectrum: against simulation.
TEST(SamplingLaws, SaddlepointMatchesSimulationForUnequalWeights) {
  std::vector<double> weights;
  for (int i = 1; i <= 40; ++i) weights.push_back(1.0 / (i * i));  // two waves dominate
  const stats::WeightedExponentialSum law(weights);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const int trials = 200000;
  const double upper = law.quantile(0.99), lower = law.quantile(0.01);
  int above = 0, below = 0;
  for (int t = 0; t < trials; ++t) {
    double x = 0;
    for (double w : weights) x -= w * std::log1p(-uniform(rng));
    above += x > upper;
    below += x < lower;
  }
  // Binomial sd of the count at p = 0.01 over 2e5 trials is 44.5; allow 5 sd.
  EXPECT_NEAR(above, 0.01 * trials, 225);
  EXPECT_NEAR(below, 0.01 * trials, 225);
}

// The law of a ratio of weighted exponential sums, P(Σ c E ≤ 0) with c of both signs: against
// the closed form of two terms, P(a E1 − b E2 ≤ 0) = b/(a + b), and against simulation for the
// law of a period m0/m1 over a tail of 40 waves where two dominate (the case the delta method
// got wrong). The saddlepoint's relative error is O(1/n): 5 % is generous for two terms.
TEST(SamplingLaws, RatioLawMatchesClosedFormAndSimulation) {
  for (const auto& [a, b] : std::vector<std::pair<double, double>>{{1, 1}, {1, 3}, {5, 1}, {1, 40}}) {
    const double exact = b / (a + b);
    EXPECT_NEAR(stats::mixed_exponential_sum_cdf_at_zero({a, -b}) / exact, 1, 0.05) << a << " " << b;
  }
  EXPECT_EQ(stats::mixed_exponential_sum_cdf_at_zero({1, 2, 0}), 0);
  EXPECT_EQ(stats::mixed_exponential_sum_cdf_at_zero({-1, -2}), 1);
  std::vector<double> mu, omega;
  for (int i = 1; i <= 40; ++i) {
    mu.push_back(1.0 / (i * i));
    omega.push_back(1 + 0.1 * i);
  }
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const int trials = 200000;
  std::vector<double> ratios;
  for (int t = 0; t < trials; ++t) {
    double m0 = 0, m1 = 0;
    for (std::size_t i = 0; i < mu.size(); ++i) {
      const double e = -mu[i] * std::log1p(-uniform(rng));
      m0 += e;
      m1 += e * omega[i];
    }
    ratios.push_back(m0 / m1);
  }
  std::sort(ratios.begin(), ratios.end());
  for (double level : {0.001, 0.01, 0.5, 0.99, 0.999}) {
    const double r = ratios[std::size_t(level * trials)];
    std::vector<double> c;
    for (std::size_t i = 0; i < mu.size(); ++i) c.push_back(mu[i] * (1 - r * omega[i]));
    const double p = stats::mixed_exponential_sum_cdf_at_zero(c);
    // Binomial sd of the empirical level, 5 of them, plus 3 % of the level for the saddlepoint.
    const double sd = std::sqrt(level * (1 - level) / trials);
    EXPECT_NEAR(p, level, 5 * sd + 0.03 * std::min(level, 1 - level)) << "level " << level;
  }
}

// The same law at any threshold, P(Σ c E ≤ x), against its closed form for distinct weights:
// the Laplace transform Π 1/(1 + c_i t) splits into partial fractions, so for x < 0
// P(S ≤ x) = Σ over c_i < 0 of A_i e^(−x/c_i), A_i = Π_(j≠i) c_i/(c_i − c_j). The case is
// statistics.hs_steady's: a change of m0 between frames is Σ w (E1 − E2) over a few dominant
// waves, whose tails the normal law misses by orders of magnitude (printed here).
// P(Σ c E ≤ x) for distinct coefficients and x < 0, by partial fractions (below).
double mixed_sum_cdf_closed_form(const std::vector<double>& c, double x) {
  double exact = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    if (c[i] > 0) continue;
    double a = 1;
    for (std::size_t j = 0; j < c.size(); ++j) {
      if (j != i) a *= c[i] / (c[i] - c[j]);
    }
    exact += a * std::exp(-x / c[i]);
  }
  return exact;
}

TEST(SamplingLaws, MixedExponentialSumMatchesItsClosedFormInTheTail) {
  const std::vector<double> c = {1.0, 0.7, 0.2, -0.95, -0.65, -0.25};
  double variance = 0;
  for (double v : c) variance += v * v;
  for (double x : {-0.5, -2.0, -5.0, -9.0}) {
    const double exact = mixed_sum_cdf_closed_form(c, x);
    const double saddlepoint = stats::mixed_exponential_sum_cdf(c, x);
    const double normal = 0.5 * std::erfc(-(x - 0.05) / std::sqrt(variance) / std::sqrt(2.0));
    std::printf("[ measure  ] P(S ≤ %g): exact %.4g, saddlepoint %.4g, normal %.4g\n", x, exact, saddlepoint, normal);
    // Lugannani–Rice's relative error stays within a few per cent into the far tail.
    EXPECT_NEAR(saddlepoint / exact, 1, 0.05) << "x = " << x;
  }
  // At zero it is the ratio law above; above every coefficient's reach, 0 or 1.
  EXPECT_DOUBLE_EQ(stats::mixed_exponential_sum_cdf({1, -2}, 0), stats::mixed_exponential_sum_cdf_at_zero({1, -2}));
  EXPECT_EQ(stats::mixed_exponential_sum_cdf({1, 2}, -1), 0);
  EXPECT_EQ(stats::mixed_exponential_sum_cdf({-1, -2}, 0.5), 1);
}

// The law of Σ w (E − E') (statistics.hs_steady's change of m0) with each pair's terms taken
// together is the law of its coefficients ±w: against mixed_exponential_sum_cdf to rounding,
// from the centre to p ~ 10⁻⁶⁰, on few and on many weights (two dominant over 5000 small ones,
// the swell on a large grid), and against the partial-fraction closed form in the tail.
TEST(SamplingLaws, ExponentialDifferenceSumIsTheMixedLawOfItsPairs) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<std::vector<double>> weight_sets = {{1.0}, {1.0, 0.6, 0.25}, {0.3, 0.3, 0.3, 0.3}};
  std::vector<double> many = {1.0, 0.8};
  for (int i = 0; i < 5000; ++i) many.push_back(1e-3 * std::pow(10.0, -3 * uniform(rng)));
  weight_sets.push_back(many);
  std::vector<double> spread;
  for (int i = 0; i < 4001; ++i) spread.push_back(std::pow(10.0, -6 * uniform(rng)));
  weight_sets.push_back(spread);
  for (const auto& w : weight_sets) {
    std::vector<double> c;
    double variance = 0;
    for (double v : w) {
      c.push_back(v);
      c.push_back(-v);
      variance += 2 * v * v;
    }
    for (double z : {-40.0, -12.0, -4.0, -1.0, -0.1, 0.0, 0.5, 3.0}) {
      const double x = z * std::sqrt(variance);
      const double paired = stats::exponential_difference_sum_cdf(w, x);
      const double mixed = stats::mixed_exponential_sum_cdf(c, x);
      ASSERT_GT(mixed, 0) << w.size() << " weights, z = " << z;
      EXPECT_NEAR(paired / mixed, 1, 1e-11) << w.size() << " weights, z = " << z << ": " << paired << " vs " << mixed;
    }
  }
  // Distinct weights: P(S ≤ x) = Σ over c_i < 0 of A_i e^(−x/c_i), A_i = Π_(j≠i) c_i/(c_i − c_j).
  const std::vector<double> w = {1.0, 0.6, 0.25};
  const std::vector<double> c = {1.0, -1.0, 0.6, -0.6, 0.25, -0.25};
  for (double x : {-0.5, -2.0, -5.0, -9.0}) {
    EXPECT_NEAR(stats::exponential_difference_sum_cdf(w, x) / mixed_sum_cdf_closed_form(c, x), 1, 0.05) << "x = " << x;
  }
  EXPECT_EQ(stats::exponential_difference_sum_cdf({}, -1), 0);
  EXPECT_EQ(stats::exponential_difference_sum_cdf({}, 0), 1);
  EXPECT_THROW(stats::exponential_difference_sum_cdf({1.0, 0.0}, -1), swell::NumericalError);
  EXPECT_THROW(stats::exponential_difference_sum_cdf({1.0}, NAN), swell::NumericalError);
}

// A² = −n − (1/n) Σ (2i + 1) (log F(x_(i)) + log S(x_(n−1−i))) over the sample in order,
// summed here over a std::sort of (F, −log S) pairs: bit for bit what the statistic gives. The
// sample is large enough for the statistic's bucketed sort and a third of it lies where
// F = 1 − e^(−x) rounds to a few doubles, whose ties only −log S orders.
TEST(SamplingLaws, AndersonDarlingIsItsSumOverTheOrderedSample) {
  std::mt19937_64 rng(21);
  std::exponential_distribution<double> exponential(1.0);
  std::uniform_real_distribution<double> tail(34.0, 40.0);
  const std::size_t n = 150000;
  std::vector<double> cdf(n), log_survival(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = i % 3 == 0 ? tail(rng) : exponential(rng);
    cdf[i] = -std::expm1(-x);
    log_survival[i] = -x;
  }
  std::vector<std::pair<double, double>> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = {cdf[i], -log_survival[i]};
  std::sort(order.begin(), order.end());
  std::size_t tied = 0;
  for (std::size_t i = 1; i < n; ++i) tied += order[i].first == order[i - 1].first;
  ASSERT_GT(tied, n / 4) << "the sample should hold runs of equal F";
  double sum = 0;
  for (std::size_t i = 0; i < n; ++i) {
    sum += double(2 * i + 1) * (std::log(order[i].first) - order[n - 1 - i].second);
  }
  const double expected = -double(n) - sum / double(n);
  EXPECT_EQ(stats::anderson_darling_statistic(cdf, log_survival), expected);
}

// Stephens (1974), Table 1.2, case 0 (distribution fully specified): asymptotic upper
// percentage points of A², given to 3 decimals. At the 1 % point the implementation gives
// 1.024 %; a simulation of 4·10⁵ samples of n = 100 gives 1.007 ± 0.016 %: within 3 %.
TEST(SamplingLaws, AndersonDarlingMatchesPublishedPercentagePoints) {
  const std::vector<std::pair<double, double>> points = {
      {1.933, 0.10}, {2.492, 0.05}, {3.070, 0.025}, {3.857, 0.01}};
  for (auto [a2, p] : points) EXPECT_NEAR(stats::anderson_darling_p(a2, 100000) / p, 1.0, 0.03) << a2;
}

// Both Anderson–Darling laws fall monotonically all the way out (a statistic of 271 once got
// p = 1 from a fitted polynomial used far outside its range).
TEST(SamplingLaws, AndersonDarlingPValuesFallMonotonicallyToZero) {
  for (int n : {10, 1000}) {
    double previous_known = 1.0, previous_fitted = 1.0;
    for (double a2 = 0.01; a2 < 1e4; a2 *= 1.01) {
      const double known = stats::anderson_darling_p(a2, n);
      const double fitted = stats::anderson_darling_exponential_p(a2, n);
      ASSERT_LE(known, previous_known + 1e-3) << "A² = " << a2;
      ASSERT_LE(fitted, previous_fitted + 1e-3) << "A² = " << a2;
      previous_known = known;
      previous_fitted = fitted;
    }
    EXPECT_LT(previous_known, 1e-12);
    EXPECT_LT(previous_fitted, 1e-12);
  }
}

// The estimated-scale law: its published percentage points (D'Agostino & Stephens 1986,
// Table 4.14: A* = 1.341 at 5 %, 1.957 at 1 %) and uniform p-values in simulation.
TEST(SamplingLaws, AndersonDarlingWithFittedScaleIsCalibrated) {
  EXPECT_NEAR(stats::anderson_darling_exponential_p(1.341, 1 << 30), 0.05, 0.003);
  EXPECT_NEAR(stats::anderson_darling_exponential_p(1.957, 1 << 30), 0.01, 0.0006);
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const int n = 200, trials = 20000;
  std::vector<double> p_values;
  for (int t = 0; t < trials; ++t) {
    std::vector<double> x(n);
    double mean = 0;
    for (double& v : x) mean += v = -std::log1p(-uniform(rng));
    mean /= n;
    std::vector<double> cdf(n), log_survival(n);
    for (int i = 0; i < n; ++i) {
      cdf[i] = -std::expm1(-x[i] / mean);
      log_survival[i] = -x[i] / mean;
    }
    p_values.push_back(
        stats::anderson_darling_exponential_p(stats::anderson_darling_statistic(cdf, log_survival), n));
  }
  std::sort(p_values.begin(), p_values.end());
  double d = 0;
  for (std::size_t i = 0; i < p_values.size(); ++i) {
    d = std::max({d, (i + 1.0) / trials - p_values[i], p_values[i] - double(i) / trials});
  }
  // KS at false-alarm 1e-3 allows √n D ≤ 1.95; the law's own table error adds ≈ 0.01.
  EXPECT_LE(d, 1.95 / std::sqrt(double(trials)) + 0.01);
}

TEST(SamplingLaws, AndersonDarlingMatchesSimulationAtSmallN) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const int n = 8, trials = 100000;
  int exceed = 0;
  for (int t = 0; t < trials; ++t) {
    std::vector<double> cdf(n), log_survival(n);
    for (int i = 0; i < n; ++i) {
      cdf[i] = uniform(rng);
      log_survival[i] = std::log1p(-cdf[i]);
    }
    exceed += stats::anderson_darling_statistic(cdf, log_survival) >= 2.492;
  }
  const double p = stats::anderson_darling_p(2.492, n);
  EXPECT_NEAR(double(exceed) / trials, p, 5 * std::sqrt(p * (1 - p) / trials));
}

TEST(SamplingLaws, FisherCombinationOfOnePValueIsItself) {
  EXPECT_NEAR(stats::fisher_combined_p({0.01}), 0.01, 1e-12);
  EXPECT_NEAR(stats::fisher_combined_p({1.0, 1.0, 1.0}), 1.0, 1e-12);
  EXPECT_LT(stats::fisher_combined_p({1e-3, 1e-3}), 1e-4);
}

// ------------------------------------------------------------------ cases

// The built-in cases of `swell check ocean`, at 64².
OceanCase builtin(const std::string& name, int n = 64) {
  for (const auto& c : swell::validation::builtin_ocean_cases(n)) {
    if (c.name == name) return c.ocean_case;
  }
  throw std::runtime_error("no built-in case " + name);
}
OceanCase jonswap_deep(int n = 64) { return builtin("jonswap_deep", n); }
OceanCase tma_shallow(int n = 64) { return builtin("tma_10m", n); }

std::string failures(const OceanCheckReport& report) {
  std::string out;
  for (const auto& r : report.results) {
    if (!r.passed) out += "\n  " + r.check + ": " + r.reason;
  }
  return out;
}

const CheckResult& find(const OceanCheckReport& report, const std::string& check) {
  for (const auto& r : report.results) {
    if (r.check == check) return r;
  }
  throw std::runtime_error("no result " + check);
}

// ------------------------------------------------------------------ right surfaces pass

struct NamedCase {
  std::string name;
  OceanCase ocean_case;
};

class RightSurfaces : public ::testing::TestWithParam<NamedCase> {};

TEST_P(RightSurfaces, PassEveryCheckFromBothImplementations) {
  const OceanCase& c = GetParam().ocean_case;
  const auto engine = run_ocean_checks(c, swell::test::render_surface(c));
  EXPECT_TRUE(swell::validation::all_passed(engine.results)) << failures(engine);
  const auto synthesized = run_ocean_checks(
      c, swell::impls::Synthesizer(c, {"fftw", swell::impls::Precision::f32}).frames());
  EXPECT_TRUE(swell::validation::all_passed(synthesized.results)) << failures(synthesized);
  // Every check ran: 10 checks, 24 results with six fields and eight frames.
  EXPECT_EQ(synthesized.results.size(), 24u) << synthesized.skipped.size();
}

INSTANTIATE_TEST_SUITE_P(BuiltInCases, RightSurfaces,
                         ::testing::Values(NamedCase{"jonswap_deep", builtin("jonswap_deep")},
                                           NamedCase{"tma_10m", builtin("tma_10m")},
                                           NamedCase{"phillips", builtin("phillips")},
                                           NamedCase{"pierson_moskowitz_cos2s",
                                                     builtin("pierson_moskowitz_cos2s")}),
                         [](const auto& info) { return info.param.name; });

// ------------------------------------------------------------------ wrong surfaces fail

struct MustFail {
  EngineBug bug;
  std::string check;      // the result that must fail
  std::string diagnosis;  // words its reason must contain
  bool tma = false;       // render on the 10 m case
  bool imaginary = false; // hand over the imaginary parts too
};

class WrongSurfaces : public ::testing::TestWithParam<MustFail> {};

TEST_P(WrongSurfaces, FailTheCheckMadeForThemWithADiagnosis) {
  const auto& p = GetParam();
  const OceanCase c = p.tma ? tma_shallow() : jonswap_deep();
  swell::test::EngineOptions options;
  options.keep_imaginary = p.imaginary;
  const auto frames = swell::test::render_surface(c, p.bug, options);
  const auto report = run_ocean_checks(c, frames);
  const auto& result = find(report, p.check);
  EXPECT_FALSE(result.passed) << swell::test::to_string(p.bug) << ": " << result.reason;
  EXPECT_NE(result.reason.find(p.diagnosis), std::string::npos) << result.reason;
  // The right surface of the same case and seed passes that check.
  const auto right = run_ocean_checks(c, swell::test::render_surface(c, EngineBug::none, options));
  EXPECT_TRUE(find(right, p.check).passed) << find(right, p.check).reason;
}

INSTANTIATE_TEST_SUITE_P(
    Bugs, WrongSurfaces,
    ::testing::Values(
        MustFail{EngineBug::independent_minus_k_real_part, "hermitian.imaginary_residue",
                 "missing conjugate pairing", false, true},
        MustFail{EngineBug::independent_minus_k_real_part, "energy", "energy off by a factor 0."},
        MustFail{EngineBug::energy_doubled, "energy", "energy off by a factor"},
        MustFail{EngineBug::energy_doubled, "moments.hs", "wrong wave height"},
        MustFail{EngineBug::sigma_wrong, "spectrum.shape", "shape differs"},
        MustFail{EngineBug::checkerboard_sign, "spectrum.unexpected_energy", "checkerboard"},
        MustFail{EngineBug::deep_water_dispersion, "dispersion.residual", "dispersion", true},
        MustFail{EngineBug::deep_water_dispersion, "dispersion.omega", "wrong dispersion", true},
        MustFail{EngineBug::reversed_time, "direction.distribution", "against the wind"},
        MustFail{EngineBug::standing_waves, "direction.distribution", "standing waves"},
        MustFail{EngineBug::same_pair_for_minus_k, "direction.travelling", "same random pair"},
        MustFail{EngineBug::uniform_noise, "statistics.gaussian_amplitudes", "not complex Gaussian"},
        MustFail{EngineBug::time_drift, "statistics.hs_steady", "drifts"},
        MustFail{EngineBug::jacobian_without_choppiness, "derived.jacobian", "without λ"},
        MustFail{EngineBug::displacement_sign_flipped, "derived.disp_x", "sign flipped"}),
    [](const auto& info) {
      std::string name = swell::test::to_string(info.param.bug) + "_" + info.param.check;
      for (char& ch : name) {
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      }
      return name;
    });

// Parseval judges the transform the checks run on: a backend that copies instead fails it.
TEST(WrongTransform, ParsevalFailsThroughABackendThatIsNotATransform) {
  const OceanCase c = jonswap_deep();
  OceanCheckOptions options;
  options.analysis_backend = "null";
  const auto report = run_ocean_checks(c, swell::test::render_surface(c), options, {"parseval"});
  ASSERT_EQ(report.results.size(), 1u);
  EXPECT_FALSE(report.results[0].passed) << report.results[0].reason;
  options.analysis_backend = "radix2";
  EXPECT_TRUE(run_ocean_checks(c, swell::test::render_surface(c), options, {"parseval"}).results[0].passed);
}

// ------------------------------------------------------------------ rounding and ω

// A case as the command line's property test draws them: the grid, the spectrum, depth (m),
// wind direction (degrees), choppiness, frames, dt (s) and seed.
OceanCase drawn_case(Grid grid, swell::reference::ModelSpec spectrum, double depth,
                     double wind_dir_deg, double choppiness, int frames, double dt,
                     std::uint64_t seed) {
  OceanCase c;
  c.grid = grid;
  c.spectrum = std::move(spectrum);
  c.depth = depth;
  c.wind_dir_deg = wind_dir_deg;
  c.choppiness = choppiness;
  c.frames = frames;
  c.dt = dt;
  c.seed = seed;
  return c;
}

// A Phillips sea of a 1 m/s wind on a 27 m patch, 5 frames 0.58 s apart: its energy lies above
// the frames' Nyquist frequency π/dt, and the waves below it that dispersion.omega measures carry
// 10⁻³¹ m² — barely above the resolution floor of fp64 frames, so rounding alone moves their
// measured ω by ~10⁻⁵ (a drawn case of the soak property test, where a bound of 10⁻⁶ failed
// swell's own frames). The bound allows for that rounding, and frames of a 1 m depth (ω about
// 9 % low at those waves) still fail.
TEST(OceanChecks, OmegaBoundAllowsForTheRoundingOfBarelyResolvedWaves) {
  const OceanCase c = drawn_case(Grid::create(32, 128, 26.9572, 26.9572),
                                 {"phillips",
                                  {{"amplitude", 0.000680384}, {"wind_speed", 1.0288},
                                   {"exponent", 4.0}, {"small_wave_cutoff", 0.00605691},
                                   {"against_wind_factor", 0.447017}},
                                  {}},
                                 13.7612, 304.073, 0.436419, 5, 0.579062, 613571);
  const auto frames = swell::impls::Synthesizer(c, {"fftw", swell::impls::Precision::f64}).frames();
  const auto report = run_ocean_checks(c, frames);
  const CheckResult& omega = find(report, "dispersion.omega");
  EXPECT_TRUE(omega.passed) << omega.reason;
  EXPECT_GT(omega.measured, 1e-6) << "the case no longer measures barely resolved waves";
  EXPECT_LT(omega.tolerance, 1e-3) << "the rounding term should stay small: " << omega.tolerance;

  OceanCase shallow = c;
  shallow.depth = 1.0;  // frames of another depth, judged against the case's
  const auto wrong = swell::impls::Synthesizer(shallow, {"fftw", swell::impls::Precision::f64}).frames();
  EXPECT_FALSE(find(run_ocean_checks(c, wrong), "dispersion.omega").passed);
}

// A two-peak sea whose six resolved waves below the frames' Nyquist frequency are of ~10⁻⁶ m
// (Ochi–Hubble, 32² over 3.9 m of 2.8 cm water, 4 fp32 frames 0.11 s apart from t0 = 1029.5 s):
// swell's own frames measured ω 1.000963 × the case's, 1.26 × the bound's rounding term when
// that held the stored numbers' rounding alone (the soak property test's seed 172052623845534).
// The engine's own inverse transform rounds the field by u log₂N too; with it the right frames
// pass, and frames of the deep-water relation (ω 3.8× the case's here) still fail.
TEST(OceanChecks, OmegaBoundAllowsForTheEnginesTransformRoundingOfWeakWaves) {
  OceanCase c = drawn_case(Grid::create(32, 32, 3.92467, 3.92467),
                           {"ochi-hubble",
                            {{"hs1", 0.00041757}, {"tp1", 19.4341}, {"lambda1", 2.5127},
                             {"hs2", 0.0711881}, {"tp2", 9.31425}, {"lambda2", 7.9749}},
                            {}},
                           0.0283861, -1.92032, -0.0446852, 4, 0.110928, 143950);
  c.spreading = {"donelan-banner", {}, {}};
  c.t0 = 1029.52;
  const auto frames = swell::impls::Synthesizer(c, {"fftw", swell::impls::Precision::f32}).frames();
  const auto report = run_ocean_checks(c, frames);
  const CheckResult& omega = find(report, "dispersion.omega");
  EXPECT_TRUE(omega.passed) << omega.reason;
  EXPECT_GT(omega.measured, 5e-4) << "the case no longer measures weak waves: " << omega.reason;

  OceanCase deep = c;
  deep.depth = std::numeric_limits<double>::infinity();  // frames of deep water, judged against the case's
  const auto wrong = swell::impls::Synthesizer(deep, {"fftw", swell::impls::Precision::f32}).frames();
  EXPECT_FALSE(find(run_ocean_checks(c, wrong), "dispersion.omega").passed);
}

// A loop period longer than every wave's own period quantizes every ω to 0 (here a Phillips
// sea on 1.3 cm of water, ω ≤ 0.03 rad/s, loop period 59 s: steps of 0.107 rad/s): nothing moves,
// and the periods Tm01, Tm02 and Tp are infinite (m0/m1 = ∞, a case the soak property test
// draws). The periods are skipped with their reason, not a numerical failure, and every other
// check judges the frames.
TEST(OceanChecks, WavesAtRestHaveNoPeriodToJudge) {
  OceanCase c = drawn_case(
      Grid::create(32, 32, 1272.52, 1272.52),
      {"phillips", {{"amplitude", 0.0225287}, {"wind_speed", 30.0188}, {"exponent", 6.0}}, {}},
      0.0133878, 24.2737, 0.527114, 4, 0.454272, 545399);
  c.loop_period = 58.9231;
  const auto frames = swell::impls::Synthesizer(c, {"fftw", swell::impls::Precision::f32}).frames();
  OceanCheckReport report;
  ASSERT_NO_THROW(report = run_ocean_checks(c, frames));
  EXPECT_TRUE(swell::validation::all_passed(report.results)) << failures(report);
  std::set<std::string> at_rest;
  for (const auto& s : report.skipped) {
    if (s.reason == swell::validation::SkipReason::no_wave_motion) at_rest.insert(s.check);
  }
  EXPECT_EQ(at_rest, (std::set<std::string>{"moments.tm01", "moments.tm02", "moments.tp"}));
  EXPECT_NO_THROW(find(report, "moments.hs"));
}

// A loop period of 74 s on a 33 m/s Pierson–Moskowitz sea over 8.5 × 15 km quantizes the
// energetic waves' ω to 1–3 steps of 0.085 rad/s, which three frames 0.37 s apart cannot tell
// apart from their mirror waves: the fits see only weak waves, 9e-12 of the frames' energy
// (soak seed 153763039676024). The frames' rounding, spread over every wave vector, is then
// judged against the frames' energy, not the fitted sliver's: right fp64 frames pass; frames
// whose ω is not quantized still fail.
TEST(OceanChecks, DispersionRoundingIsJudgedAgainstTheFramesEnergyWhenFewWavesAreIdentifiable) {
  const auto case_file = swell::validation::parse_case_toml(R"(
[grid]
n = [128, 128]
length = [8526.28, 15153.8]
[time]
t0 = 21.337
dt = 0.36934
frames = 3
[spectrum]
model = "pierson-moskowitz"
u19_5 = 33.0422
[spreading]
model = "cos-power"
p = 69.1252
one_sided = "yes"
wind_dir_deg = 96.2011
[synthesis]
choppiness = -0.448179
loop_period = 74.0592
seed = 419493
)", "loop_period_case.toml");
  const OceanCase& c = case_file.ocean;
  const auto frames = swell::impls::Synthesizer(c, {"fftw", swell::impls::Precision::f64}).frames();
  const CheckResult& right = find(run_ocean_checks(c, frames), "dispersion.residual");
  EXPECT_TRUE(right.passed) << right.reason << " (bound " << right.tolerance << ")";
  OceanCase unquantized = c;
  unquantized.loop_period = 0;
  const auto wrong = swell::impls::Synthesizer(unquantized, {"fftw", swell::impls::Precision::f64}).frames();
  const CheckResult& judged = find(run_ocean_checks(c, wrong), "dispersion.residual");
  EXPECT_FALSE(judged.passed) << judged.reason;
  EXPECT_GT(judged.measured, 1e3 * judged.tolerance) << "the scaled bound should leave the check its power";
}

// ------------------------------------------------------------------ interface

TEST(OceanChecks, RefuseMismatchedOrIncompleteInput) {
  const OceanCase c = jonswap_deep(32);
  const auto frames = swell::test::render_surface(c);
  OceanCase other = c;
  other.grid = Grid::create(64, 64, 400, 400);
  EXPECT_THROW(run_ocean_checks(other, frames), swell::InvalidInput);
  auto no_height = frames;
  for (auto& f : no_height.frames) f.fields.erase(swell::reference::Field::height);
  EXPECT_THROW(run_ocean_checks(c, no_height), swell::InvalidInput);
  EXPECT_THROW(run_ocean_checks(c, frames, {}, {"energy", "no-such-check"}), swell::InvalidInput);
  OceanCheckOptions bad;
  bad.alpha = 0;
  EXPECT_THROW(run_ocean_checks(c, frames, bad), swell::InvalidInput);
}

TEST(OceanChecks, OneFrameSkipsWhatNeedsTimeAndSaysSo) {
  OceanCase c = jonswap_deep(32);
  c.frames = 1;
  const auto report = run_ocean_checks(c, swell::test::render_surface(c));
  EXPECT_TRUE(swell::validation::all_passed(report.results)) << failures(report);
  std::set<std::string> checks;
  for (const auto& r : report.results) checks.insert(r.check);
  EXPECT_FALSE(checks.count("dispersion.residual"));
  EXPECT_FALSE(checks.count("direction.distribution"));
  EXPECT_TRUE(checks.count("energy"));
  EXPECT_GE(report.skipped.size(), 3u);
}

// Skipped checks are values: each names its check and why in a reason the table allows.
TEST(OceanChecks, SkippedChecksAreValuesTheTableAllows) {
  OceanCase c = jonswap_deep(32);
  c.frames = 1;
  const auto report = run_ocean_checks(c, swell::test::render_surface(c));
  std::map<std::string, swell::validation::SkipReason> skipped;
  for (const auto& s : report.skipped) skipped[s.check] = s.reason;
  ASSERT_TRUE(skipped.count("dispersion"));
  EXPECT_EQ(skipped["dispersion"], swell::validation::SkipReason::too_few_frames);
  ASSERT_TRUE(skipped.count("direction"));
  EXPECT_EQ(skipped["direction"], swell::validation::SkipReason::too_few_frames);
  for (const auto& s : report.skipped) {
    EXPECT_EQ(s.text(), s.check + ": " + s.why);
    const std::string head = s.check.substr(0, s.check.find('.'));
    const auto& table = swell::validation::ocean_check_table();
    const auto row = std::find_if(table.begin(), table.end(),
                                  [&](const auto& r) { return r.name == head; });
    ASSERT_NE(row, table.end()) << s.check;
    EXPECT_NE(std::find(row->skipped_when.begin(), row->skipped_when.end(), s.reason),
              row->skipped_when.end())
        << s.text() << ": a reason its row does not list";
  }
}

// The table is the one list of checks: the run order, the statistical checks that share α and
// the order the gate starts them in derive from it, and docs/checks.md's table of checks names
// them in the same order.
TEST(OceanCheckTable, RunOrderSharesOfAlphaAndDocsDeriveFromIt) {
  const auto& table = swell::validation::ocean_check_table();
  std::vector<std::string> names;
  for (const auto& row : table) names.emplace_back(row.name);
  EXPECT_EQ(swell::validation::ocean_check_names(), names);
  // Cost ranks are a permutation of 1…N; the gate's groups are the table's rows by rank.
  const auto groups = swell::validation::ocean_check_groups_longest_first();
  ASSERT_EQ(groups.size(), table.size());
  std::set<int> ranks;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const auto row = std::find_if(table.begin(), table.end(),
                                  [&](const auto& r) { return r.name == groups[g].checks.at(0); });
    ASSERT_NE(row, table.end());
    EXPECT_EQ(row->cost_rank, int(g) + 1);
    ranks.insert(row->cost_rank);
  }
  EXPECT_EQ(ranks.size(), table.size());
  // The statistical checks: energy only with an absolute scale, direction from 2 frames.
  auto shared = [](bool free, std::size_t frames) {
    std::vector<std::string> out;
    for (auto name : swell::validation::statistical_ocean_checks(free, frames)) out.emplace_back(name);
    return out;
  };
  using V = std::vector<std::string>;
  EXPECT_EQ(shared(false, 8), (V{"energy", "spectrum", "moments", "direction", "randomness", "statistics"}));
  EXPECT_EQ(shared(true, 8), (V{"spectrum", "moments", "direction", "randomness", "statistics"}));
  EXPECT_EQ(shared(false, 1), (V{"energy", "spectrum", "moments", "randomness", "statistics"}));
  // docs/checks.md §3: the checks' rows, collapsed to their check, in the table's order.
  std::ifstream docs(std::string(SWELL_SOURCE_DIR) + "/docs/checks.md");
  ASSERT_TRUE(docs) << "docs/checks.md";
  std::vector<std::string> documented;
  bool in_table = false;
  for (std::string line; std::getline(docs, line);) {
    if (line.rfind("## 3.", 0) == 0) in_table = true;
    else if (line.rfind("## ", 0) == 0) in_table = false;
    if (!in_table || line.rfind("| `", 0) != 0) continue;
    const std::string cell = line.substr(3, line.find('`', 3) - 3);
    const std::string check = cell.substr(0, cell.find('.'));
    if (documented.empty() || documented.back() != check) documented.push_back(check);
  }
  EXPECT_EQ(documented, names);
}

// A free scale: an engine whose spectrum is 7× the case's passes everything but reports 7.
TEST(OceanChecks, FreeScaleJudgesUpToTheFittedScaleAndReportsIt) {
  OceanCase c = jonswap_deep();
  OceanCase scaled = c;
  scaled.spectrum.numbers["hs"] *= std::sqrt(7.0);
  const auto frames = swell::test::render_surface(scaled);
  OceanCheckOptions options;
  options.free_scale = true;
  const auto report = run_ocean_checks(c, frames, options);
  EXPECT_TRUE(swell::validation::all_passed(report.results)) << failures(report);
  const auto right = run_ocean_checks(c, swell::test::render_surface(c), options);
  EXPECT_NEAR(report.fitted_scale / right.fitted_scale, 7.0, 1e-9);
  EXPECT_FALSE(swell::validation::all_passed(run_ocean_checks(c, frames).results));
}

// ------------------------------------------------------------------ calibration

// The count of failures over `trials` seeds that a check with false-alarm rate α exceeds with
// probability ≤ 1e-3: the binomial upper bound the calibration asserts.
int binomial_upper_bound(int trials, double alpha) {
  const boost::math::binomial_distribution<double> law(trials, alpha);
  return int(boost::math::quantile(boost::math::complement(law, 1e-3)));
}

// Kolmogorov–Smirnov distance of p-values from the uniform law.
double ks_distance(std::vector<double> p) {
  std::sort(p.begin(), p.end());
  double d = 0;
  const double n = double(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    d = std::max({d, (i + 1) / n - p[i], p[i] - i / n});
  }
  return d;
}

void calibrate(const OceanCase& base, int seeds) {
  const std::set<std::string> exact_laws = {"energy", "spectrum.shape",
                                            "statistics.gaussian_amplitudes"};
  std::map<std::string, std::map<double, int>> failed;  // check → α → count
  std::map<std::string, std::vector<double>> p_values;
  for (int s = 0; s < seeds; ++s) {
    OceanCase c = base;
    c.seed = 100000 + s;
    const auto frames = swell::impls::Synthesizer(c, {"fftw", swell::impls::Precision::f32}).frames();
    for (double alpha : {0.05, 1e-3}) {
      OceanCheckOptions options;
      options.alpha = alpha;
      const auto report = run_ocean_checks(c, frames, options);
      std::set<std::string> failed_checks;
      for (const auto& r : report.results) {
        const std::string check = r.check.substr(0, r.check.find('.'));
        failed[check][alpha];  // make the entry
        if (!r.passed) failed_checks.insert(check);
        if (alpha == 0.05 && exact_laws.count(r.check)) p_values[r.check].push_back(r.p_value);
      }
      for (const auto& check : failed_checks) ++failed[check][alpha];
    }
  }
  for (const auto& [check, by_alpha] : failed) {
    for (const auto& [alpha, count] : by_alpha) {
      const int bound = binomial_upper_bound(seeds, alpha);
      std::cout << "[ calibration ] " << check << " at α = " << alpha << ": " << count << " of "
                << seeds << " seeds failed (expected ≤ " << alpha * seeds << ", bound " << bound
                << ")\n";
      EXPECT_LE(count, bound) << check << " α = " << alpha;
    }
  }
  // Where the law is exact, the p-values are uniform: KS at false-alarm 1e-3 (λ = 1.949).
  for (const auto& [check, p] : p_values) {
    const double d = ks_distance(p);
    std::cout << "[ calibration ] " << check << ": KS distance of p-values from uniform " << d << "\n";
    EXPECT_LE(d * std::sqrt(double(p.size())), 1.949) << check;
  }
}

TEST(Calibration, FalseAlarmRatesOverTwoHundredSeedsJonswapDeep) { calibrate(jonswap_deep(), 200); }
TEST(Calibration, FalseAlarmRatesOverTwoHundredSeedsTmaShallow) { calibrate(tma_shallow(), 200); }

// The same on rank-1 lattices of about the grids' 64² points (docs/conventions.md §2.1): the
// checks judge a lattice's N coefficients by the same laws, so their false-alarm rates hold
// there too — a Korobov lattice by the spectral test and a Fibonacci one.
OceanCase on_lattice(OceanCase c, bool fibonacci) {
  c.set_lattice(std::make_shared<const swell::reference::RankOneLattice>(
      fibonacci ? swell::reference::fibonacci_lattice(19, c.grid.lx, c.grid.ly)  // N = 4181
                : swell::reference::korobov_lattice(4096, {c.grid.lx, c.grid.ly})));
  return c;
}
TEST(Calibration, FalseAlarmRatesOverTwoHundredSeedsJonswapDeepKorobovLattice) {
  calibrate(on_lattice(jonswap_deep(), false), 200);
}
TEST(Calibration, FalseAlarmRatesOverTwoHundredSeedsTmaShallowFibonacciLattice) {
  calibrate(on_lattice(tma_shallow(), true), 200);
}

}  // namespace
