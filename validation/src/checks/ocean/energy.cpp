#include "checks/ocean/analysis.hpp"
#include "swell/validation/stats/statistics.hpp"

namespace swell::validation::ocean_analysis {
namespace {

// The energy ratio an engine gets when it uses D(ω, θ)/D(ω, 0) — the spreading's shape without
// its normalization: Σ μ/D(ω, 0) / Σ μ over the resolved waves. 0 when the case has no
// spreading model (Phillips).
double unnormalized_spreading_factor(const Analysis& a) {
  const auto spectrum = a.ocean_case().directional_spectrum();
  const auto spread = std::dynamic_pointer_cast<const reference::SpreadSpectrum>(spectrum);
  if (!spread) return 0;
  const auto dispersion = reference::Dispersion::finite_depth(a.ocean_case().depth, a.ocean_case().gravity);
  double weighted = 0, total = 0;
  for (const Wave& w : a.waves()) {
    const double peak = spread->spreading()(dispersion.omega(w.k), 0.0);
    if (!(peak > 0)) continue;
    weighted += w.mu / peak;
    total += w.mu;
  }
  return total > 0 ? weighted / total : 0;
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
    // The factors engines get wrong, when the sampling range of the ratio holds one.
    const double low = measured / law.quantile(1 - alpha / 2), high = measured / law.quantile(alpha / 2);
    const double g = a.ocean_case().gravity, dk2 = a.sampling().dkx() * a.sampling().dky();
    const std::vector<std::pair<double, std::string>> known = {
        {2.0, "twice the energy: Tessendorf's (ξ1 + iξ2)√(P/2) without the ½ of E|h̃0|² = ½ΨΔk², "
              "or both halves of each ±k pair counted"},
        {0.5, "half the energy: h̃(−k) not paired as conj(h̃(k)) with only the real part kept, "
              "or a ½ too many"},
        {1 / dk2, fmt::format("amplitudes without Δkx Δky (the energy then scales with the patch: "
                              "× {:.4g} here)", 1 / dk2)},
        {std::pow(g, -1.5), "α√g instead of α g² in the spectrum (× g^(−3/2))"},
    };
    auto candidates = known;
    if (const double factor = unnormalized_spreading_factor(a); factor > 0) {
      candidates.push_back({factor, fmt::format("the spreading function not normalized (its shape "
                                                "scaled to 1 along the mean direction: × {:.3g})",
                                                factor)});
    }
    // The candidate nearest the measured ratio (in log) among those its sampling range holds.
    double best = 1e300;
    std::string meaning;
    for (const auto& [factor, text] : candidates) {
      const double distance = std::abs(std::log(factor / ratio));
      if (factor >= low && factor <= high && distance < best) {
        best = distance;
        meaning = text;
      }
    }
    // A mean level carrying the excess is heave, not a factor on the waves.
    const double level = a.periodogram0(0);
    if (ratio > 1 && level > 0.5 * (measured - law.mean())) {
      meaning = fmt::format("{:.0f} % of mean h² is the mean level (k = 0): the whole patch heaves "
                            "(spectrum.unexpected_energy)",
                            100 * level / measured);
    }
    if (!meaning.empty()) reason += " — " + meaning;
  }
  return {statistical_check("energy", a.subject(), measured, law.mean(), p, alpha,
                      fmt::format("p ≥ α = {:.0e} (two-sided, exact law of Σ I)", alpha),
                      reason)};
}

}  // namespace swell::validation::ocean_analysis
