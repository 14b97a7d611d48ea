#include "checks/ocean/analysis.hpp"
#include "swell/validation/stats/statistics.hpp"

#include <algorithm>
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
  // How unlikely the product is as an explanation: one per factor (two for 16, a specific slip
  // rather than a convention), and one more when it mixes factors and inverses. The cheapest
  // product the sampling range holds is named: × 8 is 2 × 2 × 2 (cost 3), not 16 × 1/2 (cost 4).
  int cost = 0;
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
          const bool mixed = std::any_of(std::begin(powers), std::end(powers), [](int q) { return q > 0; }) &&
                             std::any_of(std::begin(powers), std::end(powers), [](int q) { return q < 0; });
          p.cost = count + std::abs(c) + (mixed ? 1 : 0);
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
    // Every cause its sampling range holds — a single one, or (when the excess is one factor on
    // every wave) a product of up to three convention factors (cost ≤ 3) — and of those the
    // nearest the measured ratio in log, the cheaper on a tie: on a handful of waves the range
    // can hold both 2π and 8, and the nearer is named.
    struct Cause {
      double value;
      int cost;
      std::string text;
    };
    std::vector<Cause> causes;
    for (const auto& [factor, text] : candidates) causes.push_back({factor, 1, text});
    // The convention factors, alone or in products, only where the excess is one factor on
    // every wave.
    const bool one_factor = uniform_factor(a);
    if (one_factor) {
      const std::pair<double, std::string> conventions[] = {
          {2 * std::numbers::pi, "× 2π: a spectrum per Hz read as per rad/s (S(f) = 2π S(ω); a "
                                 "table whose frequency_unit or density_unit is declared wrong)"},
          {1 / (2 * std::numbers::pi), "× 1/(2π): a spectrum per rad/s read as per Hz (a table "
                                       "whose frequency_unit or density_unit is declared wrong)"},
          {16.0, "× 16: Hs² where m0 = Hs²/16 belongs"},
          {1 / 16.0, "× 1/16: m0 divided by 16 twice (Hs²/256)"}};
      for (const auto& [factor, text] : conventions) causes.push_back({factor, 1, text});
    }
    for (const auto& product : convention_products(std::sqrt(dk2))) {
      if (product.cost > 3 || !one_factor) continue;
      causes.push_back({product.value, product.cost,
                        product.text + fmt::format(" (if the engine means it, declare "
                                                   "energy_factor = {:.4g} in the spectrum)",
                                                   product.value)});
    }
    std::vector<const Cause*> held;
    for (const auto& cause : causes) {
      if (cause.value >= low && cause.value <= high) held.push_back(&cause);
    }
    std::stable_sort(held.begin(), held.end(), [&](const Cause* x, const Cause* y) {
      const double dx = std::abs(std::log(x->value / ratio)), dy = std::abs(std::log(y->value / ratio));
      return dx != dy ? dx < dy : x->cost < y->cost;
    });
    std::string meaning;
    if (!held.empty()) meaning = held[0]->text;
    // A mean level carrying the excess is heave, not a factor on the waves.
    const double level = a.periodogram0(0);
    if (ratio > 1 && level > 0.5 * (measured - law.mean())) {
      meaning = fmt::format("{:.0f} % of mean h² is the mean level (k = 0): the whole patch heaves "
                            "(spectrum.unexpected_energy)",
                            100 * level / measured);
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
