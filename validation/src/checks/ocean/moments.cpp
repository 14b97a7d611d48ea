#include <array>
#include <map>

#include "checks/ocean/analysis.hpp"
#include "swell/validation/stats/rounding.hpp"
#include "swell/validation/stats/statistics.hpp"

namespace swell::validation::ocean_analysis {

Results check_moments(const Analysis& a, OceanCheckReport& report) {
  Results out;
  const bool free = a.options().free_scale;
  const double alpha = a.options().alpha / (free ? 3 : 4);
  // m_n = Σk ω^n I(k) = Σ half plane 2 ω^n I(k); expected with μ; Cov(m_a, m_b) = Σ 4 ω^(a+b) μ².
  std::array<double, 3> measured{}, expected{};
  std::array<std::array<double, 3>, 3> cov{};
  for (const Wave& w : a.half_plane()) {
    const double I = a.periodogram0(w.index);
    double power[3] = {1, w.omega, w.omega * w.omega};
    for (int x = 0; x < 3; ++x) {
      measured[x] += 2 * power[x] * I;
      expected[x] += 2 * power[x] * w.mu;
      for (int y = 0; y < 3; ++y) cov[x][y] += 4 * power[x] * power[y] * w.mu * w.mu;
    }
  }
  // Hs = 4 √m0 with m0's exact law.
  if (!free) {
    std::vector<double> weights;
    weights.reserve(a.half_plane().size());
    for (const Wave& w : a.half_plane()) weights.push_back(2 * w.mu);
    const stats::WeightedExponentialSum law(weights);
    const double lo = 4 * std::sqrt(law.quantile(alpha / 2)), hi = 4 * std::sqrt(law.quantile(1 - alpha / 2));
    const double hs = 4 * std::sqrt(measured[0]), hs_expected = 4 * std::sqrt(expected[0]);
    const double p = law.two_sided_p(measured[0]);
    out.push_back(statistical_check("moments.hs", a.subject(), hs, hs_expected, p, alpha,
                              fmt::format("p ≥ α = {:.1e}: Hs in [{:.4g}, {:.4g}] m", alpha, lo, hi),
                              fmt::format("Hs {:.4g} m against {:.4g} m (band-limited){}", hs,
                                          hs_expected, p < alpha ? " — " + or_table(a, "wrong wave height") : "")));
  }
  // Periods as ratios of moments, T = 2π (m0/m_n)^exponent. The law of the ratio R = m0/m_n is
  // exact up to the saddlepoint: P(R ≤ r) = P(Σ 2μ(1 − r ωⁿ) E ≤ 0), a sum of exponentials of
  // both signs. (The delta method's normal law fails where few waves dominate — a patch of
  // 0.15 m holding only the spectrum's tail gives z = −5 on right surfaces, in the command
  // line's property test.) Its z is kept for the message. A period within rounding (64 u log2 N) of the
  // expected one passes whatever the law: one wave's period is exact and its law degenerate.
  // Every energetic wave at rest (ω = 0: a loop period longer than every wave's own period
  // quantizes ω down to 0) has no period to judge.
  auto at_rest = [&](const std::string& name) {
    report.skipped.push_back({"moments." + name, SkipReason::no_wave_motion,
                              "every energetic wave has ω = 0 (the loop period quantizes ω to "
                              "rest): the period is infinite"});
  };
  auto period_check = [&](const char* name, int n, double exponent) {
    if (!(expected[n] > 0)) return at_rest(name);
    // d log T = exponent (d m0/m0 − d m_n/m_n).
    const double t = 2 * kPi * std::pow(measured[0] / measured[n], exponent);
    const double t_expected = 2 * kPi * std::pow(expected[0] / expected[n], exponent);
    const double ratio = measured[0] / measured[n];
    // No energy where ω > 0 while the case puts some there: the period is infinite, and as far
    // from the expected one as a period can be (P(R ≤ r) = 1 for r = ∞).
    double below = 1;
    if (std::isfinite(ratio)) {
      std::vector<double> coefficients;
      for (const Wave& w : a.half_plane()) {
        coefficients.push_back(2 * w.mu * (1 - ratio * (n == 1 ? w.omega : w.omega * w.omega)));
      }
      below = stats::mixed_exponential_sum_cdf_at_zero(coefficients);
    }
    const double rounding = rounding_budget(kCompoundRounding, a.unit_roundoff(), a.log2n());
    const double var_log = exponent * exponent *
                           (cov[0][0] / (expected[0] * expected[0]) -
                            2 * cov[0][n] / (expected[0] * expected[n]) +
                            cov[n][n] / (expected[n] * expected[n])) +
                           std::pow(rounding_budget(kTransformRounding, a.unit_roundoff(), a.log2n()), 2);  // rounding (one wave: 0 variance)
    const double z = std::log(t / t_expected) / std::sqrt(var_log);
    const double p = std::abs(std::log(t / t_expected)) <= rounding
                         ? 1.0
                         : std::min(1.0, 2 * std::min(below, 1 - below));
    out.push_back(statistical_check(fmt::format("moments.{}", name), a.subject(), t, t_expected, p, alpha,
                              fmt::format("p ≥ α = {:.1e} (saddlepoint law of m0/m_n; delta-method z = {:.2f})", alpha, z),
                              fmt::format("{} {:.4g} s against {:.4g} s (z = {:.2f}){}", name, t,
                                          t_expected, z,
                                          p < alpha ? " — " + or_table(a, "the spectrum's frequency content differs") : "")));
  };
  period_check("tm01", 1, 1.0);
  period_check("tm02", 2, 0.5);

  // Tp: the peak of the periodogram binned in ω (bins 4 % wide). Under the right spectrum, with
  // probability ≥ 1 − α every bin lies within its two-sided α/B band (Bonferroni); the
  // measured peak then falls among the bins whose upper bound reaches the largest lower bound.
  struct Bin {
    std::vector<double> weights;
    double observed = 0, expected_energy = 0, omega_weighted = 0;
  };
  std::map<int, Bin> bins;
  for (const Wave& w : a.waves()) {
    if (w.omega <= 0) continue;
    Bin& bin = bins[int(std::floor(std::log(w.omega) / std::log(1.04)))];
    bin.weights.push_back(2 * w.mu);
    bin.observed += 2 * a.periodogram0(w.index);
    bin.expected_energy += 2 * w.mu;
    bin.omega_weighted += 2 * w.mu * w.omega;
  }
  if (bins.empty()) {
    at_rest("tp");
    if (free) report.skipped.push_back({"moments.hs", SkipReason::free_scale, "the case declares a free spectrum scale"});
    return out;
  }
  const double per_bin = alpha / double(2 * bins.size());
  double largest_lower = 0;
  std::map<int, std::pair<double, double>> band;
  for (auto& [key, bin] : bins) {
    const stats::WeightedExponentialSum law(bin.weights);
    band[key] = {law.quantile(per_bin), law.quantile(1 - per_bin)};
    largest_lower = std::max(largest_lower, band[key].first);
  }
  int peak = bins.begin()->first, expected_peak = peak;
  double t_lo = 1e300, t_hi = 0;
  for (auto& [key, bin] : bins) {
    if (bin.observed > bins[peak].observed) peak = key;
    if (bin.expected_energy > bins[expected_peak].expected_energy) expected_peak = key;
  }
  auto bin_period = [&](int key) { return 2 * kPi * bins[key].expected_energy / bins[key].omega_weighted; };
  for (auto& [key, bin] : bins) {
    if (band[key].second >= largest_lower) {
      t_lo = std::min(t_lo, bin_period(key));
      t_hi = std::max(t_hi, bin_period(key));
    }
  }
  const double tp = bin_period(peak), tp_expected = bin_period(expected_peak);
  const bool admissible = band[peak].second >= largest_lower;
  CheckResult tp_result = statistical_check(
      "moments.tp", a.subject(), tp, tp_expected, admissible ? 1.0 : 0.0, alpha,
      fmt::format("peak bin among those that can be the peak at α = {:.1e}: Tp in [{:.4g}, {:.4g}] s",
                  alpha, t_lo, t_hi),
      fmt::format("Tp {:.4g} s (peak of the periodogram in 4 % bins of ω) against {:.4g} s{}", tp,
                  tp_expected, admissible ? "" : " — the spectral peak is misplaced"));
  tp_result.p_value = std::numeric_limits<double>::quiet_NaN();  // a set test, not a p-value
  tp_result.passed = admissible;
  tp_result.tolerance = 0.5 * (t_hi - t_lo);
  out.push_back(tp_result);
  if (free) report.skipped.push_back({"moments.hs", SkipReason::free_scale, "the case declares a free spectrum scale"});
  return out;
}

}  // namespace swell::validation::ocean_analysis
