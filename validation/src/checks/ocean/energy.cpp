#include "checks/ocean/analysis.hpp"
#include "swell/validation/stats/statistics.hpp"

#include <numbers>

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

// A product of the convention factors engines multiply the energy by, e.g. "× 8 = 2 × 2 × 2".
struct ConventionProduct {
  double value = 1;
  int factors = 0;    // how many factors (the fewer, the likelier)
  std::string text;   // the product and what each factor is
};

// Every product of up to four factors from: 2 (unit-variance real and imaginary parts, a √2
// on the amplitude, both halves of each ±k pair at full variance — or their inverses), 2π
// (a spectrum in Hz read as rad/s, or the reverse), 16 (Hs² used where Hs²/16 = m0 belongs) and
// Δk = √(Δkx Δky) (amplitudes with a Δk too few or too many under the root), each with its
// power.
std::vector<ConventionProduct> convention_products(double dk) {
  struct Factor {
    double value;
    const char* symbol;
    const char* meaning;
  };
  const Factor factors[] = {
      {2.0, "2", "2: unit-variance real and imaginary parts (E|ξ|² = 2), a √2 on the amplitude, "
                 "or both halves of each ±k pair at full variance"},
      {2 * std::numbers::pi, "2π", "2π: a spectrum per Hz read as per rad/s (S(f) = 2π S(ω))"},
      {16.0, "16", "16: Hs² where m0 = Hs²/16 belongs"},
      {1 / dk, "1/Δk", ""},  // its meaning names this grid's Δk: dk_meaning
  };
  const std::string dk_meaning =
      fmt::format("1/Δk = {:.4g}: one √(Δkx Δky) missing from the amplitudes (energy per Δk, "
                  "not per Δk²)", 1 / dk);
  std::vector<ConventionProduct> out;
  const int range[4][2] = {{-3, 3}, {-1, 1}, {-1, 1}, {-2, 2}};
  for (int a = range[0][0]; a <= range[0][1]; ++a) {
    for (int b = range[1][0]; b <= range[1][1]; ++b) {
      for (int c = range[2][0]; c <= range[2][1]; ++c) {
        for (int d = range[3][0]; d <= range[3][1]; ++d) {
          const int powers[4] = {a, b, c, d};
          const int count = std::abs(a) + std::abs(b) + std::abs(c) + std::abs(d);
          if (count < 2 || count > 4) continue;  // single causes are named on their own
          ConventionProduct p;
          p.factors = count;
          std::string terms, meanings;
          for (int f = 0; f < 4; ++f) {
            if (powers[f] == 0) continue;
            p.value *= std::pow(factors[f].value, powers[f]);
            for (int i = 0; i < std::abs(powers[f]); ++i) {
              const std::string symbol = factors[f].symbol;
              const std::string inverse = f == 3 ? std::string("Δk") : "1/" + symbol;
              terms += (terms.empty() ? "" : " × ") + (powers[f] > 0 ? symbol : inverse);
            }
            meanings += (meanings.empty() ? "" : "; ") +
                        (f == 3 ? dk_meaning : std::string(factors[f].meaning)) +
                        (powers[f] < 0 ? " (inverted)" : "");
          }
          p.text = fmt::format("× {:.4g} = {}: {}", p.value, terms, meanings);
          out.push_back(std::move(p));
        }
      }
    }
  }
  return out;
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
        {2 * std::numbers::pi, "× 2π: a spectrum per Hz read as per rad/s (S(f) = 2π S(ω); a table "
                               "whose frequency_unit or density_unit is declared wrong)"},
        {1 / (2 * std::numbers::pi), "× 1/(2π): a spectrum per rad/s read as per Hz (a table whose "
                                     "frequency_unit or density_unit is declared wrong)"},
        {16.0, "× 16: Hs² where m0 = Hs²/16 belongs"},
        {1 / 16.0, "× 1/16: m0 divided by 16 twice (Hs²/256)"},
    };
    auto candidates = known;
    if (const double factor = unnormalized_spreading_factor(a); factor > 0) {
      candidates.push_back({factor, fmt::format("the spreading function not normalized (its shape "
                                                "scaled to 1 along the mean direction: × {:.3g})",
                                                factor)});
    }
    // The candidate nearest the measured ratio (in log) among those its sampling range holds;
    // failing a single cause, the product of convention factors with the fewest factors there.
    double best = 1e300;
    std::string meaning;
    for (const auto& [factor, text] : candidates) {
      const double distance = std::abs(std::log(factor / ratio));
      if (factor >= low && factor <= high && distance < best) {
        best = distance;
        meaning = text;
      }
    }
    if (meaning.empty()) {
      int fewest = 1000;
      for (const auto& product : convention_products(std::sqrt(dk2))) {
        if (product.value < low || product.value > high) continue;
        const double distance = std::abs(std::log(product.value / ratio));
        if (product.factors < fewest || (product.factors == fewest && distance < best)) {
          fewest = product.factors;
          best = distance;
          meaning = product.text + fmt::format(" (if the engine means it, declare energy_factor = "
                                               "{:.4g} in the spectrum)", product.value);
        }
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
