#include "checks/ocean/analysis.hpp"
#include "swell/validation/stats/statistics.hpp"

#include <algorithm>
#include <numbers>

namespace swell::validation::ocean_analysis {
namespace {

// Whether the excess is one factor on every wave: the measured-to-expected energy ratios below
// and above the μ-weighted median |k| agree within their sampling scatter (z < 3; I(k) is μ(k)
// Exp(1), so each half's ratio has variance r² Σμ²/(Σμ)²). A product of convention factors is
// named only then: a fault that moves energy between wave numbers (an offset grid, a wrong
// dispersion) changes the total by no convention's factor.
bool uniform_factor(const Analysis& a) {
  std::vector<const Wave*> waves;
  double total = 0;
  for (const Wave& w : a.half_plane()) {
    if (w.mu > 0) waves.push_back(&w), total += w.mu;
  }
  if (waves.size() < 4) return false;
  std::sort(waves.begin(), waves.end(), [](const Wave* x, const Wave* y) { return x->k < y->k; });
  double ratio[2] = {0, 0}, variance[2] = {0, 0};
  double mu[2] = {0, 0}, measured[2] = {0, 0}, squares[2] = {0, 0}, running = 0;
  for (const Wave* w : waves) {
    const int half = running < 0.5 * total ? 0 : 1;
    running += w->mu;
    mu[half] += w->mu;
    measured[half] += a.periodogram0(w->index);
    squares[half] += w->mu * w->mu;
  }
  for (int h = 0; h < 2; ++h) {
    if (!(mu[h] > 0)) return false;
    ratio[h] = measured[h] / mu[h];
    variance[h] = ratio[h] * ratio[h] * squares[h] / (mu[h] * mu[h]);
  }
  const double z = std::abs(ratio[0] - ratio[1]) / std::sqrt(variance[0] + variance[1]);
  return z < 3;
}

}  // namespace

// mean h² = Σk I(k) = Σ over the half plane of 2 I(k), I(k) ~ μ(k) Exp(1) independent: a
// weighted sum of exponentials, whose law the saddlepoint approximation gives.
Results check_energy(const Analysis& a, OceanCheckReport& report) {
  if (a.options().free_scale) {
    report.skipped.push_back({"energy", SkipReason::free_scale, "the case declares a free spectrum scale"});
    return {};
  }
  std::vector<double> weights;
  weights.reserve(a.half_plane().size());
  for (const Wave& w : a.half_plane()) weights.push_back(2 * w.mu);
  const stats::WeightedExponentialSum law(weights);
  const double measured = a.mean_square0();
  const double p = law.two_sided_p(measured);
  const double ratio = measured / law.mean();
  const double alpha = a.options().alpha;
  const double z = (measured - law.mean()) / std::sqrt(law.variance());
  std::string reason = fmt::format("mean h² = {:.4g} m² is {:.3f}× the band-limited m0 {:.4g} m² "
                                   "(z = {:.2f}, p = {:.2g})",
                                   measured, ratio, law.mean(), z, p);
  if (p < alpha) {
    reason += fmt::format(": energy off by a factor {:.3g} (Hs by {:.3g})", ratio, std::sqrt(ratio));
    // The factors engines get wrong, when the sampling range of the ratio holds one: the factor from the total, or, where the rings measure it more closely (a handful of waves
    // near the peak make the total noisy), the rings' median ratio (MeasuredLevel).
    double factor = ratio, low = measured / law.quantile(1 - alpha / 2), high = measured / law.quantile(alpha / 2);
    bool one_factor = uniform_factor(a);
    const MeasuredLevel& level = a.measured_level();
    if (level.rings >= 4 && level.high / level.low < high / low) {
      reason += fmt::format("; the rings of |k| put it at {:.3g}× (their median; the total rests on "
                            "fewer waves)",
                            level.level);
      factor = level.level, low = level.low, high = level.high, one_factor = level.uniform;
    }
    std::string meaning = name_scale_cause(a, factor, low, high, one_factor);
    // A mean level carrying the excess is heave, not a factor on the waves.
    const double mean_level_power = a.periodogram0(0);
    if (ratio > 1 && mean_level_power > 0.5 * (measured - law.mean())) {
      meaning = fmt::format("{:.0f} % of mean h² is the mean level (k = 0): the whole patch heaves "
                            "(spectrum.unexpected_energy)",
                            100 * mean_level_power / measured);
    }
    // A misdeclared table moves the sea, not a factor on it: its reading is the cause.
    if (!a.misdeclared_table().empty()) meaning = a.misdeclared_table();
    if (!meaning.empty()) reason += " — " + meaning;
  }
  return {statistical_check("energy", a.subject(), measured, law.mean(), p, alpha,
                      fmt::format("p ≥ α = {:.0e} (two-sided, exact law of Σ I)", alpha),
                      reason)};
}

}  // namespace swell::validation::ocean_analysis
